//! The boundary nodes shown inside a group (*Group input*, *Group output*) and how the
//! view tells them, and their "+" pins, from group instances.

use crate::graph::Node;
use crate::graph::group::{BOUNDARY, group_name};

/// The name of the empty pin a wire is dropped on to add a group input or output.
pub(in crate::app) const ADD_PIN: &str = "+";

/// Which boundary node a node of the view is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Boundary {
    /// *Group input*: outputs are the group's inputs.
    Input,
    /// *Group output*: inputs are the group's outputs.
    Output,
}

impl Boundary {
    /// The group name that marks the boundary node (no group can be used by it: names
    /// in angle brackets are never given to groups).
    pub(in crate::app) fn mark(self) -> &'static str {
        match self {
            Boundary::Input => "<group input>",
            Boundary::Output => "<group output>",
        }
    }

    pub(in crate::app) fn label(self) -> &'static str {
        match self {
            Boundary::Input => "Group input",
            Boundary::Output => "Group output",
        }
    }
}

/// Which boundary node `node` is, if it is one.
pub fn boundary(node: &Node) -> Option<Boundary> {
    let name = group_name(node).filter(|_| node.id == BOUNDARY)?;
    [Boundary::Input, Boundary::Output]
        .into_iter()
        .find(|side| side.mark() == name)
}

/// Whether `node` is an instance of a group (not a boundary node).
pub fn is_instance(node: &Node) -> bool {
    group_name(node).is_some() && boundary(node).is_none()
}

/// Whether pin `pin` of `node` is a boundary node's "+".
pub fn is_add_pin(node: &Node, pin: &str) -> bool {
    pin == ADD_PIN && boundary(node).is_some()
}
