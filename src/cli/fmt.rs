//! `veneer fmt`: rewrite graph files, and library group files, in their canonical form.

use super::{Failure, load_graph};
use clap::Args;
use std::path::{Path, PathBuf};
use veneer::graph::{layout, library};

#[derive(Args)]
pub struct FmtArgs {
    /// Graph files (or library group files, as in graphs/lib/) to rewrite in place.
    #[arg(required = true)]
    graphs: Vec<PathBuf>,
    /// Also lay the nodes out in columns, wires running left to right; inside every
    /// group the graph defines too.
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
        match library::load(path) {
            Ok(group) => rewrite_library_group(path, group, &args)?,
            Err(_) => rewrite_graph(path, &args)?,
        }
    }
    Ok(())
}

/// Rewrites graph file `path`.
fn rewrite_graph(path: &Path, args: &FmtArgs) -> Result<(), Failure> {
    let mut graph = load_graph(path)?;
    if args.arrange {
        let width = args.width.unwrap_or(f32::INFINITY);
        let height = args.height.unwrap_or(f32::INFINITY);
        layout::arrange_in_rows(&mut graph, width, height);
        layout::arrange_groups(&mut graph, width, height);
    }
    veneer::graph::save(&graph, path).map_err(|error| cannot_write(path, error))
}

/// Rewrites library group file `path`, whose content is `file`.
fn rewrite_library_group(
    path: &Path,
    mut file: library::LibraryGroup,
    args: &FmtArgs,
) -> Result<(), Failure> {
    if args.arrange {
        let group = &mut file.group;
        let (width, height) = (
            args.width.unwrap_or(f32::INFINITY),
            args.height.unwrap_or(f32::INFINITY),
        );
        layout::arrange_nodes(&mut group.nodes, &group.wires, width, height);
    }
    let text = library::to_ron(&file.name, &file.group);
    veneer::fsutil::write_atomic(path, text.as_bytes()).map_err(|error| cannot_write(path, error))
}

fn cannot_write(path: &Path, error: impl std::fmt::Display) -> Failure {
    Failure::new(format!("{}: cannot write: {error}", path.display()))
}
