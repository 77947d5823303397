//! `veneer compile`: the material as a shader module for WGSL or another engine's language.

use super::{Failure, in_file, load_graph, write_output};
use clap::{Args, ValueEnum};
use std::path::PathBuf;
use veneer::codegen::ParamMode;
use veneer::codegen::export::{Target, export};

/// How parameters appear in the output.
#[derive(Clone, Copy, ValueEnum)]
pub enum ParamsArg {
    /// As literal constants: no bindings needed.
    Baked,
    /// As one uniform block (`veneer_params`, group 1 binding 0, one vec4 per slot).
    Uniform,
}

#[derive(Args)]
pub struct CompileArgs {
    /// The graph file.
    graph: PathBuf,
    /// Shader language of the output.
    #[arg(long, value_enum, default_value = "wgsl")]
    target: Target,
    /// Parameters baked as constants or gathered in a uniform block.
    #[arg(long, value_enum, default_value = "baked")]
    params: ParamsArg,
    /// Output file (stdout when absent or `-`).
    #[arg(short, long)]
    output: Option<PathBuf>,
}

pub fn run(args: CompileArgs) -> Result<(), Failure> {
    let graph = load_graph(&args.graph)?;
    let target = args.target;
    let params = match args.params {
        ParamsArg::Baked => ParamMode::Baked,
        ParamsArg::Uniform => ParamMode::Uniform,
    };
    let bytes = export(&graph, target, params).map_err(|error| in_file(&args.graph, error))?;
    write_output(args.output.as_ref(), &bytes)
}
