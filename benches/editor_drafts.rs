//! The editor's preview thread on a multi-pass material, in one run: the cobblestones
//! (130 passes) drawn as drafts on their preview mesh at a preview panel's size, the
//! passes over the mesh's UV layout at the preview's pass size. Each draft follows a
//! parameter edit: one that only the material reads (no pass renders again), one that
//! one surface pass reads (it and the two passes of the blur after it render again),
//! one at the start of the graph (every pass renders again), against drawing again with
//! nothing changed (the baseline). Drafts per second are 1 / the time of one.

use criterion::{Criterion, criterion_group, criterion_main};
use std::cell::Cell;
use veneer::app::LiveMaterial;
use veneer::graph::{Graph, Value};
use veneer::render::{GpuContext, LiveMaterialCode, LiveRenderer, MeshView, Quality};

const COBBLESTONES: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/graphs/texture/cobblestones.ron"
);

/// The preview panel's picture, in pixels.
const PANEL: (u32, u32) = (480, 420);

fn drafts(c: &mut Criterion) {
    let gpu = GpuContext::new().expect("a wgpu adapter");
    let graph = veneer::graph::load(std::path::Path::new(COBBLESTONES)).expect("loads");
    let mut live = LiveMaterial::in_storage();
    live.update(&graph);
    let code = LiveMaterialCode::new(1, live.compiled.as_ref().expect("compiles"));
    let mesh = veneer::mesh::primitive(&graph.preview.mesh).expect("the preview mesh");
    let view = MeshView::for_preview(&graph.preview);
    let sky = gpu.sky().expect("the sky");
    let mut renderer = LiveRenderer::default();
    let mut draft = |params: &[[f32; 4]]| {
        renderer
            .render(
                &gpu,
                &code,
                params,
                "preview",
                &mesh,
                &view,
                &sky,
                PANEL,
                Quality::Draft,
            )
            .expect("draws")
    };
    // The draft scale settles, the passes render once.
    for _ in 0..4 {
        draft(&live.params(&graph));
    }
    let mut group = c.benchmark_group(format!(
        "cobblestones drafts at {}×{} on {}",
        PANEL.0,
        PANEL.1,
        gpu.adapter_description()
    ));
    group.sample_size(10);
    let unchanged = live.params(&graph);
    group.bench_function("drawn again, nothing changed (baseline)", |b| {
        b.iter(|| draft(&unchanged))
    });
    let turn = Cell::new(0u32);
    for (what, label, pin, values) in [
        (
            "an edit only the material reads",
            "shade",
            "to_max",
            [1.1, 1.2],
        ),
        (
            "an edit of one pass (the height, then its blur's two axes)",
            "pits",
            "b",
            [0.08, 0.1],
        ),
        ("an edit every pass reads", "cells", "jitter", [0.85, 0.8]),
    ] {
        let edited = |value: f64| -> Vec<[f32; 4]> {
            let mut graph: Graph = graph.clone();
            let node = graph
                .nodes
                .iter()
                .find(|n| n.label == label)
                .expect("node")
                .id;
            graph.set_input(node, pin, Value::Float(value));
            live.params(&graph)
        };
        let alternatives = values.map(edited);
        group.bench_function(format!("after {what} ('{label}' {pin})"), |b| {
            b.iter(|| {
                turn.set(turn.get() + 1);
                draft(&alternatives[(turn.get() % 2) as usize])
            })
        });
    }
    group.finish();
}

criterion_group!(benches, drafts);
criterion_main!(benches);
