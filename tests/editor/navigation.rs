//! Moving around the graph as in Blender: the wheel zooms about the cursor, middle- and
//! Alt-drag pan, a left-drag on empty canvas selects by rectangle (Shift adds, Ctrl
//! removes), Home/F frame everything and '.' the selection; every preset opens whole
//! and legible.

use super::support::{
    chain_editor, click_at, editor, flat_wood_editor, press, scratch, wheel_notch,
};
use egui::{Event, Modifiers, PointerButton, Pos2, Rect, pos2, vec2};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use std::path::PathBuf;
use veneer::app::VeneerApp;

/// The graph panel's screen area in the 1400×900 test window (left of the side panel,
/// between the menu and the status bar).
pub const GRAPH_AREA: Rect = Rect::from_min_max(pos2(0.0, 20.0), pos2(930.0, 875.0));

/// Where the node titled `title` is on screen (its largest label: the title, not a pin
/// or field of the same name).
pub fn on_screen(harness: &Harness<'static, VeneerApp>, title: &str) -> Rect {
    let rect = harness
        .query_all_by_label(title)
        .map(|node| node.rect())
        .max_by(|a, b| a.height().total_cmp(&b.height()))
        .unwrap_or_else(|| panic!("no node titled '{title}'"));
    harness.state().graph_to_screen() * rect
}

/// Drags `button` from `from` to `to` in steps, holding `modifiers`.
pub fn drag(
    harness: &mut Harness<'static, VeneerApp>,
    button: PointerButton,
    modifiers: Modifiers,
    from: Pos2,
    to: Pos2,
) {
    harness.event(Event::ModifiersChanged(modifiers));
    harness.event(Event::PointerMoved(from));
    harness.run_steps(2);
    let press = |pos, pressed| Event::PointerButton {
        pos,
        button,
        pressed,
        modifiers,
    };
    harness.event(press(from, true));
    harness.run_steps(2);
    for step in 1..=8 {
        harness.event(Event::PointerMoved(
            from + (to - from) * (step as f32 / 8.0),
        ));
        harness.run_steps(1);
    }
    harness.event(press(to, false));
    harness.run_steps(2);
    harness.event(Event::ModifiersChanged(Modifiers::NONE));
    harness.run_steps(2);
}

/// The labels of the selected nodes, sorted.
pub fn selected(harness: &Harness<'static, VeneerApp>) -> Vec<String> {
    let mut labels = harness.state().selected_labels();
    labels.sort();
    labels
}

#[test]
fn the_wheel_zooms_about_the_cursor() {
    let mut harness = editor(&scratch("nav-wheel"), None);
    let cursor = pos2(500.0, 400.0);
    let before = harness.state().graph_to_screen();
    let under_cursor = before.inverse() * cursor;
    harness.event(Event::PointerMoved(cursor));
    for _ in 0..3 {
        wheel_notch(&mut harness);
    }
    harness.run_steps(30);
    let after = harness.state().graph_to_screen();
    assert!(
        after.scaling > before.scaling * 1.3,
        "three notches zoom in: {} → {}",
        before.scaling,
        after.scaling
    );
    let moved = after * under_cursor - cursor;
    assert!(
        moved.length() < 0.5,
        "the point under the cursor moved by {moved:?}"
    );
}

#[test]
fn middle_and_alt_drags_pan() {
    let mut harness = editor(&scratch("nav-pan"), None);
    let (from, by) = (pos2(400.0, 300.0), vec2(120.0, -60.0));
    for (button, modifiers) in [
        (PointerButton::Middle, Modifiers::NONE),
        (PointerButton::Primary, Modifiers::ALT),
    ] {
        let before = harness.state().graph_to_screen();
        drag(&mut harness, button, modifiers, from, from + by);
        let after = harness.state().graph_to_screen();
        assert_eq!(after.scaling, before.scaling);
        let panned = after.translation - before.translation;
        assert!(
            (panned - by).length() < 1.0,
            "{button:?} with {modifiers:?} panned by {panned:?}, not {by:?}"
        );
    }
}

#[test]
fn a_left_drag_on_empty_canvas_selects_shift_adds_ctrl_removes() {
    let mut harness = flat_wood_editor(&scratch("nav-select"));
    let transform_before = harness.state().graph_to_screen();
    // The flat wood opens with "trunk" at the top left, "coarse warp space" right of it
    // and "tint space" below it.
    let (trunk, drift, tint) = (
        on_screen(&harness, "trunk"),
        on_screen(&harness, "coarse warp space"),
        on_screen(&harness, "tint space"),
    );
    // From empty canvas above and left of the trunk to the middle of the coarse warp space.
    let start = trunk.min - vec2(12.0, 12.0);
    drag(
        &mut harness,
        PointerButton::Primary,
        Modifiers::NONE,
        start,
        drift.center(),
    );
    assert_eq!(selected(&harness), ["coarse warp space", "trunk"]);
    assert_eq!(
        harness.state().graph_to_screen(),
        transform_before,
        "the drag selected, it did not pan"
    );
    // From the canvas right of the node's frame (and its pins), short of the next node.
    let graph = &harness.state().document().graph;
    let tint_node = graph
        .nodes
        .iter()
        .find(|n| n.label == "tint space")
        .unwrap();
    let frame = harness.state().node_on_screen(tint_node.id).unwrap();
    let right_of_tint = pos2(frame.max.x + 12.0, frame.center().y);
    drag(
        &mut harness,
        PointerButton::Primary,
        Modifiers::SHIFT,
        right_of_tint,
        tint.center(),
    );
    assert_eq!(
        selected(&harness),
        ["coarse warp space", "tint space", "trunk"]
    );
    drag(
        &mut harness,
        PointerButton::Primary,
        Modifiers::COMMAND,
        start,
        trunk.center(),
    );
    assert_eq!(selected(&harness), ["coarse warp space", "tint space"]);
}

#[test]
fn home_and_f_frame_everything_and_period_the_selection() {
    let mut harness = flat_wood_editor(&scratch("nav-frame"));
    let all = harness.state().graph_to_screen();
    for key in [egui::Key::Home, egui::Key::F] {
        drag(
            &mut harness,
            PointerButton::Middle,
            Modifiers::NONE,
            pos2(400.0, 400.0),
            pos2(100.0, 100.0),
        );
        assert_ne!(harness.state().graph_to_screen(), all);
        press(&mut harness, key, false);
        harness.run_steps(4);
        // Within a few pixels: nodes are measured again each frame.
        let framed = harness.state().graph_to_screen();
        assert!(
            (framed.translation - all.translation).length() < 4.0
                && (framed.scaling - all.scaling).abs() < 1e-3,
            "{key:?} framed {framed:?}, not everything as on open ({all:?})"
        );
    }
    super::support::select_node(&mut harness, "ring sharp");
    press(&mut harness, egui::Key::Period, false);
    harness.run_steps(4);
    let node = on_screen(&harness, "ring sharp");
    let centre = GRAPH_AREA.center();
    assert!(
        harness.state().graph_to_screen().scaling > all.scaling,
        "one node is framed closer than all of them"
    );
    assert!(
        (node.center().y - centre.y).abs() < 120.0 && (node.center().x - centre.x).abs() < 200.0,
        "'.' put the selected node at {node:?}, not around the middle {centre:?}"
    );
}

#[test]
fn every_preset_opens_whole_with_legible_titles() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("graphs");
    for (name, _) in veneer::app::PRESETS {
        let path = root.join(format!("{name}.ron"));
        let mut harness = editor(&scratch(&format!("nav-open-{name}")), Some(path.clone()));
        harness.run_steps(2);
        let graph = veneer::graph::load(&path).expect("the preset loads");
        for node in &graph.nodes {
            let title = on_screen(&harness, node.display_name());
            assert!(
                GRAPH_AREA.contains_rect(title),
                "{name}: '{}' is at {title:?}, outside the graph panel",
                node.label
            );
            assert!(
                title.height() >= 12.0,
                "{name}: '{}' is {} px high",
                node.label,
                title.height()
            );
        }
    }
}

#[test]
fn an_unlabelled_math_node_is_titled_by_its_operation() {
    let mut harness = editor(&scratch("nav-divide"), None);
    super::support::add_node(&mut harness, "divide", "Divide");
    harness.run_steps(2);
    // Node titles are the only labels of their size in the graph (the inspector, which
    // names the kind "Math" and its operation "Divide", uses the body font).
    let transform = harness.state().graph_to_screen();
    let titles = |text: &str| {
        harness
            .query_all_by_label(text)
            .map(|node| transform * node.rect())
            .filter(|rect| rect.height() >= 12.0 && GRAPH_AREA.contains_rect(*rect))
            .count()
    };
    assert_eq!(titles("Math"), 0, "the new Divide node is titled 'Math'");
    assert_eq!(titles("Divide"), 1, "the new node is titled 'Divide'");
}

#[test]
fn a_big_graph_zoomed_out_draws_outlines_that_still_select() {
    // 220 nodes (a big graph) in bands, taller than wide, that Home frames zoomed out
    // below the zoom graphs open at (0.3), with empty canvas left and right.
    let mut harness = chain_editor(&scratch("nav-outlines"), 220, 2500.0);
    harness.run_steps(2);
    press(&mut harness, egui::Key::Home, false);
    harness.run_steps(4);
    let scaling = harness.state().graph_to_screen().scaling;
    assert!(scaling < 0.3, "Home framed the chain at zoom {scaling}");
    // Outlines: a painted box and title, no widgets inside the node.
    assert!(
        harness.query_by_label("step 1").is_none(),
        "the node is drawn in full at zoom {scaling}"
    );
    let node = |harness: &Harness<'static, VeneerApp>, label: &str| {
        let graph = &harness.state().document().graph;
        let node = graph.nodes.iter().find(|n| n.label == label).unwrap();
        let rect = harness.state().node_on_screen(node.id).expect("on screen");
        (node.id, rect)
    };
    // A click on an outline selects its node alone.
    let (noise, noise_rect) = node(&harness, "noise 3");
    click_at(&mut harness, noise_rect.center());
    assert_eq!(harness.state().selected_nodes(), [noise]);
    // A box from empty canvas left of the first outline to the second selects both.
    let ((start, start_rect), (step, step_rect)) =
        (node(&harness, "start"), node(&harness, "step 1"));
    let corner = pos2(start_rect.min.x - 8.0, start_rect.center().y);
    assert!(GRAPH_AREA.contains(corner), "{corner:?} is off the panel");
    drag(
        &mut harness,
        PointerButton::Primary,
        Modifiers::NONE,
        corner,
        step_rect.center(),
    );
    let mut boxed = harness.state().selected_nodes();
    boxed.sort();
    assert_eq!(boxed, [start, step]);
    // Framed close, the nodes are whole again.
    press(&mut harness, egui::Key::Period, false);
    harness.run_steps(4);
    assert!(harness.state().graph_to_screen().scaling >= 0.3);
    assert!(
        harness.query_by_label("step 1").is_some(),
        "framed close, the node is still an outline"
    );
}
