//! `veneer geodesic`: geodesic distance fields over a mesh, one line per vertex.

use super::output::note;
use super::{Failure, write_output};
use clap::{Args, ValueEnum};
use std::path::PathBuf;
use std::time::Instant;
use veneer::geodesic::{self, HeatOptions, Method};

/// How distances are computed.
#[derive(Clone, Copy, ValueEnum)]
enum MethodName {
    /// The heat method: two sparse solves, factored once; about 1% off on good meshes.
    Heat,
    /// Exact polyhedral distances (window propagation): the reference, slowest.
    Exact,
    /// Shortest paths along edges: fast, an upper bound (a few % long on grids).
    Dijkstra,
}

#[derive(Args)]
pub struct GeodesicArgs {
    #[arg(help = super::mesh_help())]
    mesh: String,
    /// Source vertices, counted as the mesh file lists them. Repeat the option (up to
    /// four times) for several fields: one column each.
    #[arg(long, required = true)]
    sources: Vec<String>,
    /// How distances are computed.
    #[arg(long, value_enum, default_value = "heat")]
    method: MethodName,
    /// Heat method: mollify lengths and retriangulate (intrinsic Delaunay) first, for
    /// meshes with slivers or degenerate triangles. Without it, the robust method is
    /// still used, with a warning, where the plain one cannot be set up.
    #[arg(long)]
    robust: bool,
    /// Heat method: solve on the mesh's own triangles and vertices instead of its
    /// intrinsic Delaunay refinement (flipped to Delaunay, edges longer than the mean
    /// split, at most 1.5 new vertices per vertex; meshes of more than 100,000 vertices
    /// are never refined): less accurate, about half the set-up.
    #[arg(long)]
    no_refine: bool,
    /// Heat method: diffusion time as a multiple of the mean edge length squared.
    #[arg(long, default_value_t = 1.0)]
    time_factor: f64,
    /// Divide each field by its largest finite distance.
    #[arg(long)]
    normalize: bool,
    /// Output CSV: one line per vertex of the file, in its order, `inf` where no source
    /// reaches.
    #[arg(short, long)]
    output: PathBuf,
}

impl GeodesicArgs {
    /// Adds the mesh file and the CSV written to `plan`.
    pub fn plan(&self, plan: &mut veneer::fsutil::OutputPlan, job: Option<&str>) {
        super::plan_mesh_command(plan, job, &self.mesh, Some(&self.output));
    }
}

pub fn run(args: GeodesicArgs) -> Result<(), Failure> {
    args.method()
        .validate()
        .map_err(|error| Failure::new(format!("--time-factor: {error}")))?;
    let started = Instant::now();
    let mesh = veneer::mesh::Mesh::named(&args.mesh)?;
    let file_sets = parse_sources(&args, mesh.file_vertex_count())?;
    let welded = geodesic::WeldedMesh::new(&mesh);
    let loaded = started.elapsed();
    let report = veneer::mesh::analyse(&welded.mesh);
    for problem in report.problems() {
        note(format!("warning: {}: {problem}", args.mesh))?;
    }
    let source_sets: Vec<Vec<u32>> = file_sets.iter().map(|set| welded.sources(set)).collect();
    let count = welded.mesh.positions.len();
    let bar = (count > 100_000).then(|| {
        let bar = indicatif::ProgressBar::new((count * source_sets.len()) as u64);
        bar.set_style(
            indicatif::ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} {elapsed}")
                .expect("valid template"),
        );
        bar.set_message(format!("{} distances", args.method().name()));
        bar.enable_steady_tick(std::time::Duration::from_millis(200));
        bar
    });
    let solved = geodesic::fields(&welded.mesh, &source_sets, args.method(), |done, _| {
        if let Some(bar) = &bar {
            bar.set_position(done as u64);
        }
    })
    .map_err(|e| Failure::new(format!("{}: {e}", args.mesh)))?;
    let (setup, solve_time) = (solved.setup_time, solved.solve_time);
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    if let Some(fallback) = &solved.fallback {
        note(format!("warning: {}: {fallback}", args.mesh))?;
    }
    if let (Some(heat), Method::Heat(options)) = (solved.heat, solved.method) {
        if options.robust {
            note(format!(
                "robust: edges lengthened by {:.3e}",
                heat.mollified_by
            ))?;
        }
        if let Some(skipped) = heat.refinement_note() {
            note(skipped)?;
        }
        if options.robust || heat.added_vertices > 0 || heat.flips > 0 {
            note(format!(
                "intrinsic: {} flips, {} vertices added by refinement, in {:.1} ms of the set-up",
                heat.flips,
                heat.added_vertices,
                heat.refine_time.as_secs_f64() * 1e3
            ))?;
        }
    }
    let fields: Vec<Vec<f64>> = solved
        .fields
        .iter()
        .zip(&file_sets)
        .map(|(field, sources)| welded.in_file_order(field, sources))
        .map(|field| match args.normalize {
            true => geodesic::normalized(&field),
            false => field,
        })
        .collect();
    write_output(Some(&args.output), csv(&fields).as_bytes())?;
    let unreached = fields[0].iter().filter(|d| d.is_infinite()).count();
    note(format!(
        "{}: {} vertices ({} after welding), {} triangles; {}; load {:.1} ms, set-up {:.1} ms, solve {:.1} ms{}",
        args.mesh,
        fields[0].len(),
        count,
        welded.mesh.triangle_count(),
        solved.method.name(),
        loaded.as_secs_f64() * 1e3,
        setup.as_secs_f64() * 1e3,
        solve_time.as_secs_f64() * 1e3,
        if unreached > 0 {
            format!("; {unreached} vertices unreached")
        } else {
            String::new()
        }
    ))
}

/// One line per vertex, one column per field, `inf` where a field does not reach.
fn csv(fields: &[Vec<f64>]) -> String {
    let rows = fields.first().map_or(0, Vec::len);
    let mut csv = String::with_capacity(rows * 12 * fields.len());
    for vertex in 0..rows {
        let row: Vec<String> = fields
            .iter()
            .map(|field| match field[vertex] {
                d if d.is_finite() => d.to_string(),
                _ => "inf".to_string(),
            })
            .collect();
        csv.push_str(&row.join(","));
        csv.push('\n');
    }
    csv
}

impl GeodesicArgs {
    fn method(&self) -> Method {
        match self.method {
            MethodName::Heat => Method::Heat(HeatOptions {
                robust: self.robust,
                refine: !self.no_refine,
                time_factor: self.time_factor,
            }),
            MethodName::Exact => Method::Exact,
            MethodName::Dijkstra => Method::Dijkstra,
        }
    }
}

/// The source sets of the command line, checked against the file's vertex count.
fn parse_sources(args: &GeodesicArgs, count: usize) -> Result<Vec<Vec<u32>>, Failure> {
    if args.sources.len() > 4 {
        return Err(Failure::new(format!(
            "--sources: {} fields asked for, a mesh carries at most 4",
            args.sources.len()
        )));
    }
    args.sources
        .iter()
        .map(|set| {
            set.split(',')
                .map(|text| {
                    let vertex: u32 = text.trim().parse().map_err(|_| {
                        Failure::new(format!("--sources: `{text}` is not a vertex index"))
                    })?;
                    if vertex as usize >= count {
                        return Err(Failure::new(format!(
                            "{}: source vertex {vertex} does not exist (the mesh has {count})",
                            args.mesh
                        )));
                    }
                    Ok(vertex)
                })
                .collect()
        })
        .collect()
}
