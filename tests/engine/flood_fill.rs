//! The Flood fill node on the GPU: every output against its CPU image reference over
//! tiles and Voronoi cells that cross the tile's wrap, and one value per cell.

use crate::passes::{TILE, pixel_differences, show, tolerance};
use crate::support::gpu;
use veneer::codegen::compile;
use veneer::graph::{Graph, Metric, NodeId, NodeKind, Value, ValueType, WorleyFeature};
use veneer::nodes::{FloodFill, Step, Worley};
use veneer::render::FlatRenderer;

/// Staggered bricks over the unit tile: 8 columns of 4, every other column shifted half
/// a brick, so bricks cross both seams (32 bricks).
fn bricks(graph: &mut Graph) -> (NodeId, &'static str) {
    let position = graph.add("position", NodeKind::Position);
    let tiles = graph.add("bricks", NodeKind::Tiles);
    graph.set_input(tiles, "size", Value::Vec2(0.125, 0.25));
    graph.set_input(tiles, "gap", Value::Vec2(0.2, 0.1));
    graph.connect(position, "position", tiles, "p");
    (tiles, "mask")
}

/// Periodic Voronoi cells over the unit tile with lines between them.
fn voronoi(graph: &mut Graph) -> (NodeId, &'static str) {
    let position = graph.add("position", NodeKind::Position);
    let worley = graph.add(
        "cells",
        NodeKind::Worley(Worley {
            feature: WorleyFeature::F2MinusF1,
            metric: Metric::Euclidean,
            octaves: 1,
            period: 4,
            points: veneer::graph::FeaturePoints::Hashed,
        }),
    );
    graph.set_input(worley, "scale", Value::Float(4.0));
    graph.connect(position, "position", worley, "p");
    let step = graph.add(
        "lines",
        NodeKind::Step(Step {
            ty: ValueType::Float,
        }),
    );
    graph.set_input(step, "edge", Value::Float(0.15));
    graph.connect(worley, "value", step, "x");
    (step, "result")
}

/// The cells of `mask` flood-filled, output `output` shown as the albedo.
fn filled(mask: fn(&mut Graph) -> (NodeId, &'static str), output: &str, ty: ValueType) -> Graph {
    let mut graph = Graph::default();
    let (source, pin) = mask(&mut graph);
    let fill = graph.add("fill", NodeKind::FloodFill(FloodFill::default()));
    graph.set_input(fill, "seed", Value::Float(3.0));
    graph.connect(source, pin, fill, "mask");
    show(&mut graph, fill, output, ty);
    graph
}

const OUTPUTS: [(&str, ValueType); 5] = [
    ("value", ValueType::Float),
    ("colour", ValueType::Color),
    ("uv", ValueType::Vec2),
    ("gradient", ValueType::Float),
    ("centre", ValueType::Vec2),
];

#[test]
fn every_flood_fill_output_matches_its_cpu_reference_on_bricks_and_voronoi_cells() {
    let mut failures = Vec::new();
    for (name, mask) in [
        ("bricks", bricks as fn(&mut Graph) -> _),
        ("voronoi", voronoi),
    ] {
        for (output, ty) in OUTPUTS {
            let compiled = compile(&filled(mask, output, ty), &Default::default())
                .unwrap_or_else(|e| panic!("{name} {output}: {e}"));
            let differences = pixel_differences(&compiled, TILE, 64);
            let allowed = tolerance(&compiled);
            let off = differences.iter().filter(|&&d| d > allowed).count();
            if off > 0 {
                failures.push(format!("{name} {output}: {off} pixels differ"));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn every_brick_gets_one_value_of_its_own_across_the_wrap() {
    let compiled = compile(
        &filled(bricks, "value", ValueType::Float),
        &Default::default(),
    )
    .expect("the fill compiles");
    let pixels = FlatRenderer::for_compiled(gpu(), &compiled)
        .expect("the passes' pipelines build")
        .render(gpu(), TILE, 64, 0.0)
        .expect("the passes render");
    let values: std::collections::BTreeSet<u32> =
        pixels.iter().map(|pixel| pixel[0].to_bits()).collect();
    // 32 bricks, each its own value, and the mortar's 0.
    assert_eq!(values.len(), 33, "{values:?}");
    assert!(values.contains(&0.0_f32.to_bits()));
}
