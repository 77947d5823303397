//! *Fit to image…*: the Parameters panel's button opens the file browser; a fit runs on
//! its thread while the window answers and the preview shows the values it tries; it
//! stops when asked; its result is kept in one undo step or discarded. Twice, as a
//! person would.

use crate::support::{
    editor, press, preview_pixels, retype_drag_value, saved_preset, scratch, screen, shows,
};
use egui_kittest::kittest::Queryable;
use veneer::fit::image::Canvas;
use veneer::fit::prepare;
use veneer::graph::Value;
use veneer::graph::parameters::exposed;

/// The marble preset's albedo with red veins (`vein_colour` 0.8, 0.1, 0.1) over its
/// preview square, as a photo.
fn red_veined_marble(path: &std::path::Path) {
    let marble = veneer::graph::preset("marble").expect("the marble preset");
    let names = ["vein_colour".to_string()];
    let prepared = prepare(&marble, Some(&names)).expect("marble fits");
    let canvas = Canvas {
        evaluator: &prepared.evaluator,
        rect: prepared.rect,
        size: 96,
    };
    let image = canvas.render(&prepared.space, &[0.8, 0.1, 0.1]);
    let bytes = (image.pixels.iter())
        .flat_map(|p| p.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8))
        .collect();
    image::RgbImage::from_raw(96, 96, bytes)
        .expect("a square")
        .save(path)
        .expect("the photo is written");
}

/// The marble's exposed parameters' values, by name.
fn values(harness: &crate::add_node::Editor) -> Vec<(String, Value)> {
    let graph = &harness.state().document().graph;
    exposed(graph)
        .into_iter()
        .map(|p| (p.name, p.value))
        .collect()
}

/// Steps the editor until its fit has ended.
fn wait_for_the_fit(harness: &mut crate::add_node::Editor) {
    let started = std::time::Instant::now();
    while harness.state().fitting() == Some(false) {
        assert!(started.elapsed().as_secs() < 180, "the fit never ended");
        std::thread::sleep(std::time::Duration::from_millis(20));
        harness.step();
    }
    harness.step();
}

#[test]
fn fit_to_image_runs_beside_the_editor_and_is_kept_in_one_undo_step_or_discarded() {
    let dir = scratch("fit-to-image");
    let photo = dir.join("red marble.png");
    red_veined_marble(&photo);
    let marble = saved_preset(&dir, "marble");
    let mut harness = editor(&dir, Some(marble));
    let original = values(&harness);
    let before = preview_pixels(&screen(&mut harness));

    // The button opens the file browser on the graph's folder.
    harness.get_by_label("Fit to image…").click();
    harness.run_steps(3);
    assert!(shows(&harness, "Fit to image: choose a photo"));
    press(&mut harness, egui::Key::Escape, false);
    // Its size and starts beside it: one start at 64², as `--starts 1 --size 64` does.
    retype_drag_value(&mut harness, "starts 3", "1");
    retype_drag_value(&mut harness, "128 px", "64");
    assert!(shows(&harness, "starts 1") && shows(&harness, "64 px"));
    // Kept for the next session: an editor opened afterwards offers the same.
    let again = editor(&dir, None);
    assert!(
        shows(&again, "starts 1") && shows(&again, "64 px"),
        "the fit's settings are kept across sessions"
    );
    drop(again);

    for (round, keep) in [(1, false), (2, true)] {
        let ctx = harness.ctx.clone();
        harness.state_mut().fit_to_image(&ctx, photo.clone());
        harness.step();
        assert_eq!(
            harness.state().fitting(),
            Some(false),
            "round {round}: it runs"
        );
        assert!(shows(&harness, "Fit to image"), "round {round}: its window");
        assert!(shows(&harness, "Stop"), "round {round}");
        if !keep {
            // Stopped at once: it ends with the best values found so far.
            harness.get_by_label("Stop").click();
            harness.step();
        }
        wait_for_the_fit(&mut harness);
        assert_eq!(shows(&harness, "stopped at step"), !keep, "round {round}");
        assert!(shows(&harness, "fitted albedo"), "round {round}");
        assert!(shows(&harness, "at 64²"), "round {round}: the size chosen");
        assert!(shows(&harness, "Keep") && shows(&harness, "Discard"));
        // The preview shows the values found (stopped at once: the graph's own, or
        // nearly); the document is not changed yet.
        if keep {
            let shown = preview_pixels(&screen(&mut harness));
            assert!(shown != before, "round {round}: the preview shows the fit");
        }
        assert_eq!(values(&harness), original, "round {round}: not kept yet");
        harness
            .get_by_label(if keep { "Keep" } else { "Discard" })
            .click();
        harness.run_steps(3);
        assert_eq!(harness.state().fitting(), None, "round {round}: closed");
        if !keep {
            assert_eq!(values(&harness), original, "discarded");
            let shown = preview_pixels(&screen(&mut harness));
            assert!(
                shown == before,
                "discarded: the preview shows the graph again"
            );
        }
    }
    // Kept: the veins turned red, and one undo takes every value back.
    let kept = values(&harness);
    let veins = kept.iter().find(|(name, _)| name == "vein_colour");
    let Some((_, Value::Color(r, g, b))) = veins else {
        panic!("{kept:?}")
    };
    assert!(*r > g + 0.3 && *r > b + 0.3, "red veins: {kept:?}");
    press(&mut harness, egui::Key::Z, true);
    assert_eq!(values(&harness), original, "one undo step");
}

/// Where the graph exposes no parameter (only a preset is left, as after its group was
/// deleted), *Fit to image…* is greyed rather than opening a fit that can only fail.
#[test]
fn fit_to_image_is_greyed_where_the_graph_exposes_no_parameter() {
    use egui_kittest::kittest::NodeT;
    let dir = scratch("fit-to-image-nothing-exposed");
    let mut graph = veneer::graph::preset("isolines").expect("the isolines preset");
    graph.parameters.clear();
    graph.presets = [("empty".to_string(), Default::default())].into();
    assert!(exposed(&graph).is_empty(), "no group inputs either");
    let path = dir.join("bare isolines.ron");
    veneer::graph::save(&graph, &path).expect("the graph is written");
    let mut harness = editor(&dir, Some(path));
    harness.run_steps(3);
    let button = harness.get_by_label("Fit to image…");
    assert!(
        button.accesskit_node().is_disabled(),
        "greyed with nothing to fit"
    );
}
