//! Footprint-aware detail: octaves finer than a pixel are left out, so a distant view is
//! closer to the truly filtered (supersampled) pattern than full evaluation, and a near
//! view is unchanged.

use crate::support::gpu;
use veneer::codegen::{CompileOptions, Detail};
use veneer::graph::{Basis, Graph, NodeKind, Value};
use veneer::nodes::{Combine, Fbm};
use veneer::render::{FlatRect, View, render_material};

fn fbm_graph() -> Graph {
    let mut graph = Graph::default();
    let fbm = graph.add(
        "fbm",
        NodeKind::Fbm(Fbm {
            basis: Basis::Gradient,
            octaves: 8,
            normalize: true,
            rotate: false,
        }),
    );
    graph.set_input(fbm, "scale", Value::Float(1.0));
    let colour = graph.add(
        "grey",
        NodeKind::Combine(Combine {
            ty: veneer::graph::ValueType::Color,
        }),
    );
    for pin in ["x", "y", "z"] {
        graph.connect(fbm, "value", colour, pin);
    }
    let material = graph.add("material", NodeKind::Material);
    graph.connect(colour, "v", material, "albedo");
    graph
}

fn render(graph: &Graph, extent: f64, size: u32, detail: Detail) -> Vec<f64> {
    let rect = FlatRect {
        x0: 0.0,
        z0: 0.0,
        x1: extent,
        z1: extent,
        y: 0.37,
    };
    let compiled = veneer::codegen::compile(graph, &CompileOptions::with_detail(detail)).unwrap();
    let image = render_material(gpu(), &compiled, &View::Flat(rect), size, 0.0).expect("renders");
    image
        .pixels
        .chunks_exact(3)
        .map(|p| f64::from(p[0]) / 255.0)
        .collect()
}

/// `pixels` (size·factor squared) averaged over factor×factor blocks.
fn box_down(pixels: &[f64], size: usize, factor: usize) -> Vec<f64> {
    let wide = size * factor;
    let mut out = vec![0.0; size * size];
    for (k, value) in pixels.iter().enumerate() {
        let (x, y) = (k % wide / factor, k / wide / factor);
        out[y * size + x] += value / (factor * factor) as f64;
    }
    out
}

fn mean_error(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).sum::<f64>() / a.len() as f64
}

#[test]
fn far_away_the_footprint_is_nearer_the_filtered_pattern_and_near_by_it_changes_nothing() {
    let graph = fbm_graph();
    let source = veneer::codegen::compile(&graph, &CompileOptions::with_detail(Detail::Footprint))
        .unwrap()
        .module
        .source;
    assert!(
        source.contains("veneer_octave_cutoff("),
        "the cutoff is computed"
    );

    let (size, factor) = (64usize, 8usize);
    for (extent, far) in [(400.0, true), (0.5, false)] {
        let reference = box_down(
            &render(&graph, extent, (size * factor) as u32, Detail::Full),
            size,
            factor,
        );
        let full = render(&graph, extent, size as u32, Detail::Full);
        let footprint = render(&graph, extent, size as u32, Detail::Footprint);
        let (full_error, footprint_error) = (
            mean_error(&full, &reference),
            mean_error(&footprint, &reference),
        );
        println!("extent {extent}: full {full_error:.4}, footprint {footprint_error:.4}");
        if far {
            assert!(
                footprint_error < 0.5 * full_error,
                "far: full {full_error}, footprint {footprint_error}"
            );
        } else {
            assert!(
                mean_error(&full, &footprint) < 0.01,
                "near: every octave is shown either way"
            );
        }
    }
}
