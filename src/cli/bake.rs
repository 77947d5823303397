//! `veneer bake`: texture maps of one or more graphs, baked in parallel with a progress bar.

use super::Failure;
use super::output::{note, out};
use super::render::parse_flat;
use clap::{Args, ValueEnum};
use indicatif::{MultiProgress, ProgressBar, ProgressStyle};
use std::path::PathBuf;
use veneer::bake::tile::seam_text;
use veneer::bake::{
    BakeSettings, BakeSurface, BakedMap, Format, GltfSettings, Map, NormalConvention, bake,
    export_gltf, map_path,
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

#[derive(Args)]
pub struct BakeArgs {
    /// Graph files to bake (in parallel).
    #[arg(required = true)]
    graphs: Vec<PathBuf>,
    /// Width and height of every map in pixels (up to 8192 and beyond; rendered in tiles).
    #[arg(long, default_value_t = 1024)]
    size: u32,
    /// Maps to write: albedo, alpha, height, normal, specular, roughness, metallic,
    /// occlusion, emission, orm (occlusion, roughness, metallic in R, G, B).
    #[arg(long, value_delimiter = ',', default_value = "albedo,normal,height", value_parser = parse_map)]
    maps: Vec<Map>,
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
    /// Folder for the maps (`<graph>_<map>.<ext>`); default: next to each graph.
    #[arg(short, long)]
    out_dir: Option<PathBuf>,
    /// Write a glTF 2.0 model instead of map files: the mesh (`--mesh`, default the
    /// graph's preview mesh) with the material's maps baked into its UV layout (an
    /// automatic atlas for a mesh without UVs) as a metallic-roughness material. `.glb`
    /// gives one file; `.gltf` writes its buffer and PNGs beside it. One graph at a time.
    #[arg(long, value_name = "OUT.glb|OUT.gltf", conflicts_with_all = ["flat", "tile", "out_dir", "maps", "format", "normal"])]
    gltf: Option<PathBuf>,
    /// Print a JSON summary of what was written on stdout.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    parameters: super::parameters::ParameterArgs,
}

fn parse_map(text: &str) -> Result<Map, String> {
    Map::ALL
        .iter()
        .copied()
        .find(|map| map.name() == text.trim())
        .ok_or_else(|| {
            let names: Vec<&str> = Map::ALL.iter().map(|m| m.name()).collect();
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
            return;
        };
        if let Some(out) = &self.gltf {
            let by = super::by(job, first);
            for (index, path) in veneer::bake::gltf_files(out).iter().enumerate() {
                let naming = if index == 0 {
                    Naming::Given
                } else {
                    Naming::Implied
                };
                plan.writes(path, naming, &by);
            }
            return;
        }
        let format = self.settings().format;
        for (graph, stem) in self.graphs.iter().zip(self.stems()) {
            let by = super::by(job, graph);
            for &map in &self.maps {
                plan.writes(map_path(&stem, map, format), Naming::Implied, &by);
            }
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
            maps: self.maps.clone(),
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
    if let Some(out) = &args.gltf {
        return run_gltf(&args, out);
    }
    let settings = args.settings();
    if settings.size == 0 {
        return Err(Failure::new("--size must be at least 1"));
    }
    let stems = args.stems();
    let stem_refs: Vec<&std::path::Path> = stems.iter().map(PathBuf::as_path).collect();
    veneer::bake::check_outputs(&stem_refs, &settings)?;
    let graphs = args
        .graphs
        .iter()
        .zip(&stems)
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
    if args.json {
        out(serde_json::to_string_pretty(&written)?)?;
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
    }
    if failures.is_empty() {
        Ok(())
    } else {
        Err(Failure::new(failures.join("\n")))
    }
}

/// `veneer bake GRAPH --gltf OUT`: one graph exported as a glTF model.
fn run_gltf(args: &BakeArgs, out: &std::path::Path) -> Result<(), Failure> {
    let [graph_path] = args.graphs.as_slice() else {
        return Err(Failure::new(
            "--gltf exports one graph at a time; give one graph file",
        ));
    };
    if args.size == 0 {
        return Err(Failure::new("--size must be at least 1"));
    }
    let mut graph = veneer::graph::load(graph_path)?;
    args.parameters.apply(&mut graph, graph_path)?;
    let compiled = compile(&graph, &CompileOptions::default())
        .map_err(|error| Failure::new(format!("{}: {error}", graph_path.display())))?;
    let gpu = GpuContext::new()?;
    let settings = GltfSettings {
        mesh: args.mesh.clone(),
        size: args.size,
        time: args.time,
    };
    let bar = ProgressBar::new(0).with_style(
        ProgressStyle::with_template("{prefix:>16} [{bar:40}] {pos}/{len} tiles {elapsed}")
            .expect("valid template"),
    );
    bar.set_prefix("glTF");
    let written = export_gltf(&gpu, &compiled, &settings, out, |done, total| {
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
