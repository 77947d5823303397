//! `veneer check`: load, type-check, compile, validate and lint graph files.

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
    veneer::codegen::compile(&checked).map_err(|error| in_file(path, error))?;
    Ok(veneer::lint::lint(
        &checked,
        veneer::lint::preview_positions(&graph),
    ))
}

pub fn run(args: CheckArgs) -> Result<(), Failure> {
    let mut failures = Vec::new();
    for path in &args.graphs {
        match check_one(path) {
            Ok(lints) => {
                let lines = lints.iter().map(|lint| format!("warning: {lint}"));
                for line in veneer::messages::summarise(lines) {
                    eprintln!("{}: {line}", path.display());
                }
                let warnings = if lints.is_empty() {
                    String::new()
                } else {
                    format!(" ({} warnings)", lints.len())
                };
                println!("{}: ok{warnings}", path.display());
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
