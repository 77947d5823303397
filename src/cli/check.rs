//! `veneer check`: load, type-check, compile and validate graph files.

use super::{Failure, in_file};
use clap::Args;
use std::path::PathBuf;

#[derive(Args)]
pub struct CheckArgs {
    /// Graph files to check.
    #[arg(required = true)]
    graphs: Vec<PathBuf>,
}

pub fn run(args: CheckArgs) -> Result<(), Failure> {
    let mut failures = Vec::new();
    for path in &args.graphs {
        let result = veneer::graph::load(path)
            .map_err(Failure::from)
            .and_then(|graph| {
                veneer::codegen::compile_graph(&graph).map_err(|error| in_file(path, error))
            });
        match result {
            Ok(_) => println!("{}: ok", path.display()),
            Err(Failure(message, _)) => failures.push(message),
        }
    }
    if failures.is_empty() {
        Ok(())
    } else {
        Err(Failure::new(failures.join("\n")))
    }
}
