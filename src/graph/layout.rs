//! Automatic layout: nodes in columns by how far they are from the graph's inputs, each
//! column stacked top to bottom in its previous order and as wide as its widest node, so
//! wires run left to right; long chains wrap into bands of columns, one below the other.

use super::{Graph, Node, NodeId, ValueType, Wire};
use std::collections::{BTreeMap, BTreeSet};

/// Horizontal space between columns, in canvas units.
const COLUMN_GAP: f32 = 40.0;
/// Height of a node's title, and of each pin row.
const TITLE: f32 = 32.0;
const ROW: f32 = 20.0;
const GAP: f32 = 24.0;
/// Height of the output thumbnail the editor shows under a node's pins.
const THUMBNAIL: f32 = 80.0;
/// Widths the editor gives, roughly: a character of a title, of a pin label, a pin with
/// its frame margins, one number field, a colour swatch; the narrowest node.
const TITLE_CHAR: f32 = 11.0;
const LABEL_CHAR: f32 = 7.5;
const PIN: f32 = 28.0;
const FIELD: f32 = 48.0;
const SWATCH: f32 = 44.0;
const MIN_WIDTH: f32 = 120.0;

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
/// group's boundary, are left out).
pub fn arrange_nodes(nodes: &mut [Node], wires: &[Wire], width: f32, height: f32) {
    let depth = depths(nodes, wires);
    let wired: BTreeSet<(NodeId, &str)> = wires
        .iter()
        .map(|wire| (wire.to.node, wire.to.pin.as_str()))
        .collect();
    let mut by_depth: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (index, node) in nodes.iter().enumerate() {
        by_depth.entry(depth[&node.id]).or_default().push(index);
    }
    // Each depth's nodes top to bottom in their previous order, cut into columns.
    let mut columns: Vec<Vec<(usize, f32)>> = Vec::new();
    for mut members in by_depth.into_values() {
        members.sort_by(|a, b| nodes[*a].position.1.total_cmp(&nodes[*b].position.1));
        let mut column: Vec<(usize, f32)> = Vec::new();
        let mut y = 0.0;
        for index in members {
            let tall = node_height(&nodes[index]);
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
            .map(|(index, _)| node_width(&nodes[*index], &wired))
            .fold(MIN_WIDTH, f32::max);
        if x > 0.0 && x + column_width > width {
            band_top += band_height + BAND_GAP;
            band_height = 0.0;
            x = 0.0;
        }
        for (index, y) in column {
            let node = &mut nodes[index];
            node.position = (x.round(), (band_top + y).round());
            band_height = band_height.max(y + node_height(node));
        }
        x += (column_width + COLUMN_GAP).round();
    }
}

/// How wide and tall a band of nodes laid out by [`unstack`] may grow before it wraps,
/// in canvas units: about a screen at the editor's default zoom.
const UNSTACKED_BAND: (f32, f32) = (1620.0, 1000.0);

/// Lays out the nodes that sit exactly where an earlier node sits, which the editor
/// would draw one on top of the other (a generated graph with no positions, or ten
/// thousand nodes at one point, whose stacked geometry egui cannot draw in one frame).
/// When most nodes are stacked the whole level is arranged; otherwise only the stacked
/// ones are, in a band below the rest, which keeps its layout. Returns how many nodes
/// were stacked (0: nothing moved).
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
    let rest_bottom = (0..nodes.len())
        .filter(|k| stacked.binary_search(k).is_err())
        .map(|k| nodes[k].position.1 + node_height(&nodes[k]))
        .fold(f32::MIN, f32::max);
    let left = nodes
        .iter()
        .map(|node| node.position.0)
        .fold(f32::MAX, f32::min);
    let mut moved: Vec<Node> = stacked.iter().map(|&k| nodes[k].clone()).collect();
    arrange_nodes(&mut moved, wires, width, height);
    for (&k, node) in stacked.iter().zip(moved) {
        let (x, y) = node.position;
        nodes[k].position = ((left + x).round(), (rest_bottom + BAND_GAP + y).round());
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

/// How tall the editor draws `node`, roughly: its title, a row per pin and, for nodes
/// with an output, the thumbnail under the pins.
fn node_height(node: &Node) -> f32 {
    let signature = node.kind.signature();
    let pins = signature.inputs.len().max(signature.outputs.len()) as f32;
    let footer = if signature.outputs.is_empty() {
        0.0
    } else {
        THUMBNAIL
    };
    TITLE + ROW * pins + footer
}

/// How wide the editor draws `node`, roughly: its title, or its widest input row (pin,
/// label and, unless `wired`, value fields) beside its widest output label.
fn node_width(node: &Node, wired: &BTreeSet<(NodeId, &str)>) -> f32 {
    let signature = node.kind.signature();
    let label = |name: &str| name.chars().count() as f32 * LABEL_CHAR;
    let inputs = signature
        .inputs
        .iter()
        .map(|pin| {
            let fields = if wired.contains(&(node.id, pin.name)) {
                0.0
            } else {
                match pin.ty {
                    ValueType::Color => SWATCH,
                    ty => ty.width() as f32 * FIELD,
                }
            };
            PIN + label(pin.name) + fields
        })
        .fold(0.0, f32::max);
    let outputs = signature
        .outputs
        .iter()
        .map(|pin| PIN + label(pin.name))
        .fold(0.0, f32::max);
    let title = node.display_name().chars().count() as f32 * TITLE_CHAR + 2.0 * PIN;
    title.max(inputs + outputs).max(MIN_WIDTH)
}

/// Each node's depth: the longest chain of wires before it, in one pass over the nodes
/// in wire order (Kahn's algorithm), so a long chain listed backwards costs no more than
/// one listed forwards. Nodes on a cycle keep the depth their other inputs give them.
fn depths(nodes: &[Node], wires: &[Wire]) -> BTreeMap<NodeId, usize> {
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
    nodes
        .iter()
        .zip(depth)
        .map(|(node, d)| (node.id, d))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::graph::NodeKind;
    use crate::nodes::Noise;

    /// Node `id`'s rectangle as the layout reckons it: (left, top, right, bottom).
    fn extent(graph: &Graph, id: NodeId) -> (f32, f32, f32, f32) {
        let node = graph.node(id).unwrap();
        let wired = graph
            .wires
            .iter()
            .map(|wire| (wire.to.node, wire.to.pin.as_str()))
            .collect();
        let (x, y) = node.position;
        (x, y, x + node_width(node, &wired), y + node_height(node))
    }

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
        // The longest chain decides the column: d comes after c, not after a.
        let chain = [a, b, c, d];
        for pair in chain.windows(2) {
            let (left, right) = (extent(&graph, pair[0]), extent(&graph, pair[1]));
            assert!(left.2 + COLUMN_GAP <= right.0, "{left:?} then {right:?}");
        }
    }

    /// A chain of `count` nodes (a position, then transforms), all at the origin.
    fn stacked_chain(count: usize) -> Graph {
        let mut graph = Graph::default();
        let mut previous = graph.add("p", NodeKind::Position);
        let mut output = "position";
        for k in 1..count {
            let next = graph.add(&format!("t{k}"), NodeKind::Transform);
            graph.wires.push(Wire {
                from: crate::graph::PinRef::new(previous, output),
                to: crate::graph::PinRef::new(next, "p"),
            });
            (previous, output) = (next, "p");
        }
        graph
    }

    /// Whether any two nodes' rectangles intersect.
    fn overlapping(graph: &Graph) -> Option<(NodeId, NodeId)> {
        let boxes: Vec<_> = graph
            .nodes
            .iter()
            .map(|n| (n.id, extent(graph, n.id)))
            .collect();
        boxes.iter().enumerate().find_map(|(k, (a, r))| {
            boxes[k + 1..].iter().find_map(|(b, q)| {
                (r.0 < q.2 && q.0 < r.2 && r.1 < q.3 && q.1 < r.3).then_some((*a, *b))
            })
        })
    }

    #[test]
    fn a_level_stacked_at_one_point_is_laid_out_without_overlaps() {
        let mut graph = stacked_chain(300);
        assert_eq!(unstack(&mut graph.nodes, &graph.wires), 299);
        assert_eq!(overlapping(&graph), None);
        // Wrapped into bands about a screen wide, not one row 300 columns long.
        let right = graph.nodes.iter().map(|n| n.position.0).fold(0.0, f32::max);
        assert!(right < 2.0 * UNSTACKED_BAND.0, "{right}");
        // Laid out once, nothing is stacked any more.
        assert_eq!(unstack(&mut graph.nodes, &graph.wires), 0);
    }

    #[test]
    fn a_few_stacked_nodes_move_below_the_rest_which_keeps_its_layout() {
        let mut graph = stacked_chain(12);
        arrange(&mut graph);
        let laid_out = graph.clone();
        let bottom = graph
            .nodes
            .iter()
            .map(|n| extent(&graph, n.id).3)
            .fold(0.0, f32::max);
        for k in [9, 10, 11] {
            graph.nodes[k].position = graph.nodes[2].position;
        }
        assert_eq!(unstack(&mut graph.nodes, &graph.wires), 3);
        for (node, before) in graph.nodes.iter().zip(&laid_out.nodes).take(9) {
            assert_eq!(node.position, before.position, "node {} moved", node.id);
        }
        for node in &graph.nodes[9..] {
            assert!(
                node.position.1 > bottom,
                "{:?} not below {bottom}",
                node.position
            );
        }
        assert_eq!(overlapping(&graph), None);
    }

    #[test]
    fn no_shipped_preset_opens_with_stacked_nodes() {
        let folder = concat!(env!("CARGO_MANIFEST_DIR"), "/graphs");
        for entry in std::fs::read_dir(folder).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "ron") {
                let mut graph = crate::graph::load(&path).unwrap();
                assert_eq!(unstack_levels(&mut graph), 0, "{}", path.display());
            }
        }
    }

    #[test]
    fn depths_do_not_depend_on_the_order_wires_are_listed_in() {
        let mut graph = stacked_chain(50);
        let forward = depths(&graph.nodes, &graph.wires);
        graph.wires.reverse();
        assert_eq!(depths(&graph.nodes, &graph.wires), forward);
        assert_eq!(forward[&graph.nodes[49].id], 49);
    }

    #[test]
    fn a_transform_with_three_vectors_is_wider_than_its_title() {
        let mut graph = Graph::default();
        let a = graph.add("t", NodeKind::Transform);
        let (left, _, right, _) = extent(&graph, a);
        assert!(right - left > 3.0 * FIELD + PIN, "{}", right - left);
        // Wired inputs show no fields.
        let p = graph.add("p", NodeKind::Position);
        for pin in ["scale", "rotation", "offset"] {
            graph.connect(p, "position", a, pin);
        }
        let (wired_left, _, wired_right, _) = extent(&graph, a);
        assert!(wired_right - wired_left < right - left);
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
        let width = 700.0;
        arrange_in_rows(&mut graph, width, f32::INFINITY);
        let mut tops = Vec::new();
        for pair in chain.windows(2) {
            let (before, after) = (extent(&graph, pair[0]), extent(&graph, pair[1]));
            assert!(after.0 == 0.0 || after.2 <= width, "{after:?} past {width}");
            if after.1 == before.1 {
                assert!(before.2 < after.0, "left to right within a band");
            } else {
                assert!(after.1 > before.3 && after.0 == 0.0, "the next band below");
                tops.push(after.1);
            }
        }
        assert!(
            tops.len() >= 2,
            "a 7-node chain wraps more than once: {tops:?}"
        );
        let mut unwrapped = graph.clone();
        arrange(&mut unwrapped);
        assert!(
            chain
                .iter()
                .all(|id| unwrapped.node(*id).unwrap().position.1 == 0.0),
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
        let tall = node_height(graph.node(sources[0]).unwrap()) + GAP;
        arrange_in_rows(&mut graph, f32::INFINITY, 2.5 * tall);
        let at = |id| graph.node(id).unwrap().position;
        let xs: Vec<f32> = sources.iter().map(|id| at(*id).0).collect();
        assert!(xs[0] == xs[1] && xs[1] < xs[2], "{xs:?}");
        assert!(xs[2] == xs[3] && xs[3] < xs[4] && xs[4] == xs[5], "{xs:?}");
        assert_eq!(at(sources[2]).1, 0.0, "the next column starts at the top");
        assert!(at(material).0 > xs[5], "the next depth after them");
    }

    #[test]
    fn the_inside_of_a_group_is_laid_out_without_overlaps() {
        let mut graph = crate::graph::preset("wood").unwrap();
        arrange_groups(&mut graph, 1620.0, 1000.0);
        let group = &graph.groups["ring_wood"];
        let inside = Graph {
            nodes: group.nodes.clone(),
            wires: group.wires.clone(),
            ..Graph::default()
        };
        let boxes: Vec<_> = inside.nodes.iter().map(|n| extent(&inside, n.id)).collect();
        for (i, a) in boxes.iter().enumerate() {
            for b in &boxes[i + 1..] {
                let apart = a.2 <= b.0 || b.2 <= a.0 || a.3 <= b.1 || b.3 <= a.1;
                assert!(apart, "{a:?} overlaps {b:?}");
            }
        }
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
