//! `veneer render`: a graph to a PNG, lit on a mesh or flat over a plane.

use super::{Failure, in_file, load_graph, write_output};
use clap::Args;
use std::path::PathBuf;
use veneer::codegen::{CompileOptions, Detail};
use veneer::render::{FlatRect, GpuContext, View, render_material};

/// How much noise detail to compute.
#[derive(Clone, Copy, clap::ValueEnum)]
pub enum DetailName {
    /// Every octave everywhere (the CPU reference's numbers).
    Full,
    /// Leave out octaves finer than a pixel, fading the last one.
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
    /// Width and height of the image in pixels.
    #[arg(long, default_value_t = 512)]
    size: u32,
    /// Mesh to render on: a primitive (sphere, cube, torus, plane, genus2, optionally
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

pub fn run(args: RenderArgs) -> Result<(), Failure> {
    let graph = load_graph(&args.graph)?;
    let options = CompileOptions::with_detail(args.detail.into());
    let compiled =
        veneer::codegen::compile(&graph, &options).map_err(|error| in_file(&args.graph, error))?;
    let view = match args.flat {
        Some(rect) => View::Flat(rect),
        None => View::Mesh(args.mesh),
    };
    let gpu = GpuContext::new()?;
    let image = render_material(&gpu, &compiled, &view, args.size, args.time)?;
    write_output(Some(&args.output), &image.to_png()?)
}
