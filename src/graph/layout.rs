//! Automatic layout: nodes in columns by how far they are from the graph's inputs, each
//! column stacked top to bottom in its previous order, so wires run left to right; long
//! chains wrap into bands of columns, one below the other.

use super::{Graph, NodeId};
use std::collections::BTreeMap;

/// Horizontal distance between columns, in canvas units.
const COLUMN: f32 = 270.0;
/// Height of a node's title, and of each pin row.
const TITLE: f32 = 32.0;
const ROW: f32 = 20.0;
const GAP: f32 = 24.0;
/// Height of the output thumbnail the editor shows under a node's pins.
const THUMBNAIL: f32 = 80.0;

/// Space between bands of columns laid out by [`arrange_in_rows`].
const BAND_GAP: f32 = 50.0;

/// Places every node of `graph` in columns by depth (the longest chain of wires before it).
pub fn arrange(graph: &mut Graph) {
    arrange_in_rows(graph, f32::INFINITY, f32::INFINITY);
}

/// Places the nodes in columns by depth as [`arrange`] does, a column taller than
/// `height` canvas units continuing in the next one, and the columns wrapped into bands
/// (rows) no wider than `width`, each band below the one before, so that a long chain
/// or a wide graph fits a screen (at least one node a column, one column a band).
pub fn arrange_in_rows(graph: &mut Graph, width: f32, height: f32) {
    let depth = depths(graph);
    let mut by_depth: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (index, node) in graph.nodes.iter().enumerate() {
        by_depth.entry(depth[&node.id]).or_default().push(index);
    }
    // Each depth's nodes top to bottom in their previous order, cut into columns.
    let mut columns: Vec<Vec<(usize, f32)>> = Vec::new();
    for mut members in by_depth.into_values() {
        members.sort_by(|a, b| {
            graph.nodes[*a]
                .position
                .1
                .total_cmp(&graph.nodes[*b].position.1)
        });
        let mut column: Vec<(usize, f32)> = Vec::new();
        let mut y = 0.0;
        for index in members {
            let tall = node_height(&graph.nodes[index]);
            if !column.is_empty() && y + tall > height {
                columns.push(std::mem::take(&mut column));
                y = 0.0;
            }
            column.push((index, y));
            y += tall + GAP;
        }
        columns.push(column);
    }
    let per_band = ((width / COLUMN).floor() as usize).max(1);
    let (mut band_top, mut band_height) = (0.0_f32, 0.0_f32);
    for (slot, column) in columns.into_iter().enumerate() {
        if slot > 0 && slot % per_band == 0 {
            band_top += band_height + BAND_GAP;
            band_height = 0.0;
        }
        let x = (slot % per_band) as f32 * COLUMN;
        for (index, y) in column {
            let node = &mut graph.nodes[index];
            node.position = (x, band_top + y);
            band_height = band_height.max(y + node_height(node));
        }
    }
}

/// How tall the editor draws `node`, roughly: its title, a row per pin and, for nodes
/// with an output, the thumbnail under the pins.
fn node_height(node: &super::Node) -> f32 {
    let signature = node.kind.signature();
    let pins = signature.inputs.len().max(signature.outputs.len()) as f32;
    let footer = if signature.outputs.is_empty() {
        0.0
    } else {
        THUMBNAIL
    };
    TITLE + ROW * pins + footer
}

/// Each node's depth: the longest chain of wires before it.
fn depths(graph: &Graph) -> BTreeMap<NodeId, usize> {
    let mut depth: BTreeMap<NodeId, usize> = graph.nodes.iter().map(|node| (node.id, 0)).collect();
    // Longest-path relaxation; a cycle cannot raise a depth past the node count.
    for _ in 0..graph.nodes.len() {
        let mut changed = false;
        for wire in &graph.wires {
            let (Some(&from), Some(&to)) = (depth.get(&wire.from.node), depth.get(&wire.to.node))
            else {
                continue;
            };
            if to < from + 1 && from < graph.nodes.len() {
                depth.insert(wire.to.node, from + 1);
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    depth
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

    #[test]
    fn rows_wrap_columns_into_bands_below_each_other() {
        let mut graph = Graph::default();
        let mut previous = graph.add("start", NodeKind::Position);
        let mut chain = vec![previous];
        for step in 0..6 {
            let next = graph.add(&format!("step {step}"), NodeKind::Transform);
            graph.connect(
                previous,
                if step == 0 { "position" } else { "p" },
                next,
                "p",
            );
            chain.push(next);
            previous = next;
        }
        arrange_in_rows(&mut graph, 3.0 * COLUMN, f32::INFINITY);
        let at = |id| graph.node(id).unwrap().position;
        let xs: Vec<f32> = chain.iter().map(|id| at(*id).0).collect();
        assert_eq!(
            xs,
            [0.0, COLUMN, 2.0 * COLUMN, 0.0, COLUMN, 2.0 * COLUMN, 0.0]
        );
        let (first, second, third) = (at(chain[0]).1, at(chain[3]).1, at(chain[6]).1);
        assert!(
            first < second && second < third,
            "bands go down: {first} {second} {third}"
        );
        let unwrapped = {
            let mut copy = graph.clone();
            arrange(&mut copy);
            copy.nodes
                .iter()
                .map(|node| node.position.0)
                .fold(0.0, f32::max)
        };
        assert_eq!(unwrapped, 6.0 * COLUMN, "arrange keeps one band");
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
        let tall = node_height(graph.node(sources[0]).unwrap()) + GAP;
        arrange_in_rows(&mut graph, f32::INFINITY, 2.5 * tall);
        let at = |id| graph.node(id).unwrap().position;
        let xs: Vec<f32> = sources.iter().map(|id| at(*id).0).collect();
        assert_eq!(xs, [0.0, 0.0, COLUMN, COLUMN, 2.0 * COLUMN, 2.0 * COLUMN]);
        assert_eq!(at(sources[2]).1, 0.0, "the next column starts at the top");
        assert_eq!(at(material).0, 3.0 * COLUMN, "the next depth after them");
    }
}
