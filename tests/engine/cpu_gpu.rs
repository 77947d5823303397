//! The CPU evaluator (f32) against the GPU flat render for graphs built on the PCG hash,
//! whose lattice values are bit-identical on both: within 2/255 on 99.9% of pixels.

use crate::support::{cpu_flat_rgb8, difference, flat_rgb8};
use veneer::eval::{Evaluator, Surface};
use veneer::graph::{Basis, Graph, MathOp, Metric, NodeKind, Value, ValueType, WorleyFeature};
use veneer::nodes::{Combine, DomainWarp, Fbm, Math, Mix, Noise, Turbulence, Worley};
use veneer::render::FlatRect;

/// A graph touching every PCG-hashed family: value, gradient and simplex noise, the
/// three fractal modes, Worley, tiles, a warp and a ramp.
fn pcg_graph() -> Graph {
    let mut g = Graph::default();
    let warp = g.add(
        "warp",
        NodeKind::DomainWarp(DomainWarp {
            basis: Basis::Gradient,
            period: 0,
        }),
    );
    g.set_input(warp, "strength", Value::Float(0.3));
    let fbm = g.add(
        "fbm",
        NodeKind::Fbm(Fbm {
            basis: Basis::ValuePcg,
            octaves: 4,
            normalize: true,
            rotate: false,
            period: 0,
        }),
    );
    g.connect(warp, "p", fbm, "p");
    let turbulence = g.add(
        "turbulence",
        NodeKind::Turbulence(Turbulence {
            basis: Basis::Simplex,
            octaves: 3,
            normalize: false,
            rotate: false,
            period: 0,
        }),
    );
    g.set_input(turbulence, "scale", Value::Float(1.7));
    let worley = g.add(
        "cells",
        NodeKind::Worley(Worley {
            feature: WorleyFeature::F2MinusF1,
            metric: Metric::Euclidean,
            octaves: 2,
            period: 0,
            points: veneer::graph::FeaturePoints::Hashed,
        }),
    );
    let tiles = g.add("tiles", NodeKind::Tiles);
    g.set_input(tiles, "blur", Value::Float(0.05));
    let gradient = g.add(
        "gradient",
        NodeKind::Noise(Noise {
            basis: Basis::Gradient,
            period: 0,
        }),
    );
    g.set_input(gradient, "scale", Value::Float(2.5));
    let sum = g.add(
        "sum",
        NodeKind::Math(Math {
            op: MathOp::Multiply,
            ty: ValueType::Float,
        }),
    );
    g.connect(gradient, "value", sum, "a");
    g.connect(tiles, "mask", sum, "b");
    let color = g.add(
        "colour",
        NodeKind::Combine(Combine {
            ty: ValueType::Color,
        }),
    );
    g.connect(fbm, "value", color, "x");
    g.connect(turbulence, "value", color, "y");
    g.connect(worley, "value", color, "z");
    let tint = g.add(
        "tint",
        NodeKind::Mix(Mix {
            ty: ValueType::Color,
        }),
    );
    g.connect(color, "v", tint, "a");
    g.connect(sum, "result", tint, "factor");
    let material = g.add("material", NodeKind::Material);
    g.connect(tint, "result", material, "albedo");
    g
}

#[test]
fn cpu_f32_evaluation_matches_the_gpu_flat_render() {
    let graph = pcg_graph();
    let source = veneer::codegen::compile(&graph, &Default::default())
        .expect("test graph compiles")
        .module
        .source;
    let (size, rect) = (
        96u32,
        FlatRect {
            x0: -3.0,
            z0: -2.0,
            x1: 5.0,
            z1: 6.0,
            y: 0.25,
        },
    );
    let gpu = flat_rgb8(&source, rect, size);
    let cpu = cpu_flat_rgb8(&graph, rect, size);
    let diff = difference(&cpu, &gpu, 3, 2);
    assert!(diff.share_outside <= 0.001, "CPU f32 against GPU: {diff}");
}

#[test]
fn f64_reference_and_f32_agree_closely_on_pcg_noise() {
    let evaluator = Evaluator::new(&pcg_graph()).expect("test graph checks");
    let mut worst = 0.0f64;
    for k in 0..200 {
        let p = [
            k as f64 * 0.173 - 7.0,
            0.31 * k as f64,
            3.0 - 0.05 * k as f64,
        ];
        let a = evaluator.eval(&Surface::<f64>::at(p)).albedo;
        let b = evaluator.eval(&Surface::<f32>::at(p)).albedo;
        for c in 0..3 {
            worst = worst.max((a[c] - f64::from(b[c])).abs());
        }
    }
    assert!(worst < 1e-3, "f32 strays {worst} from f64");
}
