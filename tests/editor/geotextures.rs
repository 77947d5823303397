//! GeoTextures in the editor: fields solved in the background for the preview, sources
//! picked by clicking the mesh, and the field view.

use crate::support::{editor, preview_pixels, scratch, screen};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use veneer::app::VeneerApp;

/// Runs frames until the preview's fields are solved (they solve on another thread).
fn wait_for_fields(harness: &mut Harness<'static, VeneerApp>) {
    for _ in 0..600 {
        harness.step();
        if harness.state().fields_solved() {
            harness.run();
            return;
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    panic!("the fields were not solved in 12 s");
}

/// The editor on the isolines preset (two sources on genus2), its fields solved.
fn isolines(scratch_name: &str) -> Harness<'static, VeneerApp> {
    let dir = scratch(scratch_name);
    let graph = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("graphs/isolines.ron");
    let mut harness = editor(&dir, Some(graph));
    wait_for_fields(&mut harness);
    harness
}

fn sources(harness: &Harness<'static, VeneerApp>) -> Vec<u32> {
    harness.state().document().graph.preview.fields[0]
        .sources
        .clone()
}

#[test]
fn fields_solve_for_the_preview_and_a_click_on_the_mesh_adds_a_source() {
    let mut harness = isolines("fields");
    let solved = preview_pixels(&screen(&mut harness));
    assert_eq!(sources(&harness).len(), 2);

    harness.get_by_label("pick").click();
    harness.run();
    // The middle of the preview looks at the bridge between the two rings.
    let centre = egui::pos2(1170.0, 250.0);
    harness.event(egui::Event::PointerMoved(centre));
    for pressed in [true, false] {
        harness.event(egui::Event::PointerButton {
            pos: centre,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: Default::default(),
        });
    }
    harness.step();
    let picked = sources(&harness);
    assert_eq!(picked.len(), 3, "the click added a source: {picked:?}");
    assert!(harness.state().document().is_dirty(), "picking is an edit");

    wait_for_fields(&mut harness);
    for _ in 0..3 {
        harness.run();
    }
    let moved = preview_pixels(&screen(&mut harness));
    assert_ne!(solved, moved, "the isolines now ring the new source too");

    harness.get_by_label("view").click();
    harness.run();
    harness.run();
    assert_ne!(
        moved,
        preview_pixels(&screen(&mut harness)),
        "the field view replaces the material"
    );
}

#[test]
fn fields_that_cannot_be_solved_on_the_shown_mesh_are_said_over_the_preview() {
    let mut harness = isolines("fields-elsewhere");
    assert!(!crate::support::shows(&harness, "fields not solved"));
    // The cube has fewer vertices than the preset's sources are numbered on genus2.
    harness.get_by_value("genus2").click_accesskit();
    harness.run();
    harness.get_by_label("cube").click_accesskit();
    for _ in 0..200 {
        harness.step();
        if crate::support::shows(&harness, "fields not solved on this mesh") {
            return;
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    panic!("no word over the preview that the fields cannot be solved on the cube");
}

/// Picking sources and viewing a field belong to the graph they were turned on for:
/// opening a file (here the same one again) starts with both off. Before, "pick" stayed
/// on into a graph without fields, and a field added there began in it.
#[test]
fn opening_a_file_turns_picking_and_the_field_view_off() {
    use egui_kittest::kittest::NodeT;
    let mut harness = isolines("modes");
    let toggled = |harness: &Harness<'static, VeneerApp>, label: &str| {
        let toggle = harness.get_by_label(label);
        toggle.accesskit_node().toggled() == Some(egui::accesskit::Toggled::True)
    };
    for label in ["pick", "view"] {
        harness.get_by_label(label).click();
        harness.run();
        assert!(toggled(&harness, label), "'{label}' turned on");
    }
    let graph = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("graphs/isolines.ron");
    harness.state_mut().open(graph);
    wait_for_fields(&mut harness);
    for label in ["pick", "view"] {
        assert!(
            !toggled(&harness, label),
            "'{label}' is off in the file opened"
        );
    }
}
