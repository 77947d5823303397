//! `veneer compile`: the material as a shader module.

use super::{Failure, in_file, load_graph, write_output};
use clap::{Args, ValueEnum};
use std::path::PathBuf;

/// Shader languages `veneer compile` writes.
#[derive(Clone, Copy, ValueEnum)]
pub enum Target {
    Wgsl,
}

#[derive(Args)]
pub struct CompileArgs {
    /// The graph file.
    graph: PathBuf,
    /// Shader language of the output.
    #[arg(long, value_enum, default_value = "wgsl")]
    target: Target,
    /// Output file (stdout when absent or `-`).
    #[arg(short, long)]
    output: Option<PathBuf>,
}

pub fn run(args: CompileArgs) -> Result<(), Failure> {
    let graph = load_graph(&args.graph)?;
    let module =
        veneer::codegen::compile_graph(&graph).map_err(|error| in_file(&args.graph, error))?;
    match args.target {
        Target::Wgsl => write_output(args.output.as_ref(), module.source.as_bytes()),
    }
}
