//! Adding, removing, putting back, moving and arranging nodes.

use super::level::{contents, settle};
use super::wires::{check_id, check_pins, cycle_through};
use super::{Applied, Change, EditError, GraphEdit, Level};
use crate::graph::group::{self, GroupDef, group_name};
use crate::graph::{Graph, Node, NodeId, NodeKind, Wire, parameters};
use std::collections::{BTreeMap, BTreeSet, HashSet};

/// Adds `nodes` and `wires` (see [`GraphEdit::AddNodes`]).
pub(super) fn add(
    graph: &mut Graph,
    level: Level,
    mut nodes: Vec<Node>,
    wires: Vec<Wire>,
) -> Result<Applied, EditError> {
    give_group_pins(graph, &level, &mut nodes)?;
    let mut at = contents(graph, &level)?;
    let mut ids = BTreeSet::new();
    for node in &nodes {
        check_id(&at, node.id)?;
        if at.position(node.id).is_some() || !ids.insert(node.id) {
            return Err(EditError::DuplicateId {
                level: level.clone(),
                node: node.id,
            });
        }
    }
    at.insert_nodes(nodes);
    let checked = (|| {
        let mut fed = HashSet::new();
        for wire in &wires {
            if !ids.contains(&wire.from.node) && !ids.contains(&wire.to.node) {
                return Err(EditError::StrayWire {
                    level: level.clone(),
                    wire: wire.clone(),
                });
            }
            check_pins(&at, wire)?;
            let wired = !ids.contains(&wire.to.node) && at.wires.iter().any(|w| w.to == wire.to);
            if wired || !fed.insert(&wire.to) {
                return Err(EditError::InputWired {
                    level: level.clone(),
                    input: wire.to.clone(),
                });
            }
        }
        let added: Vec<NodeId> = ids.iter().copied().collect();
        match cycle_through(&at, at.wires.iter().chain(&wires), &added) {
            Some(node) => {
                let wire = wires
                    .iter()
                    .find(|w| w.to.node == node || w.from.node == node);
                Err(EditError::Cycle {
                    level: level.clone(),
                    wire: wire.cloned().unwrap_or_else(|| wires[0].clone()),
                })
            }
            None => Ok(()),
        }
    })();
    if let Err(error) = checked {
        at.nodes.retain(|node| !ids.contains(&node.id));
        return Err(error);
    }
    at.insert_wires(wires);
    settle(graph, &level);
    let inverse = GraphEdit::RemoveNodes {
        level,
        nodes: ids.into_iter().collect(),
    };
    Ok(Applied::new(inverse, Change::Structure))
}

/// Removes nodes `ids` and their wires.
pub(super) fn remove(
    graph: &mut Graph,
    level: Level,
    ids: &[NodeId],
) -> Result<Applied, EditError> {
    let at = contents(graph, &level)?;
    for id in ids {
        at.find(*id)?;
    }
    // At the top level the graph's parameters and presets can name what goes: a removal
    // that takes parameters with it reaches across the graph, undone by putting it back.
    let exposing = level.group().is_none()
        && graph.nodes.iter().any(|node| {
            ids.contains(&node.id)
                && (graph.parameters.iter().any(|p| p.node == node.id)
                    || (group_name(node).is_some() && !graph.presets.is_empty()))
        });
    if exposing {
        return super::groups::whole(graph, |graph| {
            let before = parameters::exposed_names(graph);
            take_out(graph, &level, ids);
            parameters::forget_removed(graph, &before);
            Ok(())
        });
    }
    let (nodes, wires) = take_out(graph, &level, ids);
    let inverse = GraphEdit::Restore {
        level,
        nodes,
        wires,
    };
    Ok(Applied::new(inverse, Change::Structure))
}

/// Takes nodes `ids` (all at `level`) and every wire to or from them out of the graph.
fn take_out(graph: &mut Graph, level: &Level, ids: &[NodeId]) -> (Vec<Node>, Vec<Wire>) {
    let Ok(at) = contents(graph, level) else {
        return (Vec::new(), Vec::new());
    };
    let gone: HashSet<NodeId> = ids.iter().copied().collect();
    let nodes: Vec<Node> = at
        .nodes
        .extract_if(.., |node| gone.contains(&node.id))
        .collect();
    let touching = |wire: &mut Wire| gone.contains(&wire.from.node) || gone.contains(&wire.to.node);
    let wires: Vec<Wire> = at.wires.extract_if(.., touching).collect();
    settle(graph, level);
    (nodes, wires)
}

/// Puts back `nodes` and `wires` as they are (see [`GraphEdit::Restore`]).
pub(super) fn restore(
    graph: &mut Graph,
    level: Level,
    nodes: Vec<Node>,
    wires: Vec<Wire>,
) -> Result<Applied, EditError> {
    let mut at = contents(graph, &level)?;
    for node in &nodes {
        if at.position(node.id).is_some() {
            return Err(EditError::DuplicateId {
                level,
                node: node.id,
            });
        }
    }
    let mut listed = HashSet::new();
    for wire in &wires {
        if at.has_wire(wire) || !listed.insert(wire) {
            return Err(EditError::WireExists {
                level,
                wire: wire.clone(),
            });
        }
    }
    let ids: BTreeSet<NodeId> = nodes.iter().map(|node| node.id).collect();
    let between: Vec<Wire> = wires
        .iter()
        .filter(|wire| !ids.contains(&wire.from.node) && !ids.contains(&wire.to.node))
        .cloned()
        .collect();
    let changed = !nodes.is_empty() || !wires.is_empty();
    at.insert_nodes(nodes);
    at.insert_wires(wires);
    settle(graph, &level);
    let mut undo = Vec::new();
    if !between.is_empty() {
        undo.push(GraphEdit::Disconnect {
            level: level.clone(),
            wires: between,
        });
    }
    if !ids.is_empty() {
        undo.push(GraphEdit::RemoveNodes {
            level,
            nodes: ids.into_iter().collect(),
        });
    }
    let inverse = match undo.len() {
        1 => undo.remove(0),
        _ => GraphEdit::Batch(undo),
    };
    Ok(Applied::when(changed, inverse, Change::Structure))
}

/// Moves nodes to `moves`' positions, rounded.
pub(super) fn move_to(
    graph: &mut Graph,
    level: Level,
    moves: Vec<(NodeId, (f32, f32))>,
) -> Result<Applied, EditError> {
    let at = contents(graph, &level)?;
    let mut places = Vec::with_capacity(moves.len());
    for (id, _) in &moves {
        let index = at.find(*id)?;
        places.push((index, at.nodes[index].position));
    }
    let mut changed = false;
    for ((index, _), (_, (x, y))) in places.iter().zip(&moves) {
        let position = &mut at.nodes[*index].position;
        let to = (x.round(), y.round());
        changed |= *position != to;
        *position = to;
    }
    // (Each from where it was before any of them moved, should one be listed twice.)
    let old = places.iter().zip(&moves);
    let old = old.map(|((_, from), (id, _))| (*id, *from)).collect();
    let inverse = GraphEdit::MoveNodes { level, moves: old };
    Ok(Applied::when(changed, inverse, Change::Layout))
}

/// Lays the nodes of `level` out in columns by depth.
pub(super) fn arrange(graph: &mut Graph, level: Level) -> Result<Applied, EditError> {
    let at = contents(graph, &level)?;
    let mut laid = at.nodes.clone();
    crate::graph::layout::arrange_nodes(&mut laid, at.wires, f32::INFINITY, f32::INFINITY);
    let moves = laid
        .iter()
        .zip(at.nodes.iter())
        .filter(|(new, old)| new.position != old.position)
        .map(|(new, _)| (new.id, new.position))
        .collect();
    move_to(graph, level, moves)
}

/// Gives the group nodes among `nodes` their group's current pins; refuses a group
/// the graph does not have, one whose groups do not resolve, and one that would
/// contain itself (a node, inside group `level`, of a group that holds that group).
pub(super) fn give_group_pins(
    graph: &Graph,
    level: &Level,
    nodes: &mut [Node],
) -> Result<(), EditError> {
    if !nodes.iter().any(|node| group_name(node).is_some()) {
        return Ok(());
    }
    let interfaces =
        group::interfaces(&graph.groups).map_err(|error| EditError::Refused(error.message))?;
    for node in nodes {
        let NodeKind::Group(instance) = &mut node.kind else {
            continue;
        };
        if let Some(outer) = level.group()
            && holds(&graph.groups, &instance.name, outer)
        {
            return Err(EditError::Refused(format!(
                "group '{outer}' cannot hold a node of group '{}': the group would contain \
                 itself",
                instance.name
            )));
        }
        let interface = interfaces
            .get(&instance.name)
            .ok_or_else(|| EditError::UnknownGroup(instance.name.clone()))?;
        instance.pins = interface.signature();
    }
    Ok(())
}

/// Whether group `outer` is group `inner` or holds a node of it, at any depth.
fn holds(groups: &BTreeMap<String, GroupDef>, outer: &str, inner: &str) -> bool {
    let mut seen = BTreeSet::from([outer]);
    let mut pending = vec![outer];
    while let Some(name) = pending.pop() {
        if name == inner {
            return true;
        }
        let definition = groups.get(name);
        let used = definition
            .into_iter()
            .flat_map(|d| d.nodes.iter().filter_map(group_name));
        for group in used {
            if seen.insert(group) {
                pending.push(group);
            }
        }
    }
    false
}
