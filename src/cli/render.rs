//! `veneer render`: a graph to a PNG, lit on a mesh or flat over a plane.

use super::output::note;
use super::{Failure, in_file, load_graph, write_output};
use clap::Args;
use std::path::PathBuf;
use veneer::codegen::{CompileOptions, Detail};
use veneer::fsutil::{Naming, OutputPlan};
use veneer::graph::Tessellation;
use veneer::render::{
    Backdrop, DEFAULT_KEY_LIGHT, Environment, FlatRect, GpuContext, MeshLook, Relief, SKY, ToneMap,
    View, render_material_with,
};

/// How much noise detail to compute.
#[derive(Clone, Copy, clap::ValueEnum)]
pub enum DetailName {
    /// Every octave everywhere (the CPU reference's numbers).
    Full,
    /// Filter over the pixel: leave out octaves finer than it, fading the last one, and
    /// box-filter bands, waves, rings, tiles, steps and smoothsteps over it.
    Footprint,
}

impl From<DetailName> for Detail {
    fn from(name: DetailName) -> Detail {
        match name {
            DetailName::Full => Detail::Full,
            DetailName::Footprint => Detail::Footprint,
        }
    }
}

#[derive(Args)]
pub struct RenderArgs {
    /// The graph file.
    graph: PathBuf,
    /// Output PNG.
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    parameters: super::parameters::ParameterArgs,
    /// Width and height of the image in pixels.
    #[arg(long, default_value_t = 512)]
    size: u32,
    /// Mesh to render on: a primitive (sphere, cube, torus, plane, genus2, rock, optionally
    /// with a detail level such as torus:160) or a mesh file (default: the preview mesh).
    #[arg(long, conflicts_with = "flat")]
    mesh: Option<String>,
    /// Render the albedo unlit over the plane y = Y, x from X0 to X1, z from Z0 to Z1.
    #[arg(long, value_name = "X0,Z0,X1,Z1,Y", value_parser = parse_flat, allow_hyphen_values = true)]
    flat: Option<FlatRect>,
    /// Time in seconds.
    #[arg(long, default_value_t = 0.0, value_parser = super::parse_time, allow_hyphen_values = true)]
    time: f32,
    /// Noise detail.
    #[arg(long, value_enum, default_value = "full")]
    detail: DetailName,
    /// Refine a displaced mesh until its triangles are within PX pixels of the displaced
    /// surface (adaptive tessellation; `off` draws the mesh's own triangles). Default:
    /// the graph's preview setting.
    #[arg(long, value_name = "PX|off", value_parser = parse_tessellation)]
    tessellate: Option<TessellationChoice>,
    /// Show the material's height by moving the vertices (displaced) or as bump only.
    #[arg(long, value_enum, default_value = "displaced")]
    relief: Relief,
    /// How a metallic-roughness material's light maps to the display (Blinn-Phong
    /// materials show the seeds' lighting as it is).
    #[arg(long, value_enum, default_value = "pbr-neutral")]
    tone_map: ToneMap,
    /// Exposure of a metallic-roughness material in stops (light × 2^EV).
    #[arg(long, value_name = "EV", default_value_t = 0.0, allow_hyphen_values = true, value_parser = parse_exposure)]
    exposure: f32,
    /// The environment lighting a metallic-roughness material: `sky` (procedural) or an
    /// equirectangular .hdr or .exr panorama.
    #[arg(long, value_name = "sky|FILE", default_value = SKY)]
    environment: String,
    /// Turn the environment about the vertical axis by DEG degrees.
    #[arg(long, value_name = "DEG", default_value_t = 0.0, allow_hyphen_values = true, value_parser = parse_turn)]
    environment_turn: f32,
    /// Irradiance of the key light on a metallic-roughness material (0: the
    /// environment alone).
    #[arg(long, value_name = "E", default_value_t = DEFAULT_KEY_LIGHT, value_parser = parse_key_light)]
    key_light: f32,
    /// What shows behind a metallic-roughness material.
    #[arg(long, value_enum, default_value = "blurred")]
    backdrop: Backdrop,
}

/// `--environment-turn`: finite degrees, within ±3600.
fn parse_turn(text: &str) -> Result<f32, String> {
    match text.trim().parse::<f32>() {
        Ok(degrees) if degrees.is_finite() && degrees.abs() <= 3600.0 => Ok(degrees),
        _ => Err(format!("'{text}' is not a turn from -3600 to 3600 degrees")),
    }
}

/// `--key-light`: finite, from 0 to 10⁴.
fn parse_key_light(text: &str) -> Result<f32, String> {
    match text.trim().parse::<f32>() {
        Ok(irradiance) if (0.0..=1.0e4).contains(&irradiance) => Ok(irradiance),
        _ => Err(format!("'{text}' is not a key light from 0 to 10000")),
    }
}

/// `--exposure`: finite, within ±32 stops.
fn parse_exposure(text: &str) -> Result<f32, String> {
    match text.trim().parse::<f32>() {
        Ok(ev) if ev.is_finite() && ev.abs() <= 32.0 => Ok(ev),
        _ => Err(format!("'{text}' is not an exposure from -32 to 32 stops")),
    }
}

/// `--tessellate`: off, or a tolerance in pixels.
#[derive(Clone, Copy)]
pub struct TessellationChoice(Option<Tessellation>);

fn parse_tessellation(text: &str) -> Result<TessellationChoice, String> {
    if text == "off" {
        return Ok(TessellationChoice(None));
    }
    let tolerance: f64 = text
        .parse()
        .map_err(|_| format!("'{text}' is neither a number of pixels nor 'off'"))?;
    let tessellation = Tessellation {
        tolerance,
        ..Tessellation::default()
    };
    tessellation.refinement().validate()?;
    Ok(TessellationChoice(Some(tessellation)))
}

pub fn parse_flat(text: &str) -> Result<FlatRect, String> {
    let numbers: Vec<f64> = text
        .split(',')
        .map(|part| {
            part.trim()
                .parse::<f64>()
                .map_err(|_| format!("'{part}' is not a number"))
        })
        .collect::<Result<_, _>>()?;
    match numbers[..] {
        [x0, z0, x1, z1, y] => {
            let rect = FlatRect { x0, z0, x1, z1, y };
            rect.validate().map(|()| rect)
        }
        _ => Err(format!(
            "expected five numbers X0,Z0,X1,Z1,Y, got {}",
            numbers.len()
        )),
    }
}

impl RenderArgs {
    /// Adds the graph, the parameter file, the mesh and environment files and the image
    /// to `plan`.
    pub fn plan(&self, plan: &mut OutputPlan, job: Option<&str>) {
        let by = self.parameters.plan_graph(plan, job, &self.graph);
        if let Some(mesh) = &self.mesh {
            super::plan_mesh(plan, mesh, &by);
        }
        if self.environment != SKY {
            plan.reads(&self.environment, &by);
        }
        if let Some(output) = super::output_file(&self.output) {
            plan.writes(output, Naming::Given, &by);
        }
    }
}

pub fn run(args: RenderArgs) -> Result<(), Failure> {
    // A render is a PNG: another image's extension would name a file it is not.
    let extension = args
        .output
        .extension()
        .map(|e| e.to_string_lossy().to_lowercase());
    if let Some(extension) = extension.filter(|e| e != "png") {
        return Err(Failure::new(format!(
            "{}: render writes PNG images, not .{extension}; name the output .png",
            args.output.display()
        )));
    }
    let mut graph = load_graph(&args.graph)?;
    args.parameters.apply(&mut graph, &args.graph)?;
    let options = CompileOptions::with_detail(args.detail.into());
    let mut compiled =
        veneer::codegen::compile(&graph, &options).map_err(|error| in_file(&args.graph, error))?;
    if let Some(TessellationChoice(choice)) = args.tessellate {
        compiled.preview.tessellation = choice;
    }
    let view = match args.flat {
        Some(rect) => View::Flat(rect),
        None => View::Mesh(args.mesh),
    };
    // A panorama that does not load fails before anything renders.
    let environment = (args.environment != SKY)
        .then(|| Environment::named(&args.environment).map(std::sync::Arc::new))
        .transpose()?;
    let gpu = GpuContext::new()?;
    let look = MeshLook {
        relief: args.relief,
        tone_map: args.tone_map,
        exposure: args.exposure,
        environment,
        environment_turn: args.environment_turn,
        key_light: args.key_light,
        backdrop: args.backdrop,
    };
    let rendered = render_material_with(&gpu, &compiled, &view, args.size, args.time, look)?;
    if let Some(tessellated) = rendered.tessellated {
        let (before, after) = tessellated.triangles;
        note(format!(
            "{}: tessellated {before} triangles into {after} ({}){}",
            args.graph.display(),
            veneer::messages::counted(tessellated.levels as usize, "level"),
            if tessellated.limited {
                "; warning: stopped at the triangle limit, short of the tolerance"
            } else {
                ""
            }
        ))?;
    }
    write_output(Some(&args.output), &rendered.image.to_png()?)
}
