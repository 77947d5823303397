//! Command-line interface: argument parsing and one module per subcommand.

mod bake;
mod check;
mod compile;
mod fmt;
mod geodesic;
mod mesh;
mod render;
mod report;
mod snapshot;

use clap::{Parser, Subcommand};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Veneer: procedural material node graphs compiled to WGSL.
#[derive(Parser)]
#[command(name = "veneer", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Open a graph in the node editor.
    Edit {
        /// The graph file.
        graph: PathBuf,
    },
    /// Render a graph to a PNG: on a mesh with the preview lighting, or its albedo over a plane.
    Render(render::RenderArgs),
    /// Bake texture maps (albedo, normal, height, …) as PNG or EXR.
    Bake(bake::BakeArgs),
    /// Write the material as a validated shader module.
    Compile(compile::CompileArgs),
    /// Load, type-check, compile and validate graphs; exit 1 if any has an error.
    Check(check::CheckArgs),
    /// Geodesic distances from source vertices to every vertex of a mesh, as CSV.
    Geodesic(geodesic::GeodesicArgs),
    /// Report a mesh's vertices, triangles and defects (degenerate, boundary, non-manifold, components).
    Mesh(mesh::MeshArgs),
    /// Rewrite graph files in canonical form (sorted, deterministic bytes).
    Fmt(fmt::FmtArgs),
    /// Render graphs and compare them with approved golden images (exit 1 on a difference).
    Snapshot(snapshot::SnapshotArgs),
    /// Measure error against run time (precision, hashes, octaves, geodesics, detail) and
    /// write a report with tables and plots.
    Report(report::ReportArgs),
}

/// The help of a mesh argument, with what the most detailed primitives cost.
fn mesh_help() -> String {
    format!(
        "A mesh file (OBJ, STL, PLY, glTF) or a primitive name, with an optional level of \
         detail up to {} ({})",
        veneer::mesh::MAX_DETAIL,
        veneer::mesh::DETAIL_COST
    )
}

/// A failed command: the message to print (already prefixed with the file or node) and
/// the exit code (1 unless a command documents otherwise).
pub struct Failure(pub String, pub u8);

impl<E: std::fmt::Display> From<E> for Failure {
    fn from(error: E) -> Failure {
        Failure(error.to_string(), 1)
    }
}

impl Failure {
    /// A failure with exit code 1.
    pub fn new(message: impl Into<String>) -> Failure {
        Failure(message.into(), 1)
    }
}

/// Parses the arguments, runs the subcommand, and maps failures to exit code 1.
pub fn run() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        None => editor(None),
        Some(Command::Edit { graph }) => editor(Some(graph)),
        Some(Command::Render(args)) => render::run(args),
        Some(Command::Bake(args)) => bake::run(args),
        Some(Command::Compile(args)) => compile::run(args),
        Some(Command::Check(args)) => check::run(args),
        Some(Command::Fmt(args)) => fmt::run(args),
        Some(Command::Mesh(args)) => mesh::run(args),
        Some(Command::Geodesic(args)) => geodesic::run(args),
        Some(Command::Snapshot(args)) => snapshot::run(args),
        Some(Command::Report(args)) => report::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure(message, code)) => {
            if !message.is_empty() {
                eprintln!("{message}");
            }
            ExitCode::from(code)
        }
    }
}

/// Opens the node editor (or explains how to run headless when it was left out of the build).
fn editor(graph: Option<PathBuf>) -> Result<(), Failure> {
    #[cfg(feature = "gui")]
    {
        veneer::app::run(graph).map_err(Failure::new)
    }
    #[cfg(not(feature = "gui"))]
    {
        let _ = graph;
        Err(Failure::new(
            "this build has no editor (built without the `gui` feature); render headless with\n  veneer render graphs/wood.ron -o wood.png",
        ))
    }
}

/// Loads a graph, with errors as `path:line:col: message`.
fn load_graph(path: &Path) -> Result<veneer::graph::Graph, Failure> {
    veneer::graph::load(path).map_err(Failure::from)
}

/// Prefixes every line of a multi-line error with the file it concerns.
fn in_file(path: &Path, error: impl std::fmt::Display) -> Failure {
    let lines: Vec<String> = error
        .to_string()
        .lines()
        .map(|line| format!("{}: {line}", path.display()))
        .collect();
    Failure::new(lines.join("\n"))
}

/// Writes `bytes` atomically to `path`, or to stdout when `path` is `None` or `-`.
fn write_output(path: Option<&PathBuf>, bytes: &[u8]) -> Result<(), Failure> {
    use std::io::Write;
    match path {
        Some(path) if path.as_os_str() != "-" => veneer::fsutil::write_atomic(path, bytes)
            .map_err(|error| Failure::new(format!("{}: cannot write: {error}", path.display()))),
        _ => std::io::stdout().write_all(bytes).map_err(Failure::from),
    }
}
