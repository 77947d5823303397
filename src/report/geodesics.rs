//! The report's geodesic section: heat (plain and robust) and Dijkstra against the exact
//! method on several meshes and sizes, with set-up and solve times.

use super::measure::median_ms;
use super::plot::{Plot, Series};
use super::table::{Table, number};
use super::{Context, Section};
use crate::geodesic::{self, HeatOptions, HeatSolver, Method, Triangulation};
use std::time::Instant;

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
    let methods = [
        Method::Heat(HeatOptions::default()),
        Method::Heat(HeatOptions {
            robust: true,
            ..HeatOptions::default()
        }),
        Method::Dijkstra,
    ];
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
        let started = Instant::now();
        let exact = geodesic::exact_distances(&Triangulation::from_mesh(&mesh), &[0], |_, _| {});
        let exact_ms = started.elapsed().as_secs_f64() * 1e3;
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
            let (setup_ms, solve_ms, field) = match *method {
                Method::Heat(options) => {
                    let setup = median_ms(ctx.repetitions, || {
                        let _ = HeatSolver::new(Triangulation::from_mesh(&mesh), options);
                    });
                    let solver = HeatSolver::new(Triangulation::from_mesh(&mesh), options)
                        .map_err(|e| e.to_string())?;
                    let mut source = 0;
                    let solve = median_ms(ctx.repetitions, || {
                        source = (source + 7919) % mesh.positions.len() as u32;
                        let _ = solver.distances(&[source]);
                    });
                    (setup, solve, solver.distances(&[0]))
                }
                _ => {
                    let solve = median_ms(ctx.repetitions, || {
                        let _ = geodesic::edge_distances(&mesh, &[0], |_, _| {});
                    });
                    (0.0, solve, geodesic::edge_distances(&mesh, &[0], |_, _| {}))
                }
            };
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
        slug: "geodesics",
        title: "Geodesic methods: error against time".into(),
        text: format!(
            "One source (vertex 0) on each mesh; errors are relative to the exact polyhedral distance, over vertices farther than 10% of the largest distance. Set-up is building the triangulation and factoring (heat) — done once per mesh; solve is one new set of sources. Heat and Dijkstra times are medians of {} runs; the exact method runs once. `genus2` comes from marching tetrahedra and has slivers, where the robust variant (mollified intrinsic Delaunay) helps; on the regular tori it costs a little.",
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
