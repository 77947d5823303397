//! Geodesic distance fields on a ~100k-triangle torus (`torus:160`, 102,400 triangles)
//! and the genus-2 surface, method against method in the same run:
//! - the heat method's set-up (intrinsic Delaunay refinement, cotangent Laplacian, mass
//!   matrix, two sparse Cholesky factorisations) and one re-solve with new sources: on
//!   the mesh's own triangles (the method before refinement), refined (the default) and
//!   robust;
//! - the exact method (window propagation), the accuracy reference;
//! - Dijkstra along edges, the cheap baseline.
//!
//! The mean relative error of each against the exact field is printed before the
//! timings. `benches/potpourri3d_compare.py` runs the same meshes through potpourri3d
//! (geometry-central) for an outside baseline.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use veneer::geodesic::{self, HeatOptions, HeatSolver, Method, Triangulation};

fn mean_relative_error(field: &[f64], exact: &[f64]) -> f64 {
    geodesic::relative_errors(field, exact, 0.1 * geodesic::max_finite(exact)).0
}

fn fields(c: &mut Criterion) {
    for name in ["torus:160", "genus2:40"] {
        let mesh =
            geodesic::welded_for_distances(&veneer::mesh::primitive(name).expect("primitive")).0;
        let exact = geodesic::distances(&mesh, &[0], Method::Exact, |_, _| {}).expect("exact");
        let heat_variants =
            [(false, false), (false, true), (true, true)].map(|(robust, refine)| HeatOptions {
                robust,
                refine,
                ..HeatOptions::default()
            });
        let methods = heat_variants.map(Method::Heat).into_iter();
        for method in methods.chain([Method::Dijkstra]) {
            let field = geodesic::distances(&mesh, &[0], method, |_, _| {}).expect("solvable");
            println!(
                "{name} ({} triangles): {} mean relative error against exact {:.3}%",
                mesh.triangle_count(),
                method.name(),
                100.0 * mean_relative_error(&field, &exact)
            );
        }
        let mut group = c.benchmark_group(format!(
            "geodesic {name} ({} triangles)",
            mesh.triangle_count()
        ));
        group.sample_size(10);
        for options in heat_variants {
            let label = Method::Heat(options).name();
            group.bench_function(format!("{label}: set-up (factorisation)"), |b| {
                b.iter(|| {
                    HeatSolver::new(Triangulation::from_mesh(black_box(&mesh)), options)
                        .expect("factors")
                })
            });
            let solver =
                HeatSolver::new(Triangulation::from_mesh(&mesh), options).expect("factors");
            let mut source = 0u32;
            group.bench_function(format!("{label}: re-solve with a new source"), |b| {
                b.iter(|| {
                    source = (source + 7919) % mesh.positions.len() as u32;
                    solver.distances(black_box(&[source]))
                })
            });
        }
        group.bench_function("dijkstra", |b| {
            b.iter(|| geodesic::edge_distances(black_box(&mesh), &[0], |_, _| {}))
        });
        group.bench_function("exact", |b| {
            let surface = Triangulation::from_mesh(&mesh);
            b.iter(|| geodesic::exact_distances(black_box(&surface), &[0], |_, _| {}))
        });
        group.finish();
    }
}

criterion_group!(benches, fields);
criterion_main!(benches);
