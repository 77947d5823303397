//! How a graph's groups nest: every group after the groups it uses (the order their
//! interfaces, inlining and group functions are built in), found with an explicit stack
//! rather than recursion, whatever the file holds, and the limits that keep a small
//! file from nesting or multiplying without end.

use super::Node;
use super::group::{GroupDef, GroupError, group_name};
use super::names::{chain, shown};
use crate::messages::thousands;
use std::collections::BTreeMap;

/// The most levels groups nest: a group whose definition holds no group node is one
/// level, one holding a node of that group two, and so on. Rendering a graph drives
/// the GPU driver's compiler through a call chain as deep (llvmpipe needs 0.97 GB for
/// 1,000 levels, growing with the square of the depth).
pub const MAX_GROUP_DEPTH: usize = 32;

/// The most nodes a graph's group nodes may stand for together: a group node stands
/// for every node of its group, so a few kilobytes of nested groups could otherwise
/// stand for billions. The driver compiles them all, as it would a graph file of as
/// many nodes (llvmpipe renders 262,143 inlined nodes in 14 s and 1.6 GB, a chain of
/// as many in a file in 28 s and 1.5 GB).
pub const MAX_INLINED_NODES: u64 = 300_000;

/// What walking the nesting found.
pub struct Nesting<'g> {
    /// The groups that nest properly (no cycle through them, every group they use
    /// exists and nests properly, at most [`MAX_GROUP_DEPTH`] levels), each after the
    /// groups it uses.
    pub order: Vec<&'g str>,
    /// Per group that nests properly: the nodes an instance stands for once inlined,
    /// counted up to just past [`MAX_INLINED_NODES`].
    sizes: BTreeMap<&'g str, u64>,
    /// The first problem: a cycle, an unknown group, or groups nested too deep.
    pub error: Option<GroupError>,
}

impl Nesting<'_> {
    /// How many nodes the group nodes among `nodes` (a level) stand for once inlined,
    /// counted up to just past [`MAX_INLINED_NODES`].
    pub fn inlined(&self, nodes: &[Node]) -> u64 {
        let count = nodes.iter().fold(0u64, |sum, node| {
            let size =
                group_name(node).map_or(0, |name| self.sizes.get(name).copied().unwrap_or(0));
            sum.saturating_add(size)
        });
        count.min(MAX_INLINED_NODES + 1)
    }

    /// The error for a level of `nodes` whose group nodes stand for more than
    /// [`MAX_INLINED_NODES`], if they do.
    pub fn too_many_nodes(&self, nodes: &[Node]) -> Option<GroupError> {
        (self.inlined(nodes) > MAX_INLINED_NODES).then(|| GroupError {
            node_name: None,
            message: format!(
                "the graph's group nodes stand for more than {} nodes, the most they may \
                 (each group node stands for every node of its group)",
                thousands(MAX_INLINED_NODES as usize)
            ),
        })
    }
}

/// Where the walk stands in one group.
struct Frame<'g> {
    name: &'g str,
    /// The group nodes of its definition, by id.
    inner: Vec<&'g Node>,
    next: usize,
    /// Whether something it uses does not nest properly.
    broken: bool,
    /// Levels it nests (1: no group node inside) and the group it uses that nests
    /// deepest.
    depth: usize,
    deepest: Option<&'g str>,
    size: u64,
}

/// What is known of a group once its walk ends.
#[derive(Clone, Copy)]
struct Walked<'g> {
    ok: bool,
    depth: usize,
    deepest: Option<&'g str>,
    size: u64,
}

impl<'g> Frame<'g> {
    fn new(name: &'g str, definition: &'g GroupDef) -> Frame<'g> {
        let mut inner: Vec<&Node> = definition
            .nodes
            .iter()
            .filter(|node| group_name(node).is_some())
            .collect();
        inner.sort_by_key(|node| node.id);
        let size = (definition.nodes.len() - inner.len()) as u64;
        Frame {
            name,
            inner,
            next: 0,
            broken: false,
            depth: 1,
            deepest: None,
            size,
        }
    }

    /// Takes in what is known of a group it uses.
    fn take_in(&mut self, used: &'g str, walked: Walked<'g>) {
        self.broken |= !walked.ok;
        if walked.depth + 1 > self.depth {
            self.depth = walked.depth + 1;
            self.deepest = Some(used);
        }
        self.size = self
            .size
            .saturating_add(walked.size)
            .min(MAX_INLINED_NODES + 1);
    }
}

/// Walks the groups of `groups` depth first (in name order, the group nodes of each
/// definition by id), without recursion.
pub fn nesting(groups: &BTreeMap<String, GroupDef>) -> Nesting<'_> {
    let mut nesting = Nesting {
        order: Vec::new(),
        sizes: BTreeMap::new(),
        error: None,
    };
    let mut walked: BTreeMap<&str, Walked> = BTreeMap::new();
    // Position on the stack of the groups being walked.
    let mut on_stack: BTreeMap<&str, usize> = BTreeMap::new();
    for (root, definition) in groups {
        if walked.contains_key(root.as_str()) {
            continue;
        }
        let mut stack = vec![Frame::new(root, definition)];
        on_stack.insert(root, 0);
        while let Some(top) = stack.last_mut() {
            let Some(node) = top.inner.get(top.next).copied() else {
                let frame = stack.pop().expect("the top frame");
                on_stack.remove(frame.name);
                let done = Walked {
                    ok: !frame.broken && frame.depth <= MAX_GROUP_DEPTH,
                    depth: frame.depth,
                    deepest: frame.deepest,
                    size: frame.size,
                };
                if done.ok {
                    nesting.order.push(frame.name);
                    nesting.sizes.insert(frame.name, frame.size);
                }
                walked.insert(frame.name, done);
                if let Some(parent) = stack.last_mut() {
                    parent.take_in(frame.name, done);
                }
                continue;
            };
            top.next += 1;
            let used = group_name(node).unwrap_or_default();
            let Some((used, definition)) = groups.get_key_value(used) else {
                top.broken = true;
                let error = GroupError {
                    node_name: Some(format!("group '{}' › {node}", shown(top.name))),
                    message: format!("no group named '{}' in the graph", shown(used)),
                };
                nesting.error.get_or_insert(error);
                continue;
            };
            if let Some(done) = walked.get(used.as_str()) {
                top.take_in(used, *done);
            } else if let Some(&start) = on_stack.get(used.as_str()) {
                top.broken = true;
                let mut names: Vec<&str> = stack[start..].iter().map(|frame| frame.name).collect();
                names.push(used);
                let error = GroupError {
                    node_name: None,
                    message: format!(
                        "groups contain themselves: {} (a group cannot be used inside itself)",
                        chain(&names)
                    ),
                };
                nesting.error.get_or_insert(error);
            } else {
                on_stack.insert(used, stack.len());
                stack.push(Frame::new(used, definition));
            }
        }
    }
    if nesting.error.is_none() {
        nesting.error = too_deep(&walked);
    }
    nesting
}

/// The error for the deepest group past [`MAX_GROUP_DEPTH`], with the chain of groups
/// that makes it so deep.
fn too_deep(walked: &BTreeMap<&str, Walked>) -> Option<GroupError> {
    let (mut name, deepest) = walked
        .iter()
        .filter(|(_, walked)| walked.depth > MAX_GROUP_DEPTH)
        .max_by_key(|(name, walked)| (walked.depth, std::cmp::Reverse(*name)))
        .map(|(name, walked)| (*name, *walked))?;
    let mut names = vec![name];
    while let Some(next) = walked.get(name).and_then(|walked| walked.deepest) {
        names.push(next);
        name = next;
    }
    Some(GroupError {
        node_name: None,
        message: format!(
            "groups nest {} levels deep, more than {MAX_GROUP_DEPTH}: {}",
            thousands(deepest.depth),
            chain(&names)
        ),
    })
}
