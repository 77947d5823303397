//! What the user did on the graph view, as graph edits. egui-snarl edits its snarl
//! itself (a node dragged, a wire dropped, a pin right-clicked) and so do the canvas's
//! gestures; the snarl keeps a journal of those changes (our patch), and after the
//! panel the journal is turned into [`GraphEdit`]s for the document, in proportion to
//! what changed: no frame reads the whole view back.

use crate::graph::edit::{GraphEdit, Level};
use crate::graph::{Node, NodeId, PinRef, Wire};
use egui_snarl::{Change, InPinId, OutPinId, Snarl};
use rustc_hash::{FxHashMap, FxHashSet};

/// Which graph node each node of the view shows (their ids in the level shown), and
/// back, kept as the view changes: a node removed from the view is named by it.
#[derive(Default)]
pub struct Shown {
    by_view: FxHashMap<egui_snarl::NodeId, NodeId>,
    /// (Boundary nodes left out: both carry the one boundary id.)
    by_node: FxHashMap<NodeId, egui_snarl::NodeId>,
}

impl Shown {
    /// The nodes `snarl` shows now.
    pub fn of(snarl: &Snarl<Node>) -> Shown {
        let mut shown = Shown::default();
        for (view, node) in snarl.node_ids() {
            shown.insert(view, node);
        }
        shown
    }

    /// The view's node showing graph node `node`, if one does (not a boundary node).
    pub fn view_of(&self, node: NodeId) -> Option<egui_snarl::NodeId> {
        self.by_node.get(&node).copied()
    }

    /// Notes that `view` shows `node`.
    pub fn insert(&mut self, view: egui_snarl::NodeId, node: &Node) {
        self.by_view.insert(view, node.id);
        if crate::app::canvas::boundary::boundary(node).is_none() {
            self.by_node.insert(node.id, view);
        }
    }

    /// Forgets `view`; returns the graph node it showed.
    pub fn remove(&mut self, view: egui_snarl::NodeId) -> Option<NodeId> {
        let node = self.by_view.remove(&view)?;
        if self.by_node.get(&node) == Some(&view) {
            self.by_node.remove(&node);
        }
        Some(node)
    }
}

/// The edits that make the document's level `level` what the view shows, from the
/// view's journal `journal` (as [`Snarl::take_journal`] gives it); `shown` follows.
/// `stored` finds a node of the level in the document, to tell which of a touched
/// node's settings changed. In order: nodes removed, nodes added, wires in the order
/// made, then each touched node's settings and the moves.
pub fn edits_from_journal<'g>(
    journal: &[Change],
    snarl: &Snarl<Node>,
    shown: &mut Shown,
    level: &Level,
    stored: impl Fn(NodeId) -> Option<&'g Node>,
) -> Vec<GraphEdit> {
    let mut removed = Vec::new();
    let mut added = Vec::new();
    let mut wires = Vec::new();
    let mut touched = Vec::new();
    let mut every_node = false;
    for (at, change) in journal.iter().enumerate() {
        match *change {
            Change::Inserted(view) => {
                // A node removed again in the same frame was never there.
                let gone_later = journal[at + 1..].contains(&Change::Removed(view));
                if let (false, Some(node)) = (gone_later, snarl.get_node(view)) {
                    shown.insert(view, node);
                    added.push(view);
                }
            }
            Change::Removed(view) => removed.extend(shown.remove(view)),
            Change::Connected(from, to) => wires.push((true, from, to)),
            Change::Disconnected(from, to) => wires.push((false, from, to)),
            Change::Touched(view) => touched.push(view),
            Change::TouchedAll => every_node = true,
        }
    }
    let mut edits = Vec::new();
    if !removed.is_empty() {
        edits.push(GraphEdit::RemoveNodes {
            level: level.clone(),
            nodes: removed,
        });
    }
    let added_set: FxHashSet<egui_snarl::NodeId> = added.iter().copied().collect();
    if !added.is_empty() {
        let nodes = added
            .iter()
            .filter_map(|view| as_stored(snarl, *view))
            .collect();
        edits.push(GraphEdit::AddNodes {
            level: level.clone(),
            nodes,
            wires: Vec::new(),
        });
    }
    for (connected, from, to) in wires {
        let Some(wire) = wire_of(snarl, from, to) else {
            // A node removed later in the frame took the wire with it.
            continue;
        };
        edits.push(match connected {
            true => GraphEdit::Connect {
                level: level.clone(),
                wire,
            },
            false => GraphEdit::Disconnect {
                level: level.clone(),
                wires: vec![wire],
            },
        });
    }
    if every_node {
        touched = snarl.node_ids().map(|(view, _)| view).collect();
    }
    let mut seen = FxHashSet::default();
    let mut moves = Vec::new();
    for view in touched {
        if added_set.contains(&view) || !seen.insert(view) {
            continue;
        }
        let Some(now) = as_stored(snarl, view) else {
            continue;
        };
        let boundary = level.group().is_some() && now.id == crate::graph::group::BOUNDARY;
        let Some(before) = stored(now.id).filter(|_| !boundary) else {
            continue;
        };
        settings_edits(level, before, &now, &mut edits);
        if now.position != before.position {
            moves.push((now.id, now.position));
        }
    }
    if !moves.is_empty() {
        edits.push(GraphEdit::MoveNodes {
            level: level.clone(),
            moves,
        });
    }
    edits
}

/// Node `view` of `snarl` as the document stores it: at its place in the view, on
/// whole canvas units.
fn as_stored(snarl: &Snarl<Node>, view: egui_snarl::NodeId) -> Option<Node> {
    let info = snarl.get_node_info(view)?;
    let mut node = info.value.clone();
    node.position = (info.pos.x.round(), info.pos.y.round());
    Some(node)
}

/// The wire from `from` to `to` of `snarl` by the names of its nodes and pins, while
/// both nodes are there.
fn wire_of(snarl: &Snarl<Node>, from: OutPinId, to: InPinId) -> Option<Wire> {
    let (source, target) = (snarl.get_node(from.node)?, snarl.get_node(to.node)?);
    let output = source.kind.signature().outputs.get(from.output)?.name;
    let input = target.kind.signature().inputs.get(to.input)?.name;
    Some(Wire {
        from: PinRef::new(source.id, output),
        to: PinRef::new(target.id, input),
    })
}

/// The edits that give node `before` the label, settings and constants of `now`.
fn settings_edits(level: &Level, before: &Node, now: &Node, edits: &mut Vec<GraphEdit>) {
    if now.kind != before.kind {
        edits.push(GraphEdit::SetKind {
            level: level.clone(),
            node: now.id,
            kind: now.kind.clone(),
        });
    }
    if now.label != before.label {
        edits.push(GraphEdit::SetLabel {
            level: level.clone(),
            node: now.id,
            label: now.label.clone(),
        });
    }
    if now.inputs == before.inputs {
        return;
    }
    let pins: std::collections::BTreeSet<&String> =
        now.inputs.keys().chain(before.inputs.keys()).collect();
    for pin in pins {
        let value = now.inputs.get(pin).copied();
        if value != before.inputs.get(pin).copied() {
            edits.push(GraphEdit::SetInput {
                level: level.clone(),
                node: now.id,
                pin: pin.clone(),
                value,
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::app::canvas::snarl_model::{graph_from_snarl, snarl_from_graph};
    use crate::graph::edit::apply;
    use crate::graph::{Graph, MathOp, NodeKind, Value, ValueType};
    use crate::nodes::Math;

    /// A float Math node adding its inputs.
    fn adder(id: u32) -> Node {
        let kind = NodeKind::Math(Math {
            op: MathOp::Add,
            ty: ValueType::Float,
        });
        Node::new(NodeId(id), kind)
    }

    /// Four adders, each feeding the next's `a`.
    fn chain() -> Graph {
        let mut graph = Graph::default();
        for id in 1..=4 {
            let mut node = adder(id);
            node.position = (200.0 * id as f32, 0.0);
            graph.nodes.push(node);
        }
        for id in 1..4 {
            graph.wires.push(Wire {
                from: PinRef::new(NodeId(id), "result"),
                to: PinRef::new(NodeId(id + 1), "a"),
            });
        }
        graph.canonicalize();
        graph
    }

    /// The view's journal turned into edits and applied to `graph`.
    fn take_in(graph: &mut Graph, snarl: &mut Snarl<Node>, shown: &mut Shown) -> usize {
        let journal = snarl.take_journal();
        let before = graph.clone();
        let edits = edits_from_journal(&journal, snarl, shown, &Level::Top, |id| before.node(id));
        let count = edits.len();
        apply(graph, GraphEdit::Batch(edits)).expect("the view's edits apply");
        count
    }

    fn view_of(snarl: &Snarl<Node>, id: u32) -> egui_snarl::NodeId {
        let found = snarl.node_ids().find(|(_, node)| node.id == NodeId(id));
        found.expect("the node").0
    }

    #[test]
    fn what_the_view_did_becomes_the_documents_graph() {
        let mut graph = chain();
        let mut snarl = snarl_from_graph(&graph);
        snarl.take_journal();
        let mut shown = Shown::of(&snarl);
        // A node moved, one renamed and given a constant, one removed (with its wires),
        // a node added and wired into the gap.
        let (first, second, third, fourth) = (
            view_of(&snarl, 1),
            view_of(&snarl, 2),
            view_of(&snarl, 3),
            view_of(&snarl, 4),
        );
        snarl.get_node_info_mut(first).unwrap().pos += egui::vec2(40.4, -10.0);
        snarl[second].label = "renamed".into();
        snarl[second].inputs.insert("b".into(), Value::Float(0.25));
        snarl.remove_node(third);
        let new = snarl.insert_node(egui::pos2(5.0, 6.0), adder(900));
        snarl.connect(
            OutPinId {
                node: second,
                output: 0,
            },
            InPinId {
                node: new,
                input: 0,
            },
        );
        snarl.connect(
            OutPinId {
                node: new,
                output: 0,
            },
            InPinId {
                node: fourth,
                input: 0,
            },
        );
        assert!(take_in(&mut graph, &mut snarl, &mut shown) > 0);
        assert!(
            graph_from_snarl(&snarl, &graph) == graph,
            "the document is what the view shows"
        );
        assert!(graph.node(NodeId(3)).is_none());
        assert_eq!(graph.node(NodeId(2)).unwrap().label, "renamed");
        assert_eq!(graph.node(NodeId(1)).unwrap().position, (240.0, -10.0));
        assert_eq!(graph.wires.len(), 3);
        // A wire taken off an input by the widget itself.
        snarl.drop_inputs(InPinId {
            node: fourth,
            input: 0,
        });
        assert!(take_in(&mut graph, &mut snarl, &mut shown) > 0);
        assert_eq!(graph.wires.len(), 2);
        // The journal is empty now: nothing more to take in.
        assert_eq!(take_in(&mut graph, &mut snarl, &mut shown), 0);
        // A node handed out mutably but left as it was is no edit.
        let _ = &mut snarl[second];
        assert_eq!(take_in(&mut graph, &mut snarl, &mut shown), 0);
    }

    #[test]
    fn a_node_added_and_removed_in_one_frame_is_nothing() {
        let graph = chain();
        let mut snarl = snarl_from_graph(&graph);
        snarl.take_journal();
        let mut shown = Shown::of(&snarl);
        let new = snarl.insert_node(egui::pos2(0.0, 0.0), adder(900));
        snarl.connect(
            OutPinId {
                node: new,
                output: 0,
            },
            InPinId {
                node: view_of(&snarl, 1),
                input: 0,
            },
        );
        snarl.remove_node(new);
        let journal = snarl.take_journal();
        let edits = edits_from_journal(&journal, &snarl, &mut shown, &Level::Top, |id| {
            graph.node(id)
        });
        assert!(edits.is_empty(), "{edits:?}");
    }
}
