//! Laying out nodes that sit one on top of another (a generated graph with no
//! positions, or ten thousand nodes at one point, whose stacked geometry egui cannot
//! draw in one frame).

use super::arrange::{BAND_GAP, arrange_nodes};
use super::footprint::bounds;
use crate::graph::{Graph, Node, Wire};

/// How wide and tall a band of nodes laid out by [`unstack`] may grow before it wraps,
/// in canvas units: about a screen at the editor's default zoom.
pub const UNSTACKED_BAND: (f32, f32) = (1620.0, 1000.0);

/// Lays out the nodes that sit exactly where an earlier node sits, which the editor
/// would draw one on top of the other. When most nodes are stacked the whole level is
/// arranged; otherwise only the stacked ones are, in a band below the rest, which keeps
/// its layout. Returns how many nodes were stacked (0: nothing moved).
pub fn unstack(nodes: &mut [Node], wires: &[Wire]) -> usize {
    let mut taken = std::collections::HashSet::new();
    let stacked: Vec<usize> = (0..nodes.len())
        .filter(|&k| {
            let (x, y) = nodes[k].position;
            !taken.insert((x.to_bits(), y.to_bits()))
        })
        .collect();
    let (width, height) = UNSTACKED_BAND;
    if stacked.len() * 2 >= nodes.len() {
        arrange_nodes(nodes, wires, width, height);
        return stacked.len();
    }
    let drawn = bounds(nodes, wires);
    let rest = (0..nodes.len()).filter(|k| stacked.binary_search(k).is_err());
    let rest_bottom = rest.map(|k| drawn[k].max.1).fold(f32::MIN, f32::max);
    let left = drawn.iter().map(|b| b.min.0).fold(f32::MAX, f32::min);
    let mut moved: Vec<Node> = stacked.iter().map(|&k| nodes[k].clone()).collect();
    arrange_nodes(&mut moved, wires, width, height);
    // Laid out with its first node's frame at the origin: moved to below the rest.
    let corner = bounds(&moved, wires)
        .iter()
        .fold((f32::MAX, f32::MAX), |(x, y), b| {
            (x.min(b.min.0), y.min(b.min.1))
        });
    let shift = (
        (left - corner.0).round(),
        (rest_bottom + BAND_GAP - corner.1).ceil(),
    );
    for (&k, node) in stacked.iter().zip(moved) {
        let (x, y) = node.position;
        nodes[k].position = (x + shift.0, y + shift.1);
    }
    stacked.len()
}

/// [`unstack`] on the graph's own nodes and inside each group it defines that is not
/// linked to the library (a linked group's copy stays as the library has it). Returns
/// how many nodes were stacked in all.
pub fn unstack_levels(graph: &mut Graph) -> usize {
    let inside: usize = graph
        .groups
        .values_mut()
        .filter(|group| !group.linked)
        .map(|group| unstack(&mut group.nodes, &group.wires))
        .sum();
    inside + unstack(&mut graph.nodes, &graph.wires)
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::graph::layout::footprint::overlapping;
    use crate::graph::{NodeKind, PinRef};

    /// A chain of `count` nodes (a position, then transforms), all at the origin.
    pub(in crate::graph::layout) fn stacked_chain(count: usize) -> Graph {
        let mut graph = Graph::default();
        let mut previous = graph.add("p", NodeKind::Position);
        let mut output = "position";
        for k in 1..count {
            let next = graph.add(&format!("t{k}"), NodeKind::Transform);
            graph.wires.push(Wire {
                from: PinRef::new(previous, output),
                to: PinRef::new(next, "p"),
            });
            (previous, output) = (next, "p");
        }
        graph
    }

    #[test]
    fn a_level_stacked_at_one_point_is_laid_out_without_overlaps() {
        let mut graph = stacked_chain(300);
        assert_eq!(unstack(&mut graph.nodes, &graph.wires), 299);
        assert_eq!(overlapping(&graph.nodes, &graph.wires), None);
        // Wrapped into bands about a screen wide, not one row 300 columns long.
        let right = graph.nodes.iter().map(|n| n.position.0).fold(0.0, f32::max);
        assert!(right < 2.0 * UNSTACKED_BAND.0, "{right}");
        // Laid out once, nothing is stacked any more.
        assert_eq!(unstack(&mut graph.nodes, &graph.wires), 0);
    }

    #[test]
    fn a_few_stacked_nodes_move_below_the_rest_which_keeps_its_layout() {
        let mut graph = stacked_chain(12);
        crate::graph::layout::arrange(&mut graph);
        let laid_out = graph.clone();
        let bottom = bounds(&graph.nodes, &graph.wires)
            .iter()
            .map(|b| b.max.1)
            .fold(0.0, f32::max);
        for k in [9, 10, 11] {
            graph.nodes[k].position = graph.nodes[2].position;
        }
        assert_eq!(unstack(&mut graph.nodes, &graph.wires), 3);
        for (node, before) in graph.nodes.iter().zip(&laid_out.nodes).take(9) {
            assert_eq!(node.position, before.position, "node {} moved", node.id);
        }
        let moved = bounds(&graph.nodes, &graph.wires);
        for drawn in &moved[9..] {
            assert!(drawn.min.1 > bottom, "{drawn:?} not below {bottom}");
        }
        assert_eq!(overlapping(&graph.nodes, &graph.wires), None);
    }

    #[test]
    fn no_shipped_preset_opens_with_stacked_nodes() {
        for (name, _) in crate::graph::PRESETS {
            let mut graph = crate::graph::preset(name).unwrap();
            assert_eq!(unstack_levels(&mut graph), 0, "{name}");
        }
    }
}
