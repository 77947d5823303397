//! What each node thumbnail depends on, worked out for the whole graph in one pass each
//! (linear in nodes and wires, so graphs of thousands of nodes cost no more per node
//! than small ones): a hash of everything upstream of each node, and the nodes that
//! read, directly or not, a node that fails to compile.

use crate::graph::{Graph, NodeId, NodeKind};
use rustc_hash::{FxHashMap, FxHashSet};
use std::hash::{Hash, Hasher};

/// For every node, a hash of what its outputs depend on: its kind, settings and
/// constants, those of every node upstream and the wires between them, and `time` for
/// nodes that read it (directly or through a node upstream).
pub fn upstream_hashes(graph: &Graph, time: f32) -> FxHashMap<NodeId, u64> {
    let mut reads: FxHashMap<NodeId, Vec<(usize, &crate::graph::Wire)>> = FxHashMap::default();
    for (index, wire) in graph.wires.iter().enumerate() {
        reads.entry(wire.to.node).or_default().push((index, wire));
    }
    let own: FxHashMap<NodeId, u64> = graph
        .nodes
        .iter()
        .map(|node| {
            let mut hasher = rustc_hash::FxHasher::default();
            format!("{:?}{:?}", node.kind, node.inputs).hash(&mut hasher);
            if node.kind == NodeKind::Time {
                time.to_bits().hash(&mut hasher);
            }
            (node.id, hasher.finish())
        })
        .collect();
    let mut hashes: FxHashMap<NodeId, u64> = FxHashMap::default();
    // Depth first without recursion (chains may be thousands of nodes long); a node met
    // again while its inputs are still being walked (a cycle, which checks refuse) adds
    // nothing more.
    let mut entered: FxHashSet<NodeId> = FxHashSet::default();
    for node in &graph.nodes {
        let mut stack = vec![(node.id, false)];
        while let Some((id, inputs_done)) = stack.pop() {
            if hashes.contains_key(&id) {
                continue;
            }
            let sources = reads.get(&id).map(Vec::as_slice).unwrap_or_default();
            if !inputs_done {
                if !entered.insert(id) {
                    continue;
                }
                stack.push((id, true));
                for (_, wire) in sources {
                    if !hashes.contains_key(&wire.from.node) {
                        stack.push((wire.from.node, false));
                    }
                }
                continue;
            }
            let mut hasher = rustc_hash::FxHasher::default();
            own.get(&id).hash(&mut hasher);
            for (_, wire) in sources {
                wire.hash(&mut hasher);
                hashes.get(&wire.from.node).hash(&mut hasher);
            }
            hashes.insert(id, hasher.finish());
        }
    }
    hashes
}

/// `broken` and every node that reads one of them, directly or not.
pub fn downstream_of(
    graph: &Graph,
    broken: &std::collections::BTreeSet<NodeId>,
) -> FxHashSet<NodeId> {
    let mut readers: FxHashMap<NodeId, Vec<NodeId>> = FxHashMap::default();
    for wire in &graph.wires {
        readers
            .entry(wire.from.node)
            .or_default()
            .push(wire.to.node);
    }
    let mut reached: FxHashSet<NodeId> = FxHashSet::default();
    let mut stack: Vec<NodeId> = broken.iter().copied().collect();
    while let Some(node) = stack.pop() {
        if reached.insert(node) {
            stack.extend(readers.get(&node).into_iter().flatten().copied());
        }
    }
    reached
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::graph::Value;

    /// position → a (transform) → b (transform) → material; time → unused.
    fn chain() -> (Graph, [NodeId; 4]) {
        let mut graph = Graph::default();
        let position = graph.add("position", NodeKind::Position);
        let a = graph.add("a", NodeKind::Transform);
        let b = graph.add("b", NodeKind::Transform);
        let time = graph.add("time", NodeKind::Time);
        graph.connect(position, "position", a, "p");
        graph.connect(a, "p", b, "p");
        (graph, [position, a, b, time])
    }

    #[test]
    fn a_hash_changes_with_what_is_upstream_and_only_that() {
        let (mut graph, [position, a, b, time]) = chain();
        let before = upstream_hashes(&graph, 0.0);
        graph.set_input(b, "scale", Value::Vec3(2.0, 2.0, 2.0));
        let after = upstream_hashes(&graph, 0.0);
        assert_eq!(before[&position], after[&position]);
        assert_eq!(before[&a], after[&a]);
        assert_ne!(before[&b], after[&b]);
        let later = upstream_hashes(&graph, 1.0);
        assert_ne!(later[&time], after[&time], "time moves what reads it");
        assert_eq!(later[&b], after[&b], "and nothing else");
    }

    #[test]
    fn a_chain_of_a_hundred_thousand_nodes_is_walked_without_recursion() {
        let mut graph = Graph::default();
        let mut previous = NodeId(1);
        graph
            .nodes
            .push(crate::graph::Node::new(previous, NodeKind::Position));
        let mut pin = "position";
        for k in 0..100_000 {
            let next = NodeId(k + 2);
            graph
                .nodes
                .push(crate::graph::Node::new(next, NodeKind::Transform));
            graph.wires.push(crate::graph::Wire {
                from: crate::graph::PinRef::new(previous, pin),
                to: crate::graph::PinRef::new(next, "p"),
            });
            previous = next;
            pin = "p";
        }
        assert_eq!(upstream_hashes(&graph, 0.0).len(), 100_001);
        let broken = [graph.nodes[50_000].id].into_iter().collect();
        assert_eq!(downstream_of(&graph, &broken).len(), 50_001);
    }
}
