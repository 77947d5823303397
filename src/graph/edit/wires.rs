//! Wiring: connecting (replacing the wire into the input), disconnecting, and what a
//! new wire must satisfy (pins that exist, types that convert, no cycle).

use super::level::{Contents, contents};
use super::{Applied, Change, EditError, GraphEdit, Level};
use crate::graph::group_interface::Side;
use crate::graph::{Graph, NodeId, Wire};
use std::collections::{HashMap, HashSet};

/// Connects `wire`, replacing the wires into its input.
pub(super) fn connect(graph: &mut Graph, level: Level, wire: Wire) -> Result<Applied, EditError> {
    let mut at = contents(graph, &level)?;
    check_pins(&at, &wire)?;
    let replaced: Vec<Wire> = at
        .wires
        .iter()
        .filter(|w| w.to == wire.to)
        .cloned()
        .collect();
    if replaced == [wire.clone()] {
        return Ok(Applied::unchanged(GraphEdit::Connect { level, wire }));
    }
    let kept = at.wires.iter().filter(|w| w.to != wire.to);
    if cycle_through(&at, kept.chain([&wire]), &[wire.to.node]).is_some() {
        return Err(EditError::Cycle { level, wire });
    }
    at.wires.retain(|w| w.to != wire.to);
    at.insert_wire(wire.clone());
    super::level::settle(graph, &level);
    let disconnect = GraphEdit::Disconnect {
        level: level.clone(),
        wires: vec![wire],
    };
    let inverse = if replaced.is_empty() {
        disconnect
    } else {
        let restore = GraphEdit::Restore {
            level,
            nodes: Vec::new(),
            wires: replaced,
        };
        GraphEdit::Batch(vec![disconnect, restore])
    };
    Ok(Applied::new(inverse, Change::Structure))
}

/// Removes `wires`, each of which must be there.
pub(super) fn disconnect(
    graph: &mut Graph,
    level: Level,
    wires: Vec<Wire>,
) -> Result<Applied, EditError> {
    let at = contents(graph, &level)?;
    let mut listed = HashSet::new();
    for wire in &wires {
        if !at.has_wire(wire) || !listed.insert(wire) {
            return Err(EditError::UnknownWire {
                level,
                wire: wire.clone(),
            });
        }
    }
    at.wires.retain(|wire| !listed.contains(wire));
    super::level::settle(graph, &level);
    let inverse = GraphEdit::Restore {
        level,
        nodes: Vec::new(),
        wires,
    };
    Ok(Applied::new(inverse, Change::Structure))
}

/// Refuses `wire` unless it runs from an output to an input that exist, of types that
/// convert.
pub(super) fn check_pins(at: &Contents, wire: &Wire) -> Result<(), EditError> {
    let given = at.pin_type(&wire.from, Side::Output)?;
    let expected = at.pin_type(&wire.to, Side::Input)?;
    if given.converts_to(expected) {
        Ok(())
    } else {
        Err(EditError::Types {
            level: at.level.clone(),
            wire: wire.clone(),
            given,
            expected,
        })
    }
}

/// The first of `starts` that lies on a cycle of `wires` (a group's boundary never
/// does: what enters the group does not come from what leaves it). Linear in the wires
/// (Tarjan's strongly connected components, without recursion, from `starts` only).
pub(super) fn cycle_through<'w>(
    at: &Contents,
    wires: impl Iterator<Item = &'w Wire>,
    starts: &[NodeId],
) -> Option<NodeId> {
    let mut next: HashMap<NodeId, Vec<NodeId>> = HashMap::new();
    for wire in wires {
        let (from, to) = (wire.from.node, wire.to.node);
        if from == to && !at.is_boundary(from) {
            if starts.contains(&from) {
                return Some(from);
            }
            continue;
        }
        if !at.is_boundary(from) && !at.is_boundary(to) {
            next.entry(from).or_default().push(to);
        }
    }
    Tarjan::new(&next).first_on_cycle(starts)
}

/// A walk of the graph finding strongly connected components.
struct Tarjan<'n> {
    next: &'n HashMap<NodeId, Vec<NodeId>>,
    /// Per node visited: the order it was reached in, and the lowest order it reaches.
    order: HashMap<NodeId, (usize, usize)>,
    stack: Vec<NodeId>,
    on_stack: HashSet<NodeId>,
}

impl<'n> Tarjan<'n> {
    fn new(next: &'n HashMap<NodeId, Vec<NodeId>>) -> Tarjan<'n> {
        Tarjan {
            next,
            order: HashMap::new(),
            stack: Vec::new(),
            on_stack: HashSet::new(),
        }
    }

    fn visit(&mut self, node: NodeId) {
        let count = self.order.len();
        self.order.insert(node, (count, count));
        self.stack.push(node);
        self.on_stack.insert(node);
    }

    fn lower(&mut self, node: NodeId, to: usize) {
        if let Some((_, low)) = self.order.get_mut(&node) {
            *low = (*low).min(to);
        }
    }

    /// The first of `starts` in a component of more than one node.
    fn first_on_cycle(mut self, starts: &[NodeId]) -> Option<NodeId> {
        let wanted: HashSet<NodeId> = starts.iter().copied().collect();
        for &root in starts {
            if self.order.contains_key(&root) {
                continue;
            }
            self.visit(root);
            let mut calls: Vec<(NodeId, usize)> = vec![(root, 0)];
            while let Some(&mut (node, ref mut child)) = calls.last_mut() {
                let next = self.next;
                let successors = next.get(&node).map_or(&[][..], Vec::as_slice);
                if let Some(&to) = successors.get(*child) {
                    *child += 1;
                    match self.order.get(&to) {
                        None => {
                            self.visit(to);
                            calls.push((to, 0));
                        }
                        Some(&(reached, _)) if self.on_stack.contains(&to) => {
                            self.lower(node, reached);
                        }
                        Some(_) => {}
                    }
                    continue;
                }
                calls.pop();
                let (reached, low) = self.order[&node];
                if let Some(&(parent, _)) = calls.last() {
                    self.lower(parent, low);
                }
                if low == reached {
                    let at = self.stack.iter().rposition(|n| *n == node).unwrap_or(0);
                    let component = self.stack.split_off(at);
                    for member in &component {
                        self.on_stack.remove(member);
                    }
                    if component.len() > 1
                        && let Some(start) = component.iter().find(|n| wanted.contains(n))
                    {
                        return Some(*start);
                    }
                }
            }
        }
        None
    }
}

/// Whether `id` may be a node of the level: not the boundary's id inside a group.
pub(super) fn check_id(at: &Contents, id: NodeId) -> Result<(), EditError> {
    if at.is_boundary(id) {
        return Err(EditError::BoundaryId {
            level: at.level.clone(),
        });
    }
    Ok(())
}
