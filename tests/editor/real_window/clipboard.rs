//! Pasted and duplicated nodes land clear of the nodes already there, and become the
//! selection: Delete right after takes the new node away, not the one copied.

use super::canvas::{Drawn, four_nodes, id};
use super::session::{Session, require_tools};
use veneer::graph::Graph;

/// How the node is copied: the keys, and what the user calls it.
const WAYS: [(&[&str], &str); 2] = [
    (&["ctrl+c", "ctrl+v"], "pasted"),
    (&["ctrl+d"], "duplicated"),
];

#[test]
fn pasted_and_duplicated_nodes_land_clear_and_are_selected_in_a_real_window() {
    require_tools();
    let mut session = Session::start("paste_and_duplicate");
    let graph = four_nodes();
    session.step("open four nodes in two rows of two");
    let (file, mut drawn) = session.open_drawn("grid.ron", &graph);
    for label in ["n0", "n3"] {
        for (keys, done) in WAYS {
            session.step(&format!("click {label}'s title, then {}", keys.join(", ")));
            session.click(drawn.title(id(&graph, label)), "1");
            for key in keys {
                session.key(key);
            }
            session.expect_edited(&format!(
                "{} with {label} selected added nothing",
                keys.join(", ")
            ));
            session.step("save with Ctrl+S: the new node clear of the others");
            let saved = session.save(&file);
            check_clear(&mut session, &graph, &drawn, &saved, label, done);
            session.step("press Delete: the new node goes");
            session.key("Delete");
            session.expect_edited(&format!(
                "Delete right after a node was {done} from {label} deleted nothing: the {done} \
                 node must become the selection"
            ));
            let saved = session.save(&file);
            let ids = |graph: &Graph| graph.nodes.iter().map(|node| node.id).collect::<Vec<_>>();
            if ids(&saved) != ids(&graph) {
                let gone: Vec<&str> = graph
                    .nodes
                    .iter()
                    .filter(|node| saved.node(node.id).is_none())
                    .map(|node| node.label.as_str())
                    .collect();
                session.fail(&format!(
                    "Delete right after a node was {done} from {label} deleted {gone:?} and \
                     left the {done} node: the {done} node must become the selection"
                ));
            }
            drawn = session.drawn(&graph);
        }
    }
    session.close_editor();
    session.finish();
}

/// Fails unless `saved` is `graph` and one more node, a copy of `label`, whose
/// rectangle (at the size `label` is drawn) meets no other node's.
fn check_clear(
    session: &mut Session,
    graph: &Graph,
    drawn: &Drawn,
    saved: &Graph,
    label: &str,
    done: &str,
) {
    let original = graph.node(id(graph, label)).expect("the copied node");
    let added: Vec<_> = saved
        .nodes
        .iter()
        .filter(|node| graph.node(node.id).is_none())
        .collect();
    let [copy] = added.as_slice() else {
        session.fail(&format!(
            "the saved graph has {} new nodes, not one {done} from {label}",
            added.len()
        ));
    };
    if copy.kind != original.kind {
        session.fail(&format!(
            "the {done} node is a {}, not a {} as {label} is",
            copy.kind.title(),
            original.kind.title()
        ));
    }
    let rect = |position: (f32, f32), size: (f32, f32)| {
        (
            position.0,
            position.1,
            position.0 + size.0,
            position.1 + size.1,
        )
    };
    let new = rect(copy.position, drawn.size(original.id));
    let under: Vec<String> = graph
        .nodes
        .iter()
        .filter(|node| {
            let other = rect(node.position, drawn.size(node.id));
            new.0 < other.2 && other.0 < new.2 && new.1 < other.3 && other.1 < new.3
        })
        .map(|node| format!("{} at {:?}", node.label, node.position))
        .collect();
    if !under.is_empty() {
        session.fail(&format!(
            "the node {done} from {label} landed at {:?}, on top of {}: new nodes must be \
             placed clear of the nodes already there",
            copy.position,
            under.join(" and ")
        ));
    }
}
