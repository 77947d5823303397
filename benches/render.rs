//! What the node graph costs against hand-written code, measured in the same run:
//! - the flat render of the wood preset's generated WGSL against seed 000's wood
//!   written by hand as one function (the shader a programmer would have written);
//! - graph → validated WGSL against naga's parse + validate of the same text alone;
//! - the CPU evaluator in f32 against f64;
//! - a metallic-roughness material lit by image-based lighting against the same graph
//!   under the seeds' Blinn-Phong lighting, and deriving an environment's maps.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use veneer::codegen::{CompileOptions, Detail};
use veneer::eval::{Evaluator, Surface};
use veneer::render::{FlatRect, FlatRenderer, GpuContext};

#[path = "../tests/engine/big_graphs.rs"]
mod big_graphs;

const WOOD: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/graphs/wood.ron");
const MARBLE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/graphs/marble.ron");
const SEED_NOISE: &str = include_str!("../tests/engine/reference/seed000_noise.wgsl");
const HAND_WRITTEN_WOOD: &str = include_str!("../tests/engine/reference/wood_seed000.wgsl");
const HAND_WRITTEN_MARBLE: &str = include_str!("../tests/engine/reference/marble_seed000.wgsl");

/// Generated against hand-written WGSL of the same seed 000 material, then the generated
/// one with every octave against footprint-aware detail on a view 50× wider; the time
/// the GPU spends shading (timestamp queries where the adapter has them).
fn flat_render(c: &mut Criterion) {
    let gpu = GpuContext::new().expect("a wgpu adapter");
    for (name, path, hand_written) in [
        ("wood", WOOD, HAND_WRITTEN_WOOD),
        ("marble", MARBLE, HAND_WRITTEN_MARBLE),
    ] {
        let graph = veneer::graph::load(std::path::Path::new(path)).expect("preset");
        let compile = |detail| {
            veneer::codegen::compile(&graph, &CompileOptions::with_detail(detail))
                .expect("compiles")
                .module
                .source
        };
        let hand_written = format!(
            "{}\n{SEED_NOISE}\n{hand_written}",
            veneer::codegen::library::SURFACE
        );
        let near = veneer::render::preview_rect(&graph.preview);
        let far = FlatRect {
            x0: near.x0 * 50.0,
            z0: near.z0 * 50.0,
            x1: near.x1 * 50.0,
            z1: near.z1 * 50.0,
            y: near.y,
        };
        let timing = if veneer::render::PassTimer::supported(&gpu) {
            "GPU pass time"
        } else {
            "submit to completion"
        };
        let mut group = c.benchmark_group(format!(
            "flat render 512² of {name} on {}, {timing}",
            gpu.adapter_description()
        ));
        group.sample_size(20);
        for (label, source, rect) in [
            ("hand-written seed shader", hand_written, near),
            ("generated from the graph", compile(Detail::Full), near),
            (
                "generated, every octave, 50× wider view",
                compile(Detail::Full),
                far,
            ),
            (
                "generated, footprint-aware, 50× wider view",
                compile(Detail::Footprint),
                far,
            ),
        ] {
            let renderer = FlatRenderer::new(&gpu, &source).expect("pipeline builds");
            // The shading alone: reading the image back would dominate on a real GPU.
            group.bench_function(label, |b| {
                b.iter_custom(|iterations| {
                    (0..iterations)
                        .map(|_| {
                            renderer
                                .shading_time(&gpu, rect, 512, 0.0)
                                .expect("renders")
                        })
                        .sum()
                })
            });
        }
        group.finish();
    }
}

fn compile(c: &mut Criterion) {
    let graph = veneer::graph::load(std::path::Path::new(WOOD)).expect("wood preset");
    let source = veneer::codegen::compile(&graph, &Default::default())
        .expect("compiles")
        .module
        .source;
    let mut group = c.benchmark_group("compile wood");
    group.bench_function("naga parse + validate only (baseline)", |b| {
        b.iter(|| veneer::codegen::validate(black_box(&source)).expect("valid"))
    });
    group.bench_function("check + codegen + naga", |b| {
        b.iter(|| {
            veneer::codegen::compile(black_box(&graph), &Default::default()).expect("compiles")
        })
    });
    group.finish();
}

fn cpu_eval(c: &mut Criterion) {
    let graph = veneer::graph::load(std::path::Path::new(WOOD)).expect("wood preset");
    let evaluator = Evaluator::new(&graph).expect("checks");
    let points: Vec<[f64; 3]> = (0..4096)
        .map(|k| [(k % 64) as f64 * 0.78, 0.5, (k / 64) as f64 * 0.78])
        .collect();
    let mut group = c.benchmark_group("CPU evaluator, 4096 points of wood");
    group.bench_function("f32", |b| {
        b.iter(|| {
            points
                .iter()
                .map(|p| evaluator.eval(&Surface::<f32>::at(*p)).albedo[0])
                .sum::<f32>()
        })
    });
    group.bench_function("f64 (reference)", |b| {
        b.iter(|| {
            points
                .iter()
                .map(|p| evaluator.eval(&Surface::<f64>::at(*p)).albedo[0])
                .sum::<f64>()
        })
    });
    group.finish();
}

/// `veneer bake graphs/marble.ron --size 8192 --maps albedo,normal,height --format exr`
/// against rendering the three passes alone, in the bake's bands (no conversion, no
/// encoding, no files).
fn bake_marble(c: &mut Criterion) {
    use veneer::bake::{BakeSettings, Format, Map, NormalConvention, bake};
    use veneer::render::FlatChannels;
    let gpu = GpuContext::new().expect("a wgpu adapter");
    let graph = veneer::graph::load(std::path::Path::new(MARBLE)).expect("marble preset");
    let size = 8192;
    let rect = veneer::render::preview_rect(&graph.preview);
    let source = veneer::codegen::compile(&graph, &Default::default())
        .expect("compiles")
        .module
        .source;
    let renderer = FlatRenderer::new(&gpu, &source).expect("pipeline builds");
    let rows = veneer::bake::band_rows(size, veneer::render::tile_size(&gpu));
    let dir = std::env::temp_dir().join(format!("veneer-bench-bake-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch folder");
    let mut group = c.benchmark_group(format!(
        "bake marble 8192² on {}",
        gpu.adapter_description()
    ));
    group.sample_size(10);
    group.bench_function("render the three passes only (baseline)", |b| {
        b.iter(|| {
            for channels in [
                FlatChannels::AlbedoAlpha,
                FlatChannels::HeightBump,
                FlatChannels::HeightBump,
            ] {
                renderer
                    .render_channel_bands(
                        &gpu,
                        rect,
                        size,
                        0.0,
                        channels,
                        rows,
                        |_, _| {},
                        |_, band| Ok(black_box(band)),
                    )
                    .expect("renders");
            }
        })
    });
    let settings = BakeSettings {
        surface: veneer::bake::BakeSurface::Plane(None),
        size,
        maps: vec![Map::Albedo, Map::Normal, Map::Height],
        format: Format::Exr,
        normal: NormalConvention::OpenGl,
        time: 0.0,
    };
    group.bench_function("bake albedo, normal, height to EXR", |b| {
        b.iter(|| {
            let compiled = veneer::codegen::compile(&graph, &Default::default()).expect("compiles");
            bake(&gpu, &compiled, &settings, &dir.join("marble"), |_, _| true).expect("bakes")
        })
    });
    group.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

/// Checking and compiling graphs of growing size (the target: 5,000 nodes under 2 s).
fn large_graphs(c: &mut Criterion) {
    let mut group = c.benchmark_group("check + compile a chain graph");
    group.sample_size(10);
    for nodes in [500, 5000] {
        let graph = big_graphs::chain(nodes);
        group.bench_function(format!("{nodes} nodes"), |b| {
            b.iter(|| {
                veneer::codegen::compile(black_box(&graph), &Default::default()).expect("compiles")
            })
        });
    }
    group.finish();
}

/// What `veneer check` does with a loaded graph (check, compile, validate, lint) on
/// chains of 10⁴ (the baseline), 10⁵ and 10⁶ nodes: linear cost keeps the ratios at 10
/// and 100 (the target: 10⁶ nodes under 10 s).
fn huge_graphs(c: &mut Criterion) {
    let mut group = c.benchmark_group("veneer check of a chain graph");
    group.sample_size(10);
    for nodes in [10_000, 100_000, 1_000_000] {
        let graph = big_graphs::chain(nodes);
        let positions = veneer::lint::preview_positions(&graph);
        group.bench_function(format!("{nodes} nodes"), |b| {
            b.iter(|| {
                let checked = veneer::graph::check(black_box(&graph)).expect("checks");
                veneer::codegen::compile_checked(&graph, &checked, &Default::default())
                    .expect("compiles");
                veneer::lint::lint(&checked, positions)
            })
        });
    }
    group.finish();
}

/// A colour ramp of 10⁶ stops read from its file and refused, against one of the most
/// stops a ramp accepts ([`veneer::graph::MAX_RAMP_STOPS`]) read, checked and compiled
/// (the target: under 5 s).
fn huge_ramps(c: &mut Criterion) {
    let mut group = c.benchmark_group("load and check a colour ramp");
    group.sample_size(10);
    for stops in [veneer::graph::MAX_RAMP_STOPS, 1_000_000] {
        let text = veneer::graph::to_ron(&big_graphs::ramp(stops));
        group.bench_function(format!("{stops} stops"), |b| {
            b.iter(|| {
                let graph = veneer::graph::from_ron(black_box(&text)).expect("parses");
                veneer::codegen::compile(&graph, &Default::default()).is_ok()
            })
        });
    }
    group.finish();
}

/// What image-based lighting costs: a 512² frame of `wood_polished` on the sphere with
/// metallic-roughness shading (GGX key light, split-sum environment, tone mapping) against
/// the same graph shaded Blinn-Phong (baseline); then deriving the maps of the
/// procedural sky (512 × 256) and of a 2048 × 1024 panorama.
fn image_based_lighting(c: &mut Criterion) {
    use veneer::render::{Environment, EnvironmentMaps, GpuMesh, MeshRenderer, MeshView};
    let gpu = GpuContext::new().expect("a wgpu adapter");
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/graphs/wood_polished.ron");
    let graph = veneer::graph::load(std::path::Path::new(path)).expect("preset");
    let mesh = veneer::mesh::primitive("sphere").expect("the sphere");
    let uploaded = GpuMesh::new(&gpu.device, &mesh);
    let view = MeshView::for_preview(&graph.preview);
    let mut group = c.benchmark_group(format!(
        "image-based lighting on {}",
        gpu.adapter_description()
    ));
    group.sample_size(20);
    for (label, shading) in [
        (
            "512² frame, Blinn-Phong (baseline)",
            veneer::graph::Shading::BlinnPhong,
        ),
        (
            "512² frame, metallic-roughness with IBL",
            veneer::graph::Shading::MetallicRoughness,
        ),
    ] {
        let graph = veneer::graph::Graph {
            shading,
            ..graph.clone()
        };
        let module = veneer::codegen::compile(&graph, &CompileOptions::default())
            .expect("compiles")
            .module;
        let renderer = MeshRenderer::new(&gpu, &module.source, module.uses).expect("pipeline");
        group.bench_function(label, |b| {
            b.iter_custom(|iterations| {
                (0..iterations)
                    .map(|_| {
                        renderer
                            .frame_time(&gpu, &uploaded, &view, 512)
                            .expect("renders")
                    })
                    .sum()
            })
        });
    }
    let panorama = Environment::from_fn("bench", 2048, |d| {
        glam::Vec3::new(1.0 + d.y, 0.5 + 0.5 * d.x, 0.2 + d.z * d.z)
    });
    for (label, environment) in [
        ("derive the sky's maps (512 × 256)", Environment::sky()),
        ("derive a 2048 × 1024 panorama's maps", panorama),
    ] {
        group.bench_function(label, |b| {
            b.iter(|| {
                let maps = EnvironmentMaps::new(&gpu, &environment).expect("maps");
                // Until the GPU has finished deriving them.
                gpu.device
                    .poll(wgpu::PollType::Wait {
                        submission_index: None,
                        timeout: None,
                    })
                    .expect("the GPU finishes");
                black_box(maps)
            })
        });
    }
    group.finish();
}

criterion_group!(
    benches,
    image_based_lighting,
    flat_render,
    compile,
    cpu_eval,
    bake_marble,
    large_graphs,
    huge_graphs,
    huge_ramps
);
criterion_main!(benches);
