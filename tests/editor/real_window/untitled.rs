//! An untitled graph with changes: Ctrl+N asks, Save asks for a path, and once the
//! file is written the editor goes on to the new graph.

use super::canvas::grid;
use super::session::{STEP, Session, require_tools};
use super::shot::{diff, free_spots, full};
use std::time::Duration;
use veneer::graph::NodeKind;

/// The title of the graph Ctrl+N starts.
const NEW: &str = "Untitled — Veneer";

/// How long the unsaved-changes prompt waits before its Save and Discard buttons
/// respond (`ARM_SECONDS` in `src/app/dialogs.rs`, 0.6 s), and a little more.
const ARMED: Duration = Duration::from_millis(900);

#[test]
fn ctrl_n_on_an_edited_untitled_graph_saves_it_and_starts_a_new_one_in_a_real_window() {
    require_tools();
    let mut session = Session::start("untitled_ctrl_n");
    let graph = grid(1, &[NodeKind::Position]);
    session.step("open a graph, then Ctrl+N: a new untitled graph");
    session.open_drawn("start.ron", &graph);
    session.key("ctrl+n");
    session.expect_title(NEW);
    for round in 1..=2 {
        session.step("edit it: add a Noise node");
        let shot = session.zoom_out((12, 40), 2);
        let Some((at, _)) = free_spots(&shot) else {
            session.fail("no empty canvas for a node");
        };
        session.add_node_at_once(at, "noise");
        session.expect_title(&format!("* {NEW}"));

        session.step("Ctrl+N: the unsaved-changes prompt");
        let before = session.shot();
        session.key("ctrl+n");
        session.expect_dialog(&before, "the unsaved-changes prompt");
        std::thread::sleep(ARMED);
        // Tab goes to the first button, Save, whether Cancel or nothing has the focus
        // (from the last button it wraps round).
        session.key("Tab");
        let asking = session.settled(full(&before));

        session.step("Save: the Save as dialog");
        session.key("Return");
        let whole = full(&asking);
        session.wait_for("the Save as dialog in place of the prompt", STEP, |s| {
            (diff(&asking, &s.shot(), whole, true).0 > 200).then_some(())
        });
        session.settled(whole);

        session.step("type a path and Enter: the file is written");
        let saved = session.dir.join(format!("untitled {round}.ron"));
        session.type_text(&saved.display().to_string());
        session.key("Return");
        let written = session.wait_for("the file written", STEP, |_| {
            veneer::graph::load(&saved).ok()
        });
        let titles: Vec<&str> = written.nodes.iter().map(|n| n.kind.title()).collect();
        if titles != ["Material", "Noise"] {
            session.fail(&format!(
                "{} holds {titles:?}, not the untitled graph's Material and Noise",
                saved.display()
            ));
        }

        session.step("the editor goes on to the new graph");
        let what = format!("the window title '{NEW}'");
        if session
            .try_wait_for(&what, STEP, |s| (s.title() == NEW).then_some(()))
            .is_none()
        {
            let title = session.title();
            session.fail(&format!(
                "Ctrl+N → Save → a path → Enter wrote {} but the window stayed on it \
                 ('{title}'), not the new graph ('{NEW}'): once the file is written, the \
                 editor must go on to what Ctrl+N asked for",
                saved.display()
            ));
        }
    }
    session.close_editor();
    session.finish();
}
