//! What each node thumbnail depends on, worked out for the whole graph in one pass each
//! (linear in nodes and wires, so graphs of thousands of nodes cost no more per node
//! than small ones): a hash of everything upstream of each node, and which tiles fit
//! one atlas.

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

/// The tiles that fit one atlas ([`within_atlas`]).
pub struct Fit {
    /// The pins kept, in order.
    pub pins: Vec<crate::graph::PinRef>,
    /// The nodes of the pins left out.
    pub too_deep: FxHashSet<NodeId>,
    /// Every node upstream of the pins kept, themselves included: what the atlas copies.
    pub upstream: FxHashSet<NodeId>,
}

/// The pins of `pins` whose tiles fit an atlas of at most `limit` graph nodes, the
/// nodes of those that do not, and the nodes the kept ones read. Pins are taken in order, each adding the nodes upstream
/// of it that no pin before it needed; one that would take the atlas past `limit` is
/// left out (the walk over its nodes stops there, so the work is at most `limit` nodes
/// a pin). The atlas is one shader: a tile of a node 5,000 deep in a chain made it a
/// shader of 5,000 nodes, which lavapipe took over 20 seconds to compile.
pub fn within_atlas(graph: &Graph, pins: &[crate::graph::PinRef], limit: usize) -> Fit {
    let sources = graph.linked(|wire| (wire.to.node, wire.from.node));
    let mut taken: FxHashSet<NodeId> = FxHashSet::default();
    let (mut kept, mut left_out) = (Vec::new(), FxHashSet::default());
    for pin in pins {
        let mut new: FxHashSet<NodeId> = FxHashSet::default();
        let mut stack = vec![pin.node];
        while let Some(node) = stack.pop() {
            if taken.len() + new.len() > limit {
                break;
            }
            if !taken.contains(&node) && new.insert(node) {
                stack.extend(sources.get(&node).into_iter().flatten().copied());
            }
        }
        if taken.len() + new.len() > limit {
            left_out.insert(pin.node);
        } else {
            taken.extend(new);
            kept.push(pin.clone());
        }
    }
    Fit {
        pins: kept,
        too_deep: left_out,
        upstream: taken,
    }
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
        assert_eq!(graph.downstream([graph.nodes[50_000].id]).len(), 50_001);
    }

    #[test]
    fn tiles_fit_the_atlas_in_order_and_deep_ones_are_left_out() {
        // start → n1 → … → n9: node k has k + 1 nodes upstream of it, itself included.
        let mut graph = Graph::default();
        let mut chain = vec![graph.add("start", NodeKind::Position)];
        for k in 1..10 {
            let node = graph.add(&format!("n{k}"), NodeKind::Transform);
            let from = if k == 1 { "position" } else { "p" };
            graph.connect(chain[k - 1], from, node, "p");
            chain.push(node);
        }
        let pin = |k: usize| crate::graph::PinRef::new(chain[k], "p");
        // n2 needs 3 nodes, n4 two more, n8 four more: 9 > 6, left out.
        let fit = within_atlas(&graph, &[pin(2), pin(4), pin(8), pin(5)], 6);
        assert_eq!(fit.pins, [pin(2), pin(4), pin(5)]);
        assert_eq!(fit.too_deep, FxHashSet::from_iter([chain[8]]));
        assert_eq!(fit.upstream, graph.upstream([chain[5]]), "what n5 reads");
        // Shared nodes count once: n9 alone fits 10 nodes, and n3 then adds none.
        let fit = within_atlas(&graph, &[pin(9), pin(3)], 10);
        assert_eq!((fit.pins.len(), fit.too_deep.len()), (2, 0));
    }
}
