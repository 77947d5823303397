//! `veneer fmt`: rewrite graph files in their canonical form.

use super::{Failure, load_graph};
use clap::Args;
use std::path::PathBuf;

#[derive(Args)]
pub struct FmtArgs {
    /// Graph files to rewrite in place.
    #[arg(required = true)]
    graphs: Vec<PathBuf>,
    /// Also lay the nodes out in columns, wires running left to right.
    #[arg(long)]
    arrange: bool,
}

pub fn run(args: FmtArgs) -> Result<(), Failure> {
    for path in &args.graphs {
        let mut graph = load_graph(path)?;
        if args.arrange {
            veneer::graph::layout::arrange(&mut graph);
        }
        veneer::graph::save(&graph, path)
            .map_err(|error| Failure::new(format!("{}: cannot write: {error}", path.display())))?;
    }
    Ok(())
}
