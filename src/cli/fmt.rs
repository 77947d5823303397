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
    /// With --arrange: wrap the columns into rows no wider than this (canvas units).
    #[arg(long, requires = "arrange")]
    width: Option<f32>,
    /// With --arrange: continue a column taller than this (canvas units) in the next.
    #[arg(long, requires = "arrange")]
    height: Option<f32>,
}

pub fn run(args: FmtArgs) -> Result<(), Failure> {
    for path in &args.graphs {
        let mut graph = load_graph(path)?;
        if args.arrange {
            let width = args.width.unwrap_or(f32::INFINITY);
            let height = args.height.unwrap_or(f32::INFINITY);
            veneer::graph::layout::arrange_in_rows(&mut graph, width, height);
        }
        veneer::graph::save(&graph, path)
            .map_err(|error| Failure::new(format!("{}: cannot write: {error}", path.display())))?;
    }
    Ok(())
}
