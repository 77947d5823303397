//! Laying out random graphs: after arranging in rows of any size, and after laying out
//! nodes stacked on others, no two nodes' footprints (the rectangles the editor draws
//! them in) intersect; a node placed among them lands clear of every one.

use crate::properties::random_graph;
use proptest::prelude::*;
use std::collections::BTreeSet;
use veneer::graph::layout::{Footprint, Taken, arrange_in_rows, bounds, overlapping, unstack};
use veneer::graph::{Graph, Node, NodeKind, Value};

/// A random graph whose nodes' sizes vary: labels of random lengths (`seeds`), and
/// some unwired inputs holding large numbers.
fn varied_graph(kinds: &[u32], choices: &[u32], seeds: &[u32]) -> Graph {
    let mut graph = random_graph(kinds, choices, true);
    let mut seed = seeds.iter().cycle();
    for node in &mut graph.nodes {
        let pick = *seed.next().expect("seeds are not empty");
        node.label = "w".repeat(pick as usize % 40);
        if pick.is_multiple_of(3) {
            for pin in node.kind.signature().inputs {
                let large = f64::from(pick) * 1.0e-3 - 1.0e3;
                let value = Value::Vec3(large, -large, large).convert(pin.ty);
                node.inputs.insert(pin.name.to_string(), value);
            }
        }
    }
    graph
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn random_graphs_are_laid_out_without_nodes_over_each_other(
        kinds in prop::collection::vec(0u32..8192, 1..40),
        choices in prop::collection::vec(any::<u32>(), 1..64),
        seeds in prop::collection::vec(any::<u32>(), 1..16),
        stacks in prop::collection::vec((any::<usize>(), any::<usize>()), 0..30),
        width in 0.0f32..3000.0,
        height in 0.0f32..2000.0,
    ) {
        let mut graph = varied_graph(&kinds, &choices, &seeds);
        let mut unstacked = graph.clone();
        unstack(&mut unstacked.nodes, &unstacked.wires);
        prop_assert_eq!(overlapping(&unstacked.nodes, &unstacked.wires), None, "unstacked");
        arrange_in_rows(&mut graph, width, height);
        prop_assert_eq!(overlapping(&graph.nodes, &graph.wires), None, "arranged");
        // A new node wanted where the first one is lands clear of them all.
        let new = Node::new(graph.next_id(), NodeKind::Transform);
        let wanted = graph.nodes[0].position;
        let area = Footprint::of(&new, |_| false).at(wanted);
        let (dx, dy) = Taken::of(&graph.nodes, &graph.wires).clear_move(&[area]);
        let at = (wanted.0 + dx, wanted.1 + dy);
        let taken = bounds(&graph.nodes, &graph.wires);
        let placed = Footprint::of(&new, |_| false).at(at);
        prop_assert!(taken.iter().all(|b| !b.intersects(&placed)), "placed at {:?}", at);
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
        prop_assert_eq!(overlapping(&graph.nodes, &graph.wires), None, "restacked");
    }
}
