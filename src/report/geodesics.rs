//! The report's geodesic section: heat (unrefined, refined, robust) and Dijkstra against the exact
//! method on several meshes and sizes, with set-up and solve times.

use super::measure::{median_of, samples_ms};
use super::plot::{Plot, Series};
use super::table::{Table, number};
use super::{Context, Section};
use crate::geodesic::{self, HeatOptions, HeatSolver, Method, Triangulation};
use crate::mesh::Mesh;
use std::time::Instant;

/// The methods measured against the exact one: heat on the mesh's own vertices, on its
/// intrinsic Delaunay refinement (the default) and robust (mollified, then refined),
/// and Dijkstra.
pub const APPROXIMATE: [Method; 4] = [
    Method::Heat(HeatOptions {
        time_factor: 1.0,
        robust: false,
        refine: false,
    }),
    Method::Heat(HeatOptions {
        time_factor: 1.0,
        robust: false,
        refine: true,
    }),
    Method::Heat(HeatOptions {
        time_factor: 1.0,
        robust: true,
        refine: true,
    }),
    Method::Dijkstra,
];

/// Wall times of computing a distance field on a (welded) mesh by one method, in
/// milliseconds, one entry per repetition, and the field from vertex 0.
pub struct FieldTimes {
    /// Building the intrinsic triangulation and factoring (heat); 0 for the others.
    pub setup_ms: Vec<f64>,
    /// One field from one source (heat: with the factored solver; each repetition a
    /// different vertex; exact: the triangulation included).
    pub solve_ms: Vec<f64>,
    /// The distances from vertex 0.
    pub field: Vec<f64>,
}

impl FieldTimes {
    /// The time of one field from scratch (set-up and solve), per repetition.
    pub fn total_ms(&self) -> Vec<f64> {
        self.setup_ms
            .iter()
            .zip(&self.solve_ms)
            .map(|(setup, solve)| setup + solve)
            .collect()
    }
}

/// Times `method` on `mesh` over `runs` repetitions. Heat and Dijkstra take a warm-up
/// run first; the exact method, which takes seconds on the larger meshes, does not (its
/// first timed run gives the field).
pub fn time_field(mesh: &Mesh, method: Method, runs: usize) -> Result<FieldTimes, String> {
    let runs = runs.max(1);
    match method {
        Method::Heat(options) => {
            let setup_ms = samples_ms(runs, || {
                let _ = HeatSolver::new(Triangulation::from_mesh(mesh), options);
            });
            let solver = HeatSolver::new(Triangulation::from_mesh(mesh), options)
                .map_err(|e| e.to_string())?;
            let mut source = 0;
            let solve_ms = samples_ms(runs, || {
                source = (source + 7919) % mesh.positions.len() as u32;
                let _ = solver.distances(&[source]);
            });
            Ok(FieldTimes {
                setup_ms,
                solve_ms,
                field: solver.distances(&[0]),
            })
        }
        Method::Dijkstra => Ok(FieldTimes {
            setup_ms: vec![0.0; runs],
            solve_ms: samples_ms(runs, || {
                let _ = geodesic::edge_distances(mesh, &[0], |_, _| {});
            }),
            field: geodesic::edge_distances(mesh, &[0], |_, _| {}),
        }),
        Method::Exact => {
            let mut field = Vec::new();
            let solve_ms = (0..runs)
                .map(|_| {
                    let started = Instant::now();
                    field =
                        geodesic::exact_distances(&Triangulation::from_mesh(mesh), &[0], |_, _| {});
                    started.elapsed().as_secs_f64() * 1e3
                })
                .collect();
            Ok(FieldTimes {
                setup_ms: vec![0.0; runs],
                solve_ms,
                field,
            })
        }
    }
}

/// Every method against exact on each mesh of the context.
pub fn geodesics(ctx: &Context) -> Result<Section, String> {
    let mut table = Table::new(&[
        "mesh",
        "triangles",
        "method",
        "mean rel. error",
        "max rel. error",
        "set-up ms",
        "solve ms",
    ]);
    let methods = APPROXIMATE;
    let mut series: Vec<Series> = methods
        .iter()
        .map(|m| Series {
            name: m.name().into(),
            points: Vec::new(),
            joined: false,
        })
        .collect();
    for name in ctx.meshes {
        let mesh =
            geodesic::welded_for_distances(&crate::mesh::primitive(name).ok_or("primitive")?).0;
        let triangles = mesh.triangle_count().to_string();
        let exact = time_field(&mesh, Method::Exact, 1)?;
        let (exact_ms, exact) = (exact.solve_ms[0], exact.field);
        table.push(vec![
            name.to_string(),
            triangles.clone(),
            "exact".into(),
            "0".into(),
            "0".into(),
            "0".into(),
            number(exact_ms, 3),
        ]);
        for (method, series) in methods.iter().zip(&mut series) {
            let timed = time_field(&mesh, *method, ctx.repetitions)?;
            let (setup_ms, solve_ms, field) = (
                median_of(&timed.setup_ms),
                median_of(&timed.solve_ms),
                timed.field,
            );
            let (mean, max) =
                geodesic::relative_errors(&field, &exact, 0.1 * geodesic::max_finite(&exact));
            series.points.push((solve_ms, mean));
            table.push(vec![
                name.to_string(),
                triangles.clone(),
                method.name().into(),
                number(mean, 3),
                number(max, 3),
                number(setup_ms, 3),
                number(solve_ms, 3),
            ]);
        }
        (ctx.progress)();
    }
    Ok(Section {
        title: "Geodesic methods: error against time".into(),
        text: format!(
            "One source (vertex 0) on each mesh; errors are relative to the exact polyhedral distance, over vertices farther than 10% of the largest distance. Set-up is building the triangulation, flipping and refining it, and factoring (heat) — done once per mesh; solve is one new set of sources. Heat and Dijkstra times are medians of {} runs; the exact method runs once. The heat method runs on the mesh's own triangles (unrefined, as before issue #36) and on its intrinsic Delaunay refinement (the default: edges flipped to Delaunay, those longer than the mean split), plain and robust (mollified first). `genus2` comes from marching tetrahedra and has slivers, which the flips remove; the tori's long grid edges are what refinement splits.",
            ctx.repetitions
        ),
        table,
        plot: Plot {
            title: "Geodesics: error against solve time".into(),
            x_label: "solve time (ms)".into(),
            y_label: "mean relative error against exact".into(),
            series,
        },
    })
}
