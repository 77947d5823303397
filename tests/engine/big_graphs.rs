//! Big graphs built in linear time — a long chain, a colour ramp of many stops — for the
//! scale tests and the render benchmark (`benches/render.rs` includes this file).

use veneer::graph::{Basis, Graph, MathOp, Node, NodeId, NodeKind, PinRef, ValueType, Wire};
use veneer::nodes::{ColorRamp, Math, Noise};

/// A graph of `nodes` nodes (at least 2): a noise, then a chain where every third node is
/// a gradient noise scaled by the previous value and the others cycle through the math
/// operations, ending in the material's alpha.
pub fn chain(nodes: usize) -> Graph {
    let mut graph = Graph::default();
    let mut previous = (
        push(
            &mut graph,
            "start",
            NodeKind::Noise(Noise {
                basis: Basis::ValuePcg,
                period: 0,
            }),
        ),
        "value",
    );
    for k in 1..nodes - 1 {
        let (kind, input, output) = if k % 3 == 0 {
            let kind = NodeKind::Noise(Noise {
                basis: Basis::Gradient,
                period: 0,
            });
            (kind, "scale", "value")
        } else {
            let kind = NodeKind::Math(Math {
                op: MathOp::ALL[k % 7],
                ty: ValueType::Float,
            });
            (kind, "a", "result")
        };
        let label = if k % 3 == 0 { "noise" } else { "step" };
        let node = push(&mut graph, &format!("{label} {k}"), kind);
        connect(&mut graph, previous, node, input);
        previous = (node, output);
    }
    let material = push(&mut graph, "material", NodeKind::Material);
    connect(&mut graph, previous, material, "alpha");
    graph
}

/// Appends a node with the next id.
fn push(graph: &mut Graph, label: &str, kind: NodeKind) -> NodeId {
    let id = NodeId(graph.nodes.len() as u32 + 1);
    let mut node = Node::new(id, kind);
    node.label = label.to_string();
    graph.nodes.push(node);
    id
}

/// Appends a wire (the graph's `connect` looks for a wire to replace, which is quadratic
/// over a whole chain).
fn connect(graph: &mut Graph, (from, pin): (NodeId, &str), to: NodeId, input: &str) {
    graph.wires.push(Wire {
        from: PinRef::new(from, pin),
        to: PinRef::new(to, input),
    });
}

/// A noise through a linear colour ramp of `stops` stops (evenly spaced greys) into the
/// material's albedo.
pub fn ramp(stops: usize) -> Graph {
    use veneer::graph::{RampInterpolation, RampStop};
    let mut graph = Graph::default();
    let noise = push(
        &mut graph,
        "noise",
        NodeKind::Noise(Noise {
            basis: Basis::ValuePcg,
            period: 0,
        }),
    );
    let stops = (0..stops)
        .map(|k| {
            let t = k as f64 / stops.max(2) as f64;
            RampStop {
                position: t,
                color: (t, t, t),
            }
        })
        .collect();
    let kind = NodeKind::ColorRamp(ColorRamp {
        stops,
        interpolation: RampInterpolation::Linear,
    });
    let ramp = push(&mut graph, "ramp", kind);
    connect(&mut graph, (noise, "value"), ramp, "factor");
    let material = push(&mut graph, "material", NodeKind::Material);
    connect(&mut graph, (ramp, "color"), material, "albedo");
    graph
}
