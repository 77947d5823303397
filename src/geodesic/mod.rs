//! Geodesic distance fields on triangle meshes: the distance along the surface from a
//! set of source vertices to every vertex (the minimum over the sources). Vertices no
//! source reaches get `f64::INFINITY`, never NaN.
//!
//! Three methods trade accuracy for time: [`Method::Exact`] (window propagation, the
//! reference), [`Method::Heat`] (two sparse solves, factored once per mesh, about 1%
//! off on good meshes) and [`Method::Dijkstra`] (paths along edges, an upper bound a few
//! percent long). `veneer report` measures each against the exact one.

mod attach;
mod delaunay;
mod dijkstra;
mod exact;
mod fallback;
mod file_order;
mod heat;
mod refine;
mod triangulation;

pub use crate::graph::{HeatOptions, Method};
pub use attach::{FieldError, attach_fields, check_field_sources};
pub use dijkstra::edge_distances;
pub use exact::exact_distances;
pub use fallback::{Fallback, heat_solver};
pub use file_order::WeldedMesh;
pub use heat::{HeatError, HeatSetup, HeatSolver, REFINE_UP_TO, diffuse};
pub use triangulation::{NO_TWIN, Triangulation, split};

use crate::mesh::Mesh;
use std::time::{Duration, Instant};

/// Distances from `sources` over `mesh` (welded: vertices shared by the triangles
/// around them) by `method`, reporting progress as `(done, total)` where the method
/// can tell.
pub fn distances(
    mesh: &Mesh,
    sources: &[u32],
    method: Method,
    progress: impl FnMut(usize, usize),
) -> Result<Vec<f64>, HeatError> {
    Ok(fields(mesh, &[sources.to_vec()], method, progress)?
        .fields
        .remove(0))
}

/// Fields and what computing them cost.
pub struct Solved {
    /// One field per set of sources.
    pub fields: Vec<Vec<f64>>,
    /// Time spent on the set-up shared by all fields (the heat method's factorisation).
    pub setup_time: Duration,
    /// Time spent computing the fields once set up (not freeing the set-up after).
    pub solve_time: Duration,
    /// What the heat method's set-up did, when it ran.
    pub heat: Option<HeatSetup>,
    /// The method the fields were computed with: the one asked for, or the robust heat
    /// method where the plain one could not be set up.
    pub method: Method,
    /// Why the robust heat method replaced the plain one, when it did.
    pub fallback: Option<Fallback>,
}

/// One field per set of sources (a material spreading from each set), sharing the set-up
/// of the mesh between them (the heat method factors once). Progress counts vertices
/// over all fields. The plain heat method falls back to the robust one when it cannot
/// be set up ([`heat_solver`]).
pub fn fields(
    mesh: &Mesh,
    source_sets: &[Vec<u32>],
    method: Method,
    mut progress: impl FnMut(usize, usize),
) -> Result<Solved, HeatError> {
    let started = Instant::now();
    let n = mesh.positions.len();
    let total = n * source_sets.len();
    let (heat, fallback) = match method {
        Method::Heat(options) => {
            let (solver, fallback) = heat_solver(mesh, options)?;
            (Some(solver), fallback)
        }
        _ => (None, None),
    };
    let method = match (method, &fallback) {
        (Method::Heat(options), Some(_)) => Method::Heat(HeatOptions {
            robust: true,
            ..options
        }),
        _ => method,
    };
    let surface = (method == Method::Exact).then(|| Triangulation::from_mesh(mesh));
    let setup_time = started.elapsed();
    let solving = Instant::now();
    let mut fields = Vec::with_capacity(source_sets.len());
    for (i, sources) in source_sets.iter().enumerate() {
        let mut within = |done: usize, _: usize| progress(i * n + done, total);
        fields.push(match (&heat, &surface) {
            (Some(solver), _) => solver.distances(sources),
            (_, Some(surface)) => exact_distances(surface, sources, &mut within),
            _ => edge_distances(mesh, sources, &mut within),
        });
        progress((i + 1) * n, total);
    }
    let solve_time = solving.elapsed();
    Ok(Solved {
        fields,
        setup_time,
        solve_time,
        heat: heat.map(|solver| solver.setup()),
        method,
        fallback,
    })
}

/// `mesh` with coincident vertices merged (files split vertices along UV and normal
/// seams, which would cut every path), and the index of each original vertex in it.
pub fn welded_for_distances(mesh: &Mesh) -> (Mesh, Vec<u32>) {
    let extent = mesh
        .positions
        .iter()
        .flat_map(|p| p.iter())
        .fold(0.0f32, |m, c| m.max(c.abs()));
    crate::mesh::weld(mesh, 1.0e-6 * extent.max(1.0))
}

/// Mean and largest relative error of `field` against `reference` over the vertices the
/// reference puts farther than `near` from the sources (relative errors blow up at the
/// sources themselves, so accuracy tables leave the nearest vertices out).
pub fn relative_errors(field: &[f64], reference: &[f64], near: f64) -> (f64, f64) {
    let errors: Vec<f64> = field
        .iter()
        .zip(reference)
        .filter(|(_, r)| r.is_finite() && **r > near)
        .map(|(f, r)| (f - r).abs() / r)
        .collect();
    let mean = errors.iter().sum::<f64>() / errors.len().max(1) as f64;
    (mean, errors.iter().copied().fold(0.0, f64::max))
}

/// The largest finite value of a field (0 when none is finite).
pub fn max_finite(field: &[f64]) -> f64 {
    field
        .iter()
        .copied()
        .filter(|d| d.is_finite())
        .fold(0.0, f64::max)
}

/// `field` divided by its largest finite value, so that reached vertices lie in [0, 1];
/// unreached vertices stay infinite.
pub fn normalized(field: &[f64]) -> Vec<f64> {
    let max = max_finite(field);
    field
        .iter()
        .map(|&d| {
            if d.is_finite() && max > 0.0 {
                d / max
            } else {
                d
            }
        })
        .collect()
}
