//! Why an edit was refused.

use super::Level;
use crate::graph::{NodeId, PinRef, ValueType, Wire};

/// Why [`super::apply`] refused an edit (the graph is left as it was).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum EditError {
    #[error("no group named '{0}'")]
    UnknownGroup(String),
    #[error("{level} has no node {node}")]
    UnknownNode { level: Level, node: NodeId },
    #[error("{level}: node {node} has no {side} '{pin}'")]
    UnknownPin {
        level: Level,
        node: NodeId,
        side: &'static str,
        pin: String,
    },
    #[error("{level} has a node {node} already")]
    DuplicateId { level: Level, node: NodeId },
    #[error(
        "{level}: node id {} stands for the group's inputs and outputs",
        crate::graph::group::BOUNDARY
    )]
    BoundaryId { level: Level },
    #[error("{level}: the wire from {} to {} would close a cycle", end(&.wire.from), end(&.wire.to))]
    Cycle { level: Level, wire: Wire },
    #[error("{level}: cannot connect {} to {}: it gives {given} but the input expects {expected}", end(&.wire.from), end(&.wire.to))]
    Types {
        level: Level,
        wire: Wire,
        given: ValueType,
        expected: ValueType,
    },
    #[error("{level} has no wire from {} to {}", end(&.wire.from), end(&.wire.to))]
    UnknownWire { level: Level, wire: Wire },
    #[error("{level} has the wire from {} to {} already", end(&.wire.from), end(&.wire.to))]
    WireExists { level: Level, wire: Wire },
    #[error("{level}: input {} is wired already (connect replaces a wire)", end(.input))]
    InputWired { level: Level, input: PinRef },
    #[error("{level}: the wire from {} to {} reaches none of the nodes added", end(&.wire.from), end(&.wire.to))]
    StrayWire { level: Level, wire: Wire },
    #[error("{level}: node {node} is a {kind}; a node keeps its kind (and a group node its group)")]
    KindChange {
        level: Level,
        node: NodeId,
        kind: &'static str,
    },
    #[error("group '{group}' has no {side} {index}")]
    UnknownGroupPin {
        group: String,
        side: &'static str,
        index: usize,
    },
    /// What a graph operation said (grouping, renaming a group's pin, a preset…).
    #[error("{0}")]
    Refused(String),
}

/// A pin as messages name it: `#3.value`.
fn end(pin: &PinRef) -> String {
    format!("{}.{}", pin.node, pin.pin)
}
