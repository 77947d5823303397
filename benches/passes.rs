//! Multi-pass materials, in the same run: the Gaussian blur at radius 64 against radius
//! 8 at 2048² (separable: its cost grows with the radius, not its square), and the worn
//! bricks' and the cobblestones' 2048² albedo bakes against rendering their passes alone
//! and against their passes with the material drawn and read back (the bake's overhead
//! on top of its buffers).
//! Every iteration renders the passes again (a new time).

use criterion::{Criterion, criterion_group, criterion_main};
use std::cell::Cell;
use veneer::bake::{BakeSettings, BakeSurface, Format, Map, NormalConvention, UNIT_TILE, bake};
use veneer::codegen::{Compiled, compile};
use veneer::graph::{Basis, Graph, NodeKind, Value, ValueType};
use veneer::nodes::{Blur, Noise, RadiusUnit};
use veneer::render::{FlatChannels, FlatRenderer, GpuContext};

const SIZE: u32 = 2048;
/// The texture graphs measured: each one's bake against its passes alone.
const TEXTURES: [(&str, &str); 2] = [
    (
        "worn bricks",
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/graphs/texture/worn_bricks.ron"
        ),
    ),
    (
        "cobblestones",
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/graphs/texture/cobblestones.ron"
        ),
    ),
];

/// A periodic noise blurred by `radius` texels, as the albedo.
fn blurred(radius: f64) -> Compiled {
    let mut graph = Graph::default();
    let position = graph.add("position", NodeKind::Position);
    let noise = graph.add(
        "grain",
        NodeKind::Noise(Noise {
            basis: Basis::Gradient,
            period: 8,
        }),
    );
    graph.set_input(noise, "scale", Value::Float(8.0));
    let blur = graph.add(
        "soft",
        NodeKind::Blur(Blur {
            ty: ValueType::Float,
            unit: RadiusUnit::Texels,
        }),
    );
    graph.set_input(blur, "radius", Value::Float(radius));
    let material = graph.add("material", NodeKind::Material);
    graph.connect(position, "position", noise, "p");
    graph.connect(noise, "value", blur, "image");
    graph.connect(blur, "result", material, "albedo");
    compile(&graph, &Default::default()).expect("the blur compiles")
}

/// Renders the passes of `flat` for a size² output at a time never used before (so all
/// of them render), and one pixel of the material.
fn passes_alone(gpu: &GpuContext, flat: &FlatRenderer, time: &Cell<f32>) {
    time.set(time.get() + 1.0);
    let one = (0, 0);
    flat.render_region(
        gpu,
        UNIT_TILE,
        SIZE,
        time.get(),
        FlatChannels::AlbedoAlpha,
        one,
        (1, 1),
    )
    .expect("the passes render");
}

fn passes(c: &mut Criterion) {
    let gpu = GpuContext::new().expect("a wgpu adapter");
    let time = Cell::new(0.0f32);
    let mut group = c.benchmark_group(format!(
        "passes at {SIZE}² on {}",
        gpu.adapter_description()
    ));
    group.sample_size(10);
    for radius in [8.0, 64.0] {
        let flat = FlatRenderer::for_compiled(&gpu, &blurred(radius)).expect("pipelines");
        group.bench_function(
            format!("blur of radius {radius} texels (the noise and two axes)"),
            |b| b.iter(|| passes_alone(&gpu, &flat, &time)),
        );
    }
    let dir = std::env::temp_dir().join(format!("veneer-bench-passes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a scratch folder");
    for (name, path) in TEXTURES {
        let graph = veneer::graph::load(std::path::Path::new(path)).expect("the graph loads");
        let compiled = compile(&graph, &Default::default()).expect("the graph compiles");
        let flat = FlatRenderer::for_compiled(&gpu, &compiled).expect("pipelines");
        group.bench_function(
            format!(
                "{name}: its {} passes alone (baseline)",
                compiled.passes.passes.len()
            ),
            |b| b.iter(|| passes_alone(&gpu, &flat, &time)),
        );
        group.bench_function(
            format!("{name}: its passes and the material at every pixel, read back"),
            |b| {
                b.iter(|| {
                    time.set(time.get() + 1.0);
                    flat.render(&gpu, UNIT_TILE, SIZE, time.get())
                        .expect("renders")
                })
            },
        );
        group.bench_function(
            format!("{name}: the albedo map baked as a tile, PNG written"),
            |b| {
                b.iter(|| {
                    time.set(time.get() + 1.0);
                    let settings = BakeSettings {
                        surface: BakeSurface::Tile(None),
                        size: SIZE,
                        maps: vec![Map::Albedo],
                        format: Format::Png8,
                        normal: NormalConvention::OpenGl,
                        time: time.get(),
                    };
                    bake(&gpu, &compiled, &settings, &dir.join("map"), |_, _| true).expect("bakes")
                })
            },
        );
    }
    group.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

criterion_group!(benches, passes);
criterion_main!(benches);
