//! The side panel's inspector: the selected node's inputs, a group's interface, and the
//! graph's exposed parameters.

pub(in crate::app) mod body;
pub(in crate::app) mod frames;
pub(in crate::app) mod group;
pub(in crate::app) mod group_interface;
pub(in crate::app) mod node;
pub(in crate::app) mod parameters;
