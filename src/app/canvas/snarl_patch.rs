//! The graph view following the document: an edit made to the document from outside
//! the view (the inspector's group and parameter panels, undo, redo) is carried into
//! the snarl by what it changed, node by node and wire by wire. Edits the view cannot
//! follow that way (grouping, a group's pins, a whole graph) have it built again.

use crate::app::canvas::view_edits::Shown;
use crate::graph::edit::{GraphEdit, Level};
use crate::graph::{Graph, Node, NodeId, Wire};
use egui::Pos2;
use egui_snarl::{InPinId, OutPinId, Snarl};

/// Carries `edit`, just applied to the document's `graph`, into `snarl`, which shows
/// level `shown_level` (`shown` follows). Returns `false` when the view must be built
/// again instead (the snarl may then be half patched).
pub fn follow(
    snarl: &mut Snarl<Node>,
    shown: &mut Shown,
    shown_level: &Level,
    edit: &GraphEdit,
    graph: &Graph,
) -> bool {
    let followed = match edit {
        GraphEdit::Batch(edits) => edits
            .iter()
            .all(|edit| follow(snarl, shown, shown_level, edit, graph)),
        _ => match edit.node_level() {
            // Edits of nodes at a level not shown change nothing shown.
            Some(level) if level != shown_level => true,
            // Inside a group wires reach its boundary, which both boundary nodes
            // show: the node edits are followed, the rest builds the view again.
            Some(Level::Group(_)) => refresh_only(snarl, shown, edit, graph, shown_level),
            Some(Level::Top) => follow_at_level(snarl, shown, edit, graph, shown_level),
            None => matches!(edit, GraphEdit::Set(_) | GraphEdit::SetLinked { .. }),
        },
    };
    // What was just done to the view is the document's already.
    snarl.take_journal();
    followed
}

/// The nodes of `level` of `graph`, in id order.
fn level_nodes<'g>(graph: &'g Graph, level: &Level) -> &'g [Node] {
    match level {
        Level::Top => &graph.nodes,
        Level::Group(name) => graph.groups.get(name).map_or(&[], |group| &group.nodes),
    }
}

/// Node `id` of `nodes` (in id order).
fn find(nodes: &[Node], id: NodeId) -> Option<&Node> {
    let at = nodes.partition_point(|node| node.id < id);
    nodes.get(at).filter(|node| node.id == id)
}

/// Follows the edits that change nodes in place (constants, labels, settings that
/// keep the pins, places); `false` for the others.
fn refresh_only(
    snarl: &mut Snarl<Node>,
    shown: &Shown,
    edit: &GraphEdit,
    graph: &Graph,
    level: &Level,
) -> bool {
    let nodes = level_nodes(graph, level);
    match edit {
        GraphEdit::SetInput { node, .. }
        | GraphEdit::SetLabel { node, .. }
        | GraphEdit::SetKind { node, .. } => refresh(snarl, shown, nodes, *node),
        GraphEdit::MoveNodes { moves, .. } => moves
            .iter()
            .all(|(node, _)| refresh(snarl, shown, nodes, *node)),
        _ => false,
    }
}

/// Shows node `id` as `nodes` has it now; `false` when its pins changed (its wires
/// would be at other pins) or it is not shown.
fn refresh(snarl: &mut Snarl<Node>, shown: &Shown, nodes: &[Node], id: NodeId) -> bool {
    let (Some(view), Some(node)) = (shown.view_of(id), find(nodes, id)) else {
        return false;
    };
    let Some(info) = snarl.get_node_info_mut(view) else {
        return false;
    };
    if info.value.kind.signature() != node.kind.signature() {
        return false;
    }
    info.value = node.clone();
    info.pos = Pos2::new(node.position.0, node.position.1);
    true
}

/// Follows an edit of the level shown, the top level.
fn follow_at_level(
    snarl: &mut Snarl<Node>,
    shown: &mut Shown,
    edit: &GraphEdit,
    graph: &Graph,
    level: &Level,
) -> bool {
    match edit {
        GraphEdit::AddNodes { nodes, wires, .. } | GraphEdit::Restore { nodes, wires, .. } => {
            for added in nodes {
                // As the document keeps it (a group node with its group's pins).
                let Some(node) = find(&graph.nodes, added.id) else {
                    return false;
                };
                let at = Pos2::new(node.position.0, node.position.1);
                let view = snarl.insert_node(at, node.clone());
                shown.insert(view, node);
            }
            wires.iter().all(|wire| connect(snarl, shown, wire))
        }
        GraphEdit::RemoveNodes { nodes, .. } => {
            for node in nodes {
                if let Some(view) = shown.view_of(*node) {
                    shown.remove(view);
                    snarl.remove_node(view);
                }
            }
            true
        }
        GraphEdit::Connect { wire, .. } => {
            let Some((_, to)) = pins(snarl, shown, wire) else {
                return false;
            };
            snarl.drop_inputs(to);
            connect(snarl, shown, wire)
        }
        GraphEdit::Disconnect { wires, .. } => wires.iter().all(|wire| {
            pins(snarl, shown, wire).is_some_and(|(from, to)| {
                snarl.disconnect(from, to);
                true
            })
        }),
        _ => refresh_only(snarl, shown, edit, graph, level),
    }
}

/// The view's pins of `wire`, when both its nodes are shown with those pins.
fn pins(snarl: &Snarl<Node>, shown: &Shown, wire: &Wire) -> Option<(OutPinId, InPinId)> {
    let (from, to) = (shown.view_of(wire.from.node)?, shown.view_of(wire.to.node)?);
    let output = snarl
        .get_node(from)?
        .kind
        .signature()
        .output(&wire.from.pin)?
        .0;
    let input = snarl.get_node(to)?.kind.signature().input(&wire.to.pin)?.0;
    Some((OutPinId { node: from, output }, InPinId { node: to, input }))
}

/// Draws `wire` in the view; `false` when it cannot be shown.
fn connect(snarl: &mut Snarl<Node>, shown: &Shown, wire: &Wire) -> bool {
    match pins(snarl, shown, wire) {
        Some((from, to)) => {
            snarl.connect(from, to);
            true
        }
        None => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::app::canvas::snarl_model::{graph_from_snarl, snarl_from_graph};
    use crate::graph::edit::{History, apply};
    use crate::graph::{NodeKind, Value};

    /// The flat wood graph: its group dissolved, so the top level has many nodes.
    fn flat_wood() -> Graph {
        let mut graph = crate::graph::preset("wood").expect("the wood preset");
        graph.canonicalize();
        let group = graph
            .nodes
            .iter()
            .find(|node| matches!(node.kind, NodeKind::Group(_)))
            .expect("the group node")
            .id;
        apply(
            &mut graph,
            GraphEdit::Ungroup {
                level: Level::Top,
                node: group,
            },
        )
        .expect("ungrouped");
        graph
    }

    #[test]
    fn undo_and_redo_are_followed_without_building_the_view_again() {
        let mut graph = flat_wood();
        let mut snarl = snarl_from_graph(&graph);
        snarl.take_journal();
        let mut shown = Shown::of(&snarl);
        let mut history = History::new();
        // A node with a constant input of a float.
        let (first, pin) = graph
            .nodes
            .iter()
            .find_map(|node| {
                let signature = node.kind.signature();
                let pin = signature.inputs.iter().find(|pin| {
                    pin.ty == crate::graph::ValueType::Float
                        && matches!(pin.default, crate::graph::PinDefault::Const(_))
                })?;
                Some((node.id, pin.name.to_string()))
            })
            .expect("a float constant");
        let last = graph.nodes.last().unwrap().id;
        let edits = [
            GraphEdit::SetInput {
                level: Level::Top,
                node: first,
                pin,
                value: Some(Value::Float(0.5)),
            },
            GraphEdit::RemoveNodes {
                level: Level::Top,
                nodes: vec![first],
            },
            GraphEdit::MoveNodes {
                level: Level::Top,
                moves: vec![(last, (-500.0, 20.0))],
            },
        ];
        // The view follows each edit, and shows the document after it.
        let mut followed = |snarl: &mut Snarl<Node>, edit: &GraphEdit, graph: &Graph| {
            assert!(
                follow(snarl, &mut shown, &Level::Top, edit, graph),
                "{edit:?}"
            );
            assert!(graph_from_snarl(snarl, graph) == *graph, "{edit:?}");
        };
        for edit in edits {
            history.apply(&mut graph, edit.clone()).expect("applies");
            followed(&mut snarl, &edit, &graph);
        }
        for _ in 0..3 {
            let step = history.undo(&mut graph).unwrap().expect("undoes");
            followed(&mut snarl, &step.edit, &graph);
        }
        assert!(graph == flat_wood());
        for _ in 0..3 {
            let step = history.redo(&mut graph).unwrap().expect("redoes");
            followed(&mut snarl, &step.edit, &graph);
        }
        // A wire made and taken back.
        let wire = graph.wires[0].clone();
        let edit = GraphEdit::Disconnect {
            level: Level::Top,
            wires: vec![wire.clone()],
        };
        history.apply(&mut graph, edit.clone()).unwrap();
        followed(&mut snarl, &edit, &graph);
        let step = history.undo(&mut graph).unwrap().unwrap();
        followed(&mut snarl, &step.edit, &graph);
        assert!(graph.wires.contains(&wire));
        assert!(
            snarl.take_journal().is_empty(),
            "following leaves no journal"
        );
    }
}
