//! Multi-pass materials over a mesh's UV layout: a buffer rendered at the mesh's UVs
//! and read back there draws what the graph without it draws (on the mesh, in the UV
//! bake and in the editor's preview), texels between UV islands are filled with their
//! nearest island's, and the command line's mesh views and glTF export take such
//! materials.

use crate::passes::show;
use crate::support::{gpu, run_veneer, temp_dir};
use veneer::codegen::compile;
use veneer::graph::{Basis, Graph, NodeKind, Value, ValueType};
use veneer::nodes::{Buffer, Noise};
use veneer::render::{LiveMaterialCode, LiveRenderer, MeshView, Quality, View, render_material};

/// A smooth noise of the surface position as the albedo: read at once (`buffered`
/// false), or through a float buffer over the domain.
fn noise_albedo(buffered: bool) -> Graph {
    let mut graph = Graph::default();
    let position = graph.add("position", NodeKind::Position);
    let noise = graph.add(
        "noise",
        NodeKind::Noise(Noise {
            basis: Basis::Gradient,
            period: 0,
        }),
    );
    graph.set_input(noise, "scale", Value::Float(1.5));
    graph.connect(position, "position", noise, "p");
    if buffered {
        let buffer = graph.add("buffer", NodeKind::Buffer(Buffer::default()));
        graph.connect(noise, "value", buffer, "value");
        show(&mut graph, buffer, "value", ValueType::Float);
    } else {
        show(&mut graph, noise, "value", ValueType::Float);
    }
    graph
}

/// How far apart two RGBA8 pictures are over their colour channels, in 8-bit steps.
struct Apart {
    mean: f64,
    largest: u8,
    /// The share of channel values more than [`FAR`] steps apart.
    far: f64,
}

/// Steps apart that only pixels on a silhouette reach: there a sample of a triangle
/// beyond its edge reads the buffer at a uv extrapolated past the layout.
const FAR: u8 = 6;

fn apart(a: &[u8], b: &[u8]) -> Apart {
    let steps: Vec<u8> = (a.chunks_exact(4).zip(b.chunks_exact(4)))
        .flat_map(|(p, q)| (0..3).map(move |c| p[c].abs_diff(q[c])))
        .collect();
    let count = steps.len() as f64;
    Apart {
        mean: steps.iter().map(|&s| f64::from(s)).sum::<f64>() / count,
        largest: steps.iter().copied().max().unwrap_or(0),
        far: steps.iter().filter(|&&s| s > FAR).count() as f64 / count,
    }
}

impl Apart {
    /// Whether the pictures differ only as bilinear reading and silhouettes make them.
    fn alike(&self) -> bool {
        self.mean < 0.25 && self.far < 1e-3
    }
}

#[test]
fn a_buffered_noise_on_a_mesh_draws_like_the_noise_itself() {
    // The buffer spans each mesh's UV layout, so read at the mesh's UVs it gives back
    // the noise, up to its bilinear reading between texel centres. The cube's faces
    // each span the whole unit square: it is drawn with an atlas, whose six islands lie
    // apart. Were the buffer rendered over the flat tile, over the overlapping faces, or
    // were the texels around the islands left empty (read at their borders), the
    // pictures would differ by far more.
    let direct = compile(&noise_albedo(false), &Default::default()).expect("compiles");
    let buffered = compile(&noise_albedo(true), &Default::default()).expect("compiles");
    assert_eq!(buffered.passes.passes.len(), 1, "one pass: the buffer");
    for mesh in ["sphere", "torus", "cube"] {
        let view = View::Mesh(Some(mesh.into()));
        let drawn = |compiled| {
            render_material(gpu(), compiled, &view, 128, 0.0)
                .unwrap_or_else(|e| panic!("{mesh}: {e}"))
                .pixels
        };
        let apart = apart(&drawn(&direct), &drawn(&buffered));
        assert!(
            apart.alike(),
            "{mesh}: mean {:.3}, {} far, largest {} steps apart",
            apart.mean,
            apart.far,
            apart.largest
        );
    }
}

#[test]
fn a_uv_bake_through_a_buffer_of_its_own_size_gives_back_its_texels() {
    // Baked over the torus's UV layout at the buffer's size, every texel of the map is
    // read at (all but exactly) a texel centre of the buffer: the maps are the same but
    // for rounding.
    let dir = temp_dir("mesh-passes-bake");
    let out = dir.join("maps");
    std::fs::create_dir_all(&out).expect("makes the folder");
    for (name, buffered) in [("direct", false), ("buffered", true)] {
        let file = dir.join(format!("{name}.ron"));
        veneer::graph::save(&noise_albedo(buffered), &file).expect("saves");
        let (file, out) = (file.to_str().expect("utf-8"), out.to_str().expect("utf-8"));
        let args = [
            "bake", file, "--size", "64", "--mesh", "torus", "--maps", "albedo",
        ];
        let baked = run_veneer(&[&args[..], &["-o", out]].concat());
        let stderr = String::from_utf8_lossy(&baked.stderr);
        assert!(baked.status.success(), "{name}: {stderr}");
    }
    let read = |name: &str| {
        let image = image::open(out.join(format!("{name}_albedo.png"))).expect("a PNG");
        image.to_rgba8().into_raw()
    };
    let apart = apart(&read("direct"), &read("buffered"));
    assert!(
        apart.largest <= 1 && apart.mean < 0.05,
        "mean {:.3}, largest {}",
        apart.mean,
        apart.largest
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_command_line_draws_and_exports_a_multi_pass_material_on_meshes() {
    let dir = temp_dir("mesh-passes-cli");
    let graph = dir.join("blurred.ron");
    let source = crate::support::root("graphs/texture/blurred_noise.ron");
    std::fs::copy(&source, &graph).expect("copies");
    let graph = graph.to_str().expect("utf-8");
    for (args, written) in [
        (vec!["render", graph, "--mesh", "torus", "-o"], "mesh.png"),
        (vec!["bake", graph, "--gltf"], "material.glb"),
    ] {
        let path = dir.join(written);
        let path = path.to_str().expect("utf-8");
        let output = run_veneer(&[&args[..], &[path, "--size", "48"][..]].concat());
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(output.status.success(), "{args:?}: {stderr}");
        assert!(std::fs::metadata(path).is_ok_and(|m| m.len() > 0), "{path}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_editor_preview_draws_a_multi_pass_material_on_its_mesh() {
    // The live renderer (the preview thread's) on the sphere: its passes over the
    // sphere's UV layout at the preview's pass size; the same picture as the noise
    // read at once, but for the buffer's bilinear reading.
    let gpu = gpu();
    let sky = gpu.sky().expect("the default environment");
    let mesh = veneer::mesh::primitive("sphere").expect("a sphere");
    let drawn = |graph: &Graph| {
        let mut live = veneer::app::LiveMaterial::in_storage();
        live.update(graph);
        let code = LiveMaterialCode::new(1, live.compiled.as_ref().expect("it compiles"));
        let view = MeshView::for_preview(&graph.preview);
        let (_, pixels) = LiveRenderer::default()
            .render(
                gpu,
                &code,
                &live.params(graph),
                "sphere",
                &mesh,
                &view,
                &sky,
                (128, 128),
                Quality::Full,
            )
            .expect("the preview draws");
        (code.passes.is_some(), pixels)
    };
    let (direct_passes, direct) = drawn(&noise_albedo(false));
    let (buffered_passes, buffered) = drawn(&noise_albedo(true));
    assert!(!direct_passes && buffered_passes);
    let apart = apart(&direct, &buffered);
    assert!(
        apart.alike(),
        "mean {:.3}, {} far, largest {} steps apart",
        apart.mean,
        apart.far,
        apart.largest
    );
}
