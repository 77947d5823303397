//! Alt+drag pans the view wherever it starts, and never moves a node.

use super::canvas::{four_nodes, id};
use super::session::{Session, require_tools};

#[test]
fn alt_drag_on_a_node_pans_the_view_and_leaves_the_node_in_a_real_window() {
    require_tools();
    let mut session = Session::start("alt_drag_on_a_node");
    let graph = four_nodes();
    session.step("open four nodes in two rows of two");
    let (file, mut drawn) = session.open_drawn("grid.ron", &graph);
    for (label, by) in [("n0", (90, 60)), ("n3", (-90, -60))] {
        session.step(&format!("Alt+drag from {label}'s title by {by:?} pixels"));
        let from = drawn.title(id(&graph, label));
        session.drag(from, (from.0 + by.0, from.1 + by.1), Some("alt"));
        session.step("save with Ctrl+S");
        let saved = session.save(&file);
        let moved: Vec<String> = graph
            .nodes
            .iter()
            .filter_map(|node| {
                let now = saved.node(node.id)?.position;
                (now != node.position)
                    .then(|| format!("{} from {:?} to {now:?}", node.label, node.position))
            })
            .collect();
        if !moved.is_empty() {
            session.fail(&format!(
                "an Alt+drag that started on {label}'s title moved {}: Alt+drag pans the view \
                 and must never move a node",
                moved.join(", ")
            ));
        }
        session.step("the view panned by the drag");
        let before = drawn.rect(id(&graph, "n1"));
        drawn = session.drawn(&graph);
        let after = drawn.rect(id(&graph, "n1"));
        let panned = (after.x0 - before.x0, after.y0 - before.y0);
        if (panned.0 - by.0).abs() > 3 || (panned.1 - by.1).abs() > 3 {
            session.fail(&format!(
                "an Alt+drag by {by:?} pixels moved the view by {panned:?}: it must pan with \
                 the pointer"
            ));
        }
    }
    session.close_editor();
    session.finish();
}
