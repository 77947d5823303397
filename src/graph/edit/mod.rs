//! Graph edits as commands: every change the editor makes to a [`Graph`] is a
//! [`GraphEdit`], applied by [`apply`], which returns the edit that undoes it and what
//! changed ([`Change`]), so that undo and redo are made of commands (not snapshots) and
//! the preview learns exactly what to redo: a value, the layout, settings or the
//! structure.
//!
//! The graph is kept as [`Graph::canonicalize`] leaves it (nodes by id, wires sorted,
//! positions on whole canvas units) and resolved (every group node showing its group's
//! pins, as loading leaves it): `apply` expects such a graph and keeps it so, and an edit
//! followed by its inverse gives back a graph equal to the one before. An edit that is
//! refused changes nothing. The common edits cost in proportion to what they change
//! (and a scan of the level's wires); the rare whole-graph ones (grouping, ungrouping,
//! renaming or removing a group's pins) keep the graph as it was for their undo.

mod command;
mod error;
mod groups;
pub mod history;
mod level;
mod nodes;
#[cfg(test)]
mod properties;
mod settings;
#[cfg(test)]
mod tests;
mod values;
mod wires;

pub use command::{GraphEdit, GraphSetting, GroupPin};
pub use error::EditError;
pub use history::{History, Step};
pub use level::Level;

use super::{Graph, NodeId};

/// What one edit changed, for the preview and the other followers of the graph.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Change {
    /// The constant of input `pin` of node `node` at `level` changed: the preview can
    /// update the value in place, with no recompile.
    Value {
        level: Level,
        node: NodeId,
        pin: String,
    },
    /// Positions, labels or comment frames: nothing to recompile.
    Layout,
    /// The graph's settings (name, preview settings, alpha, shading, a group's link to
    /// the library).
    Settings,
    /// Nodes, wires, node settings or groups: the material must be compiled again.
    Structure,
}

/// An edit carried out.
#[derive(Clone, Debug, PartialEq)]
pub struct Applied {
    /// The edit that undoes it.
    pub inverse: GraphEdit,
    /// What changed, each once (empty: the edit set what was there already).
    pub changes: Vec<Change>,
}

impl Applied {
    /// An edit undone by `inverse` that changed `change`.
    fn new(inverse: GraphEdit, change: Change) -> Applied {
        Applied {
            inverse,
            changes: vec![change],
        }
    }

    /// An edit that changed nothing (undone by `inverse`, which changes nothing either).
    fn unchanged(inverse: GraphEdit) -> Applied {
        Applied {
            inverse,
            changes: Vec::new(),
        }
    }

    /// An edit undone by `inverse` that changed `change` if it `changed` anything.
    fn when(changed: bool, inverse: GraphEdit, change: Change) -> Applied {
        match changed {
            true => Applied::new(inverse, change),
            false => Applied::unchanged(inverse),
        }
    }

    /// Whether the material must be compiled again.
    pub fn recompiles(&self) -> bool {
        self.changes.contains(&Change::Structure)
    }
}

/// Carries out `edit` on `graph` (canonical and resolved), returning its inverse and
/// what changed; a refused edit leaves the graph as it was. An edit that changes a
/// group's contents makes a linked group local (as editing it in the editor does); its
/// inverse links it again.
pub fn apply(graph: &mut Graph, edit: GraphEdit) -> Result<Applied, EditError> {
    let linked = edit
        .edited_group()
        .filter(|name| graph.groups.get(*name).is_some_and(|group| group.linked))
        .map(str::to_string);
    let mut applied = dispatch(graph, edit)?;
    if let Some(name) = linked.filter(|_| !applied.changes.is_empty())
        && let Some(group) = graph.groups.get_mut(&name)
        && group.linked
    {
        group.linked = false;
        let relink = GraphEdit::SetLinked {
            group: name,
            linked: true,
        };
        applied.inverse = GraphEdit::Batch(vec![applied.inverse, relink]);
    }
    Ok(applied)
}

/// Carries out `edit` by its kind.
fn dispatch(graph: &mut Graph, edit: GraphEdit) -> Result<Applied, EditError> {
    match edit {
        GraphEdit::AddNodes {
            level,
            nodes,
            wires,
        } => nodes::add(graph, level, nodes, wires),
        GraphEdit::RemoveNodes { level, nodes } => nodes::remove(graph, level, &nodes),
        GraphEdit::Restore {
            level,
            nodes,
            wires,
        } => nodes::restore(graph, level, nodes, wires),
        GraphEdit::MoveNodes { level, moves } => nodes::move_to(graph, level, moves),
        GraphEdit::Arrange { level } => nodes::arrange(graph, level),
        GraphEdit::Connect { level, wire } => wires::connect(graph, level, wire),
        GraphEdit::Disconnect { level, wires } => wires::disconnect(graph, level, wires),
        GraphEdit::SetInput {
            level,
            node,
            pin,
            value,
        } => values::set_input(graph, level, node, pin, value),
        GraphEdit::SetLabel { level, node, label } => values::set_label(graph, level, node, label),
        GraphEdit::SetKind { level, node, kind } => values::set_kind(graph, level, node, kind),
        GraphEdit::ApplyPreset { name } => values::apply_preset(graph, &name),
        GraphEdit::Set(setting) => Ok(settings::set(graph, setting)),
        GraphEdit::SetLinked { group, linked } => settings::set_linked(graph, group, linked),
        GraphEdit::AddGroupPin { group, index, pin } => groups::add_pin(graph, group, index, pin),
        GraphEdit::DropGroupPin { group, side, index } => {
            groups::drop_pin(graph, group, side, index)
        }
        GraphEdit::SetGroupInput { group, input } => groups::set_input(graph, group, input),
        GraphEdit::RenameGroupPin {
            group,
            side,
            old,
            new,
        } => groups::rename_pin(graph, &group, side, &old, &new),
        GraphEdit::RemoveGroupPin { group, side, name } => {
            groups::remove_pin(graph, &group, side, &name)
        }
        GraphEdit::SetGroup { name, definition } => groups::set(graph, name, definition),
        GraphEdit::Group { level, nodes, name } => groups::group(graph, &level, &nodes, &name),
        GraphEdit::Ungroup { level, node } => groups::ungroup(graph, &level, node),
        GraphEdit::ReplaceGraph(replacement) => Ok(replace(graph, *replacement)),
        GraphEdit::Batch(edits) => batch(graph, edits),
    }
}

/// Puts `replacement` in the place of `graph`.
fn replace(graph: &mut Graph, replacement: Graph) -> Applied {
    if *graph == replacement {
        return Applied::unchanged(GraphEdit::ReplaceGraph(Box::new(replacement)));
    }
    let before = std::mem::replace(graph, replacement);
    Applied {
        inverse: GraphEdit::ReplaceGraph(Box::new(before)),
        changes: vec![Change::Structure, Change::Settings],
    }
}

/// Carries out `edits` in order, all or none: when one is refused, those before it are
/// undone.
fn batch(graph: &mut Graph, edits: Vec<GraphEdit>) -> Result<Applied, EditError> {
    let mut inverses = Vec::with_capacity(edits.len());
    let mut changes = Vec::new();
    let mut seen = std::collections::HashSet::new();
    for edit in edits {
        match apply(graph, edit) {
            Ok(applied) => {
                inverses.push(applied.inverse);
                for change in applied.changes {
                    if seen.insert(change.clone()) {
                        changes.push(change);
                    }
                }
            }
            Err(error) => {
                for inverse in inverses.into_iter().rev() {
                    // The inverse of an edit just made applies to the graph it left.
                    let undone = apply(graph, inverse);
                    debug_assert!(undone.is_ok(), "{undone:?}");
                }
                return Err(error);
            }
        }
    }
    inverses.reverse();
    Ok(Applied {
        inverse: GraphEdit::Batch(inverses),
        changes,
    })
}
