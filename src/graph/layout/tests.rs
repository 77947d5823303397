//! No two footprints intersect: in every shipped preset and the groups it defines, and
//! after arranging them in rows of any size (random graphs: the engine's tests).

use super::*;
use crate::graph::{Graph, Node, Wire};

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
            assert_eq!(overlapping(nodes, wires), None, "{name}{level}");
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
                let found = overlapping(nodes, wires);
                assert_eq!(found, None, "{name}{level} in {width} × {height}");
            }
        }
    }
}
