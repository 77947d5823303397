//! The levels of a graph an edit is made at (the top level, a group's definition) and
//! the contents of one: its nodes, in id order, and wires, sorted.

use super::EditError;
use crate::graph::group::{BOUNDARY, GroupInput, GroupOutput};
use crate::graph::group_interface::Side;
use crate::graph::{Graph, Node, NodeId, PinRef, ValueType, Wire};
use std::cmp::Ordering;
use std::fmt;

/// Where in a graph a node edit is made.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Level {
    /// The graph's own nodes.
    Top,
    /// The definition of the group of this name.
    Group(String),
}

impl Level {
    /// The group whose definition it is, if it is one.
    pub fn group(&self) -> Option<&str> {
        match self {
            Level::Top => None,
            Level::Group(name) => Some(name),
        }
    }
}

impl fmt::Display for Level {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Level::Top => f.write_str("the graph"),
            Level::Group(name) => write!(f, "group '{name}'"),
        }
    }
}

/// The contents of one level, to edit.
pub(super) struct Contents<'g> {
    pub level: &'g Level,
    pub nodes: &'g mut Vec<Node>,
    pub wires: &'g mut Vec<Wire>,
    /// A group definition's declared inputs and outputs (the pins of its boundary);
    /// `None` at the top level.
    boundary: Option<(&'g [GroupInput], &'g [GroupOutput])>,
}

/// The contents of `level` of `graph`.
pub(super) fn contents<'g>(
    graph: &'g mut Graph,
    level: &'g Level,
) -> Result<Contents<'g>, EditError> {
    Ok(match level {
        Level::Top => Contents {
            level,
            nodes: &mut graph.nodes,
            wires: &mut graph.wires,
            boundary: None,
        },
        Level::Group(name) => {
            let definition = graph
                .groups
                .get_mut(name)
                .ok_or_else(|| EditError::UnknownGroup(name.clone()))?;
            Contents {
                level,
                nodes: &mut definition.nodes,
                wires: &mut definition.wires,
                boundary: Some((&definition.inputs, &definition.outputs)),
            }
        }
    })
}

impl Contents<'_> {
    /// Whether `id` stands for the group's boundary here.
    pub fn is_boundary(&self, id: NodeId) -> bool {
        self.boundary.is_some() && id == BOUNDARY
    }

    /// The index of the (first) node with `id`.
    pub fn position(&self, id: NodeId) -> Option<usize> {
        let at = self.nodes.partition_point(|node| node.id < id);
        (self.nodes.get(at)?.id == id).then_some(at)
    }

    /// The index of the node with `id`, or why there is none.
    pub fn find(&self, id: NodeId) -> Result<usize, EditError> {
        self.position(id).ok_or_else(|| EditError::UnknownNode {
            level: self.level.clone(),
            node: id,
        })
    }

    /// Puts `nodes` in their places in id order (after the nodes of their ids, in
    /// the order given), on whole canvas units.
    pub fn insert_nodes(&mut self, nodes: Vec<Node>) {
        let rounded = nodes.into_iter().map(|mut node| {
            node.position = (node.position.0.round(), node.position.1.round());
            node
        });
        insert_sorted(self.nodes, rounded.collect(), |a, b| a.id.cmp(&b.id));
    }

    /// Puts `wires`, none of which is there yet, in their places in sorted order.
    pub fn insert_wires(&mut self, wires: Vec<Wire>) {
        insert_sorted(self.wires, wires, Wire::cmp);
    }

    /// Puts `wire` in its place in sorted order, unless it is there already.
    pub fn insert_wire(&mut self, wire: Wire) {
        if let Err(at) = self.wires.binary_search(&wire) {
            self.wires.insert(at, wire);
        }
    }

    /// Whether `wire` is there.
    pub fn has_wire(&self, wire: &Wire) -> bool {
        self.wires.binary_search(wire).is_ok()
    }

    /// The type of pin `pin` on `side` of its node: a node's input or output, or at a
    /// group's boundary, a group output fed (an input of the boundary) or a group input
    /// read (an output of it).
    pub fn pin_type(&self, pin: &PinRef, side: Side) -> Result<ValueType, EditError> {
        let found = match (self.boundary, side) {
            (Some((inputs, _)), Side::Output) if pin.node == BOUNDARY => {
                inputs.iter().find(|i| i.name == pin.pin).map(|i| i.ty)
            }
            (Some((_, outputs)), Side::Input) if pin.node == BOUNDARY => {
                outputs.iter().find(|o| o.name == pin.pin).map(|o| o.ty)
            }
            _ => {
                let signature = self.nodes[self.find(pin.node)?].kind.signature();
                match side {
                    Side::Input => signature.input(&pin.pin).map(|(_, input)| input.ty),
                    Side::Output => signature.output(&pin.pin).map(|(_, output)| output.ty),
                }
            }
        };
        found.ok_or_else(|| EditError::UnknownPin {
            level: self.level.clone(),
            node: pin.node,
            side: side.word(),
            pin: pin.pin.clone(),
        })
    }
}

/// Brings every group node's pins up to date after an edit inside group `level`: what
/// a group's definition holds (its inner group nodes, their unwired inputs and their
/// values) makes the pins of the groups around it. Nothing to do at the top level.
pub(super) fn settle(graph: &mut Graph, level: &Level) {
    if level.group().is_some() {
        crate::graph::group::resolve(graph);
    }
}

/// Puts `items` into `sorted` (in the order `order` gives) after the equal ones already
/// there, keeping their order: one by one when they are few, else appended and sorted
/// (a stable sort, linear on a sorted run and a short one).
fn insert_sorted<T>(sorted: &mut Vec<T>, items: Vec<T>, order: impl Fn(&T, &T) -> Ordering) {
    if items.len() <= 8 {
        for item in items {
            let at = sorted.partition_point(|other| order(other, &item) != Ordering::Greater);
            sorted.insert(at, item);
        }
    } else {
        sorted.extend(items);
        sorted.sort_by(order);
    }
}
