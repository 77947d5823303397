//! Property tests on randomly generated graphs: each either compiles to WGSL that naga
//! accepts or is rejected by the check (never a naga error after the check passed, never
//! a panic); saving is byte-stable; and with the PCG hash the CPU evaluator agrees with
//! the GPU flat render.

use crate::support::{compiled_rgb8, cpu_flat_rgb8, difference};
use proptest::prelude::*;
use veneer::codegen::{CompileError, compile};
use veneer::graph::{Basis, Graph, NodeKind, PinDefault, ValueType};
use veneer::render::FlatRect;

/// A node kind from a seed, over every kind the registry lists with the settings its
/// tests cover (sine-hash bases only when `sine` is allowed).
fn kind(seed: u32, sine: bool) -> NodeKind {
    let kinds: Vec<NodeKind> = NodeKind::examples()
        .into_iter()
        .filter(|kind| *kind != NodeKind::Material)
        .filter(|kind| sine || kind.basis() != Some(Basis::ValueSine))
        .collect();
    kinds[seed as usize % kinds.len()].clone()
}

/// A random graph: each node's inputs wired (or not) to compatible outputs of earlier
/// nodes by `choices`, a material at the end fed from the last node.
pub fn random_graph(kinds: &[u32], choices: &[u32], sine: bool) -> Graph {
    let mut graph = Graph::default();
    let mut outputs: Vec<(veneer::graph::NodeId, &'static str, ValueType)> = Vec::new();
    let mut choice = choices.iter().cycle();
    for &seed in kinds {
        let kind = kind(seed, sine);
        let signature = kind.signature();
        let node = graph.add("", kind);
        for pin in &signature.inputs {
            let pick = *choice.next().expect("choices are not empty");
            let candidates: Vec<_> = outputs
                .iter()
                .filter(|(_, _, ty)| ty.converts_to(pin.ty))
                .collect();
            let wire = pin.default == PinDefault::Required || !pick.is_multiple_of(3);
            if wire && !candidates.is_empty() {
                let (from, name, _) = candidates[pick as usize % candidates.len()];
                graph.connect(*from, name, node, pin.name);
            }
        }
        outputs.extend(signature.outputs.iter().map(|pin| (node, pin.name, pin.ty)));
    }
    let material = graph.add("material", NodeKind::Material);
    if let Some((from, name, ty)) = outputs
        .iter()
        .rev()
        .find(|(_, _, ty)| ty.converts_to(ValueType::Color))
    {
        let _ = ty;
        graph.connect(*from, name, material, "albedo");
    }
    graph
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 500, ..ProptestConfig::default() })]

    #[test]
    fn random_graphs_compile_or_are_rejected_by_the_check(
        kinds in prop::collection::vec(0u32..8192, 1..24),
        choices in prop::collection::vec(any::<u32>(), 1..64),
    ) {
        let graph = random_graph(&kinds, &choices, true);
        match compile(&graph, &Default::default()) {
            Ok(compiled) => prop_assert!(compiled.source().contains("fn veneer_material(")),
            Err(CompileError::Check(errors)) => prop_assert!(!errors.is_empty()),
            Err(CompileError::Validation(error)) => prop_assert!(false, "naga rejected a checked graph: {error}\n{}", veneer::graph::to_ron(&graph)),
        }
        let text = veneer::graph::to_ron(&graph);
        let reloaded = veneer::graph::from_ron(&text).expect("saved graphs load");
        prop_assert_eq!(veneer::graph::to_ron(&reloaded), text);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    #[test]
    fn random_pcg_graphs_agree_between_cpu_and_gpu(
        kinds in prop::collection::vec(0u32..8192, 2..10),
        choices in prop::collection::vec(any::<u32>(), 1..32),
    ) {
        let graph = random_graph(&kinds, &choices, false);
        let Ok(compiled) = compile(&graph, &Default::default()) else { return Ok(()) };
        let rect = FlatRect { x0: -2.0, z0: -1.5, x1: 3.0, z1: 2.5, y: 0.3 };
        let diff = difference(&cpu_flat_rgb8(&graph, rect, 24), &compiled_rgb8(&compiled, rect, 24), 3, 2);
        // Floors, fracts and steps can flip on the last bit: allow a few such pixels.
        prop_assert!(diff.share_outside <= 0.02, "{diff}\n{}", veneer::graph::to_ron(&graph));
    }
}
