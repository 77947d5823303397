//! Command-line interface: argument parsing and one module per subcommand.

mod bake;
mod batch;
mod check;
mod compile;
mod fit;
mod fmt;
mod geodesic;
mod import;
mod mesh;
mod mesh_field;
mod output;
mod parameters;
mod render;
mod report;
mod snapshot;

use clap::{Parser, Subcommand};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use veneer::fsutil::{Naming, OutputPlan};

/// Veneer: procedural material node graphs compiled to WGSL.
#[derive(Parser)]
#[command(name = "veneer", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Open a graph in the node editor.
    Edit {
        /// The graph file.
        graph: PathBuf,
        /// Write a CSV line per frame to this file (when it began, the main thread's
        /// milliseconds, the graph's revision and compile count), to measure the window.
        #[arg(long, value_name = "FILE")]
        frame_log: Option<PathBuf>,
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
    /// A mesh field (curvature, ambient occlusion, thickness) at every vertex of a mesh, as CSV.
    MeshField(mesh_field::MeshFieldArgs),
    /// Report a mesh's vertices, triangles and defects (degenerate, boundary, non-manifold, components).
    Mesh(mesh::MeshArgs),
    /// Read a MaterialX document (standard nodes Veneer has, Veneer's own definitions) as a graph.
    Import(import::ImportArgs),
    /// Fit a graph's exposed parameters so that its albedo looks like a photo.
    Fit(fit::FitArgs),
    /// Rewrite graph files in canonical form (sorted, deterministic bytes).
    Fmt(fmt::FmtArgs),
    /// Render graphs and compare them with approved golden images (exit 1 on a difference).
    Snapshot(snapshot::SnapshotArgs),
    /// Run the render, bake, snapshot and compile jobs of a batch file, or one shard of them.
    Batch(batch::BatchArgs),
    /// Measure error against run time (precision, hashes, octaves, geodesics, detail) and
    /// write a report with tables and plots.
    Report(report::ReportArgs),
}

impl Command {
    /// Adds the files this command reads and writes to `plan`, as done by `job` (a batch's
    /// job) or, run on its own, by each of its graphs (or meshes). `fmt` rewrites its
    /// inputs by design; `check` writes nothing; a batch plans its jobs itself.
    fn plan(&self, plan: &mut OutputPlan, job: Option<&str>) {
        match self {
            Command::Edit { graph, frame_log } => {
                let by = by(job, graph);
                plan.reads(graph, &by);
                if let Some(log) = frame_log {
                    plan.writes(log, Naming::Given, &by);
                }
            }
            Command::Render(args) => args.plan(plan, job),
            Command::Bake(args) => args.plan(plan, job),
            Command::Compile(args) => args.plan(plan, job),
            Command::Import(args) => args.plan(plan, job),
            Command::Fit(args) => args.plan(plan, job),
            Command::Geodesic(args) => args.plan(plan, job),
            Command::MeshField(args) => args.plan(plan, job),
            Command::Mesh(args) => args.plan(plan, job),
            Command::Snapshot(args) => args.plan(plan, job),
            Command::Report(args) => args.plan(plan, job.unwrap_or("report")),
            Command::Check(_) | Command::Fmt(_) | Command::Batch(_) => {}
        }
    }

    /// The exit code of bad input: 2 for `snapshot`, whose 1 means "differs".
    fn bad_input_code(&self) -> u8 {
        match self {
            Command::Snapshot(_) => 2,
            _ => 1,
        }
    }
}

/// Who reads or writes in an output plan: the batch job, or else `file`.
fn by(job: Option<&str>, file: impl AsRef<Path>) -> String {
    job.map_or_else(|| file.as_ref().display().to_string(), str::to_string)
}

/// An output path that names a file, not stdout (`-`).
fn output_file(path: &Path) -> Option<&Path> {
    (path.as_os_str() != "-").then_some(path)
}

/// Adds a mesh argument to `plan` when it names a file, not a primitive (as
/// [`veneer::mesh::Mesh::named`] tells them apart: a file has an extension).
fn plan_mesh(plan: &mut OutputPlan, mesh: &str, by: &str) {
    if Path::new(mesh).extension().is_some() {
        plan.reads(mesh, by);
    }
}

/// Adds a mesh command's mesh file and output (unless none, or stdout) to `plan`.
fn plan_mesh_command(plan: &mut OutputPlan, job: Option<&str>, mesh: &str, output: Option<&Path>) {
    let by = by(job, mesh);
    plan_mesh(plan, mesh, &by);
    if let Some(output) = output.and_then(output_file) {
        plan.writes(output, Naming::Given, &by);
    }
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

    /// The reader of stdout went away (a closed pipe): stop writing and end quietly,
    /// as `head` expects of the program before it.
    pub fn reader_gone() -> Failure {
        Failure(String::new(), 0)
    }
}

/// The exit code of a command line (program name first) that does not parse: 0 for
/// `--help` and `--version`, which clap reports as errors; else the code of bad input,
/// 1 by the contract, 2 for `veneer snapshot`, where 1 means "differs".
pub fn usage_exit_code(args: &[std::ffi::OsString], error: &clap::Error) -> u8 {
    if !error.use_stderr() {
        return 0;
    }
    match args.get(1).and_then(|arg| arg.to_str()) {
        Some("snapshot") => 2,
        _ => 1,
    }
}

/// Parses a command line (program name first) as `veneer` does; the fuzz target
/// `cli_args` feeds it arbitrary arguments.
pub fn parse_from(args: &[std::ffi::OsString]) -> Result<Cli, clap::Error> {
    Cli::try_parse_from(args)
}

/// Parses the process's arguments: help and version go to stdout with exit code 0,
/// usage errors to stderr with the exit code of bad input.
fn parse_arguments() -> Result<Cli, ExitCode> {
    let args: Vec<std::ffi::OsString> = std::env::args_os().collect();
    parse_from(&args).map_err(|error| {
        // The message cannot be written anywhere else when the stream itself fails.
        let _ = error.print();
        ExitCode::from(usage_exit_code(&args, &error))
    })
}

/// Parses the arguments, runs the subcommand, and maps failures to their exit codes.
pub fn run() -> ExitCode {
    let cli = match parse_arguments() {
        Ok(cli) => cli,
        Err(code) => return code,
    };
    match execute(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(failure) => ExitCode::from(output::report_failure(failure)),
    }
}

/// Runs a parsed command line's subcommand (the tests run commands in-process through it),
/// once its output plan holds: no output that is an input, none written twice, no file
/// Veneer names itself standing as a link or special file.
pub fn execute(cli: Cli) -> Result<(), Failure> {
    if let Some(command) = &cli.command {
        let mut plan = OutputPlan::new();
        command.plan(&mut plan, None);
        plan.check()
            .map_err(|message| Failure(message, command.bad_input_code()))?;
    }
    match cli.command {
        None => editor(None, None),
        Some(Command::Edit { graph, frame_log }) => editor(Some(graph), frame_log),
        Some(Command::Render(args)) => render::run(args),
        Some(Command::Bake(args)) => bake::run(args),
        Some(Command::Compile(args)) => compile::run(args),
        Some(Command::Check(args)) => check::run(args),
        Some(Command::Fmt(args)) => fmt::run(args),
        Some(Command::Import(args)) => import::run(args),
        Some(Command::Fit(args)) => fit::run(args),
        Some(Command::Mesh(args)) => mesh::run(args),
        Some(Command::Geodesic(args)) => geodesic::run(args),
        Some(Command::MeshField(args)) => mesh_field::run(args),
        Some(Command::Snapshot(args)) => snapshot::run(args),
        Some(Command::Report(args)) => report::run(args),
        Some(Command::Batch(args)) => batch::run(args),
    }
}

/// Opens the node editor (or explains how to run headless when it was left out of the build).
fn editor(graph: Option<PathBuf>, frame_log: Option<PathBuf>) -> Result<(), Failure> {
    #[cfg(feature = "gui")]
    {
        veneer::app::run(graph, frame_log).map_err(Failure::new)
    }
    #[cfg(not(feature = "gui"))]
    {
        let _ = (graph, frame_log);
        Err(Failure::new(
            "this build has no editor (built without the `gui` feature); render headless with\n  veneer render graphs/wood.ron -o wood.png",
        ))
    }
}

/// A `--time` value: seconds, finite (an infinite or NaN time makes every animated
/// pattern NaN, and the image uniform).
fn parse_time(text: &str) -> Result<f32, String> {
    match text.trim().parse::<f32>() {
        Ok(seconds) if seconds.is_finite() => Ok(seconds),
        Ok(_) => Err("the time must be a finite number of seconds".into()),
        Err(_) => Err(format!("'{text}' is not a number of seconds")),
    }
}

/// Loads a graph, with errors as `path:line:col: message`.
/// Reads file `path` as RON, or as JSON when its extension is `.json` (parameter and
/// batch files); errors name the file, line and column.
fn read_ron_or_json<T: serde::de::DeserializeOwned>(path: &Path) -> Result<T, Failure> {
    let bytes = veneer::fsutil::read_limited(path, veneer::fsutil::ReadLimit::GRAPH)
        .map_err(|error| Failure::new(format!("{}: cannot read: {error}", path.display())))?;
    let text = String::from_utf8_lossy(&bytes);
    let json = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"));
    veneer::graph::parameters::parse_ron_or_json(&text, json)
        .map_err(|error| Failure::new(format!("{}:{error}", path.display())))
}

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

/// Whether an output path names a folder (an existing one, or any path ending in `/`).
fn names_folder(path: &Path) -> bool {
    path.is_dir() || path.as_os_str().as_encoded_bytes().ends_with(b"/")
}

/// Writes `bytes` atomically to `path`, or to stdout when `path` is `None` or `-`.
fn write_output(path: Option<&PathBuf>, bytes: &[u8]) -> Result<(), Failure> {
    match path {
        Some(path) if names_folder(path) => Err(Failure::new(format!(
            "{}: is a folder; give the output a file name",
            path.display()
        ))),
        Some(path) if path.as_os_str() != "-" => veneer::fsutil::write_atomic(path, bytes)
            .map_err(|error| Failure::new(format!("{}: cannot write: {error}", path.display()))),
        _ => output::out_bytes(bytes),
    }
}
