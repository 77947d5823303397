//! Where new nodes go: added, pasted and duplicated nodes are moved, together, to the
//! nearest place where none of them lies on a node already there (by the nodes'
//! footprints, `crate::graph::layout`'s, which are never smaller than what is drawn).

use crate::app::canvas::snarl_model::graph_from_snarl;
use crate::graph::layout::{Taken, bounds};
use crate::graph::{Graph, Node};
use egui::vec2;
use egui_snarl::{NodeId, Snarl};

/// Moves the nodes `placed` of `snarl` together (their layout kept) by the shortest
/// move after which none of them is near another node of the level.
pub fn clear_of(snarl: &mut Snarl<Node>, placed: &[NodeId]) {
    let ids: Vec<crate::graph::NodeId> = placed
        .iter()
        .filter_map(|id| Some(snarl.get_node(*id)?.id))
        .collect();
    let level = graph_from_snarl(snarl, &Graph::default());
    let (new, old): (Vec<Node>, Vec<Node>) = level
        .nodes
        .into_iter()
        .partition(|node| ids.contains(&node.id));
    let (dx, dy) = Taken::of(&old, &level.wires).clear_move(&bounds(&new, &level.wires));
    for id in placed {
        if let Some(info) = snarl.get_node_info_mut(*id) {
            info.pos += vec2(dx, dy);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::app::canvas::snarl_model::snarl_from_graph;
    use crate::graph::NodeKind;

    fn at(snarl: &Snarl<Node>, id: NodeId) -> egui::Pos2 {
        snarl.get_node_info(id).expect("a node").pos
    }

    #[test]
    fn nodes_put_on_others_move_together_to_the_nearest_free_place() {
        let graph = crate::app::preset("marble").expect("the marble preset");
        let mut snarl = snarl_from_graph(&graph);
        let first = snarl.node_ids().next().expect("a node").0;
        let on_it = snarl.get_node_info(first).unwrap().pos + vec2(10.0, 10.0);
        let node = |id| Node::new(crate::graph::NodeId(id), NodeKind::Material);
        let a = snarl.insert_node(on_it, node(900));
        let b = snarl.insert_node(on_it + vec2(0.0, 400.0), node(901));
        clear_of(&mut snarl, &[a, b]);
        assert_eq!(
            at(&snarl, b) - at(&snarl, a),
            vec2(0.0, 400.0),
            "their layout is kept"
        );
        let level = graph_from_snarl(&snarl, &Graph::default());
        assert_eq!(
            crate::graph::layout::overlapping(&level.nodes, &level.wires),
            None
        );
        assert!((at(&snarl, a) - on_it).length() < 1000.0, "moved far");
        // A place already free is kept.
        let free = at(&snarl, a);
        clear_of(&mut snarl, &[a, b]);
        assert_eq!(at(&snarl, a), free);
    }
}
