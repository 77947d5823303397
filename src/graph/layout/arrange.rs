//! Automatic layout: nodes in columns by how far they are from the graph's inputs, each
//! column stacked top to bottom in its previous order and as wide as its widest node, so
//! wires run left to right; long chains wrap into bands of columns, one below the other.

use super::footprint::footprints;
use crate::graph::{Graph, Node, NodeId, Wire};
use std::collections::BTreeMap;

/// Horizontal space between columns, in canvas units.
pub(super) const COLUMN_GAP: f32 = 40.0;
/// Vertical space between nodes of a column.
pub(super) const GAP: f32 = 24.0;
/// Space between bands of columns laid out by [`arrange_in_rows`].
pub(super) const BAND_GAP: f32 = 50.0;

/// Places every node of `graph` in columns by depth (the longest chain of wires before it).
pub fn arrange(graph: &mut Graph) {
    arrange_in_rows(graph, f32::INFINITY, f32::INFINITY);
}

/// Places the nodes in columns by depth as [`arrange`] does, a column taller than
/// `height` canvas units continuing in the next one, and the columns wrapped into bands
/// (rows) no wider than `width`, each band below the one before, so that a long chain
/// or a wide graph fits a screen (at least one node a column, one column a band).
pub fn arrange_in_rows(graph: &mut Graph, width: f32, height: f32) {
    arrange_nodes(&mut graph.nodes, &graph.wires, width, height);
}

/// Lays out the inside of every group `graph` defines as [`arrange_in_rows`] does; the
/// editor puts the group's input and output nodes left and right of it.
pub fn arrange_groups(graph: &mut Graph, width: f32, height: f32) {
    for group in graph.groups.values_mut() {
        arrange_nodes(&mut group.nodes, &group.wires, width, height);
    }
}

/// [`arrange_in_rows`] for `nodes` joined by `wires` (wires to other nodes, such as a
/// group's boundary, are left out). No two nodes' footprints intersect afterwards.
pub fn arrange_nodes(nodes: &mut [Node], wires: &[Wire], width: f32, height: f32) {
    let sizes = footprints(nodes, wires);
    let depth = depths(nodes, wires);
    let mut by_depth: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (index, depth) in depth.into_iter().enumerate() {
        by_depth.entry(depth).or_default().push(index);
    }
    // Each depth's nodes top to bottom in their previous order, cut into columns.
    let mut columns: Vec<Vec<(usize, f32)>> = Vec::new();
    for mut members in by_depth.into_values() {
        members.sort_by(|a, b| nodes[*a].position.1.total_cmp(&nodes[*b].position.1));
        let mut column: Vec<(usize, f32)> = Vec::new();
        let mut y = 0.0;
        for index in members {
            let tall = sizes[index].height;
            if !column.is_empty() && y + tall > height {
                columns.push(std::mem::take(&mut column));
                y = 0.0;
            }
            column.push((index, y));
            y += tall + GAP;
        }
        columns.push(column);
    }
    let (mut band_top, mut band_height, mut x) = (0.0_f32, 0.0_f32, 0.0_f32);
    for column in columns {
        let column_width = column
            .iter()
            .map(|(index, _)| sizes[*index].width)
            .fold(0.0, f32::max);
        if x > 0.0 && x + column_width > width {
            band_top += band_height + BAND_GAP;
            band_height = 0.0;
            x = 0.0;
        }
        for (index, y) in column {
            nodes[index].position = (x, band_top + y);
            band_height = band_height.max(y + sizes[index].height);
        }
        x += column_width + COLUMN_GAP;
    }
}

/// Each node's depth, in the order of `nodes`: the longest chain of wires before it, in
/// one pass over the nodes in wire order (Kahn's algorithm), so a long chain listed
/// backwards costs no more than one listed forwards. Nodes on a cycle keep the depth
/// their other inputs give them.
pub(super) fn depths(nodes: &[Node], wires: &[Wire]) -> Vec<usize> {
    let index: std::collections::HashMap<NodeId, usize> = nodes
        .iter()
        .enumerate()
        .map(|(k, node)| (node.id, k))
        .collect();
    let mut outgoing: Vec<Vec<usize>> = vec![Vec::new(); nodes.len()];
    let mut waiting = vec![0usize; nodes.len()];
    for wire in wires {
        if let (Some(&from), Some(&to)) = (index.get(&wire.from.node), index.get(&wire.to.node)) {
            outgoing[from].push(to);
            waiting[to] += 1;
        }
    }
    let mut depth = vec![0usize; nodes.len()];
    let mut ready: Vec<usize> = (0..nodes.len()).filter(|&k| waiting[k] == 0).collect();
    while let Some(from) = ready.pop() {
        for &to in &outgoing[from] {
            depth[to] = depth[to].max(depth[from] + 1);
            waiting[to] -= 1;
            if waiting[to] == 0 {
                ready.push(to);
            }
        }
    }
    depth
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::graph::layout::footprint::bounds;
    use crate::graph::layout::footprint::overlapping;
    use crate::graph::{Basis, NodeKind};

    /// Node `id`'s rectangle as drawn: (left, top, right, bottom).
    fn extent(graph: &Graph, id: NodeId) -> (f32, f32, f32, f32) {
        let drawn = bounds(&graph.nodes, &graph.wires);
        let index = graph.nodes.iter().position(|n| n.id == id).unwrap();
        let b = drawn[index];
        (b.min.0, b.min.1, b.max.0, b.max.1)
    }

    #[test]
    fn wires_run_left_to_right_and_columns_do_not_overlap() {
        let mut graph = Graph::default();
        let a = graph.add("a", NodeKind::Position);
        let b = graph.add("b", NodeKind::Transform);
        let noise = crate::nodes::Noise {
            basis: Basis::Gradient,
            period: 0,
        };
        let c = graph.add("c", NodeKind::Noise(noise));
        let d = graph.add("d", NodeKind::Material);
        graph.connect(a, "position", b, "p");
        graph.connect(b, "p", c, "p");
        graph.connect(c, "value", d, "albedo");
        graph.connect(a, "position", d, "bump");
        arrange(&mut graph);
        // The longest chain decides the column: d comes after c, not after a.
        let chain = [a, b, c, d];
        for pair in chain.windows(2) {
            let (left, right) = (extent(&graph, pair[0]), extent(&graph, pair[1]));
            assert!(left.2 + COLUMN_GAP <= right.0, "{left:?} then {right:?}");
        }
    }

    #[test]
    fn depths_do_not_depend_on_the_order_wires_are_listed_in() {
        let mut graph = crate::graph::layout::unstack::tests::stacked_chain(50);
        let forward = depths(&graph.nodes, &graph.wires);
        graph.wires.reverse();
        assert_eq!(depths(&graph.nodes, &graph.wires), forward);
        assert_eq!(forward[49], 49);
    }

    #[test]
    fn rows_wrap_columns_into_bands_below_each_other() {
        let mut graph = Graph::default();
        let mut previous = graph.add("start", NodeKind::Position);
        let mut chain = vec![previous];
        for step in 0..6 {
            let next = graph.add(&format!("step {step}"), NodeKind::Transform);
            let output = if step == 0 { "position" } else { "p" };
            graph.connect(previous, output, next, "p");
            chain.push(next);
            previous = next;
        }
        let width = 700.0;
        arrange_in_rows(&mut graph, width, f32::INFINITY);
        let left = extent(&graph, chain[0]).0;
        let mut tops = Vec::new();
        for pair in chain.windows(2) {
            let (before, after) = (extent(&graph, pair[0]), extent(&graph, pair[1]));
            assert!(
                after.0 == left || after.2 <= left + width,
                "{after:?} past {width}"
            );
            if after.1 == before.1 {
                assert!(before.2 < after.0, "left to right within a band");
            } else {
                assert!(after.1 > before.3 && after.0 == left, "the next band below");
                tops.push(after.1);
            }
        }
        assert!(
            tops.len() >= 2,
            "a 7-node chain wraps more than once: {tops:?}"
        );
        let mut unwrapped = graph.clone();
        arrange(&mut unwrapped);
        let top = |id| unwrapped.node(id).unwrap().position.1;
        assert!(
            chain.iter().all(|id| top(*id) == 0.0),
            "arrange keeps one band"
        );
    }

    #[test]
    fn a_column_taller_than_the_height_goes_on_in_the_next() {
        let mut graph = Graph::default();
        let material = graph.add("material", NodeKind::Material);
        let sources: Vec<NodeId> = (0..6)
            .map(|k| graph.add(&format!("value {k}"), NodeKind::Position))
            .collect();
        for (source, pin) in sources.iter().zip(["albedo", "alpha", "specular"]) {
            graph.connect(*source, "position", material, pin);
        }
        let tall = footprints(&graph.nodes, &graph.wires)[1].height + GAP;
        arrange_in_rows(&mut graph, f32::INFINITY, 2.5 * tall);
        let at = |id| graph.node(id).unwrap().position;
        let xs: Vec<f32> = sources.iter().map(|id| at(*id).0).collect();
        assert!(xs[0] == xs[1] && xs[1] < xs[2], "{xs:?}");
        assert!(xs[2] == xs[3] && xs[3] < xs[4] && xs[4] == xs[5], "{xs:?}");
        assert_eq!(at(sources[2]).1, 0.0, "the next column starts at the top");
        assert!(at(material).0 > xs[5], "the next depth after them");
    }

    #[test]
    fn the_inside_of_a_group_is_laid_out_left_to_right_without_overlaps() {
        let mut graph = crate::graph::preset("wood").unwrap();
        arrange_groups(&mut graph, 1620.0, 1000.0);
        let group = &graph.groups["ring_wood"];
        let inside = Graph {
            nodes: group.nodes.clone(),
            wires: group.wires.clone(),
            ..Graph::default()
        };
        assert_eq!(overlapping(&inside.nodes, &inside.wires), None);
        let boundary = crate::graph::group::BOUNDARY;
        let inner = inside
            .wires
            .iter()
            .filter(|wire| wire.from.node != boundary && wire.to.node != boundary);
        for wire in inner {
            let (from, to) = (
                extent(&inside, wire.from.node),
                extent(&inside, wire.to.node),
            );
            // Left to right, or on to a band below.
            let onwards = from.2 < to.0 || to.1 > from.3;
            assert!(onwards, "a wire runs backwards: {wire:?}");
        }
    }
}
