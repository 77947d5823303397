//! Property tests on randomly generated graphs: each either compiles to WGSL that naga
//! accepts or is rejected by the check (never a naga error after the check passed, never
//! a panic); saving is byte-stable; and with the PCG hash the CPU evaluator agrees with
//! the GPU flat render.

use crate::support::{cpu_flat_rgb8, difference, flat_rgb8};
use proptest::prelude::*;
use veneer::codegen::{CompileError, compile};
use veneer::graph::{
    Basis, Graph, MathOp, Metric, NodeKind, PinDefault, UnaryOp, ValueType, WorleyFeature,
};
use veneer::render::FlatRect;

/// A node kind from a seed, over every kind (sine-hash bases only when `sine` is allowed).
fn kind(seed: u32, sine: bool) -> NodeKind {
    let types = [
        ValueType::Float,
        ValueType::Vec2,
        ValueType::Vec3,
        ValueType::Color,
    ];
    let ty = types[(seed / 64) as usize % 4];
    let vector = types[1 + (seed / 64) as usize % 3];
    let bases: &[Basis] = if sine {
        &Basis::ALL
    } else {
        &[Basis::ValuePcg, Basis::Gradient, Basis::Simplex]
    };
    let basis = bases[(seed / 256) as usize % bases.len()];
    let octaves = 1 + seed / 1024 % 6;
    match seed % 34 {
        0 => NodeKind::Position,
        1 => NodeKind::Normal,
        2 => NodeKind::Uv,
        3 => NodeKind::Time,
        4 => NodeKind::Constant { ty },
        5 => NodeKind::Transform,
        6 => NodeKind::Project,
        7 => NodeKind::Cylindrical,
        8 => NodeKind::DomainWarp { basis },
        9 => NodeKind::Noise { basis },
        10 => NodeKind::Fbm {
            basis,
            octaves,
            normalize: seed % 2 == 0,
        },
        11 => NodeKind::Turbulence {
            basis,
            octaves,
            normalize: seed % 2 == 1,
        },
        12 => NodeKind::FractalSum {
            basis,
            octaves,
            normalize: seed % 2 == 0,
        },
        13 => NodeKind::Worley {
            feature: WorleyFeature::F2MinusF1,
            metric: Metric::Manhattan,
            octaves: octaves.min(3),
        },
        14 => NodeKind::SineBand,
        15 => NodeKind::TriangleWave,
        16 => NodeKind::Tiles,
        17 => NodeKind::Rings,
        18 => NodeKind::Math {
            op: MathOp::ALL[(seed / 32) as usize % 7],
            ty,
        },
        19 => NodeKind::Unary {
            op: UnaryOp::ALL[(seed / 32) as usize % 7],
            ty,
        },
        20 => NodeKind::Mix { ty },
        21 => NodeKind::Clamp { ty },
        22 => NodeKind::Step { ty },
        23 => NodeKind::Smoothstep,
        24 => NodeKind::Remap,
        25 => NodeKind::Length { ty: vector },
        26 => NodeKind::Dot { ty: vector },
        27 => NodeKind::Normalize { ty: vector },
        28 => NodeKind::Split { ty: vector },
        29 => NodeKind::Front,
        30 => NodeKind::Layers { ty },
        31 => NodeKind::Isolines,
        32 => NodeKind::NoiseBump { basis },
        _ => NodeKind::Combine { ty: vector },
    }
}

/// A random graph: each node's inputs wired (or not) to compatible outputs of earlier
/// nodes by `choices`, a material at the end fed from the last node.
fn random_graph(kinds: &[u32], choices: &[u32], sine: bool) -> Graph {
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
            let wire = pin.default == PinDefault::Required || pick % 3 != 0;
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
        let diff = difference(&cpu_flat_rgb8(&graph, rect, 24), &flat_rgb8(compiled.source(), rect, 24), 3, 2);
        // Floors, fracts and steps can flip on the last bit: allow a few such pixels.
        prop_assert!(diff.share_outside <= 0.02, "{diff}\n{}", veneer::graph::to_ron(&graph));
    }
}
