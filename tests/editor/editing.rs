//! Editing in the real editor: the preset loads and renders, nodes are added through the
//! search menu and wired, parameters change the preview without recompiling, undo
//! restores it, and compile errors land on the node that caused them.

use crate::support::{
    add_node, editor, flat_wood_editor, press, preview_pixels, retype_drag_value, saved_preset,
    scratch, screen, select_node, shows, wire_into_alpha,
};
use egui_kittest::kittest::Queryable;
use veneer::graph::NodeKind;
use veneer::nodes::Worley;

#[test]
fn opens_on_the_wood_preset_with_the_material_on_a_sphere() {
    let dir = scratch("open");
    let mut harness = editor(&dir, None);
    // The node thumbnails come from another thread: the snapshot waits for them, then
    // frames the graph again (Home) now that every node has its final size, so that
    // the view does not depend on when the thumbnails arrived.
    crate::thumbnails::settle(&mut harness);
    press(&mut harness, egui::Key::Home, false);
    harness.run_steps(16);
    let image = screen(&mut harness);
    let app = harness.state();
    assert_eq!(app.document().graph.name, "Wood");
    assert!(app.live().errors.is_empty() && app.live().compiled.is_some());
    assert_eq!(
        app.pipelines_built(),
        1,
        "the preview built the material's pipeline once"
    );
    assert!(shows(&harness, "material compiles"));
    // The sphere is lit wood: brownish pixels in the middle of the preview.
    let centre = image.get_pixel(1170, 250).0;
    assert!(
        centre[0] > centre[2] + 20 && centre[0] > 60,
        "not wood-coloured: {centre:?}"
    );
    // Between runs, node edges can land a pixel or two apart (egui settles widget sizes
    // over frames) and the preview's "reset view" button may be caught mid-layout: up
    // to 4,000 pixels (0.3% of the window) may differ.
    let options = egui_kittest::SnapshotOptions::new()
        .output_path("tests/editor/snapshots")
        .threshold(2.0)
        .max_failed_pixels(4000);
    if let Err(error) = egui_kittest::try_image_snapshot_options(&image, "editor_wood", &options) {
        panic!("{error}");
    }
}

#[test]
fn adds_a_node_through_the_search_menu_and_wires_it_from_the_inspector() {
    let dir = scratch("add");
    let mut harness = flat_wood_editor(&dir);
    let before = harness.state().document().graph.nodes.len();
    add_node(&mut harness, "worley", "Worley");
    let graph = &harness.state().document().graph;
    assert_eq!(graph.nodes.len(), before + 1);
    let worley = graph
        .nodes
        .iter()
        .find(|n| matches!(n.kind, NodeKind::Worley(Worley { .. })))
        .expect("a Worley node")
        .id;

    // Selection follows clicks from node to node, and the selected node's output shows
    // in a thumbnail: the bare rings, brown.
    select_node(&mut harness, "ring colour");
    let image = crate::support::screen(&mut harness);
    assert!(harness.state().thumbnail().compiled.is_some());
    let rings = image.get_pixel(1030, 615).0;
    assert!(
        rings[0] > rings[2] + 30,
        "the thumbnail shows the ring colours: {rings:?}"
    );
    select_node(&mut harness, "wood colour");
    // Wire the new node into the material's alpha through the inspector's connect choice.
    wire_into_alpha(&mut harness, "Worley · value");
    let graph = &harness.state().document().graph;
    let wire = graph.wire_into(graph.material().unwrap().id, "alpha");
    assert_eq!(wire.map(|w| w.from.node), Some(worley));
    assert_eq!(
        harness.state().live().compiles,
        3,
        "adding and wiring are structural edits"
    );
}

#[test]
fn a_parameter_edit_changes_the_preview_without_recompiling_and_undo_restores_it() {
    let dir = scratch("parameter");
    let mut harness = editor(&dir, None);
    let original = preview_pixels(&screen(&mut harness));
    let compiles = harness.state().live().compiles;
    select_node(&mut harness, "material");
    // Type a much lower shininess into the inspector's drag value: a broad highlight.
    retype_drag_value(&mut harness, "24.0", "2");
    assert!(harness.state().document().is_dirty());
    let edited = preview_pixels(&screen(&mut harness));
    assert_ne!(original, edited, "the preview shows the new colour");
    assert_eq!(
        harness.state().live().compiles,
        compiles,
        "a parameter edit never recompiles"
    );
    assert_eq!(harness.state().pipelines_built(), 1);

    press(&mut harness, egui::Key::Z, true);
    let undone = preview_pixels(&screen(&mut harness));
    assert_eq!(undone, original, "undo restores the preview");
    assert!(!harness.state().document().is_dirty());
}

#[test]
fn a_compile_error_is_shown_on_the_node_that_caused_it() {
    let dir = scratch("error");
    let mut harness = editor(&dir, None);
    let before = preview_pixels(&screen(&mut harness));
    add_node(&mut harness, "smoothstep", "Smoothstep");
    wire_into_alpha(&mut harness, "Smoothstep · result");
    let app = harness.state();
    let smoothstep = app
        .document()
        .graph
        .nodes
        .iter()
        .map(|n| n.id)
        .max()
        .expect("the new node has the largest id");
    assert_eq!(
        app.document().graph.node(smoothstep).unwrap().kind,
        NodeKind::Smoothstep
    );
    assert!(
        app.live().errors.contains_key(&Some(smoothstep)),
        "{:?}",
        app.live().errors
    );
    assert!(shows(
        &harness,
        &format!("node 'Smoothstep' ({smoothstep}): input 'x' (float) must be connected")
    ));
    assert!(
        app.live().compiled.is_some(),
        "the last good material stays"
    );
    let after = preview_pixels(&screen(&mut harness));
    assert_eq!(
        harness.state().pipelines_built(),
        1,
        "no pipeline for the broken graph"
    );
    assert_eq!(
        before, after,
        "the preview keeps showing the last good material"
    );
}

#[test]
fn a_comment_frame_is_drawn_around_the_selected_nodes_and_undone() {
    let dir = scratch("frame");
    let mut harness = flat_wood_editor(&dir);
    select_node(&mut harness, "wood colour");
    harness.get_by_label("Edit").click_accesskit();
    harness.run();
    harness
        .get_by_label("Frame selected nodes")
        .click_accesskit();
    harness.run();
    let frames = &harness.state().document().graph.frames;
    assert_eq!(frames.len(), 1);
    assert_eq!(
        harness.state().live().compiles,
        1,
        "a comment frame never recompiles"
    );
    let node = harness
        .state()
        .document()
        .graph
        .nodes
        .iter()
        .find(|n| n.label == "wood colour")
        .unwrap();
    let (x, y) = node.position;
    assert!(
        frames[0].min.0 < x && frames[0].min.1 < y && frames[0].max.0 > x && frames[0].max.1 > y
    );
    screen(&mut harness)
        .save(dir.join("frame.png"))
        .expect("screenshot");
    press(&mut harness, egui::Key::Escape, false);
    press(&mut harness, egui::Key::Z, true);
    assert!(
        harness.state().document().graph.frames.is_empty(),
        "undo removes the frame"
    );
}

#[test]
fn a_numerical_hazard_is_marked_on_its_node_without_blocking_the_material() {
    let dir = scratch("lint");
    let mut harness = flat_wood_editor(&dir);
    select_node(&mut harness, "ring sharp");
    // Make the smoothstep's edges equal by typing 0.85 into edge0 (0.25 in the inspector).
    retype_drag_value(&mut harness, "0.250", "0.85");
    let app = harness.state();
    let node = app
        .document()
        .graph
        .nodes
        .iter()
        .find(|n| n.label == "ring sharp")
        .unwrap()
        .id;
    eprintln!(
        "inputs: {:?}",
        app.document().graph.node(node).unwrap().inputs
    );
    assert!(
        app.live()
            .warnings
            .top
            .get(&node)
            .is_some_and(|w| w.contains("a hard step")),
        "{:?}",
        app.live().warnings
    );
    assert!(app.live().errors.is_empty(), "a warning is not an error");
    assert!(shows(
        &harness,
        "1 numerical warning (see the marked nodes)"
    ));
}

#[test]
fn the_material_node_names_its_shading_beside_its_title() {
    use veneer::graph::Shading;
    use veneer::graph::edit::{GraphEdit, GraphSetting};
    let mut harness = editor(&scratch("shading-name"), None);
    // Drawn in the node's header: level with its title.
    let beside_title = |harness: &crate::add_node::Editor, name: &str| {
        let title = harness
            .query_all_by_label("material")
            .map(|node| node.rect())
            .max_by(|a, b| a.height().total_cmp(&b.height()))
            .expect("the material node's title");
        harness
            .query_all_by_label(name)
            .any(|label| (label.rect().center().y - title.center().y).abs() < title.height())
    };
    assert!(beside_title(&harness, "Blinn-Phong"));
    let metallic = GraphEdit::Set(GraphSetting::Shading(Shading::MetallicRoughness));
    harness
        .state_mut()
        .apply_edit(metallic)
        .expect("shading set");
    harness.run();
    assert!(beside_title(&harness, "metallic-roughness"));
    assert!(!beside_title(&harness, "Blinn-Phong"));
}

/// Text a shader cannot compute with (`inf`, `nan`) or that is no number at all, typed
/// into a node's field or a parameter's, leaves the value, the file's saved state and the
/// undo history as they were (before, `inf` was stored and saved, and `veneer check`
/// then refused the file; `nan` in a parameter's slider became its maximum).
#[test]
fn typing_what_is_not_a_finite_number_changes_nothing() {
    let dir = scratch("not-finite");
    let marble = saved_preset(&dir, "marble");
    let mut harness = editor(&dir, Some(marble));
    let original = harness.state().document().graph.clone();
    select_node(&mut harness, "material");
    for text in ["inf", "nan", "abc"] {
        retype_drag_value(&mut harness, "64.0", text);
        retype_drag_value(&mut harness, "3.0", text);
        let document = harness.state().document();
        assert_eq!(document.graph, original, "'{text}' changes no value");
        assert!(!document.is_dirty(), "'{text}' leaves the file saved");
        assert!(!document.history.can_undo(), "'{text}' adds no undo step");
    }
}
