//! The snarl as a view of the document's `Graph`: built from a graph, read back into
//! one, new ids, the cycle check for a wire, and a comment frame around nodes.

use crate::graph::{Graph, Node, NodeId, PinRef, Wire};
use egui::Pos2;
use egui_snarl::Snarl;
use egui_snarl::{InPinId, OutPinId};
use std::collections::BTreeMap;

/// A snarl showing `graph`, nodes at their saved positions (its journal empty).
pub fn snarl_from_graph(graph: &Graph) -> Snarl<Node> {
    let mut snarl = Snarl::new();
    insert_graph(&mut snarl, graph, |_, node| {
        (node.clone(), Pos2::new(node.position.0, node.position.1))
    });
    // Building the view is no edit.
    snarl.take_journal();
    snarl
}

/// Inserts the nodes of `graph` into `snarl`, each as `place` makes it (the node to
/// insert and where), then the wires between them. Returns the snarl id of every node.
pub fn insert_graph(
    snarl: &mut Snarl<Node>,
    graph: &Graph,
    mut place: impl FnMut(&Snarl<Node>, &Node) -> (Node, Pos2),
) -> BTreeMap<NodeId, egui_snarl::NodeId> {
    let mut ids = BTreeMap::new();
    for node in &graph.nodes {
        let (inserted, position) = place(snarl, node);
        ids.insert(node.id, snarl.insert_node(position, inserted));
    }
    for wire in &graph.wires {
        let (Some(from), Some(to)) = (graph.node(wire.from.node), graph.node(wire.to.node)) else {
            continue;
        };
        let output = from.kind.signature().output(&wire.from.pin).map(|(i, _)| i);
        let input = to.kind.signature().input(&wire.to.pin).map(|(i, _)| i);
        if let (Some(output), Some(input)) = (output, input) {
            snarl.connect(
                OutPinId {
                    node: ids[&wire.from.node],
                    output,
                },
                InPinId {
                    node: ids[&wire.to.node],
                    input,
                },
            );
        }
    }
    ids
}

/// The graph a snarl shows, with `meta`'s name, version and preview settings. The
/// wires of `meta` that the view cannot show, at a pin a group node does not show (a
/// group that does not resolve, or whose interface changed under it), are kept while
/// both their nodes are: only the check may call them wrong, never the view drop them.
pub fn graph_from_snarl(snarl: &Snarl<Node>, meta: &Graph) -> Graph {
    let mut graph = Graph {
        nodes: Vec::new(),
        wires: Vec::new(),
        ..meta.clone()
    };
    for (position, node) in snarl.nodes_pos() {
        let mut node = node.clone();
        node.position = (position.x.round(), position.y.round());
        graph.nodes.push(node);
    }
    for (from, to) in snarl.wires() {
        let (source, target) = (&snarl[from.node], &snarl[to.node]);
        let output = source
            .kind
            .signature()
            .outputs
            .get(from.output)
            .map(|pin| pin.name);
        let input = target
            .kind
            .signature()
            .inputs
            .get(to.input)
            .map(|pin| pin.name);
        if let (Some(output), Some(input)) = (output, input) {
            graph.wires.push(Wire {
                from: PinRef::new(source.id, output),
                to: PinRef::new(target.id, input),
            });
        }
    }
    let unshown = unshown_wires(&graph.nodes, &meta.wires);
    graph.wires.extend(unshown);
    graph.canonicalize();
    graph
}

/// The wires among `wires` between nodes of `nodes` that reach a pin one of them, a
/// group node, does not show.
fn unshown_wires(nodes: &[Node], wires: &[Wire]) -> Vec<Wire> {
    let by_id: BTreeMap<NodeId, &Node> = nodes.iter().map(|node| (node.id, node)).collect();
    let hidden = |node: &Node, pin: &str, output: bool| {
        let signature = node.kind.signature();
        crate::app::canvas::boundary::is_instance(node)
            && if output {
                signature.output(pin).is_none()
            } else {
                signature.input(pin).is_none()
            }
    };
    wires
        .iter()
        .filter(|wire| {
            let (Some(from), Some(to)) = (by_id.get(&wire.from.node), by_id.get(&wire.to.node))
            else {
                return false;
            };
            hidden(from, &wire.from.pin, true) || hidden(to, &wire.to.pin, false)
        })
        .cloned()
        .collect()
}

/// The id a new node gets: one past the largest in use.
pub fn next_node_id(snarl: &Snarl<Node>) -> NodeId {
    NodeId(snarl.nodes().map(|node| node.id.0 + 1).max().unwrap_or(1))
}

/// Whether a wire from `from` to `to` would close a cycle (`from` already depends on `to`).
pub(in crate::app) fn would_cycle(
    snarl: &Snarl<Node>,
    from: egui_snarl::NodeId,
    to: egui_snarl::NodeId,
) -> bool {
    let mut stack = vec![from];
    let mut seen = std::collections::BTreeSet::new();
    while let Some(node) = stack.pop() {
        if node == to {
            return true;
        }
        if seen.insert(node) {
            stack.extend(
                snarl
                    .wires()
                    .filter(|(_, input)| input.node == node)
                    .map(|(output, _)| output.node),
            );
        }
    }
    false
}

/// A frame around the nodes `selection`, titled `title` (node sizes are estimated).
pub fn frame_around(
    snarl: &Snarl<Node>,
    selection: &[egui_snarl::NodeId],
    title: &str,
) -> Option<crate::graph::Frame> {
    let positions: Vec<Pos2> = selection
        .iter()
        .filter_map(|id| snarl.get_node_info(*id))
        .map(|info| info.pos)
        .collect();
    let first = *positions.first()?;
    let bounds = positions.iter().fold(
        egui::Rect::from_min_size(first, egui::vec2(220.0, 180.0)),
        |rect, pos| rect.union(egui::Rect::from_min_size(*pos, egui::vec2(220.0, 180.0))),
    );
    let bounds = bounds
        .expand2(egui::vec2(30.0, 30.0))
        .union(egui::Rect::from_min_size(
            bounds.min - egui::vec2(30.0, 70.0),
            egui::Vec2::ZERO,
        ));
    Some(crate::graph::Frame {
        title: title.to_string(),
        min: (bounds.min.x, bounds.min.y),
        max: (bounds.max.x, bounds.max.y),
        color: (0.45, 0.65, 0.95),
    })
}
