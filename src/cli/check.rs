//! `veneer check`: load, type-check, compile, validate and lint graph files.

use super::output::{note, out};
use super::{Failure, in_file};
use clap::Args;
use std::path::PathBuf;

#[derive(Args)]
pub struct CheckArgs {
    /// Graph files to check; numerical hazards are printed as warnings (they do not fail the check).
    #[arg(required = true)]
    graphs: Vec<PathBuf>,
}

/// The lints of a graph that compiles.
fn check_one(path: &PathBuf) -> Result<Vec<veneer::lint::Lint>, Failure> {
    let graph = veneer::graph::load(path)?;
    let checked = veneer::graph::check(&graph)
        .map_err(|errors| in_file(path, veneer::codegen::CompileError::Check(errors)))?;
    let module = veneer::codegen::compile(&checked).map_err(|error| in_file(path, error))?;
    check_preview_mesh(&graph, module.uses.fields).map_err(|error| in_file(path, error))?;
    Ok(veneer::lint::lint(
        &checked,
        veneer::lint::preview_positions(&graph),
    ))
}

/// What a render would find wrong with the preview mesh: a mesh that does not load, or
/// field sources it does not have.
fn check_preview_mesh(graph: &veneer::graph::Graph, used_fields: [bool; 4]) -> Result<(), String> {
    let mesh =
        veneer::mesh::preview_mesh(&graph.preview.mesh).map_err(|error| error.to_string())?;
    veneer::geodesic::check_field_sources(
        &graph.preview.fields,
        mesh.file_vertex_count(),
        used_fields,
    )
    .map_err(|error| format!("preview mesh {}: {error}", graph.preview.mesh))
}

pub fn run(args: CheckArgs) -> Result<(), Failure> {
    let mut failures = Vec::new();
    for path in &args.graphs {
        match check_one(path) {
            Ok(lints) => {
                let lines = lints.iter().map(|lint| format!("warning: {lint}"));
                for line in veneer::messages::summarise(lines) {
                    note(format!("{}: {line}", path.display()))?;
                }
                let warnings = if lints.is_empty() {
                    String::new()
                } else {
                    format!(" ({} warnings)", lints.len())
                };
                out(format!("{}: ok{warnings}", path.display()))?;
            }
            Err(Failure(message, _)) => failures.push(message),
        }
    }
    if failures.is_empty() {
        Ok(())
    } else {
        Err(Failure::new(failures.join("\n")))
    }
}
