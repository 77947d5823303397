//! Automatic layout: nodes in columns by how far they are from the graph's inputs, each
//! column stacked top to bottom in its previous order, so wires run left to right.

use super::{Graph, NodeId};
use std::collections::BTreeMap;

/// Horizontal distance between columns, in canvas units.
const COLUMN: f32 = 320.0;
/// Height of a node's title, and of each pin row.
const TITLE: f32 = 40.0;
const ROW: f32 = 26.0;
const GAP: f32 = 30.0;

/// Places every node of `graph` in columns by depth (the longest chain of wires before it).
pub fn arrange(graph: &mut Graph) {
    let mut depth: BTreeMap<NodeId, usize> = graph.nodes.iter().map(|node| (node.id, 0)).collect();
    // Longest-path relaxation; a cycle cannot raise a depth past the node count.
    for _ in 0..graph.nodes.len() {
        let mut changed = false;
        for wire in &graph.wires {
            let (Some(&from), Some(&to)) = (depth.get(&wire.from.node), depth.get(&wire.to.node))
            else {
                continue;
            };
            if to < from + 1 && from + 1 <= graph.nodes.len() {
                depth.insert(wire.to.node, from + 1);
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    let mut columns: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (index, node) in graph.nodes.iter().enumerate() {
        columns.entry(depth[&node.id]).or_default().push(index);
    }
    for (column, mut members) in columns {
        members.sort_by(|a, b| {
            graph.nodes[*a]
                .position
                .1
                .total_cmp(&graph.nodes[*b].position.1)
        });
        let mut y = 0.0;
        for index in members {
            let node = &mut graph.nodes[index];
            let signature = node.kind.signature();
            node.position = (column as f32 * COLUMN, y);
            y += TITLE + ROW * signature.inputs.len().max(signature.outputs.len()) as f32 + GAP;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::graph::NodeKind;
    use crate::nodes::Noise;

    #[test]
    fn wires_run_left_to_right_and_columns_do_not_overlap() {
        let mut graph = Graph::default();
        let a = graph.add("a", NodeKind::Position);
        let b = graph.add("b", NodeKind::Transform);
        let c = graph.add(
            "c",
            NodeKind::Noise(Noise {
                basis: crate::graph::Basis::Gradient,
            }),
        );
        let d = graph.add("d", NodeKind::Material);
        graph.connect(a, "position", b, "p");
        graph.connect(b, "p", c, "p");
        graph.connect(c, "value", d, "albedo");
        graph.connect(a, "position", d, "bump");
        arrange(&mut graph);
        let x = |id| graph.node(id).unwrap().position.0;
        assert!(x(a) < x(b) && x(b) < x(c) && x(c) < x(d));
        assert_eq!(x(d), 3.0 * COLUMN, "the longest chain decides the column");
    }
}
