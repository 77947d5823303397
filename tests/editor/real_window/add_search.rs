//! A right click on empty canvas opens the add-node search at the mouse, and the
//! letters typed next go into it: none of them is a shortcut (T toggles thumbnails).

use super::canvas::grid;
use super::gestures::Opener;
use super::session::{Session, require_tools};
use super::shot::{diff, free_spots};
use veneer::graph::NodeKind;

#[test]
fn a_right_click_opens_the_search_and_typing_goes_into_it_in_a_real_window() {
    require_tools();
    let mut session = Session::start("right_click_search");
    let mut graph = grid(2, &[NodeKind::Position, NodeKind::Invert]);
    session.step("open two nodes with thumbnails, and make room beside them");
    let (file, _) = session.open_drawn("grid.ron", &graph);
    let shot = session.zoom_out((12, 40), 1);
    let drawn = session.drawn(&graph);
    let Some((first, second)) = free_spots(&shot) else {
        session.fail("no empty canvas for two nodes");
    };
    for at in [first, second] {
        session.step(&format!(
            "right-click empty canvas at {at:?}, type 'transform' (T toggles thumbnails), Enter"
        ));
        let before = session.shot();
        session.add_node_by(Opener::RightClick, at, "transform");
        let after = session.shot();
        for (id, rect) in &drawn.nodes {
            if diff(&before, &after, *rect, false).0 > 0 {
                let label = &graph.node(*id).expect("a node of the graph").label;
                session.fail(&format!(
                    "typing 'transform' into the search changed node {label} (T toggles the \
                     thumbnails): the letters typed into the search must not fire shortcuts"
                ));
            }
        }
        session.step("save with Ctrl+S: one more node, a Transform");
        let saved = session.save(&file);
        let added: Vec<&str> = saved
            .nodes
            .iter()
            .filter(|node| graph.node(node.id).is_none())
            .map(|node| node.kind.title())
            .collect();
        if added != ["Transform"] {
            session.fail(&format!(
                "the saved graph's new nodes are {added:?}, not one Transform"
            ));
        }
        graph = saved;
    }
    session.close_editor();
    session.finish();
}
