//! No two footprints intersect: in every shipped preset and the groups it defines, and
//! after every way of laying nodes out, on the presets and on random graphs.

use super::*;
use crate::graph::{Graph, Node, NodeId, NodeKind, PinRef, Value, Wire};
use proptest::prelude::*;
use std::collections::BTreeSet;

/// Two nodes of `nodes` (joined by `wires`) whose footprints intersect, if any.
pub(super) fn overlap(nodes: &[Node], wires: &[Wire]) -> Option<(NodeId, NodeId)> {
    let drawn = bounds(nodes, wires);
    let mut order: Vec<usize> = (0..nodes.len()).collect();
    order.sort_by(|a, b| drawn[*a].min.0.total_cmp(&drawn[*b].min.0));
    // A sweep from left to right: only nodes whose spans in x meet are compared.
    for (k, &a) in order.iter().enumerate() {
        for &b in &order[k + 1..] {
            if drawn[b].min.0 >= drawn[a].max.0 {
                break;
            }
            if drawn[a].intersects(&drawn[b]) {
                return Some((nodes[a].id, nodes[b].id));
            }
        }
    }
    None
}

/// Every level of `graph`: its own nodes and each group definition's, named.
fn levels(graph: &Graph) -> Vec<(String, &[Node], &[Wire])> {
    let top = (String::new(), &graph.nodes[..], &graph.wires[..]);
    let groups = graph
        .groups
        .iter()
        .map(|(name, group)| (format!(" › {name}"), &group.nodes[..], &group.wires[..]));
    std::iter::once(top).chain(groups).collect()
}

/// Every preset, by name.
fn presets() -> impl Iterator<Item = (&'static str, Graph)> {
    crate::graph::PRESETS
        .iter()
        .map(|(name, _)| (*name, crate::graph::preset(name).expect("presets load")))
}

#[test]
fn no_shipped_preset_has_nodes_over_each_other() {
    for (name, graph) in presets() {
        for (level, nodes, wires) in levels(&graph) {
            assert_eq!(overlap(nodes, wires), None, "{name}{level}");
        }
    }
}

#[test]
fn arranging_a_preset_in_any_rows_leaves_no_nodes_over_each_other() {
    let limits = [
        (f32::INFINITY, f32::INFINITY),
        (1620.0, 1000.0),
        (400.0, 300.0),
        (0.0, 0.0),
    ];
    for (name, preset) in presets() {
        for (width, height) in limits {
            let mut graph = preset.clone();
            arrange_in_rows(&mut graph, width, height);
            arrange_groups(&mut graph, width, height);
            for (level, nodes, wires) in levels(&graph) {
                let found = overlap(nodes, wires);
                assert_eq!(found, None, "{name}{level} in {width} × {height}");
            }
        }
    }
}

/// A random level, every node at the origin: nodes of every kind the tests cover,
/// picked by `kinds`, with labels of random lengths, values, and wires from earlier
/// nodes' outputs picked by `choices`.
fn random_level(kinds: &[u32], choices: &[u32]) -> Graph {
    let examples = NodeKind::examples();
    let mut graph = Graph::default();
    let mut outputs: Vec<(NodeId, &'static str, crate::graph::ValueType)> = Vec::new();
    let mut choice = choices.iter().cycle();
    for &seed in kinds {
        let kind = examples[seed as usize % examples.len()].clone();
        let signature = kind.signature();
        let label = "w".repeat(seed as usize % 40);
        let node = graph.add(&label, kind);
        for pin in &signature.inputs {
            let pick = *choice.next().expect("choices are not empty");
            let candidates: Vec<_> = outputs
                .iter()
                .filter(|(_, _, ty)| ty.converts_to(pin.ty))
                .collect();
            if pick % 3 != 0 && !candidates.is_empty() {
                let (from, name, _) = candidates[pick as usize % candidates.len()];
                graph.wires.push(Wire {
                    from: PinRef::new(*from, name),
                    to: PinRef::new(node, pin.name),
                });
            } else if pick % 5 == 0 {
                let big = f64::from(pick) * 1.0e-3 - 1.0e3;
                graph.set_input(node, pin.name, Value::Vec3(big, -big, big).convert(pin.ty));
            }
        }
        outputs.extend(signature.outputs.iter().map(|pin| (node, pin.name, pin.ty)));
    }
    graph
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn random_levels_are_laid_out_without_nodes_over_each_other(
        kinds in prop::collection::vec(0u32..4096, 1..40),
        choices in prop::collection::vec(any::<u32>(), 1..64),
        stacks in prop::collection::vec((any::<usize>(), any::<usize>()), 0..30),
        width in 0.0f32..3000.0,
        height in 0.0f32..2000.0,
    ) {
        let mut graph = random_level(&kinds, &choices);
        let mut unstacked = graph.clone();
        unstack(&mut unstacked.nodes, &unstacked.wires);
        prop_assert_eq!(overlap(&unstacked.nodes, &unstacked.wires), None, "unstacked");
        arrange_in_rows(&mut graph, width, height);
        prop_assert_eq!(overlap(&graph.nodes, &graph.wires), None, "arranged");
        // Some nodes put right on earlier ones, which stay: laid out again, below the
        // rest or all anew.
        let count = graph.nodes.len();
        let (mut moved, mut stayed) = (BTreeSet::new(), BTreeSet::new());
        for (from, onto) in stacks {
            let (from, onto) = (from % count, onto % count);
            if onto < from && !moved.contains(&onto) && !stayed.contains(&from) {
                graph.nodes[from].position = graph.nodes[onto].position;
                moved.insert(from);
                stayed.insert(onto);
            }
        }
        unstack(&mut graph.nodes, &graph.wires);
        prop_assert_eq!(overlap(&graph.nodes, &graph.wires), None, "restacked");
    }
}
