//! Node thumbnails of the wood preset, in the same run: one 64×64 flat render of the
//! whole material (baked, the baseline: what one tile would cost drawn alone), then the
//! atlas refreshed as the editor refreshes it: every tile (on opening, or after a
//! structural edit) and the three tiles a value edit of "tint amount" reaches. Each
//! includes the readback of the atlas, as the editor's drawing thread does.

use criterion::{Criterion, criterion_group, criterion_main};
use veneer::app::{LiveMaterial, TILE_PIXELS, atlas_graph, placement, tile_params};
use veneer::codegen::param_values;
use veneer::graph::PinRef;
use veneer::render::{AtlasLayout, FlatRenderer, GpuContext, ThumbnailRenderer};

const WOOD: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/graphs/wood.ron");

fn wood_thumbnails(c: &mut Criterion) {
    let gpu = GpuContext::new().expect("a wgpu adapter");
    let graph = veneer::graph::load(std::path::Path::new(WOOD)).expect("wood preset");
    let pins: Vec<PinRef> = graph
        .nodes
        .iter()
        .filter_map(|node| {
            let output = node.kind.signature().outputs.first()?.name;
            Some(PinRef::new(node.id, output))
        })
        .collect();
    let atlas = atlas_graph(&graph, &pins).expect("wood has a material");
    let mut live = LiveMaterial::default();
    live.update(&atlas.graph);
    let module = &live.compiled.as_ref().expect("the atlas compiles").module;
    let values = param_values(&atlas.graph, &module.params);
    let tiles: Vec<(usize, Vec<[f32; 4]>)> = (0..atlas.pins.len())
        .map(|index| {
            let params = tile_params(&values, &module.params, &atlas.selectors, index);
            (index, params)
        })
        .collect();
    // "tint amount", "tint shade", "wood colour": what a value edit of the first reaches.
    let reached: Vec<(usize, Vec<[f32; 4]>)> = ["tint amount", "tint shade", "wood colour"]
        .iter()
        .map(|label| {
            let node = graph.nodes.iter().find(|n| n.label == *label).unwrap().id;
            let index = atlas.pins.iter().position(|p| p.node == node).unwrap();
            tiles[index].clone()
        })
        .collect();
    let layout = AtlasLayout::for_tiles(tiles.len(), 8, TILE_PIXELS);
    let rect = placement(&graph);
    let mut renderer =
        ThumbnailRenderer::new(&gpu, &module.source, module.params.len(), None).expect("pipeline");
    let baked = veneer::codegen::compile(&graph, &Default::default()).expect("wood compiles");
    let flat = FlatRenderer::new(&gpu, baked.source()).expect("flat pipeline");

    let mut group = c.benchmark_group(format!(
        "wood thumbnails ({} tiles of {TILE_PIXELS}²) on {}",
        tiles.len(),
        gpu.adapter_description()
    ));
    group.sample_size(10);
    group.bench_function("one 64×64 flat render of the material (baseline)", |b| {
        b.iter(|| flat.render(&gpu, rect, TILE_PIXELS, 0.0).expect("renders"))
    });
    group.bench_function("refresh every tile", |b| {
        b.iter(|| {
            renderer
                .render(&gpu, layout, (rect, 0.0), &[], &tiles)
                .expect("renders")
        })
    });
    group.bench_function("refresh after a value edit (3 tiles)", |b| {
        b.iter(|| {
            renderer
                .render(&gpu, layout, (rect, 0.0), &[], &reached)
                .expect("renders")
        })
    });
    group.finish();
}

criterion_group!(benches, wood_thumbnails);
criterion_main!(benches);
