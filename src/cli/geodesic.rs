//! `veneer geodesic`: a geodesic distance field over a mesh, one line per vertex.

use super::{Failure, write_output};
use clap::{Args, ValueEnum};
use std::path::PathBuf;
use std::time::Instant;

/// How distances are computed.
#[derive(Clone, Copy, ValueEnum)]
enum Method {
    /// Shortest paths along edges: fast, an upper bound (a few % long on grids).
    Dijkstra,
}

#[derive(Args)]
pub struct GeodesicArgs {
    /// A mesh file (OBJ, STL, PLY, glTF) or a primitive name.
    mesh: String,
    /// Source vertices, counted as the mesh file lists them.
    #[arg(long, value_delimiter = ',', required = true)]
    sources: Vec<u32>,
    /// How distances are computed.
    #[arg(long, value_enum, default_value = "dijkstra")]
    method: Method,
    /// Divide by the largest finite distance.
    #[arg(long)]
    normalize: bool,
    /// Output CSV: one distance per vertex in file order, `inf` where no source reaches.
    #[arg(short, long)]
    output: PathBuf,
}

pub fn run(args: GeodesicArgs) -> Result<(), Failure> {
    let started = Instant::now();
    let mesh = match veneer::mesh::primitive(&args.mesh) {
        Some(primitive) => primitive,
        None => veneer::mesh::load(std::path::Path::new(&args.mesh))?,
    };
    let count = mesh.positions.len();
    if let Some(bad) = args.sources.iter().find(|&&s| s as usize >= count) {
        return Err(Failure::new(format!(
            "{}: source vertex {bad} does not exist (the mesh has {count})",
            args.mesh
        )));
    }
    // Files often split vertices at seams: weld so that distances cross them.
    let extent = mesh
        .positions
        .iter()
        .flat_map(|p| p.iter())
        .fold(0.0f32, |m, c| m.max(c.abs()));
    let (welded, remap) = veneer::mesh::weld(&mesh, 1.0e-6 * extent.max(1.0));
    let sources: Vec<u32> = args.sources.iter().map(|&s| remap[s as usize]).collect();
    let setup = started.elapsed();
    let bar = (welded.positions.len() > 100_000)
        .then(|| indicatif::ProgressBar::new(welded.positions.len() as u64));
    let solving = Instant::now();
    let field = match args.method {
        Method::Dijkstra => veneer::geodesic::edge_distances(&welded, &sources, |done, _| {
            if let Some(bar) = &bar {
                bar.set_position(done as u64);
            }
        }),
    };
    let solve = solving.elapsed();
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    let field = if args.normalize {
        veneer::geodesic::normalized(&field)
    } else {
        field
    };
    let mut csv = String::with_capacity(count * 12);
    for &vertex in &remap {
        let distance = field[vertex as usize];
        csv.push_str(&if distance.is_finite() {
            format!("{distance}\n")
        } else {
            "inf\n".to_string()
        });
    }
    write_output(Some(&args.output), csv.as_bytes())?;
    eprintln!(
        "{}: {} vertices ({} after welding), {} triangles; set-up {:.1} ms, solve {:.1} ms",
        args.mesh,
        count,
        welded.positions.len(),
        welded.triangle_count(),
        setup.as_secs_f64() * 1e3,
        solve.as_secs_f64() * 1e3
    );
    Ok(())
}
