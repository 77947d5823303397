//! `veneer bake`: texture maps of one or more graphs, baked in parallel with a progress bar.

mod mesh;

use super::Failure;
use super::output::{note, out};
use super::render::parse_flat;
use clap::{Args, ValueEnum};
use indicatif::{MultiProgress, ProgressBar, ProgressStyle};
use std::path::PathBuf;
use veneer::bake::tile::seam_text;
use veneer::bake::{
    BakeSettings, BakeSurface, BakedMap, Format, Map, MeshMap, MeshMapSettings, ModelFormat,
    ModelSettings, NormalConvention, bake, map_path, mesh_map_path,
};
use veneer::codegen::{CompileOptions, compile};
use veneer::fsutil::{Naming, OutputPlan};
use veneer::render::{FlatRect, GpuContext};

#[derive(Clone, Copy, ValueEnum)]
enum FormatArg {
    /// 8-bit PNG.
    Png,
    /// 16-bit PNG.
    Png16,
    /// 32-bit float OpenEXR.
    Exr,
}

#[derive(Clone, Copy, ValueEnum)]
enum NormalArg {
    /// Green up (OpenGL, Blender, Godot, Unity).
    Gl,
    /// Green down (DirectX, Unreal).
    Dx,
}

/// A map `--maps` names: one of the material's, or one of the mesh's own.
#[derive(Clone, Copy, Debug, PartialEq)]
enum MapArg {
    Material(Map),
    Mesh(MeshMap),
}

#[derive(Args)]
pub struct BakeArgs {
    /// Graph files to bake (in parallel); none when every map is a mesh map.
    graphs: Vec<PathBuf>,
    /// Width and height of every map in pixels (up to 8192 and beyond; rendered in tiles).
    #[arg(long, default_value_t = 1024)]
    size: u32,
    /// Maps to write: the material's albedo, alpha, height, normal, specular, roughness,
    /// metallic, occlusion, emission, orm (occlusion, roughness, metallic in R, G, B);
    /// with --mesh, the mesh's own ao, curvature, thickness, position, world-normal
    /// (per texel of its UV layout, no graph needed: without graphs they are named after
    /// the mesh).
    /// With --from, normal and height are the high mesh's, and the default.
    #[arg(long, value_delimiter = ',', value_parser = parse_map)]
    maps: Option<Vec<MapArg>>,
    /// File format of the maps.
    #[arg(long, value_enum, default_value = "png")]
    format: FormatArg,
    /// Green-channel convention of normal maps.
    #[arg(long, value_enum, default_value = "gl")]
    normal: NormalArg,
    /// The plane rectangle X0,Z0,X1,Z1,Y to bake (default: each graph's preview square).
    #[arg(long, value_name = "X0,Z0,X1,Z1,Y", value_parser = parse_flat, allow_hyphen_values = true, conflicts_with = "mesh")]
    flat: Option<FlatRect>,
    /// Bake one tile of a repeating texture: over the unit square (x, z from 0 to 1 at
    /// y = 0, or `--flat`'s rectangle), each map's opposite edges checked to continue
    /// each other and the seams reported (a graph that does not repeat over the tile is
    /// refused before anything is written); normal maps take their differences across
    /// the edges, so they tile too.
    #[arg(long, conflicts_with = "mesh")]
    tile: bool,
    /// Bake into the UV layout of this primitive or mesh file instead of over a plane (an
    /// automatic atlas for a mesh without UVs).
    #[arg(long, value_name = "NAME|FILE")]
    mesh: Option<String>,
    /// Time in seconds.
    #[arg(long, default_value_t = 0.0, value_parser = super::parse_time, allow_hyphen_values = true)]
    time: f32,
    /// Bake the normal and height maps of this detailed mesh into --mesh's UV layout (high
    /// to low): rays along the low mesh's normals from the cage inwards; no graph.
    #[arg(long, value_name = "HIGH", requires = "mesh", conflicts_with_all = ["graphs", "flat", "tile", "gltf"])]
    from: Option<String>,
    /// With --from: how far outside and inside the low surface rays look for the high one,
    /// in percent of the low mesh's bounding radius (1 to 100).
    #[arg(long, default_value_t = 10)]
    cage: u32,
    /// Mesh maps ao and thickness: rays per texel (1 to 4096), the accuracy knob.
    #[arg(long, default_value_t = 8)]
    samples: u32,
    /// Mesh maps ao and thickness: how far rays look, in percent of the mesh's bounding
    /// radius (1 to 400).
    #[arg(long, default_value_t = 50)]
    distance: u32,
    /// Mesh map curvature: the radius convexity is measured at, in percent of the
    /// bounding radius (1 to 100).
    #[arg(long, default_value_t = 5)]
    radius: u32,
    /// Mesh maps ao and thickness: pool each texel's rays with those of its neighbours on
    /// the same surface up to this many texels away (0 to 8; 0: each texel alone).
    #[arg(long, default_value_t = 3)]
    pool: u32,
    /// Folder for the maps (`<graph>_<map>.<ext>`); default: next to each graph.
    #[arg(short, long)]
    out_dir: Option<PathBuf>,
    /// Write a glTF 2.0 model instead of map files: the mesh (`--mesh`, default the
    /// graph's preview mesh) with the material's maps baked into its UV layout (an
    /// automatic atlas for a mesh without UVs) as a metallic-roughness material. `.glb`
    /// gives one file; `.gltf` writes its buffer and PNGs beside it. One graph at a time.
    #[arg(long, value_name = "OUT.glb|OUT.gltf", conflicts_with_all = ["flat", "tile", "out_dir", "maps", "format", "normal"])]
    gltf: Option<PathBuf>,
    /// Write a USD stage instead of map files: the mesh (as for --gltf) bound to a
    /// material with a UsdPreviewSurface reading the baked maps and, beside it for
    /// renderers that read MaterialX, the same maps in an OpenPBR Surface. `.usdz` gives
    /// one package; `.usda` writes its PNGs beside it. One graph at a time.
    #[arg(long, value_name = "OUT.usda|OUT.usdz", conflicts_with_all = ["flat", "tile", "out_dir", "maps", "format", "normal", "gltf"])]
    usd: Option<PathBuf>,
    /// Print a JSON summary of what was written on stdout.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    parameters: super::parameters::ParameterArgs,
}

fn parse_map(text: &str) -> Result<MapArg, String> {
    let materials = Map::ALL.map(|map| (map.name(), MapArg::Material(map)));
    let meshes = MeshMap::ALL.map(|map| (map.name(), MapArg::Mesh(map)));
    let mut all = materials.iter().chain(&meshes);
    all.clone()
        .find(|(name, _)| *name == text.trim())
        .map(|(_, map)| *map)
        .ok_or_else(|| {
            let names: Vec<&str> = all.by_ref().map(|(name, _)| *name).collect();
            format!(
                "unknown map '{text}' (expected one of: {})",
                names.join(", ")
            )
        })
}

impl BakeArgs {
    /// Adds the graphs, the parameter file, the mesh file and every file the bake writes
    /// (each graph's maps, or the glTF files) to `plan`.
    pub fn plan(&self, plan: &mut OutputPlan, job: Option<&str>) {
        for graph in &self.graphs {
            let by = self.parameters.plan_graph(plan, job, graph);
            if let Some(mesh) = &self.mesh {
                super::plan_mesh(plan, mesh, &by);
            }
        }
        let Some(first) = self.graphs.first() else {
            if let Some(mesh) = &self.mesh {
                self.plan_mesh_maps(plan, job, mesh);
            }
            return;
        };
        if let Some((format, out)) = self.model() {
            plan.writes_beside(&format.files(out), &super::by(job, first));
            return;
        }
        let format = self.settings().format;
        for (graph, stem) in self.graphs.iter().zip(self.stems()) {
            let by = super::by(job, graph);
            for map in self.material_maps() {
                plan.writes(map_path(&stem, map, format), Naming::Implied, &by);
            }
            for map in self.mesh_maps() {
                plan.writes(mesh_map_path(&stem, map, format), Naming::Implied, &by);
            }
        }
    }

    /// The model `--gltf` or `--usd` asks for, and where it goes.
    fn model(&self) -> Option<(ModelFormat, &std::path::Path)> {
        (self.gltf.as_deref().map(|out| (ModelFormat::Gltf, out)))
            .or_else(|| self.usd.as_deref().map(|out| (ModelFormat::Usd, out)))
    }

    /// Plans a bake of mesh maps alone: the mesh read, its maps written.
    fn plan_mesh_maps(&self, plan: &mut OutputPlan, job: Option<&str>, mesh: &str) {
        let by = super::by(job, mesh);
        super::plan_mesh(plan, mesh, &by);
        let (stem, format) = (self.mesh_stem(mesh), self.settings().format);
        for map in self.mesh_maps() {
            plan.writes(mesh_map_path(&stem, map, format), Naming::Implied, &by);
        }
    }

    /// The maps asked for: `--maps`, else normal and height with `--from`, else albedo,
    /// normal and height.
    fn maps(&self) -> Vec<MapArg> {
        let default = match self.from {
            Some(_) => vec![Map::Normal, Map::Height],
            None => vec![Map::Albedo, Map::Normal, Map::Height],
        };
        (self.maps.clone()).unwrap_or_else(|| default.into_iter().map(MapArg::Material).collect())
    }

    /// The material maps `--maps` names, in its order.
    fn material_maps(&self) -> Vec<Map> {
        (self.maps().into_iter())
            .filter_map(|map| match map {
                MapArg::Material(map) => Some(map),
                MapArg::Mesh(_) => None,
            })
            .collect()
    }

    /// The mesh maps `--maps` names, in its order.
    fn mesh_maps(&self) -> Vec<MeshMap> {
        (self.maps().into_iter())
            .filter_map(|map| match map {
                MapArg::Mesh(map) => Some(map),
                MapArg::Material(_) => None,
            })
            .collect()
    }

    /// How the mesh maps are baked.
    fn mesh_map_settings(&self) -> MeshMapSettings {
        MeshMapSettings {
            size: self.size,
            format: self.settings().format,
            samples: self.samples,
            distance: self.distance,
            radius: self.radius,
            pooling: self.pool,
        }
    }

    /// Where mesh maps baked without a graph go: `<mesh>_<map>.<ext>` in `--out-dir`, or
    /// beside the mesh file (a primitive's in the current folder, `torus:96` as
    /// `torus-96`).
    fn mesh_stem(&self, mesh: &str) -> PathBuf {
        let path = std::path::Path::new(mesh);
        let name = match path.extension() {
            Some(_) => path
                .file_stem()
                .unwrap_or_default()
                .to_string_lossy()
                .into_owned(),
            None => mesh.replace(':', "-"),
        };
        match (&self.out_dir, path.extension()) {
            (Some(dir), _) => dir.join(name),
            (None, Some(_)) => path.with_file_name(name),
            (None, None) => PathBuf::from(name),
        }
    }

    /// What the maps are baked as.
    fn settings(&self) -> BakeSettings {
        BakeSettings {
            surface: match &self.mesh {
                Some(mesh) => BakeSurface::MeshUv(mesh.clone()),
                None if self.tile => BakeSurface::Tile(self.flat),
                None => BakeSurface::Plane(self.flat),
            },
            size: self.size,
            maps: self.material_maps(),
            format: match self.format {
                FormatArg::Png => Format::Png8,
                FormatArg::Png16 => Format::Png16,
                FormatArg::Exr => Format::Exr,
            },
            normal: match self.normal {
                NormalArg::Gl => NormalConvention::OpenGl,
                NormalArg::Dx => NormalConvention::DirectX,
            },
            time: self.time,
        }
    }

    /// Each graph's maps' path without `_<map>.<ext>`: in `--out-dir`, or beside the graph.
    fn stems(&self) -> Vec<PathBuf> {
        (self.graphs.iter())
            .map(|path| match &self.out_dir {
                Some(dir) => dir.join(path.file_stem().unwrap_or_default()),
                None => path.with_extension(""),
            })
            .collect()
    }
}

pub fn run(args: BakeArgs) -> Result<(), Failure> {
    if let Some((format, out)) = args.model() {
        return run_model(&args, out, format);
    }
    if args.size == 0 {
        return Err(Failure::new("--size must be at least 1"));
    }
    if let (Some(low), Some(high)) = (&args.mesh, &args.from) {
        return mesh::run_transfer(&args, low, high);
    }
    let names = |maps: Vec<&'static str>| maps.join(", ");
    let mesh_maps = args.mesh_maps();
    if args.mesh.is_none() && !mesh_maps.is_empty() {
        return Err(Failure::new(format!(
            "the mesh maps ({}) are baked into a mesh's UV layout: give --mesh",
            names(mesh_maps.iter().map(|map| map.name()).collect())
        )));
    }
    if args.graphs.is_empty() && !args.material_maps().is_empty() {
        return Err(Failure::new(format!(
            "the material maps ({}) need a graph file; without one, --maps takes only mesh maps ({})",
            names(args.material_maps().iter().map(|map| map.name()).collect()),
            names(MeshMap::ALL.iter().map(|map| map.name()).collect())
        )));
    }
    let stems = match (&args.mesh, args.graphs.is_empty()) {
        (Some(mesh), true) => vec![args.mesh_stem(mesh)],
        _ => args.stems(),
    };
    let (mut written, mut failures) = match args.material_maps().is_empty() {
        true => (Vec::new(), Vec::new()),
        false => bake_material_maps(&args, &stems)?,
    };
    let mut mesh_written = Vec::new();
    if let (Some(mesh), false) = (&args.mesh, mesh_maps.is_empty()) {
        match mesh::bake_mesh(&args, mesh, &mesh_maps, &stems) {
            Ok(maps) => mesh_written = maps,
            Err(Failure(message, _)) => failures.push(message),
        }
    }
    if args.json {
        let mut all: Vec<serde_json::Value> = Vec::new();
        all.extend(
            written
                .drain(..)
                .map(serde_json::to_value)
                .collect::<Result<Vec<_>, _>>()?,
        );
        all.extend((mesh_written.iter().map(serde_json::to_value)).collect::<Result<Vec<_>, _>>()?);
        out(serde_json::to_string_pretty(&all)?)?;
    } else {
        for map in &written {
            let seams = map.seams.map_or(String::new(), |seams| {
                format!(
                    "; tiles: edges differ by up to {} left/right, {} top/bottom",
                    seam_text(seams.left_right),
                    seam_text(seams.top_bottom)
                )
            });
            note(format!(
                "wrote {} ({}×{}, {} bytes{seams})",
                map.path.display(),
                map.size,
                map.size,
                map.bytes
            ))?;
        }
        for map in &mesh_written {
            let rays = match map.rays_per_texel {
                0 => String::new(),
                rays => format!(", {rays} rays per texel pooled over ±{} texels", args.pool),
            };
            note(format!(
                "wrote {} ({}×{}, {} bytes; {} texels covered{rays}, {:.2} s)",
                map.path.display(),
                map.size,
                map.size,
                map.bytes,
                map.covered_texels,
                map.seconds
            ))?;
        }
    }
    if failures.is_empty() {
        Ok(())
    } else {
        Err(Failure::new(failures.join("\n")))
    }
}

/// The material maps of every graph, baked in parallel: what was written, and the
/// failures of graphs that did not bake (the others bake on).
fn bake_material_maps(
    args: &BakeArgs,
    stems: &[PathBuf],
) -> Result<(Vec<BakedMap>, Vec<String>), Failure> {
    let settings = args.settings();
    let stem_refs: Vec<&std::path::Path> = stems.iter().map(PathBuf::as_path).collect();
    veneer::bake::check_outputs(&stem_refs, &settings)?;
    let graphs = args
        .graphs
        .iter()
        .zip(stems)
        .map(|(path, stem)| {
            let mut graph = veneer::graph::load(path)?;
            args.parameters.apply(&mut graph, path)?;
            Ok::<_, Failure>((path, stem, graph))
        })
        .collect::<Result<Vec<_>, _>>()?;
    // Every graph is checked and compiled once, here, before any GPU work; one that does
    // not compile fails on its own while the others bake.
    let compiled: Vec<_> = graphs
        .into_iter()
        .map(|(path, stem, graph)| {
            let compiled = compile(&graph, &CompileOptions::default())
                .map_err(|error| format!("{}: {error}", path.display()));
            (path, stem, compiled)
        })
        .collect();
    if let veneer::bake::BakeSurface::Tile(_) = settings.surface {
        for (path, _, compiled) in &compiled {
            for seamed in compiled
                .iter()
                .flat_map(veneer::bake::bitmap_seams::seamed_bitmaps)
            {
                note(format!("warning: {}: {seamed}", path.display()))?;
            }
        }
    }
    let gpu = GpuContext::new()?;
    let bars = MultiProgress::new();
    let style = ProgressStyle::with_template("{prefix:>16} [{bar:40}] {pos}/{len} tiles {elapsed}")
        .expect("valid template");
    let results: Vec<Result<Vec<BakedMap>, Failure>> = std::thread::scope(|scope| {
        let tasks: Vec<_> = compiled
            .iter()
            .map(|(path, stem, compiled)| {
                let compiled = match compiled {
                    Ok(compiled) => compiled,
                    Err(message) => return Err(Failure::new(message.clone())),
                };
                let bar = bars.add(ProgressBar::new(0).with_style(style.clone()));
                bar.set_prefix(
                    path.file_stem()
                        .map(|s| s.to_string_lossy().into_owned())
                        .unwrap_or_default(),
                );
                let (gpu, settings) = (&gpu, &settings);
                Ok(scope.spawn(move || {
                    let result = bake(gpu, compiled, settings, stem, |done, total| {
                        bar.set_length(total);
                        bar.set_position(done);
                        true
                    });
                    bar.finish();
                    result.map_err(|error| Failure::new(format!("{}: {error}", path.display())))
                }))
            })
            .collect();
        tasks
            .into_iter()
            .map(|task| {
                task?
                    .join()
                    .unwrap_or_else(|_| Err(Failure::new("a bake thread panicked")))
            })
            .collect()
    });
    let mut written = Vec::new();
    let mut failures = Vec::new();
    for result in results {
        match result {
            Ok(maps) => written.extend(maps),
            Err(Failure(message, _)) => failures.push(message),
        }
    }
    Ok((written, failures))
}

/// `veneer bake GRAPH --gltf OUT` or `--usd OUT`: one graph exported as a model in the
/// `format` `export` writes.
fn run_model(args: &BakeArgs, out: &std::path::Path, format: ModelFormat) -> Result<(), Failure> {
    let [graph_path] = args.graphs.as_slice() else {
        return Err(Failure::new(format!(
            "{} exports one graph at a time; give one graph file",
            format.name()
        )));
    };
    if args.size == 0 {
        return Err(Failure::new("--size must be at least 1"));
    }
    if let Some(why) = format.refuses(out) {
        return Err(Failure::new(format!("{}: {why}", out.display())));
    }
    let mut graph = veneer::graph::load(graph_path)?;
    args.parameters.apply(&mut graph, graph_path)?;
    let compiled = compile(&graph, &CompileOptions::default())
        .map_err(|error| Failure::new(format!("{}: {error}", graph_path.display())))?;
    let gpu = GpuContext::new()?;
    let settings = ModelSettings {
        mesh: args.mesh.clone(),
        size: args.size,
        time: args.time,
    };
    let bar = ProgressBar::new(0).with_style(
        ProgressStyle::with_template("{prefix:>16} [{bar:40}] {pos}/{len} tiles {elapsed}")
            .expect("valid template"),
    );
    bar.set_prefix(format.name());
    let written = format
        .export(&gpu, &compiled, &settings, out, |done, total| {
            bar.set_length(total);
            bar.set_position(done);
            true
        })
        .map_err(|error| Failure::new(format!("{}: {error}", graph_path.display())))?;
    bar.finish_and_clear();
    if args.json {
        out_json(&written)?;
    } else {
        for path in &written {
            let bytes = std::fs::metadata(path).map(|m| m.len()).unwrap_or(0);
            note(format!("wrote {} ({bytes} bytes)", path.display()))?;
        }
    }
    Ok(())
}

/// The files an export wrote, as a JSON list on stdout.
fn out_json(written: &[PathBuf]) -> Result<(), Failure> {
    out(serde_json::to_string_pretty(written)?)
}
