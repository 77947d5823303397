//! The edits: what the editor changes in a graph, each a value that [`super::apply`]
//! carries out and whose inverse is an edit too.

use super::Level;
use crate::graph::group::{GroupDef, GroupInput, GroupOutput};
use crate::graph::group_interface::Side;
use crate::graph::{
    AlphaMode, Frame, Graph, Node, NodeId, NodeKind, Preview, Shading, Value, Wire,
};
use std::collections::BTreeSet;

/// One change to a graph. Node edits name the level they are made at: the top level,
/// or the definition of a group (nested groups are all in `graph.groups`, by name),
/// where wires reach the group's inputs and outputs through the node id
/// [`crate::graph::group::BOUNDARY`].
#[derive(Clone, Debug, PartialEq)]
pub enum GraphEdit {
    /// Adds `nodes`, whose ids the level does not use (and, inside a group, not the
    /// boundary's), at their positions (rounded), and `wires`, each reaching one of
    /// them and none feeding an input that is wired already. Group nodes take their
    /// group's current pins. Refused when a pin is unknown, the types do not convert or
    /// a wire would close a cycle. Undone by [`GraphEdit::RemoveNodes`].
    AddNodes {
        level: Level,
        nodes: Vec<Node>,
        wires: Vec<Wire>,
    },
    /// Removes nodes and every wire to or from them. Undone by [`GraphEdit::Restore`].
    RemoveNodes { level: Level, nodes: Vec<NodeId> },
    /// Puts back nodes and wires exactly as given, checking only that none of them is
    /// there already: the inverse of removing them (a graph as loaded may hold what
    /// [`GraphEdit::AddNodes`] refuses).
    Restore {
        level: Level,
        nodes: Vec<Node>,
        wires: Vec<Wire>,
    },
    /// Connects an output to an input, replacing the wire into that input, if any.
    /// Refused when the types do not convert or the wire would close a cycle.
    Connect { level: Level, wire: Wire },
    /// Removes wires (each must be there).
    Disconnect { level: Level, wires: Vec<Wire> },
    /// Sets the constant of input `pin` of `node`, or clears it (`None`) back to the
    /// pin's default.
    SetInput {
        level: Level,
        node: NodeId,
        pin: String,
        value: Option<Value>,
    },
    /// Renames a node.
    SetLabel {
        level: Level,
        node: NodeId,
        label: String,
    },
    /// Changes the settings of a node (its kind with other settings: a Math node's
    /// operation, a ramp's stops); the kind itself stays, and a group node's group too.
    SetKind {
        level: Level,
        node: NodeId,
        kind: NodeKind,
    },
    /// Moves nodes to new positions (rounded to whole canvas units).
    MoveNodes {
        level: Level,
        moves: Vec<(NodeId, (f32, f32))>,
    },
    /// Lays the level's nodes out in columns by depth ([`crate::graph::layout`]).
    /// Undone by [`GraphEdit::MoveNodes`].
    Arrange { level: Level },
    /// Sets one of the graph's settings.
    Set(GraphSetting),
    /// Applies parameter preset `name` ([`crate::graph::parameters::apply_preset`]).
    /// Undone by setting the inputs it changed back.
    ApplyPreset { name: String },
    /// Declares a new input or output of group `group` at `index` among its side's pins
    /// (the pin's name must be free); wires to it are [`GraphEdit::Connect`]s at the
    /// group's level. Undone by [`GraphEdit::DropGroupPin`].
    AddGroupPin {
        group: String,
        index: usize,
        pin: GroupPin,
    },
    /// Takes back the declaration of pin `index` of `side` of group `group`, and nothing
    /// else (the inverse of [`GraphEdit::AddGroupPin`]; [`GraphEdit::RemoveGroupPin`]
    /// removes a pin and what uses it).
    DropGroupPin {
        group: String,
        side: Side,
        index: usize,
    },
    /// Sets the default, range and widget of the group input named as `input` is.
    SetGroupInput { group: String, input: GroupInput },
    /// Renames a group's input or output, following it into every instance, inherited
    /// input, exposed parameter and preset ([`crate::graph::group_interface::rename`]).
    RenameGroupPin {
        group: String,
        side: Side,
        old: String,
        new: String,
    },
    /// Removes a group's input or output and every wire to or from it
    /// ([`crate::graph::group_interface::remove`]).
    RemoveGroupPin {
        group: String,
        side: Side,
        name: String,
    },
    /// Makes a group follow the library (`linked`) or keep its own definition.
    SetLinked { group: String, linked: bool },
    /// Adds, replaces (`Some`) or removes (`None`) the definition of group `name`, as
    /// given: a group taken in from the library, or the inverse of that.
    SetGroup {
        name: String,
        definition: Option<Box<GroupDef>>,
    },
    /// Turns `nodes` of `level` into a new group `name` with one node of it in their
    /// place ([`crate::graph::group::group_nodes`]); the new node takes the next free id
    /// of the level.
    Group {
        level: Level,
        nodes: BTreeSet<NodeId>,
        name: String,
    },
    /// Dissolves group node `node` of `level` into its definition's nodes
    /// ([`crate::graph::group::ungroup`]).
    Ungroup { level: Level, node: NodeId },
    /// Replaces the whole graph: the inverse of the whole-graph edits.
    ReplaceGraph(Box<Graph>),
    /// Several edits as one, in order: all or none.
    Batch(Vec<GraphEdit>),
}

/// A setting of the whole graph.
#[derive(Clone, Debug, PartialEq)]
pub enum GraphSetting {
    Name(String),
    Preview(Preview),
    Alpha(AlphaMode),
    Shading(Shading),
    /// The comment frames (a layout change).
    Frames(Vec<Frame>),
}

/// A declared input or output of a group.
#[derive(Clone, Debug, PartialEq)]
pub enum GroupPin {
    Input(GroupInput),
    Output(GroupOutput),
}

impl GroupPin {
    /// Which side of the group it is on.
    pub fn side(&self) -> Side {
        match self {
            GroupPin::Input(_) => Side::Input,
            GroupPin::Output(_) => Side::Output,
        }
    }

    /// Its name.
    pub fn name(&self) -> &str {
        match self {
            GroupPin::Input(input) => &input.name,
            GroupPin::Output(output) => &output.name,
        }
    }
}

impl GraphEdit {
    /// The level of an edit of nodes or wires in place (adding, removing or restoring
    /// nodes, wiring, a constant, a label, settings, places); `None` for the others.
    pub fn node_level(&self) -> Option<&Level> {
        match self {
            GraphEdit::AddNodes { level, .. }
            | GraphEdit::RemoveNodes { level, .. }
            | GraphEdit::Restore { level, .. }
            | GraphEdit::Connect { level, .. }
            | GraphEdit::Disconnect { level, .. }
            | GraphEdit::SetInput { level, .. }
            | GraphEdit::SetLabel { level, .. }
            | GraphEdit::SetKind { level, .. }
            | GraphEdit::MoveNodes { level, .. } => Some(level),
            _ => None,
        }
    }

    /// The group whose definition the edit changes, if it is one group's (an edit of
    /// a group's contents makes a linked group local).
    pub(super) fn edited_group(&self) -> Option<&str> {
        if let Some(level) = self.node_level() {
            return level.group();
        }
        match self {
            GraphEdit::Arrange { level }
            | GraphEdit::Group { level, .. }
            | GraphEdit::Ungroup { level, .. } => level.group(),
            GraphEdit::AddGroupPin { group, .. }
            | GraphEdit::DropGroupPin { group, .. }
            | GraphEdit::SetGroupInput { group, .. }
            | GraphEdit::RenameGroupPin { group, .. }
            | GraphEdit::RemoveGroupPin { group, .. } => Some(group),
            // (Node and wire edits: their level's group, above.)
            _ => None,
        }
    }

    /// Whether `self` and `other` set the same thing (the same input, the same nodes'
    /// positions, the same setting…), so that during a drag the first one's inverse
    /// undoes both.
    pub fn same_target(&self, other: &GraphEdit) -> bool {
        use GraphEdit as E;
        match (self, other) {
            (
                E::SetInput {
                    level, node, pin, ..
                },
                E::SetInput {
                    level: l,
                    node: n,
                    pin: p,
                    ..
                },
            ) => (level, node, pin) == (l, n, p),
            (
                E::SetLabel { level, node, .. },
                E::SetLabel {
                    level: l, node: n, ..
                },
            )
            | (
                E::SetKind { level, node, .. },
                E::SetKind {
                    level: l, node: n, ..
                },
            ) => (level, node) == (l, n),
            (E::MoveNodes { level, moves }, E::MoveNodes { level: l, moves: m }) => {
                level == l && moves.len() == m.len() && moves.iter().zip(m).all(|(a, b)| a.0 == b.0)
            }
            (E::Set(a), E::Set(b)) => std::mem::discriminant(a) == std::mem::discriminant(b),
            (E::SetGroupInput { group, input }, E::SetGroupInput { group: g, input: i }) => {
                group == g && input.name == i.name
            }
            _ => false,
        }
    }
}
