//! Check + codegen + naga on arbitrary graphs built from node kinds, constants and wires
//! (structure-aware, so that most inputs are graphs worth compiling): every graph either
//! compiles to WGSL that naga accepts in every parameter mode and detail, or the check
//! rejects it; the CPU evaluator accepts exactly what the check accepts and never
//! panics.

#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use veneer::codegen::{CompileError, CompileOptions, Detail, ParamMode, compile};
use veneer::eval::{Evaluator, Surface};
use veneer::graph::{Graph, NodeId, NodeKind, Value};

/// A node and the constants of some of its inputs (pins by index into its signature).
#[derive(Arbitrary, Debug)]
struct FuzzNode {
    kind: NodeKind,
    constants: Vec<(u8, Value)>,
}

/// A wire between pins given by index (node, then pin within its signature).
#[derive(Arbitrary, Debug)]
struct FuzzWire {
    from: u8,
    output: u8,
    to: u8,
    input: u8,
}

#[derive(Arbitrary, Debug)]
struct FuzzGraph {
    nodes: Vec<FuzzNode>,
    wires: Vec<FuzzWire>,
    point: [f32; 3],
}

fn build(fuzz: &FuzzGraph) -> Graph {
    let mut graph = Graph::default();
    let ids: Vec<NodeId> = fuzz
        .nodes
        .iter()
        .map(|node| {
            let id = graph.add("", node.kind.clone());
            let inputs = node.kind.signature().inputs;
            for (pin, value) in &node.constants {
                if let Some(pin) = inputs.get(*pin as usize % inputs.len().max(1)) {
                    graph.set_input(id, pin.name, *value);
                }
            }
            id
        })
        .collect();
    if ids.is_empty() {
        return graph;
    }
    for wire in &fuzz.wires {
        let (from, to) = (
            ids[wire.from as usize % ids.len()],
            ids[wire.to as usize % ids.len()],
        );
        let outputs = graph.node(from).expect("added").kind.signature().outputs;
        let inputs = graph.node(to).expect("added").kind.signature().inputs;
        if outputs.is_empty() || inputs.is_empty() {
            continue;
        }
        let output = outputs[wire.output as usize % outputs.len()].name;
        let input = inputs[wire.input as usize % inputs.len()].name;
        graph.connect(from, output, to, input);
    }
    graph
}

fuzz_target!(|fuzz: FuzzGraph| {
    let graph = build(&fuzz);
    let mut accepted = None;
    for (mode, detail) in [
        (ParamMode::Baked, Detail::Full),
        (ParamMode::Uniform, Detail::Footprint),
        (ParamMode::Storage, Detail::Footprint),
    ] {
        let options = CompileOptions {
            params: mode,
            detail,
        };
        let compiled = match compile(&graph, &options) {
            Ok(_) => true,
            Err(CompileError::Check(errors)) => {
                assert!(!errors.is_empty(), "rejected without an error");
                false
            }
            Err(CompileError::Validation(error)) => panic!(
                "naga rejected a checked graph: {error}\n{}",
                veneer::graph::to_ron(&graph)
            ),
        };
        assert!(
            accepted.is_none_or(|earlier| earlier == compiled),
            "one mode compiled, the other was rejected"
        );
        accepted = Some(compiled);
    }
    match Evaluator::new(&graph) {
        Ok(evaluator) => {
            assert_eq!(
                accepted,
                Some(true),
                "the evaluator accepted a graph the check rejected"
            );
            let point = fuzz.point.map(f64::from);
            evaluator.eval(&Surface::<f32>::at(point));
            evaluator.eval(&Surface::<f64>::at(point));
        }
        Err(_) => assert_eq!(
            accepted,
            Some(false),
            "the evaluator rejected a checked graph"
        ),
    }
});
