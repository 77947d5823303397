//! The graph behind a node's thumbnail: the same graph with the node's first output
//! shown as the material's albedo.

use crate::graph::{Graph, NodeId, NodeKind, ValueType};
use crate::nodes::{Combine, Split};

/// `graph` with the first output of `node` wired into the material's albedo (a vec2 as
/// red and green), or `None` for the material node itself and nodes without outputs.
pub fn probe_graph(graph: &Graph, node: NodeId) -> Option<Graph> {
    let output = *graph.node(node)?.kind.signature().outputs.first()?;
    let material = graph
        .nodes
        .iter()
        .find(|n| n.kind == NodeKind::Material)?
        .id;
    let mut probe = graph.clone();
    if output.ty == ValueType::Vec2 {
        let split = probe.add(
            "probe split",
            NodeKind::Split(Split {
                ty: ValueType::Vec2,
            }),
        );
        let combine = probe.add(
            "probe colour",
            NodeKind::Combine(Combine {
                ty: ValueType::Color,
            }),
        );
        probe.connect(node, output.name, split, "v");
        probe.connect(split, "x", combine, "x");
        probe.connect(split, "y", combine, "y");
        probe.connect(combine, "v", material, "albedo");
    } else {
        probe.connect(node, output.name, material, "albedo");
    }
    Some(probe)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::codegen::compile;

    #[test]
    fn every_node_of_the_presets_can_be_probed() {
        for (name, _) in crate::app::PRESETS {
            let graph = crate::app::preset(name).unwrap();
            for node in &graph.nodes {
                match probe_graph(&graph, node.id) {
                    Some(probe) => {
                        compile(&probe, &Default::default())
                            .unwrap_or_else(|e| panic!("{name} {node}: {e}"));
                    }
                    None => assert_eq!(node.kind, NodeKind::Material),
                }
            }
        }
    }
}
