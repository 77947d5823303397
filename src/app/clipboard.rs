//! Copy, paste and duplicate: selected nodes travel as a RON graph fragment, so they can
//! be pasted into another window (or a text editor) and back.

use super::graph_view::{graph_from_snarl, insert_graph, next_node_id};
use crate::graph::{Graph, Node, NodeId};

use egui::Pos2;
use egui_snarl::Snarl;

/// The selected nodes and the wires between them, as RON text.
pub fn copy(snarl: &Snarl<Node>, selection: &[egui_snarl::NodeId]) -> String {
    let ids: Vec<NodeId> = selection
        .iter()
        .filter_map(|id| snarl.get_node(*id))
        .map(|node| node.id)
        .collect();
    let mut fragment = graph_from_snarl(snarl, &Graph::default());
    fragment.nodes.retain(|node| ids.contains(&node.id));
    fragment
        .wires
        .retain(|wire| ids.contains(&wire.from.node) && ids.contains(&wire.to.node));
    crate::graph::to_ron(&fragment)
}

/// Inserts the nodes of a copied fragment with fresh ids, offset so they do not cover
/// the originals, wires between them kept. Returns how many nodes were added.
pub fn paste(snarl: &mut Snarl<Node>, text: &str) -> Result<usize, String> {
    let fragment = crate::graph::from_ron(text).map_err(|error| error.to_string())?;
    let placed = insert_graph(snarl, &fragment, |snarl, node| {
        let mut copy = node.clone();
        copy.id = next_node_id(snarl);
        (
            copy,
            Pos2::new(node.position.0 + 40.0, node.position.1 + 40.0),
        )
    });
    Ok(placed.len())
}

/// Copies and pastes the selection in one step.
pub fn duplicate(snarl: &mut Snarl<Node>, selection: &[egui_snarl::NodeId]) {
    if !selection.is_empty() {
        let text = copy(snarl, selection);
        let _ = paste(snarl, &text);
    }
}

/// A place for a new node: right of everything already there.
pub fn free_position(snarl: &Snarl<Node>) -> Pos2 {
    let right = snarl
        .nodes_pos()
        .map(|(pos, _)| pos.x)
        .fold(0.0f32, f32::max);
    let top = snarl
        .nodes_pos()
        .map(|(pos, _)| pos.y)
        .fold(f32::INFINITY, f32::min);
    Pos2::new(right + 260.0, if top.is_finite() { top } else { 0.0 })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::app::graph_view::snarl_from_graph;

    #[test]
    fn copied_nodes_paste_with_new_ids_and_their_wires() {
        let graph = crate::app::preset("marble").unwrap();
        let mut snarl = snarl_from_graph(&graph);
        let selection: Vec<_> = snarl.node_ids().map(|(id, _)| id).take(3).collect();
        let text = copy(&snarl, &selection);
        assert_eq!(paste(&mut snarl, &text), Ok(3));
        let pasted = graph_from_snarl(&snarl, &graph);
        assert_eq!(pasted.nodes.len(), graph.nodes.len() + 3);
        assert_eq!(
            pasted.wires.len(),
            graph.wires.len() + 1,
            "the one wire among the copied nodes comes along"
        );
        assert!(paste(&mut snarl, "not ron").is_err());
    }
}
