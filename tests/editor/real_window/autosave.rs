//! Autosave on a timer: an edit reaches the recovery file while the window sits still
//! (no input, so no repaint), and SIGTERM leaves the last edit there.

use super::canvas::grid;
use super::session::{Session, require_tools};
use super::shot::free_spots;
use std::time::Duration;
use veneer::graph::{Graph, NodeKind};

/// How long after an edit, the mouse still, the recovery file must hold it: the
/// autosave interval (`AUTOSAVE_SECONDS` in `src/app/recovery.rs`, 5 s) and as long
/// again.
const STILL: Duration = Duration::from_secs(10);

/// The titles of `graph`'s nodes, in its order.
fn titles(graph: &Graph) -> Vec<&'static str> {
    graph.nodes.iter().map(|node| node.kind.title()).collect()
}

#[test]
fn edits_reach_the_recovery_file_with_the_mouse_still_and_after_sigterm_in_a_real_window() {
    require_tools();
    let mut session = Session::start("still_mouse_autosave");
    let graph = grid(2, &[NodeKind::Position, NodeKind::Invert]);
    session.step("open two nodes");
    session.open_drawn("grid.ron", &graph);
    session.step("make room: the wheel zooms out about the pointer");
    let shot = session.zoom_out((12, 40), 2);
    let Some((first, second)) = free_spots(&shot) else {
        session.fail("no empty canvas for two nodes");
    };
    let with = |extra: &[&'static str]| {
        let mut titles = titles(&graph);
        titles.extend(extra);
        titles
    };

    session.step("add a Noise node, then keep the mouse still");
    session.add_node_at_once(first, "noise");
    let noise = with(&["Noise"]);
    expect_recovered(&mut session, &noise, "adding a Noise node");

    // Within the autosave interval of the last write, so that only the timer (or a
    // repaint) can write it.
    session.step("add a Remap node at once, then keep the mouse still");
    session.add_node_at_once(second, "remap");
    expect_recovered(
        &mut session,
        &with(&["Noise", "Remap"]),
        "adding a Remap node",
    );

    session.step("undo with Ctrl+Z, the mouse still");
    session.key("ctrl+z");
    expect_recovered(&mut session, &noise, "undoing the Remap node");

    session.step("SIGTERM: the recovery file keeps the last edit");
    session.close_editor();
    let left = session.recovered();
    if left.as_ref().map(titles) != Some(noise.clone()) {
        session.fail(&format!(
            "after SIGTERM the recovery files {:?} hold {:?}, not {noise:?}",
            session.recovery_files(),
            left.as_ref().map(titles)
        ));
    }
    session.finish();
}

/// Fails unless, within [`STILL`] of `edit` and no input since, the editor's recovery
/// file holds a graph of nodes titled `expected`.
fn expect_recovered(session: &mut Session, expected: &[&str], edit: &str) {
    let what = format!("the recovery file to hold {expected:?}");
    let found = session.try_wait_for(&what, STILL, |s| {
        s.recovered().filter(|saved| titles(saved) == expected)
    });
    if found.is_none() {
        let held = match session.recovered() {
            Some(graph) => format!("the recovery file holds {:?}", titles(&graph)),
            None => format!("the recovery files are {:?}", session.recovery_files()),
        };
        session.fail(&format!(
            "{STILL:?} after {edit}, the mouse still, {held}, not {expected:?}: autosave must \
             write the work on its timer (every AUTOSAVE_SECONDS, 5 s), not only when the \
             window repaints"
        ));
    }
}
