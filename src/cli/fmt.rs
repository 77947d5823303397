//! `veneer fmt`: rewrite graph files in their canonical form.

use super::{Failure, load_graph};
use clap::Args;
use std::path::PathBuf;

#[derive(Args)]
pub struct FmtArgs {
    /// Graph files to rewrite in place.
    #[arg(required = true)]
    graphs: Vec<PathBuf>,
}

pub fn run(args: FmtArgs) -> Result<(), Failure> {
    for path in &args.graphs {
        let graph = load_graph(path)?;
        veneer::graph::save(&graph, path)
            .map_err(|error| Failure::new(format!("{}: cannot write: {error}", path.display())))?;
    }
    Ok(())
}
