//! Groups: their declared inputs and outputs, their definitions, and grouping and
//! ungrouping nodes. Renaming or removing a group's pin, grouping and ungrouping reach
//! across the whole graph (instances, inherited inputs, parameters, presets): their
//! inverse is the graph as it was.

use super::level::settle;
use super::{Applied, Change, EditError, GraphEdit, GroupPin, Level};
use crate::graph::group::{self, BOUNDARY, GroupDef, GroupInput};
use crate::graph::group_interface::{self, Side};
use crate::graph::{Graph, Node, NodeId, NodeKind};
use crate::nodes::Group;
use crate::nodes::pins::{InputPin, PinDefault, PinRange, Signature, intern, output};
use std::collections::BTreeSet;

/// The definition of group `name`.
fn definition<'g>(graph: &'g mut Graph, name: &str) -> Result<&'g mut GroupDef, EditError> {
    graph
        .groups
        .get_mut(name)
        .ok_or_else(|| EditError::UnknownGroup(name.to_string()))
}

/// The names of the pins on `side` of `definition`, in order.
fn pin_names(definition: &GroupDef, side: Side) -> Vec<&str> {
    match side {
        Side::Input => definition.inputs.iter().map(|i| i.name.as_str()).collect(),
        Side::Output => definition.outputs.iter().map(|o| o.name.as_str()).collect(),
    }
}

/// Declares `pin` at `index` of its side of group `name`.
pub(super) fn add_pin(
    graph: &mut Graph,
    name: String,
    index: usize,
    pin: GroupPin,
) -> Result<Applied, EditError> {
    let definition = definition(graph, &name)?;
    let side = pin.side();
    let names = pin_names(definition, side);
    if names.contains(&pin.name()) {
        return Err(EditError::Refused(format!(
            "group '{name}' has an {} named '{}' already",
            side.word(),
            pin.name()
        )));
    }
    if index > names.len() {
        return Err(EditError::UnknownGroupPin {
            group: name,
            side: side.word(),
            index,
        });
    }
    match pin {
        GroupPin::Input(input) => definition.inputs.insert(index, input),
        GroupPin::Output(output) => definition.outputs.insert(index, output),
    }
    settle(graph, &Level::Group(name.clone()));
    let inverse = GraphEdit::DropGroupPin {
        group: name,
        side,
        index,
    };
    Ok(Applied::new(inverse, Change::Structure))
}

/// Takes back the declaration of pin `index` of `side` of group `name`.
pub(super) fn drop_pin(
    graph: &mut Graph,
    name: String,
    side: Side,
    index: usize,
) -> Result<Applied, EditError> {
    let definition = definition(graph, &name)?;
    if index >= pin_names(definition, side).len() {
        return Err(EditError::UnknownGroupPin {
            group: name,
            side: side.word(),
            index,
        });
    }
    let pin = match side {
        Side::Input => GroupPin::Input(definition.inputs.remove(index)),
        Side::Output => GroupPin::Output(definition.outputs.remove(index)),
    };
    settle(graph, &Level::Group(name.clone()));
    let inverse = GraphEdit::AddGroupPin {
        group: name,
        index,
        pin,
    };
    Ok(Applied::new(inverse, Change::Structure))
}

/// Sets the default, range and widget of the input of group `name` that `input` names.
pub(super) fn set_input(
    graph: &mut Graph,
    name: String,
    input: GroupInput,
) -> Result<Applied, EditError> {
    let definition = definition(graph, &name)?;
    let Some(declared) = definition.inputs.iter_mut().find(|i| i.name == input.name) else {
        return Err(EditError::Refused(format!(
            "group '{name}' has no input '{}'",
            input.name
        )));
    };
    let old = std::mem::replace(declared, input);
    let changed = old != *declared;
    if changed {
        settle(graph, &Level::Group(name.clone()));
    }
    let inverse = GraphEdit::SetGroupInput {
        group: name,
        input: old,
    };
    Ok(Applied::when(changed, inverse, Change::Structure))
}

/// Renames pin `old` of `side` of group `name` to `new`, everywhere it is named.
pub(super) fn rename_pin(
    graph: &mut Graph,
    name: &str,
    side: Side,
    old: &str,
    new: &str,
) -> Result<Applied, EditError> {
    whole(graph, |graph| {
        group_interface::rename(graph, name, side, old, new)
    })
}

/// Removes pin `pin` of `side` of group `name`, and what uses it.
pub(super) fn remove_pin(
    graph: &mut Graph,
    name: &str,
    side: Side,
    pin: &str,
) -> Result<Applied, EditError> {
    whole(graph, |graph| {
        group_interface::remove(graph, name, side, pin)
    })
}

/// Adds, replaces or removes the definition of group `name`.
pub(super) fn set(
    graph: &mut Graph,
    name: String,
    definition: Option<Box<GroupDef>>,
) -> Result<Applied, EditError> {
    let old = match definition {
        Some(mut definition) => {
            definition.canonicalize();
            graph.groups.insert(name.clone(), *definition)
        }
        None => graph.groups.remove(&name),
    };
    let changed = old.as_ref() != graph.groups.get(&name);
    if changed {
        group::resolve(graph);
    }
    let inverse = GraphEdit::SetGroup {
        name,
        definition: old.map(Box::new),
    };
    Ok(Applied::when(changed, inverse, Change::Structure))
}

/// Turns `nodes` of `level` into group `name`, with a node of it in their place.
pub(super) fn group(
    graph: &mut Graph,
    level: &Level,
    nodes: &BTreeSet<NodeId>,
    name: &str,
) -> Result<Applied, EditError> {
    whole(graph, |graph| {
        on_level(graph, level, |local| {
            if let Some(missing) = nodes.iter().find(|id| local.node(**id).is_none()) {
                return Err(EditError::UnknownNode {
                    level: level.clone(),
                    node: *missing,
                }
                .to_string());
            }
            if level.group().is_some() && nodes.contains(&BOUNDARY) {
                return Err(EditError::BoundaryId {
                    level: level.clone(),
                }
                .to_string());
            }
            group::group_nodes(local, nodes, name).map(drop)
        })
    })
}

/// Dissolves group node `node` of `level` into its definition's nodes.
pub(super) fn ungroup(
    graph: &mut Graph,
    level: &Level,
    node: NodeId,
) -> Result<Applied, EditError> {
    whole(graph, |graph| {
        on_level(graph, level, |local| group::ungroup(local, node).map(drop))
    })
}

/// Carries out `edit` on a copy of `graph` and takes the copy in (resolved and in
/// canonical order): an edit that reaches across the whole graph, undone by putting
/// the graph back as it was.
pub(super) fn whole(
    graph: &mut Graph,
    edit: impl FnOnce(&mut Graph) -> Result<(), String>,
) -> Result<Applied, EditError> {
    let mut edited = graph.clone();
    edit(&mut edited).map_err(EditError::Refused)?;
    group::resolve(&mut edited);
    edited.canonicalize();
    let before = std::mem::replace(graph, edited);
    let inverse = GraphEdit::ReplaceGraph(Box::new(before));
    Ok(Applied {
        inverse,
        changes: vec![Change::Structure, Change::Settings],
    })
}

/// Runs `edit` on `level` of `graph` as a graph of its own: the graph itself, or a
/// group's nodes and wires with its boundary as one node of id [`BOUNDARY`] (its
/// outputs the group's inputs, its inputs the group's outputs) and every group of the
/// graph (the one edited standing for its declared pins alone), so that the graph
/// operations grouping and ungrouping work inside groups too.
fn on_level(
    graph: &mut Graph,
    level: &Level,
    edit: impl FnOnce(&mut Graph) -> Result<(), String>,
) -> Result<(), String> {
    let Some(name) = level.group() else {
        return edit(graph);
    };
    let definition = definition(graph, name).map_err(|error| error.to_string())?;
    let declared = GroupDef {
        linked: definition.linked,
        inputs: definition.inputs.clone(),
        outputs: definition.outputs.clone(),
        nodes: Vec::new(),
        wires: Vec::new(),
    };
    let mut inner = std::mem::replace(definition, declared);
    let boundary = boundary_node(&inner);
    inner.nodes.push(boundary);
    let mut local = Graph {
        nodes: std::mem::take(&mut inner.nodes),
        wires: std::mem::take(&mut inner.wires),
        groups: std::mem::take(&mut graph.groups),
        ..Graph::default()
    };
    let done = edit(&mut local);
    local.nodes.retain(|node| node.id != BOUNDARY);
    inner.nodes = local.nodes;
    inner.wires = local.wires;
    graph.groups = local.groups;
    graph.groups.insert(name.to_string(), inner);
    done
}

/// A node standing for the boundary of group `definition`.
fn boundary_node(definition: &GroupDef) -> Node {
    let inputs = definition.outputs.iter().map(|output| InputPin {
        name: intern(&output.name),
        ty: output.ty,
        default: PinDefault::Required,
        range: PinRange::ANY,
        sampled: false,
        re_evaluated: false,
    });
    let outputs = (definition.inputs.iter()).map(|input| output(intern(&input.name), input.ty));
    let pins = Signature::new(inputs.collect(), outputs.collect());
    Node::new(
        BOUNDARY,
        NodeKind::Group(Group {
            name: "<group boundary>".to_string(),
            pins,
        }),
    )
}
