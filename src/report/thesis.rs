//! The report's GeoTexture sections, seed 003's Tables 5.1–5.3 in form: the time of one
//! distance field per model and method, and frame rates near and far for each of the
//! thesis's textures, on meshes of the sizes the thesis used.

use super::geodesics::{APPROXIMATE, time_field};
use super::measure::{mean_deviation, samples};
use super::plot::{Plot, Series};
use super::table::{Table, number};
use super::{Context, Section};
use crate::codegen::{CompileOptions, compile};
use crate::geodesic::{self, Method};
use crate::graph::FieldSource;
use crate::mesh::Mesh;
use crate::render::{GpuMesh, MeshRenderer, MeshView, PassTimer, Relief};
use glam::Vec3;

/// The thesis's models (Table 5.1) and their triangle counts, in its order.
pub const THESIS_MODELS: [(&str, u32); 4] = [
    ("Fertility", 10_000),
    ("Genus3", 13_312),
    ("Chair", 25_524),
    ("Hebe", 7_989),
];

/// The meshes standing in for [`THESIS_MODELS`], one for one: `torus:50` (10,000
/// triangles, genus 1), `genus2:18` (marching tetrahedra, slivers), `sphere:80`
/// (regular quads, pole fans) and `scan:14`, a lumpy, grainy blob polygonised by
/// marching tetrahedra (see [`scan`]).
pub const MODELS: [&str; 4] = ["torus:50", "genus2:18", "sphere:80", "scan:14"];

/// Smaller stand-ins for `--quick`.
pub const QUICK_MODELS: [&str; 4] = ["torus:12", "genus2:8", "sphere:12", "scan:6"];

/// The thesis's textures (Tables 5.2 and 5.3, with the waves of §5.3.3 added) as the
/// presets that transcribe them, and the names the thesis gives them.
/// The waves appear three times, as figure 5.10 compares them: displaced on the model's
/// own triangles, shaded as bump only, and displaced with adaptive tessellation (the
/// adaptive preset refines each view's mesh before it is timed).
pub const TEXTURES: [(&str, &str, Relief); 8] = [
    ("thesis_c2_sand_water", "Water/Sand", Relief::Displaced),
    ("thesis_c3_moss_granite", "Moss", Relief::Displaced),
    ("thesis_c4_paint_metal_rust", "Rust", Relief::Displaced),
    ("thesis_c5_water_lava", "Water/Lava", Relief::Displaced),
    ("isolines", "Isolines", Relief::Displaced),
    ("thesis_c6_waves", "Waves", Relief::Displaced),
    ("thesis_c6_waves_adaptive", "Waves, bump only", Relief::Bump),
    (
        "thesis_c6_waves_adaptive",
        "Waves, tessellated",
        Relief::Displaced,
    ),
];

/// Camera distances from the mesh's centre (vertical field of view 40°): near, the mesh
/// overfills the frame; far, it covers a few percent of it.
const NEAR: f32 = 1.5;
const FAR: f32 = 9.0;

/// The time the textures are drawn at (seconds; their fronts part-way across).
const TIME: f32 = 3.0;

/// A stand-in for a scanned statue (the thesis's Hebe): an upright ellipsoid with lumps
/// and a fine grain of sines, polygonised by marching tetrahedra every `1 / detail`, so
/// its triangles are as uneven as a reconstructed scan's (slivers, no regular rows).
pub fn scan(detail: u32) -> Mesh {
    let f = |p: Vec3| {
        let body = (p / Vec3::new(0.5, 0.85, 0.5)).length() - 1.0;
        let lumps = 0.12 * (5.0 * p.x).sin() * (4.0 * p.y + 1.0).sin() * (6.0 * p.z + 2.0).sin();
        let grain = 0.02 * (29.0 * p.x + 3.0).sin() * (31.0 * p.y).sin() * (37.0 * p.z + 1.0).sin();
        body - lumps - grain
    };
    let extent = Vec3::new(0.7, 1.0, 0.7);
    crate::mesh::polygonize(f, -extent, extent, 1.0 / detail.max(1) as f32)
}

/// The mesh a model name stands for: `scan:N` or a primitive.
fn model(name: &str) -> Result<Mesh, String> {
    match name.split_once(':') {
        Some(("scan", detail)) => detail
            .parse()
            .map(scan)
            .map_err(|_| format!("{name}: bad detail")),
        _ => crate::mesh::primitive(name).ok_or_else(|| format!("{name}: no such primitive")),
    }
}

/// The models of the context, welded (seams do not cut distances), with their names.
fn models<'a>(ctx: &Context<'a>) -> Result<Vec<(&'a str, Mesh)>, String> {
    ctx.models
        .iter()
        .map(|&name| Ok((name, geodesic::welded_for_distances(&model(name)?).0)))
        .collect()
}

/// The methods of Table 5.1: exact, then those the geodesic section measures against it.
fn methods() -> [Method; 4] {
    [
        Method::Exact,
        APPROXIMATE[0],
        APPROXIMATE[1],
        APPROXIMATE[2],
    ]
}

/// Table 5.1: the time of one distance field from one source, from scratch, on each
/// model by each method.
pub fn distance_times(ctx: &Context) -> Result<Section, String> {
    let methods = methods();
    let mut header = vec![
        "mesh".to_string(),
        "thesis model of similar size".into(),
        "triangles".into(),
    ];
    for method in &methods {
        header.push(format!("{} mean ms", method.name()));
        header.push(format!("{} deviation ms", method.name()));
    }
    let mut table = Table::new(&header.iter().map(String::as_str).collect::<Vec<_>>());
    let mut series: Vec<Series> = methods
        .iter()
        .map(|m| Series {
            name: m.name().into(),
            points: Vec::new(),
            joined: true,
        })
        .collect();
    let mut failures = Vec::new();
    for (k, (name, mesh)) in models(ctx)?.into_iter().enumerate() {
        let (like, like_triangles) = THESIS_MODELS[k % THESIS_MODELS.len()];
        let triangles = mesh.triangle_count();
        let mut row = vec![
            name.to_string(),
            format!("{like} ({like_triangles} triangles)"),
            triangles.to_string(),
        ];
        for (method, series) in methods.iter().zip(&mut series) {
            match time_field(&mesh, *method, ctx.repetitions) {
                Ok(times) => {
                    let (mean, deviation) = mean_deviation(&times.total_ms());
                    series.points.push((triangles as f64, mean));
                    row.extend([number(mean, 3), number(deviation, 2)]);
                }
                Err(error) => {
                    failures.push(format!("{} on `{name}`: {error}", method.name()));
                    row.extend(["failed".to_string(), "—".into()]);
                }
            }
        }
        table.push(row);
        (ctx.progress)();
    }
    for series in &mut series {
        series.points.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    let failed = if failures.is_empty() {
        String::new()
    } else {
        format!(" Failed: {}.", failures.join("; "))
    };
    Ok(Section {
        title: "Distance-field time per model (thesis Table 5.1)".into(),
        text: format!(
            "Seed 003's Table 5.1 gives, for each model, its triangles, the charts its base mesh was cut into and the mean and standard deviation of the time to compute one distance field in preprocessing: 1.78 s (Hebe, 7,989 triangles, 101 charts) to 9.36 s (Chair, 25,524 triangles, 127 charts) on an Intel Core 2 6420 at 2.13 GHz. Veneer has no charts: each method works on the whole (welded) mesh, so the stand-ins are meshes of similar size rather than the thesis's models — `torus`, `genus2` (marching tetrahedra, with slivers), `sphere` (regular rows, pole fans) and `scan`, an upright lumpy blob with a fine grain polygonised by marching tetrahedra, standing in for the scanned Hebe. Each cell is the mean and standard deviation over {} repetitions of one field from one source from scratch: heat includes building the intrinsic triangulation and factoring (set-up) and one solve, exact includes its triangulation; heat and Dijkstra after one untimed warm-up run. Once a mesh is set up, a new heat field costs only its solve (see *Geodesic methods*).{failed}",
            ctx.repetitions
        ),
        table,
        plot: Plot {
            title: "Distance-field time against triangles".into(),
            x_label: "triangles".into(),
            y_label: "mean time of one field from scratch (ms)".into(),
            series,
        },
    })
}

/// The vertex of `mesh` nearest to `point`.
fn nearest_vertex(mesh: &Mesh, point: Vec3) -> u32 {
    (0..mesh.positions.len())
        .min_by(|&a, &b| {
            let d = |k: usize| Vec3::from(mesh.positions[k]).distance_squared(point);
            d(a).total_cmp(&d(b))
        })
        .unwrap_or(0) as u32
}

/// A texture's fields with each source moved from its own preview mesh to the nearest
/// vertex of `mesh`, so that the fronts start where the preset starts them.
fn moved_fields(
    fields: &[FieldSource],
    preview: &Mesh,
    mesh: &Mesh,
) -> Result<Vec<FieldSource>, String> {
    fields
        .iter()
        .map(|field| {
            let sources = field
                .sources
                .iter()
                .map(|&v| {
                    preview
                        .positions
                        .get(v as usize)
                        .map(|&p| nearest_vertex(mesh, Vec3::from(p)))
                        .ok_or_else(|| format!("source {v} is not a vertex of its preview mesh"))
                })
                .collect::<Result<_, _>>()?;
            Ok(FieldSource {
                sources,
                method: field.method,
            })
        })
        .collect()
}

/// The share of a rendered frame that is not `background` (the colour of a pixel that
/// shows no mesh).
fn covered(pixels: &[[u8; 4]], background: [u8; 4]) -> f64 {
    pixels.iter().filter(|&&p| p != background).count() as f64 / pixels.len().max(1) as f64
}

/// One texture ready to draw: its label, renderer and fields.
struct Texture {
    label: &'static str,
    renderer: MeshRenderer,
    /// The material and refinement of a texture drawn with adaptive tessellation.
    tessellation: Option<(crate::graph::CheckedGraph, crate::mesh::Refinement)>,
    fields: Vec<FieldSource>,
    used: [bool; 4],
    preview: Mesh,
    view: MeshView,
}

/// The textures of [`TEXTURES`], compiled with every octave and built once.
fn textures(ctx: &Context) -> Result<Vec<Texture>, String> {
    TEXTURES
        .iter()
        .map(|&(preset, label, relief)| {
            let graph = crate::graph::preset(preset).ok_or(format!("{preset}: no preset"))?;
            let compiled =
                compile(&graph, &CompileOptions::default()).map_err(|e| e.to_string())?;
            let module = &compiled.module;
            let renderer = MeshRenderer::with_relief(ctx.gpu, &module.source, module.uses, relief)
                .map_err(|e| e.to_string())?;
            let tessellation = graph
                .preview
                .tessellation
                .filter(|_| relief == Relief::Displaced)
                .map(|settings| (compiled.checked.clone(), settings.refinement()));
            let preview =
                crate::mesh::preview_mesh(&graph.preview.mesh).map_err(|e| e.to_string())?;
            let mut view = MeshView::for_preview(&graph.preview);
            view.time = TIME;
            Ok(Texture {
                label,
                renderer,
                tessellation,
                fields: graph.preview.fields.clone(),
                used: module.uses.fields,
                preview,
                view,
            })
        })
        .collect()
}

/// Tables 5.2 and 5.3: frames a second near and far for each texture on each model.
pub fn frame_rates(ctx: &Context) -> Result<Section, String> {
    let textures = textures(ctx)?;
    let mut header = vec![
        "mesh".to_string(),
        "triangles".into(),
        "near: frame covered".into(),
        "far: frame covered".into(),
    ];
    for texture in &textures {
        header.push(format!("{} near fps", texture.label));
        header.push(format!("{} far fps", texture.label));
    }
    header.push("timed by".into());
    let mut table = Table::new(&header.iter().map(String::as_str).collect::<Vec<_>>());
    let mut series: Vec<Series> = textures
        .iter()
        .map(|t| Series {
            name: t.label.into(),
            points: Vec::new(),
            joined: false,
        })
        .collect();
    let size = ctx.timing_size;
    let timed_by = if PassTimer::supported(ctx.gpu) {
        "GPU timestamps"
    } else {
        "wall clock"
    };
    for (name, mesh) in models(ctx)? {
        let mut cells = Vec::new();
        let mut coverage = [f64::NAN; 2];
        for (t, (texture, series)) in textures.iter().zip(&mut series).enumerate() {
            let mut textured = mesh.clone();
            let fields = moved_fields(&texture.fields, &texture.preview, &mesh)?;
            geodesic::attach_fields(&mut textured, &fields, texture.used, |_, _| {})
                .map_err(|e| format!("{} on `{name}`: {e}", texture.label))?;
            let views = [NEAR, FAR].map(|distance| MeshView {
                distance,
                ..texture.view.clone()
            });
            // Each view's mesh: the model's, or refined for that view.
            let drawn = views.each_ref().map(|view| match &texture.tessellation {
                Some((graph, refinement)) => {
                    crate::render::tessellate(graph, &textured, view, size, refinement).mesh
                }
                None => textured.clone(),
            });
            if t == 0 {
                let frame = |view: &MeshView| {
                    texture
                        .renderer
                        .render(ctx.gpu, &textured, view, size)
                        .map_err(|e| e.to_string())
                };
                let far = frame(&views[1])?;
                // The far frame's corner shows no mesh: its colour is the background's.
                coverage = [covered(&frame(&views[0])?, far[0]), covered(&far, far[0])];
            }
            for (v, view) in views.iter().enumerate() {
                let uploaded = GpuMesh::new(&ctx.gpu.device, &drawn[v]);
                let frame_ms = samples(ctx.repetitions, || {
                    texture
                        .renderer
                        .frame_time(ctx.gpu, &uploaded, view, size)
                        .map_or(f64::NAN, |time| time.as_secs_f64() * 1e3)
                });
                let (mean, _) = mean_deviation(&frame_ms);
                series
                    .points
                    .push((coverage[v] * f64::from(size * size), mean));
                cells.push(number(1e3 / mean, 3));
            }
        }
        let mut row = vec![
            name.to_string(),
            mesh.triangle_count().to_string(),
            format!("{:.1}%", 100.0 * coverage[0]),
            format!("{:.1}%", 100.0 * coverage[1]),
        ];
        row.extend(cells);
        row.push(timed_by.into());
        table.push(row);
        (ctx.progress)();
    }
    Ok(Section {
        title: "Frame rates near and far (thesis Tables 5.2 and 5.3)".into(),
        text: format!(
            "Seed 003's Tables 5.2 and 5.3 give the mean frames a second of each texture on each model near (the model close to the camera: many fragments) and far (few fragments), measured on an NVIDIA GeForce 8600 GT: near 3–18 fps and far 32–117 fps for the textures, 71–148 and 219–247 fps for the isolines. Here each texture is its appendix-C preset (C.2 water/sand, C.3 moss, C.4 rust, C.5 water/lava, the isolines preset and the C.6 waves, which the thesis timed separately on a GTS 450: 390 fps shaded as bump, 360 fps displaced with hardware tessellation; here they are timed three ways, as its figure 5.10 compares them: displaced on the model's own triangles, shaded as bump only, and displaced with adaptive tessellation, the mesh refined for each view until the displaced surface is within 0.5 px of its triangles, which takes the CPU milliseconds a view that are not in the frame times), on the meshes of *Distance-field time*, its field sources moved to the mesh's nearest vertices and its fields solved by heat on the whole mesh (no charts). A frame is {size}² pixels, 4× multisampled as `veneer render`, at time {TIME} s, the camera at distance {NEAR} (near) or {FAR} (far) from the mesh's centre with a 40° field of view; the covered columns are the share of the frame's pixels the mesh shows in. Frames a second are 1000 over the mean, over {} repetitions after a warm-up, of the frame's time measured by the adapter {} with {}. As in the thesis, a near frame's cost follows the fragments shaded and the texture's complexity, not the number of fields; far frames also pay for what does not depend on the fragments (clearing and resolving the multisampled frame, the vertex stage, each triangle's set-up), which a software rasteriser feels most.",
            ctx.repetitions,
            ctx.gpu.adapter_description(),
            if timed_by == "wall clock" {
                "the wall clock from submitting the frame to its completion (the adapter has no timestamp queries)"
            } else {
                "GPU timestamp queries around the render pass (no submission or reading back)"
            }
        ),
        table,
        plot: Plot {
            title: "Frame time against pixels covered".into(),
            x_label: "pixels covered by the mesh".into(),
            y_label: "mean frame time (ms)".into(),
            series,
        },
    })
}
