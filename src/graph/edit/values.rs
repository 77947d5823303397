//! What a node holds: its input constants, label and settings, and the parameter
//! presets that set many inputs at once.

use super::level::{contents, settle};
use super::{Applied, Change, EditError, GraphEdit, Level};
use crate::graph::group::group_name;
use crate::graph::{Graph, NodeId, NodeKind, Value, parameters};

/// Sets (or clears) the constant of input `pin` of `node`.
pub(super) fn set_input(
    graph: &mut Graph,
    level: Level,
    node: NodeId,
    pin: String,
    value: Option<Value>,
) -> Result<Applied, EditError> {
    let at = contents(graph, &level)?;
    let index = at.find(node)?;
    let target = &mut at.nodes[index];
    if target.kind.signature().input(&pin).is_none() {
        return Err(EditError::UnknownPin {
            level,
            node,
            side: "input",
            pin,
        });
    }
    let old = match value {
        Some(value) => target.inputs.insert(pin.clone(), value),
        None => target.inputs.remove(&pin),
    };
    let changed = old != value;
    // A group node's values inside a group are the defaults of inputs the group
    // around it inherits.
    let instance = group_name(target).is_some();
    if changed && instance {
        settle(graph, &level);
    }
    let change = Change::Value {
        level: level.clone(),
        node,
        pin: pin.clone(),
    };
    let inverse = GraphEdit::SetInput {
        level,
        node,
        pin,
        value: old,
    };
    Ok(Applied::when(changed, inverse, change))
}

/// Renames `node`.
pub(super) fn set_label(
    graph: &mut Graph,
    level: Level,
    node: NodeId,
    label: String,
) -> Result<Applied, EditError> {
    let at = contents(graph, &level)?;
    let index = at.find(node)?;
    let target = &mut at.nodes[index];
    let old = std::mem::replace(&mut target.label, label);
    let changed = old != target.label;
    // Inside a group, a group node's label qualifies the names of the inputs the group
    // around it inherits from it.
    if changed && group_name(target).is_some() {
        settle(graph, &level);
    }
    let inverse = GraphEdit::SetLabel {
        level,
        node,
        label: old,
    };
    Ok(Applied::when(changed, inverse, Change::Layout))
}

/// Changes the settings of `node` to those of `kind`, a kind of the same sort.
pub(super) fn set_kind(
    graph: &mut Graph,
    level: Level,
    node: NodeId,
    kind: NodeKind,
) -> Result<Applied, EditError> {
    let at = contents(graph, &level)?;
    let index = at.find(node)?;
    let target = &mut at.nodes[index];
    let same_sort = std::mem::discriminant(&target.kind) == std::mem::discriminant(&kind);
    if !same_sort || group_name(target).is_some() {
        return Err(EditError::KindChange {
            level: level.clone(),
            node,
            kind: target.kind.title(),
        });
    }
    let old = std::mem::replace(&mut target.kind, kind);
    let changed = old != target.kind;
    let inverse = GraphEdit::SetKind {
        level,
        node,
        kind: old,
    };
    Ok(Applied::when(changed, inverse, Change::Structure))
}

/// Applies parameter preset `name`; undone by setting back the inputs it changed.
pub(super) fn apply_preset(graph: &mut Graph, name: &str) -> Result<Applied, EditError> {
    let targets: Vec<(NodeId, String)> = parameters::exposed(graph)
        .into_iter()
        .map(|entry| (entry.target.node, entry.target.pin))
        .collect();
    let value_of = |graph: &Graph, (node, pin): &(NodeId, String)| {
        let at = graph.nodes.partition_point(|n| n.id < *node);
        let found = graph.nodes.get(at).filter(|n| n.id == *node);
        found.and_then(|n| n.inputs.get(pin).copied())
    };
    let before: Vec<Option<Value>> = targets.iter().map(|t| value_of(graph, t)).collect();
    let applied = parameters::apply_preset(graph, name);
    let mut undo = Vec::new();
    let mut changes = Vec::new();
    for (target, old) in targets.into_iter().zip(before) {
        if value_of(graph, &target) == old {
            continue;
        }
        let (node, pin) = target;
        changes.push(Change::Value {
            level: Level::Top,
            node,
            pin: pin.clone(),
        });
        undo.push(GraphEdit::SetInput {
            level: Level::Top,
            node,
            pin,
            value: old,
        });
    }
    let inverse = GraphEdit::Batch(undo);
    if let Err(error) = applied {
        // Refused part way: what it set is set back.
        let undone = super::apply(graph, inverse);
        debug_assert!(undone.is_ok(), "{undone:?}");
        return Err(EditError::Refused(error.to_string()));
    }
    Ok(Applied { inverse, changes })
}
