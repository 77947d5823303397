//! Copy, paste and duplicate: selected nodes travel as a RON graph fragment, so they can
//! be pasted into another window (or a text editor) and back.

use crate::app::canvas::snarl_model::{graph_from_snarl, insert_graph, next_node_id};
use crate::graph::group::{GroupDef, resolve};
use crate::graph::{Graph, Node, NodeId};
use std::collections::BTreeMap;

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

/// Inserts the nodes of a copied fragment with fresh ids, wires between them kept, moved
/// together (their layout kept) so that their top-left corner is at `at` (the mouse, in
/// graph coordinates). Group nodes get the pins of `groups` (the graph's) by their
/// group's name. Returns the snarl ids of the new nodes (the caller places them clear of
/// the others).
pub fn paste(
    snarl: &mut Snarl<Node>,
    text: &str,
    at: Pos2,
    groups: &BTreeMap<String, GroupDef>,
) -> Result<Vec<egui_snarl::NodeId>, String> {
    let mut fragment = crate::graph::from_ron(text).map_err(|error| error.to_string())?;
    if fragment
        .nodes
        .iter()
        .any(|node| crate::graph::group::group_name(node).is_some())
    {
        fragment.groups = groups.clone();
        resolve(&mut fragment);
    }
    let corner = fragment
        .nodes
        .iter()
        .map(|node| Pos2::new(node.position.0, node.position.1))
        .reduce(|a, b| a.min(b))
        .unwrap_or(at);
    let shift = at - corner;
    let placed = insert_graph(snarl, &fragment, |snarl, node| {
        let mut copy = node.clone();
        copy.id = next_node_id(snarl);
        (copy, Pos2::new(node.position.0, node.position.1) + shift)
    });
    Ok(placed.into_values().collect())
}

/// Copies and pastes the selection in one step, at `at` as `paste` places them.
pub fn duplicate(
    snarl: &mut Snarl<Node>,
    selection: &[egui_snarl::NodeId],
    at: Pos2,
    groups: &BTreeMap<String, GroupDef>,
) -> Vec<egui_snarl::NodeId> {
    if selection.is_empty() {
        return Vec::new();
    }
    let text = copy(snarl, selection);
    paste(snarl, &text, at, groups).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::app::canvas::snarl_model::snarl_from_graph;

    #[test]
    fn copied_nodes_paste_with_new_ids_and_their_wires() {
        // (A preset without groups: three plain nodes to copy.)
        let graph = crate::app::preset("wood_classic").unwrap();
        let mut snarl = snarl_from_graph(&graph);
        let selection: Vec<_> = snarl.node_ids().map(|(id, _)| id).take(3).collect();
        let text = copy(&snarl, &selection);
        let at = Pos2::new(-500.0, 900.0);
        let pasted = paste(&mut snarl, &text, at, &BTreeMap::new()).expect("a fragment");
        assert_eq!(pasted.len(), 3);
        let positions: Vec<Pos2> = pasted
            .iter()
            .map(|id| snarl.get_node_info(*id).unwrap().pos)
            .collect();
        let corner = positions.iter().copied().reduce(Pos2::min).unwrap();
        assert_eq!(
            corner, at,
            "the pasted nodes' top-left corner is at the mouse"
        );
        let originals: Vec<Pos2> = selection
            .iter()
            .map(|id| snarl.get_node_info(*id).unwrap().pos)
            .collect();
        let original_corner = originals.iter().copied().reduce(Pos2::min).unwrap();
        let layout = |points: &[Pos2], corner: Pos2| {
            let mut offsets: Vec<(i32, i32)> = points
                .iter()
                .map(|p| ((p.x - corner.x) as i32, (p.y - corner.y) as i32))
                .collect();
            offsets.sort();
            offsets
        };
        assert_eq!(
            layout(&positions, corner),
            layout(&originals, original_corner),
            "the copies keep their layout"
        );
        let pasted = graph_from_snarl(&snarl, &graph);
        assert_eq!(pasted.nodes.len(), graph.nodes.len() + 3);
        assert_eq!(
            pasted.wires.len(),
            graph.wires.len() + 1,
            "the one wire among the copied nodes comes along"
        );
        assert!(paste(&mut snarl, "not ron", at, &BTreeMap::new()).is_err());
    }

    #[test]
    fn a_duplicate_at_its_originals_is_placed_beside_them_and_selected() {
        let graph = crate::app::preset("marble").unwrap();
        let mut canvas = crate::app::canvas::Canvas::new(snarl_from_graph(&graph));
        let (node, _) = canvas.snarl.node_ids().next().unwrap();
        let original = canvas.snarl.get_node_info(node).unwrap().pos;
        for _ in 0..2 {
            let at = original + egui::vec2(5.0, 5.0);
            let copies = duplicate(&mut canvas.snarl, &[node], at, &graph.groups);
            canvas.placed(copies.clone());
            assert_eq!(*canvas.selection, copies);
            let copy = canvas.snarl.get_node_info(copies[0]).unwrap().pos;
            let others = canvas
                .snarl
                .nodes_pos_ids()
                .filter(|(id, ..)| *id != copies[0]);
            for (_, pos, _) in others {
                assert!((copy - pos).length() >= 40.0, "{copy:?} on {pos:?}");
            }
        }
    }
}
