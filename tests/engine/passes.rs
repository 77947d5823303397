//! Multi-pass materials: every image node's GPU passes against its CPU image reference,
//! how the compiler cuts a graph into passes (one buffer per cut, only reachable cuts),
//! the checks on sampled inputs, extremes, and tiles baked through the passes.

use crate::support::{gpu, run_veneer, temp_dir};
use veneer::bake::tile::SEAM_TOLERANCE;
use veneer::bake::{BakeSettings, BakeSurface, Format, Map, NormalConvention, bake};
use veneer::codegen::passes::PassKind;
use veneer::codegen::{CompileError, Compiled, compile};
use veneer::eval::Evaluator;
use veneer::graph::{Basis, Graph, NodeId, NodeKind, PinDefault, Value, ValueType};
use veneer::nodes::passes::BufferFormat;
use veneer::nodes::{Blur, Combine, HeightToNormal, Noise, RadiusUnit, Split, Warp};
use veneer::render::{FlatRect, FlatRenderer};

/// The node labelled `label`.
fn by_label(graph: &Graph, label: &str) -> NodeId {
    let node = graph.nodes.iter().find(|node| node.label == label);
    node.unwrap_or_else(|| panic!("no node '{label}'")).id
}

/// The unit tile, where periodic noises repeat.
pub(crate) const TILE: FlatRect = FlatRect {
    x0: 0.0,
    z0: 0.0,
    x1: 1.0,
    z1: 1.0,
    y: 0.0,
};

/// A periodic noise of `basis` over the unit tile (4 cells), fed by the position.
fn tile_noise(graph: &mut Graph, label: &str, basis: Basis) -> NodeId {
    let position = graph.add(&format!("{label} position"), NodeKind::Position);
    let noise = graph.add(label, NodeKind::Noise(Noise { basis, period: 4 }));
    graph.set_input(noise, "scale", Value::Float(4.0));
    graph.connect(position, "position", noise, "p");
    noise
}

/// A value of type `ty` varying over the tile, each lane differently: two periodic
/// noises combined (a float is the first alone).
fn tile_source(graph: &mut Graph, ty: ValueType) -> (NodeId, &'static str) {
    let a = tile_noise(graph, "a", Basis::Gradient);
    if ty == ValueType::Float {
        return (a, "value");
    }
    let b = tile_noise(graph, "b", Basis::ValuePcg);
    let combine = graph.add("source", NodeKind::Combine(Combine { ty }));
    graph.connect(a, "value", combine, "x");
    graph.connect(b, "value", combine, "y");
    if ty.width() == 3 {
        graph.connect(a, "value", combine, "z");
    }
    (combine, "v")
}

/// A material showing output `output` (of type `ty`) of `node` as its albedo.
pub(crate) fn show(graph: &mut Graph, node: NodeId, output: &str, ty: ValueType) {
    let material = graph.add("material", NodeKind::Material);
    if ty == ValueType::Vec2 {
        let split = graph.add("lanes", NodeKind::Split(Split { ty }));
        let colour = graph.add(
            "colour",
            NodeKind::Combine(Combine {
                ty: ValueType::Color,
            }),
        );
        graph.connect(node, output, split, "v");
        graph.connect(split, "x", colour, "x");
        graph.connect(split, "y", colour, "y");
        graph.connect(colour, "v", material, "albedo");
    } else {
        graph.connect(node, output, material, "albedo");
    }
}

/// A graph of `kind` reading a varying source through each sampled input, its other
/// inputs wired to noises where they are 0 by default (a warp's vector or intensity, an
/// offset, an angle), shown as the albedo.
pub(crate) fn image_graph(kind: &NodeKind) -> Graph {
    let mut graph = Graph::default();
    let signature = kind.signature();
    let node = graph.add("under test", kind.clone());
    for pin in &signature.inputs {
        if pin.sampled {
            let (source, output) = tile_source(&mut graph, pin.ty);
            graph.connect(source, output, node, pin.name);
        } else if pin.default == PinDefault::Const(Value::Vec2(0.0, 0.0))
            || pin.default == PinDefault::Const(Value::Float(0.0))
        {
            let (source, output) = tile_source(&mut graph, pin.ty);
            graph.connect(source, output, node, pin.name);
        }
    }
    let out = &signature.outputs[0];
    show(&mut graph, node, out.name, out.ty);
    graph
}

/// Per pixel, the largest difference between the GPU's flat render of `compiled`
/// (albedo) and the CPU reference's (f64 from the same f32 positions), over a size²
/// image of `rect`.
pub(crate) fn pixel_differences(compiled: &Compiled, rect: FlatRect, size: u32) -> Vec<f64> {
    pixel_differences_in::<f64>(compiled, rect, size)
}

/// [`pixel_differences`] against the CPU evaluator in precision `R`.
fn pixel_differences_in<R: veneer::eval::Real + Send>(
    compiled: &Compiled,
    rect: FlatRect,
    size: u32,
) -> Vec<f64> {
    let gpu_pixels = FlatRenderer::for_compiled(gpu(), compiled)
        .expect("the passes' pipelines build")
        .render(gpu(), rect, size, 0.0)
        .expect("the passes render");
    let evaluator = Evaluator::from_checked(compiled.checked.clone());
    let cpu_pixels = evaluator.flat::<R>(&compiled.passes, rect, size, 0.0);
    (gpu_pixels.iter().zip(&cpu_pixels))
        .map(|(gpu, cpu)| {
            (0..3)
                .map(|k| (f64::from(gpu[k]) - cpu.albedo[k].to_f64()).abs())
                .fold(0.0, f64::max)
        })
        .collect()
}

/// The largest difference between the GPU's flat render and the CPU reference's.
fn gpu_against_cpu(compiled: &Compiled, rect: FlatRect, size: u32) -> f64 {
    pixel_differences(compiled, rect, size)
        .into_iter()
        .fold(0.0, f64::max)
}

/// The image nodes that threshold a mask (their tests allow a few pixels off where the
/// mask lies within rounding of its threshold).
const THRESHOLDED: [&str; 2] = ["Distance", "Bevel"];

/// The tolerance of an image node's GPU output against its CPU reference: f32 against
/// f64 arithmetic, plus one step of an 8-bit or half-float buffer where a value lies on
/// a rounding boundary (the GPU rounds its f32, the CPU its f64).
pub(crate) fn tolerance(compiled: &Compiled) -> f64 {
    let step = |format| match format {
        BufferFormat::Unorm8 => 1.0 / 255.0,
        BufferFormat::Float16 => 1.0 / 1024.0,
        BufferFormat::Float32 => 0.0,
    };
    let coarsest = (compiled.passes.passes.iter())
        .map(|pass| step(pass.spec.format))
        .fold(0.0, f64::max);
    // Bicubic weights sum past 1 in places: allow a step and a quarter.
    1e-4 + 1.25 * coarsest
}

#[test]
fn every_image_node_matches_its_cpu_reference() {
    let mut failures = Vec::new();
    let image_kinds: Vec<NodeKind> = NodeKind::examples()
        .into_iter()
        .filter(NodeKind::samples)
        // Flood fill compares in `flood_fill.rs` over masks with no texel at the
        // threshold: here one texel of noise within f32 rounding of 0.5 joins or splits
        // whole cells, whose random values then differ.
        .filter(|kind| kind.name() != "FloodFill")
        .collect();
    assert!(image_kinds.len() >= 4, "the registry lists the image nodes");
    for kind in image_kinds {
        let graph = image_graph(&kind);
        let compiled = compile(&graph, &Default::default())
            .unwrap_or_else(|e| panic!("{kind:?}: {e}\n{}", veneer::graph::to_ron(&graph)));
        assert!(!compiled.passes.is_empty(), "{kind:?} renders passes");
        let differences = pixel_differences(&compiled, TILE, 48);
        let allowed = tolerance(&compiled);
        let worst = differences.iter().copied().fold(0.0, f64::max);
        let off = differences.iter().filter(|&&d| d > allowed).count();
        // A mask thresholds at 0.5: a texel within rounding of it may fall either side
        // on the GPU and the CPU, and move the distances around it by a texel.
        let may_be_off = if THRESHOLDED.contains(&kind.name()) {
            differences.len() / 50
        } else {
            0
        };
        if off > may_be_off {
            failures.push(format!(
                "{kind:?}: {off} pixels differ, by up to {worst:.2e} (allowed {allowed:.1e})"
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A noise read by a blur and by a height-to-normal node, the blur's result as the
/// albedo and the normal as the material's normal.
fn blurred_and_normal(radius: f64) -> Graph {
    let mut graph = Graph::default();
    let noise = tile_noise(&mut graph, "grain", Basis::Gradient);
    let blur = graph.add(
        "soft",
        NodeKind::Blur(Blur {
            ty: ValueType::Float,
            unit: RadiusUnit::Texels,
        }),
    );
    graph.set_input(blur, "radius", Value::Float(radius));
    graph.connect(noise, "value", blur, "image");
    let normal = graph.add(
        "relief",
        NodeKind::HeightToNormal(HeightToNormal {
            convention: veneer::nodes::NormalConvention::OpenGl,
        }),
    );
    graph.connect(noise, "value", normal, "height");
    let material = graph.add("material", NodeKind::Material);
    graph.connect(blur, "result", material, "albedo");
    graph.connect(blur, "result", material, "height");
    graph.connect(normal, "normal", material, "normal");
    graph
}

#[test]
fn readers_of_one_cut_share_its_buffer_and_unreachable_cuts_render_nothing() {
    let graph = blurred_and_normal(6.0);
    let compiled = compile(&graph, &Default::default()).expect("compiles");
    let labels: Vec<&str> = (compiled.passes.passes.iter())
        .map(|pass| pass.label.as_str())
        .collect();
    // The noise once (read by both), then the blur's two axes over it.
    assert_eq!(labels.len(), 3, "{labels:?}");
    assert!(labels[0].contains("'grain'"), "{labels:?}");
    assert!(
        labels[1].contains("x axis") && labels[2].contains("y axis"),
        "{labels:?}"
    );
    assert_eq!(
        compiled.passes.reads,
        [2, 0],
        "the material reads the blur and the noise"
    );

    // A blur nobody reads adds no pass; a blur of the blur adds its cut and two axes.
    let mut more = graph.clone();
    let (soft, material) = (by_label(&more, "soft"), by_label(&more, "material"));
    let dangling = more.add("unread", more.node(soft).expect("the blur").kind.clone());
    more.connect(soft, "result", dangling, "image");
    assert_eq!(
        compile(&more, &Default::default())
            .expect("compiles")
            .passes
            .passes
            .len(),
        3
    );
    more.connect(dangling, "result", material, "albedo");
    let chained = compile(&more, &Default::default()).expect("compiles");
    assert_eq!(chained.passes.passes.len(), 6);
    // Every pass reads only buffers rendered before it.
    for (index, pass) in chained.passes.passes.iter().enumerate() {
        assert!(
            pass.reads().iter().all(|&read| read < index),
            "{}",
            pass.label
        );
    }
    let worst = gpu_against_cpu(&chained, TILE, 32);
    assert!(worst <= 1e-4, "a blur of a blur differs by {worst:.2e}");

    // The same graph's output rendered twice gives the same bytes.
    let renderer = FlatRenderer::for_compiled(gpu(), &chained).expect("pipelines");
    let first = renderer.render(gpu(), TILE, 32, 0.0).expect("renders");
    let fresh = FlatRenderer::for_compiled(gpu(), &chained).expect("pipelines");
    assert_eq!(first, fresh.render(gpu(), TILE, 32, 0.0).expect("renders"));
}

#[test]
fn sampled_inputs_need_a_wire_and_a_blur_a_constant_finite_radius() {
    let check_error = |graph: &Graph| match compile(graph, &Default::default()) {
        Err(CompileError::Check(errors)) => errors
            .iter()
            .map(|e| format!("{}: {}", e.node_name.clone().unwrap_or_default(), e.message))
            .collect::<Vec<_>>()
            .join("\n"),
        other => panic!(
            "expected a check error, got {:?}",
            other.map(|c| c.passes.passes.len())
        ),
    };
    let mut wired_radius = blurred_and_normal(4.0);
    let (soft, grain) = (
        by_label(&wired_radius, "soft"),
        by_label(&wired_radius, "grain"),
    );
    wired_radius.connect(grain, "value", soft, "radius");
    let message = check_error(&wired_radius);
    assert!(
        message.contains("'soft'") && message.contains("radius must be a constant"),
        "{message}"
    );
    for radius in [f64::NAN, -1.0] {
        let message = check_error(&blurred_and_normal(radius));
        assert!(
            message.contains("'soft'") && message.contains("radius"),
            "{message}"
        );
    }
    let mut unwired = blurred_and_normal(4.0);
    (unwired.wires).retain(|wire| !(wire.to.node == soft && wire.to.pin == "image"));
    unwired.set_input(soft, "image", Value::Float(0.5));
    let message = check_error(&unwired);
    assert!(
        message.contains("'soft'") && message.contains("read as a buffer and must be connected"),
        "{message}"
    );
}

#[test]
fn image_nodes_stay_finite_at_extremes() {
    // A radius past the limit blurs at the limit; a rectangle far from the origin.
    let compiled = compile(&blurred_and_normal(1e9), &Default::default()).expect("compiles");
    let far = FlatRect {
        x0: 1e7,
        z0: -1e7,
        x1: 1e7 + 1.0,
        z1: -1e7 + 1.0,
        y: 3e6,
    };
    for rect in [TILE, far] {
        let pixels = FlatRenderer::for_compiled(gpu(), &compiled)
            .expect("pipelines")
            .render(gpu(), rect, 16, 0.0)
            .expect("renders");
        assert!(pixels.iter().flatten().all(|v| v.is_finite()), "{rect:?}");
    }
    // A warp moved by 1e30 of a vector reads the buffer somewhere, finitely.
    let warp = NodeKind::Warp(Warp {
        ty: ValueType::Float,
    });
    let mut graph = image_graph(&warp);
    let node = by_label(&graph, "under test");
    graph.set_input(node, "amount", Value::Float(1e30));
    let compiled = compile(&graph, &Default::default()).expect("compiles");
    let worst = gpu_against_cpu(&compiled, TILE, 16);
    assert!(worst.is_finite(), "a huge warp gives {worst}");
}

#[test]
fn a_blurred_periodic_noise_bakes_a_seamless_tile() {
    let dir = temp_dir("passes-tile");
    let settings = BakeSettings {
        surface: BakeSurface::Tile(None),
        size: 64,
        maps: vec![Map::Albedo, Map::Normal, Map::Height],
        format: Format::Png8,
        normal: NormalConvention::OpenGl,
        time: 0.0,
    };
    let compiled = compile(&blurred_and_normal(12.0), &Default::default()).expect("compiles");
    let maps = bake(gpu(), &compiled, &settings, &dir.join("blurred"), |_, _| {
        true
    })
    .expect("the tile bakes through its passes");
    for map in &maps {
        let seams = map.seams.expect("a tile reports its seams");
        assert!(seams.worst() <= SEAM_TOLERANCE, "{:?}: {seams:?}", map.map);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Runs an independent validator over an exported file.
fn validate_with(tool: &str, file: &std::path::Path) {
    let output = std::process::Command::new(tool)
        .arg(file)
        .output()
        .unwrap_or_else(|e| panic!("{tool} is needed (`.ci/run` installs it): {e}"));
    assert!(
        output.status.success(),
        "{tool} rejects {}:\n{}",
        file.display(),
        String::from_utf8_lossy(&output.stdout)
    );
}

#[test]
fn a_multi_pass_material_exports_a_module_per_pass_and_a_manifest_for_every_target() {
    use veneer::codegen::ParamMode;
    use veneer::codegen::export::Target;
    use veneer::codegen::manifest::export_passes;
    let dir = temp_dir("passes-export");
    let graph = blurred_and_normal(5.0);
    for params in [ParamMode::Baked, ParamMode::Uniform] {
        let options = veneer::codegen::CompileOptions::with_params(params);
        let compiled = compile(&graph, &options).expect("compiles");
        for (target, name, _) in Target::ALL {
            let files = export_passes(&compiled, target, "blurred")
                .unwrap_or_else(|e| panic!("{name} {params:?}: {e}"));
            // The material, a module per pass, the manifest.
            assert_eq!(files.len(), compiled.passes.passes.len() + 2, "{name}");
            for file in &files[..files.len() - 1] {
                let path = dir.join(format!("{params:?}-{}", file.name));
                std::fs::write(&path, &file.bytes).expect("written");
                match target {
                    Target::Glsl | Target::GlslEs => validate_with("glslangValidator", &path),
                    Target::Spirv => validate_with("spirv-val", &path),
                    Target::Wgsl | Target::Hlsl | Target::Msl => {}
                }
            }
            let manifest: serde_json::Value =
                serde_json::from_slice(&files.last().expect("a manifest").bytes).expect("JSON");
            assert_eq!(manifest["target"], name);
            assert_eq!(manifest["material"]["file"], files[0].name);
            let passes = manifest["passes"].as_array().expect("passes");
            for (index, pass) in passes.iter().enumerate() {
                assert_eq!(pass["buffer"], index);
                assert_eq!(pass["file"], files[index + 1].name);
                assert_eq!(pass["edge"], "wrap");
                for read in pass["reads"].as_array().expect("reads") {
                    assert!(read["buffer"].as_u64().expect("a buffer") < index as u64);
                }
            }
            assert_eq!(passes[0]["kind"], "surface");
            assert_eq!(passes[1]["kind"], "stage");
            assert_eq!(passes[0]["format"], "rgba32float");
        }
    }

    // The command line writes them together beside the file it is given, and refuses
    // to put several modules on stdout.
    let graph_path = dir.join("blurred.ron");
    std::fs::write(&graph_path, veneer::graph::to_ron(&graph)).expect("writes");
    let graph_arg = graph_path.to_str().expect("utf-8");
    let output = run_veneer(&["compile", graph_arg]);
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("give `-o FILE`"));
    let out = dir.join("out").join("soft.frag");
    std::fs::create_dir_all(out.parent().expect("a folder")).expect("folder");
    let output = run_veneer(&[
        "compile",
        graph_arg,
        "--target",
        "glsl",
        "-o",
        out.to_str().expect("utf-8"),
    ]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let mut written: Vec<String> = std::fs::read_dir(dir.join("out"))
        .expect("listed")
        .map(|entry| {
            entry
                .expect("entry")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    written.sort();
    assert_eq!(
        written,
        [
            "soft.frag",
            "soft.pass0.frag",
            "soft.pass1.frag",
            "soft.pass2.frag",
            "soft.passes.json"
        ]
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_shipped_texture_graphs_bake_seamless_tiles_that_match_their_cpu_reference() {
    let dir = temp_dir("passes-shipped");
    let paths = crate::support::texture_graphs();
    assert!(!paths.is_empty());
    let settings = BakeSettings {
        surface: BakeSurface::Tile(None),
        size: 64,
        maps: vec![Map::Albedo, Map::Normal],
        format: Format::Png8,
        normal: NormalConvention::OpenGl,
        time: 0.0,
    };
    for path in paths {
        let graph = veneer::graph::load(&path).expect("loads");
        let compiled = compile(&graph, &Default::default()).expect("compiles");
        assert!(!compiled.passes.is_empty(), "{}", path.display());
        let maps = bake(gpu(), &compiled, &settings, &dir.join("map"), |_, _| true)
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        for map in &maps {
            let seams = map.seams.expect("a tile reports its seams");
            assert!(
                seams.worst() <= SEAM_TOLERANCE,
                "{}: {seams:?}",
                path.display()
            );
        }
        let sine_hash = (compiled.checked.order.iter())
            .any(|checked| checked.node.kind.basis() == Some(veneer::graph::Basis::ValueSine));
        if sine_hash {
            // The sine hash's bits follow the precision and the adapter's `sin` (a
            // herringbone's ring_wood group): against f32, within 2/255 on 99% of pixels.
            let differences = pixel_differences_in::<f32>(&compiled, TILE, 32);
            let off = differences.iter().filter(|d| **d > 2.0 / 255.0).count();
            assert!(
                off * 100 <= differences.len(),
                "{}: {off} pixels differ",
                path.display()
            );
        } else {
            let worst = gpu_against_cpu(&compiled, TILE, 32);
            assert!(worst <= 1e-4, "{}: differs by {worst:.2e}", path.display());
        }
        // Buffers only the next step reads share two scratch textures: a texture of its
        // own per cut and per node result after stages, not one per stage.
        let flat = FlatRenderer::for_compiled(gpu(), &compiled).expect("pipelines");
        // (Uploaded files take their own size.)
        let bitmap_bytes: u64 = (compiled.passes.passes.iter())
            .filter(|pass| matches!(pass.kind, PassKind::Bitmap { .. }))
            .map(|pass| {
                let (width, height) = pass.extent(64);
                u64::from(width) * u64::from(height) * 16
            })
            .sum();
        let own_textures = (flat.pass_bytes(64) - bitmap_bytes) / (64 * 64 * 16);
        let surfaces = (compiled.passes.passes.iter())
            .filter(|pass| matches!(pass.kind, PassKind::Surface { .. }))
            .count() as u64;
        assert!(
            own_textures <= 2 * surfaces + 2,
            "{}: {own_textures} textures",
            path.display()
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_value_edit_renders_again_only_the_passes_it_reaches() {
    use veneer::codegen::{CompileOptions, ParamMode, param_values};
    let path = crate::support::root("graphs/texture/blurred_noise.ron");
    let graph = veneer::graph::load(&path).expect("loads");
    let compiled =
        compile(&graph, &CompileOptions::with_params(ParamMode::Uniform)).expect("compiles");
    // The noise, then the blur's two axes over it.
    assert_eq!(compiled.passes.passes.len(), 3);
    let renderer = FlatRenderer::for_compiled(gpu(), &compiled).expect("pipelines");
    let render = |graph: &Graph| {
        renderer.write_params(gpu(), &param_values(graph, &compiled.module.params));
        let pixels = renderer.render(gpu(), TILE, 32, 0.0).expect("renders");
        (renderer.passes_rendered(), pixels)
    };
    let (first, _) = render(&graph);
    assert_eq!(first, 3, "the first render renders every pass");
    assert_eq!(render(&graph).0, 3, "the same values render nothing again");

    // The material's own values and the normal's strength reach no pass.
    let mut edited = graph.clone();
    let material = by_label(&edited, "material");
    edited.set_input(material, "roughness", Value::Float(0.2));
    let relief = by_label(&edited, "relief");
    edited.set_input(relief, "strength", Value::Float(0.02));
    assert_eq!(render(&edited).0, 3);

    // The noise's gain reaches its pass and the blur's two downstream of it; the
    // picture is then the edited graph's.
    let grain = by_label(&edited, "grain");
    edited.set_input(grain, "gain", Value::Float(0.8));
    let (count, pixels) = render(&edited);
    assert_eq!(count, 6);
    let baked = compile(&edited, &Default::default()).expect("compiles");
    let expected = FlatRenderer::for_compiled(gpu(), &baked)
        .expect("pipelines")
        .render(gpu(), TILE, 32, 0.0)
        .expect("renders");
    let worst = (pixels.iter().zip(&expected))
        .flat_map(|(a, b)| (0..3).map(move |k| (a[k] - b[k]).abs()))
        .fold(0.0f32, f32::max);
    assert!(worst < 1e-5, "the edited preview differs by {worst}");
}

#[test]
fn a_buffer_node_sets_the_buffer_that_the_image_nodes_it_feeds_read() {
    use veneer::nodes::passes::{EdgeMode, Filter, Resolution};
    let mut graph = Graph::default();
    let noise = tile_noise(&mut graph, "grain", Basis::Gradient);
    let buffer = graph.add(
        "coarse",
        NodeKind::Buffer(veneer::nodes::Buffer {
            ty: ValueType::Float,
            resolution: Resolution::Half,
            size: 512,
            format: BufferFormat::Unorm8,
            edge: EdgeMode::Mirror,
            filter: Filter::Bilinear,
        }),
    );
    graph.connect(noise, "value", buffer, "value");
    let blur = graph.add(
        "soft",
        NodeKind::Blur(Blur {
            ty: ValueType::Float,
            unit: RadiusUnit::Texels,
        }),
    );
    graph.connect(buffer, "value", blur, "image");
    show(&mut graph, blur, "result", ValueType::Float);
    let compiled = compile(&graph, &Default::default()).expect("compiles");
    // The noise rendered once at the Buffer node's settings, then the blur's two axes.
    let passes = &compiled.passes.passes;
    assert_eq!(passes.len(), 3);
    assert_eq!(passes[0].spec.resolution, Resolution::Half);
    assert_eq!(passes[0].spec.format, BufferFormat::Unorm8);
    assert!(
        passes[1..]
            .iter()
            .all(|pass| pass.spec.edge == EdgeMode::Mirror)
    );
    assert_eq!(passes[0].spec.texels(48), 24);
    let worst = gpu_against_cpu(&compiled, TILE, 48);
    assert!(worst <= tolerance(&compiled), "differs by {worst:.2e}");
}

#[test]
fn auto_levels_stretches_a_noise_to_fill_zero_to_one_and_reports_its_totals() {
    for output in ["result", "min", "max", "mean"] {
        let mut graph = Graph::default();
        let (source, pin) = tile_source(&mut graph, ValueType::Float);
        let levels = graph.add("levels", NodeKind::AutoLevels);
        graph.connect(source, pin, levels, "image");
        show(&mut graph, levels, output, ValueType::Float);
        let compiled = compile(&graph, &Default::default()).expect("compiles");
        let worst = gpu_against_cpu(&compiled, TILE, 48);
        assert!(worst <= 1e-4, "{output}: differs by {worst:.2e}");
        if output == "result" {
            // The buffer's texel centres are the picture's pixel centres: its lowest
            // and highest texels show as 0 and 1.
            let pixels = FlatRenderer::for_compiled(gpu(), &compiled)
                .expect("pipelines")
                .render(gpu(), TILE, 48, 0.0)
                .expect("renders");
            let values: Vec<f32> = pixels.iter().map(|pixel| pixel[0]).collect();
            let low = values.iter().copied().fold(f32::MAX, f32::min);
            let high = values.iter().copied().fold(f32::MIN, f32::max);
            assert!(
                low.abs() < 1e-6 && (high - 1.0).abs() < 1e-6,
                "{low} to {high}"
            );
        }
    }
}
