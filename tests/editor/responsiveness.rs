//! The editor stays responsive: frames without input do no whole-graph work, a drag
//! draws drafts and never recompiles (and a box selection, which changes nothing drawn,
//! draws none), the UI keeps answering (showing the last good material) while a new one
//! compiles on the preview thread, time plays by the clock and starts again with another
//! graph, and graphs of thousands of nodes (more parameters than a uniform block holds)
//! open and show their material.

use crate::support::{
    chain_editor, editor, preview_pixels, scratch, screen, select_node, settle_previews,
    settle_previews_within,
};
use egui::{Event, PointerButton, pos2};
use egui_kittest::kittest::Queryable;
use veneer::render::Quality;

#[test]
fn frames_without_input_do_no_whole_graph_work() {
    let mut harness = editor(&scratch("idle"), None);
    settle_previews(&mut harness);
    let (revision, reads) = harness.state().revision();
    for _ in 0..10 {
        harness.step();
    }
    // Moving the pointer over the graph is no edit either.
    for x in [400.0, 420.0, 440.0] {
        harness.event(Event::PointerMoved(pos2(x, 700.0)));
        harness.step();
    }
    assert_eq!(
        harness.state().revision(),
        (revision, reads),
        "idle and hover frames read the graph view back"
    );
    // Edits are commands: a click that edits nothing takes nothing in from the view.
    harness.get_by_label("View").click();
    harness.run();
    assert_eq!(
        harness.state().revision(),
        (revision, reads),
        "a menu opened changes nothing and reads nothing"
    );
}

#[test]
fn the_ui_answers_while_a_new_material_compiles_on_the_preview_thread() {
    let mut harness = editor(&scratch("compiling"), None);
    let before = preview_pixels(&screen(&mut harness));
    assert_eq!(harness.state().pipelines_built(), 1);
    // Every octave instead of what the footprint shows: a new material.
    harness.get_by_label("every octave").click();
    harness.step();
    assert_eq!(harness.state().live().compiles, 2, "the click recompiled");
    assert!(
        !harness.state().preview_settled(),
        "the frame came back before the new pipeline was built"
    );
    let during = preview_pixels(&harness.render().expect("renders"));
    assert_eq!(
        during, before,
        "the last good material stays on screen meanwhile"
    );
    let after = preview_pixels(&screen(&mut harness));
    assert_eq!(harness.state().pipelines_built(), 2);
    assert_ne!(after, before, "then the new material shows");
}

#[test]
fn a_drag_draws_drafts_without_recompiling_and_refines_when_let_go() {
    let mut harness = editor(&scratch("drafts"), None);
    settle_previews(&mut harness);
    assert_eq!(harness.state().preview_quality(), Some(Quality::Full));
    select_node(&mut harness, "material");
    let mut at = harness
        .get_all_by_value("24.0")
        .next()
        .expect("the shininess drag value")
        .rect()
        .center();
    harness.event(Event::PointerMoved(at));
    harness.step();
    let press = |pos, pressed| Event::PointerButton {
        pos,
        button: PointerButton::Primary,
        pressed,
        modifiers: Default::default(),
    };
    harness.event(press(at, true));
    harness.step();
    let started = std::time::Instant::now();
    while harness.state().preview_quality() != Some(Quality::Draft) {
        assert!(
            started.elapsed() < std::time::Duration::from_secs(60),
            "no draft while dragging"
        );
        at.x += 1.0;
        harness.event(Event::PointerMoved(at));
        harness.step();
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    assert!(
        !harness.state().preview_settled(),
        "a draft is not the full picture"
    );
    for _ in 0..40 {
        at.x += 1.0;
        harness.event(Event::PointerMoved(at));
        harness.step();
    }
    harness.event(press(at, false));
    settle_previews(&mut harness);
    assert_eq!(harness.state().preview_quality(), Some(Quality::Full));
    assert_eq!(
        harness.state().live().compiles,
        1,
        "a drag never recompiles"
    );
    assert!(
        harness.state().document().is_dirty(),
        "the drag changed the shininess"
    );
}

#[test]
fn a_box_selection_over_empty_canvas_keeps_the_full_picture() {
    let mut harness = editor(&scratch("box-no-draft"), None);
    settle_previews(&mut harness);
    assert!(harness.state().preview_settled());
    // Below the material node, where no node lies.
    let material = crate::navigation::on_screen(&harness, "material");
    let from = material.left_bottom() + egui::vec2(0.0, 120.0);
    assert!(crate::navigation::GRAPH_AREA.contains(from + egui::vec2(160.0, 100.0)));
    let press = |pos, pressed| Event::PointerButton {
        pos,
        button: PointerButton::Primary,
        pressed,
        modifiers: Default::default(),
    };
    harness.event(Event::PointerMoved(from));
    harness.step();
    harness.event(press(from, true));
    harness.step();
    for step in 1..=20 {
        harness.event(Event::PointerMoved(
            from + egui::vec2(8.0, 5.0) * step as f32,
        ));
        harness.step();
        assert!(
            harness.state().preview_settled(),
            "step {step}: a box dragged over nothing posted a draft"
        );
    }
    harness.event(press(from + egui::vec2(160.0, 100.0), false));
    harness.step();
    assert!(harness.state().preview_settled());
    assert_eq!(harness.state().preview_quality(), Some(Quality::Full));
}

#[test]
fn time_plays_and_starts_again_paused_with_another_graph() {
    let mut harness = editor(&scratch("time"), None);
    harness.get_by_label("▶").click();
    harness.step();
    let started = std::time::Instant::now();
    while started.elapsed() < std::time::Duration::from_millis(400) {
        harness.step();
    }
    let (time, playing) = harness.state().preview_time();
    assert!(playing && time > 0.2, "time plays: {time} s after 0.4 s");
    // Playing repaints every frame: steps, not `run`.
    harness.get_by_label("File").click_accesskit();
    harness.run_steps(3);
    harness
        .get_by_label_contains("Open preset")
        .click_accesskit();
    harness.run_steps(3);
    harness.get_by_label("marble").click_accesskit();
    harness.run_steps(3);
    assert_eq!(harness.state().document().graph.name, "Marble");
    assert_eq!(harness.state().preview_time(), (0.0, false));
}

#[test]
fn a_graph_of_two_thousand_nodes_opens_and_shows_its_material() {
    let mut harness = chain_editor(&scratch("big"), 2000, 1620.0);
    // The software rasteriser takes its time over a shader of two thousand nodes.
    settle_previews_within(&mut harness, 300);
    let app = harness.state();
    assert!(app.live().errors.is_empty(), "{:?}", app.live().errors);
    let module = &app.live().compiled.as_ref().expect("it compiles").module;
    assert!(
        module.params.len() > veneer::app::UNIFORM_SLOTS,
        "more parameters than a uniform block holds: {}",
        module.params.len()
    );
    assert_eq!(app.pipelines_built(), 1, "and the preview shows it");
    assert!(app.preview_error().is_none(), "{:?}", app.preview_error());
    assert_eq!(app.document().graph.nodes.len(), 2000);
}
