//! The heat method (Crane, Weischedel & Wardetzky 2013/2017): diffuse heat from the
//! sources for a short time with one backward-Euler step, normalise its gradient
//! into unit vectors pointing away from the sources, and recover the distance whose
//! gradient best matches them with a Poisson solve. Both linear systems are factored
//! once per mesh (sparse Cholesky from faer), so a new set of sources costs two pairs of
//! triangular solves and two passes over the triangles.

use super::triangulation::Triangulation;
use crate::graph::{HeatOptions, TimeFactorError};
use faer::linalg::solvers::Solve;
use faer::sparse::{
    SparseColMat, SymbolicSparseColMat, Triplet,
    linalg::solvers::{Llt, SymbolicLlt},
};
use glam::DVec2;
use std::time::{Duration, Instant};

/// Why a heat solver could not be set up.
#[derive(Debug, thiserror::Error)]
pub enum HeatError {
    /// A system could not be factored: the matrix, faer's reason, and whether the robust
    /// option was on already.
    #[error("the {0} matrix could not be factored ({1}){hint}", hint = robust_hint(*.2))]
    Factorisation(&'static str, String, bool),
    /// A time factor outside [`HeatOptions::TIME_FACTORS`].
    #[error(transparent)]
    TimeFactor(#[from] TimeFactorError),
}

/// What to try after a failed factorisation.
fn robust_hint(robust: bool) -> &'static str {
    if robust {
        "; the mesh has parts the robust option could not repair (look for non-manifold edges or separate pieces)"
    } else {
        "; the robust option handles poor triangles"
    }
}

/// The most vertices (used by triangles) a mesh may have for the heat method to refine
/// it. Refining costs the set-up 1.5–2× the unrefined method's up to here and more beyond
/// (the flipped triangulation factors with more fill on large meshes: 2.4× on
/// `torus:256`, 3.6× on `torus:512`), so larger meshes are solved unrefined.
pub const REFINE_UP_TO: usize = 100_000;

/// What setting up the solver did and cost.
#[derive(Clone, Copy, Debug, Default)]
pub struct HeatSetup {
    /// The diffusion time used.
    pub time_step: f64,
    /// How much every edge was lengthened by mollification (robust only).
    pub mollified_by: f64,
    /// How many intrinsic edge flips the Delaunay retriangulation took (robust or
    /// refined).
    pub flips: usize,
    /// How many vertices intrinsic refinement added (refined only).
    pub added_vertices: usize,
    /// Time spent flipping and refining (part of `factor_time`).
    pub refine_time: Duration,
    /// Refinement was asked for but the mesh has more than [`REFINE_UP_TO`] vertices.
    pub refinement_skipped: bool,
    /// Time spent building and factoring the matrices.
    pub factor_time: Duration,
}

impl HeatSetup {
    /// Why the field was solved unrefined, where refinement was skipped for the mesh's
    /// size (the note `veneer geodesic` prints and the editor shows under the field).
    pub fn refinement_note(&self) -> Option<String> {
        self.refinement_skipped.then(|| {
            format!(
                "solved unrefined: the mesh has more than {REFINE_UP_TO} vertices, where \
                 refining would more than double the set-up"
            )
        })
    }
}

/// The per-triangle quantities the gradient and divergence need.
struct Corner {
    layout: [DVec2; 3],
    /// The cotangent of the angle at each corner.
    cotans: [f64; 3],
    /// The length of the edge from each corner to the next.
    lengths: [f64; 3],
    area: f64,
}

/// A factored system restricted to some of the vertices.
struct Restricted {
    llt: Llt<u32, f64>,
    /// Original vertex of each row.
    rows: Vec<u32>,
}

/// A heat-method solver for one mesh, reusable for any set of sources.
pub struct HeatSolver {
    /// The mesh's vertices, which come first (refinement numbers its own after them).
    mesh_vertices: usize,
    vertex_count: usize,
    faces: Vec<[u32; 3]>,
    corners: Vec<Corner>,
    /// Vertices with no area around them (in no triangle, or only degenerate ones).
    dead: Vec<bool>,
    components: Vec<usize>,
    heat: Llt<u32, f64>,
    /// The heat system with zero heat held on the boundary, when there is one.
    dirichlet: Option<Restricted>,
    poisson: Llt<u32, f64>,
    setup: HeatSetup,
}

impl HeatSolver {
    /// Builds and factors the heat and Poisson systems of `triangulation`.
    pub fn new(triangulation: Triangulation, options: HeatOptions) -> Result<Self, HeatError> {
        options.validate()?;
        Self::build(triangulation, options).map_err(|error| match error {
            HeatError::Factorisation(matrix, reason, _) => {
                HeatError::Factorisation(matrix, reason, options.robust)
            }
            other => other,
        })
    }

    fn build(mut triangulation: Triangulation, options: HeatOptions) -> Result<Self, HeatError> {
        let started = Instant::now();
        let mut setup = HeatSetup::default();
        let mesh_vertices = triangulation.vertex_count;
        if options.robust {
            setup.mollified_by = triangulation.mollify(1.0e-5);
        }
        let used = triangulation.used_vertex_count();
        let refine = options.refine && used <= REFINE_UP_TO;
        setup.refinement_skipped = options.refine && !refine;
        if options.robust || refine {
            setup.flips = triangulation.flip_to_delaunay();
        }
        if refine {
            let (added, flips) = triangulation.refine(used * 3 / 2);
            setup.added_vertices = added;
            setup.flips += flips;
        }
        setup.refine_time = started.elapsed();
        let n = triangulation.vertex_count;
        let corners = corners(&triangulation);
        let operators = Operators::new(n, &triangulation.faces, &corners);
        let h = triangulation.mean_edge_length();
        setup.time_step = options.time_factor * h * h;
        let t = setup.time_step;
        let regularisation = 1.0e-8 / (h * h).max(f64::MIN_POSITIVE);
        let heat_matrix = operators.combine(t, 1.0);
        let boundary = triangulation.boundary_vertices();
        let held = boundary.iter().zip(&operators.dead).any(|(&b, &d)| b && !d);
        let keep: Vec<bool> = boundary.iter().map(|&b| !b).collect();
        // The boundary system (where there is one) is factored beside the other two.
        let (factors, dirichlet) = rayon::join(
            || {
                factor_alike(
                    ["heat", "Poisson"],
                    [&heat_matrix, &operators.combine(1.0, regularisation)],
                )
            },
            || held.then(|| restricted(&heat_matrix, &keep)).transpose(),
        );
        let [heat, poisson] = factors?;
        let dirichlet = dirichlet?;
        let dead = operators.dead;
        setup.factor_time = started.elapsed();
        Ok(HeatSolver {
            mesh_vertices,
            vertex_count: n,
            components: triangulation.components(),
            faces: triangulation.faces,
            corners,
            dead,
            heat,
            dirichlet,
            poisson,
            setup,
        })
    }

    /// What setting up cost and changed.
    pub fn setup(&self) -> HeatSetup {
        self.setup
    }

    /// The distance from the nearest of `sources` to every vertex of the mesh; `inf` for
    /// vertices no source reaches. Sources out of range are ignored.
    pub fn distances(&self, sources: &[u32]) -> Vec<f64> {
        let n = self.vertex_count;
        let sources: Vec<usize> = sources
            .iter()
            .map(|&s| s as usize)
            .filter(|&s| s < self.mesh_vertices)
            .collect();
        let mut heat = vec![0.0; n];
        for &s in &sources {
            heat[s] = 1.0;
        }
        // The boundary system starts from the same heat, restricted to its rows.
        let mut held: Option<Vec<f64>> = self
            .dirichlet
            .as_ref()
            .map(|dirichlet| dirichlet.rows.iter().map(|&v| heat[v as usize]).collect());
        solve(&self.heat, &mut heat);
        if let (Some(dirichlet), Some(held)) = (&self.dirichlet, held.as_mut()) {
            solve(&dirichlet.llt, held);
            // The average of both; boundary vertices hold no heat in the second.
            for u in heat.iter_mut() {
                *u *= 0.5;
            }
            for (&v, &value) in dirichlet.rows.iter().zip(held.iter()) {
                heat[v as usize] += 0.5 * value;
            }
        }
        let mut potential = self.divergence_of_normalised_gradient(&heat);
        solve(&self.poisson, &mut potential);
        let mut distances = self.shift_to_sources(potential, &sources);
        distances.truncate(self.mesh_vertices);
        distances
    }

    /// `−∇·X` at each vertex, where `X = −∇u/|∇u|` on each triangle (zero where the
    /// heat is flat to rounding). Each triangle's share is worked out in parallel, then
    /// summed into the vertices in triangle order, so the result is the same on every run.
    fn divergence_of_normalised_gradient(&self, heat: &[f64]) -> Vec<f64> {
        use rayon::prelude::*;
        let shares: Vec<Option<[f64; 3]>> = self
            .faces
            .par_iter()
            .zip(&self.corners)
            .map(|(face, corner)| {
                if corner.area <= 0.0 {
                    return None;
                }
                let p = corner.layout;
                let u = face.map(|v| heat[v as usize]);
                let gradient = (0..3)
                    .map(|i| {
                        let edge = p[(i + 2) % 3] - p[(i + 1) % 3];
                        u[i] * edge.perp()
                    })
                    .fold(DVec2::ZERO, |sum, g| sum + g)
                    / (2.0 * corner.area);
                // A gradient within rounding of the face's own values has no direction.
                let length = gradient.length();
                let scale = u.iter().fold(0.0f64, |m, v| m.max(v.abs()))
                    / corner.lengths.iter().fold(0.0f64, |m, &l| m.max(l));
                if !(length > 1.0e-9 * scale && length.is_finite()) {
                    return None;
                }
                let x = -gradient / length;
                Some([0, 1, 2].map(|i| {
                    let (j, k) = ((i + 1) % 3, (i + 2) % 3);
                    let flux = corner.cotans[k] * (p[j] - p[i]).dot(x)
                        + corner.cotans[j] * (p[k] - p[i]).dot(x);
                    -0.5 * flux
                }))
            })
            .collect();
        let mut divergence = vec![0.0; self.vertex_count];
        for (face, share) in self.faces.iter().zip(shares) {
            if let Some(share) = share {
                for i in 0..3 {
                    divergence[face[i] as usize] += share[i];
                }
            }
        }
        divergence
    }

    /// Moves each component's potential so its sources sit at 0, clamps the rest at 0,
    /// and marks components without a source (and dead vertices) as unreached.
    fn shift_to_sources(&self, potential: Vec<f64>, sources: &[usize]) -> Vec<f64> {
        let mut offsets: std::collections::HashMap<usize, (f64, usize)> = Default::default();
        for &s in sources.iter().filter(|&&s| !self.dead[s]) {
            let entry = offsets.entry(self.components[s]).or_default();
            entry.0 += potential[s];
            entry.1 += 1;
        }
        let mut distances: Vec<f64> = potential
            .iter()
            .enumerate()
            .map(|(v, &phi)| match offsets.get(&self.components[v]) {
                Some(&(sum, count)) if !self.dead[v] => (phi - sum / count as f64).max(0.0),
                _ => f64::INFINITY,
            })
            .collect();
        for &s in sources {
            distances[s] = 0.0;
        }
        self.reach_dead_vertices(&mut distances);
        distances
    }

    /// Vertices with no area around them (only in degenerate triangles) take the
    /// shortest edge path from the reached vertices of their triangles.
    fn reach_dead_vertices(&self, distances: &mut [f64]) {
        let mut changed = self.dead.iter().any(|&d| d);
        while changed {
            changed = false;
            for (face, corner) in self.faces.iter().zip(&self.corners) {
                for i in 0..3 {
                    let v = face[i] as usize;
                    if !self.dead[v] {
                        continue;
                    }
                    // The edges to the next and to the previous corner.
                    for (j, length) in [
                        ((i + 1) % 3, corner.lengths[i]),
                        ((i + 2) % 3, corner.lengths[(i + 2) % 3]),
                    ] {
                        let via = distances[face[j] as usize] + length;
                        if via < distances[v] {
                            distances[v] = via;
                            changed = true;
                        }
                    }
                }
            }
        }
    }
}

/// The per-triangle quantities of every triangle of `triangulation`.
fn corners(triangulation: &Triangulation) -> Vec<Corner> {
    (0..triangulation.faces.len())
        .map(|f| Corner {
            layout: triangulation.layout(f),
            cotans: [1, 2, 0].map(|k| triangulation.cotan_across(f, k).unwrap_or(0.0)),
            lengths: triangulation.lengths[f],
            area: triangulation.area(f),
        })
        .collect()
}

/// A quantity spread over the surface by heat diffusion for `time` and read back as a
/// density at the vertices of `triangulation`: one backward-Euler step,
/// `(M + time·L) u = b`, stable however stiff, a smoothing whose kernel is a Gaussian of
/// the geodesic distance with variance `2·time`. `amount(v, m)` gives `b` at vertex `v`
/// whose lumped area is `m`: a density `d` there gives `d·m`, a quantity already
/// integrated over the vertex's share of the surface gives itself. Vertices with no area
/// around them read 0. Give it an intrinsic Delaunay triangulation
/// ([`Triangulation::flip_to_delaunay`]) so every weight is non-negative and the system
/// can be factored.
pub fn diffuse(
    triangulation: &Triangulation,
    time: f64,
    amount: impl Fn(usize, f64) -> f64,
) -> Result<Vec<f64>, HeatError> {
    let n = triangulation.vertex_count;
    let operators = Operators::new(n, &triangulation.faces, &corners(triangulation));
    let system = factor("diffusion", &operators.combine(time, 1.0))?;
    let mut smoothed: Vec<f64> = (0..n)
        .map(|v| {
            if operators.dead[v] {
                0.0
            } else {
                amount(v, operators.mass[v])
            }
        })
        .collect();
    solve(&system, &mut smoothed);
    Ok(smoothed)
}

/// The cotangent Laplacian `L` and the lumped mass `M` (a third of each triangle's area
/// at each of its corners) of a triangulation.
struct Operators {
    /// The lower triangle of `L`, every diagonal entry present (first in its column).
    laplacian: SparseColMat<u32, f64>,
    mass: Vec<f64>,
    /// Vertices with no area around them (in no triangle, or only degenerate ones).
    dead: Vec<bool>,
}

impl Operators {
    /// Assembles `L` column by column: each edge's weight is half the sum of the
    /// cotangents across it, summed over the triangles on it (and over the edges joining
    /// the same two vertices, which an intrinsic triangulation may have), in triangle
    /// order, so the matrix is the same on every run.
    fn new(n: usize, faces: &[[u32; 3]], corners: &[Corner]) -> Operators {
        let mut mass = vec![0.0; n];
        let mut diagonal = vec![0.0; n];
        // (column, row, weight) below the diagonal: column < row.
        let mut below: Vec<(u32, u32, f64)> = Vec::with_capacity(faces.len() * 3);
        for (face, corner) in faces.iter().zip(corners) {
            if corner.area <= 0.0 {
                continue;
            }
            for k in 0..3 {
                mass[face[k] as usize] += corner.area / 3.0;
                let weight = 0.5 * corner.cotans[(k + 2) % 3];
                let (a, b) = (face[k], face[(k + 1) % 3]);
                diagonal[a as usize] += weight;
                diagonal[b as usize] += weight;
                below.push((a.min(b), a.max(b), -weight));
            }
        }
        // Stable: contributions to one entry stay in triangle order.
        below.sort_by_key(|&(col, row, _)| (col, row));
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::with_capacity(n + below.len());
        let mut values = Vec::with_capacity(n + below.len());
        let mut next = below.iter().peekable();
        for col in 0..n as u32 {
            col_ptr.push(row_idx.len() as u32);
            row_idx.push(col);
            values.push(diagonal[col as usize]);
            while let Some(&&(_, row, weight)) = next.peek().filter(|entry| entry.0 == col) {
                next.next();
                if row_idx.last() == Some(&row) {
                    *values.last_mut().expect("a value per row") += weight;
                } else {
                    row_idx.push(row);
                    values.push(weight);
                }
            }
        }
        col_ptr.push(row_idx.len() as u32);
        let pattern = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        let dead = mass.iter().map(|&m| m <= 0.0).collect();
        Operators {
            laplacian: SparseColMat::new(pattern, values),
            mass,
            dead,
        }
    }

    /// `a·L + b·M` (lower triangle), with 1 on the diagonal of dead vertices.
    fn combine(&self, a: f64, b: f64) -> SparseColMat<u32, f64> {
        let mut matrix = self.laplacian.clone();
        let diagonal: Vec<usize> = matrix.symbolic().col_ptr()[..self.mass.len()]
            .iter()
            .map(|&start| start as usize)
            .collect();
        let values = matrix.val_mut();
        for value in values.iter_mut() {
            *value *= a;
        }
        for (v, &at) in diagonal.iter().enumerate() {
            values[at] = if self.dead[v] {
                1.0
            } else {
                values[at] + b * self.mass[v]
            };
        }
        matrix
    }
}

/// Sparse Cholesky factorisation of the symmetric matrix given by its lower triangle.
fn factor(name: &'static str, matrix: &SparseColMat<u32, f64>) -> Result<Llt<u32, f64>, HeatError> {
    matrix
        .sp_cholesky(faer::Side::Lower)
        .map_err(|e| HeatError::Factorisation(name, e.to_string(), false))
}

/// Factors two matrices with the same pattern of non-zeros, analysing the pattern once
/// and computing both factors at the same time.
fn factor_alike(
    names: [&'static str; 2],
    matrices: [&SparseColMat<u32, f64>; 2],
) -> Result<[Llt<u32, f64>; 2], HeatError> {
    let symbolic = SymbolicLlt::try_new(matrices[0].symbolic(), faer::Side::Lower)
        .map_err(|e| HeatError::Factorisation(names[0], format!("{e:?}"), false))?;
    let numeric = |i: usize| {
        Llt::try_new_with_symbolic(symbolic.clone(), matrices[i].as_ref(), faer::Side::Lower)
            .map_err(|e| HeatError::Factorisation(names[i], e.to_string(), false))
    };
    let (first, second) = rayon::join(|| numeric(0), || numeric(1));
    Ok([first?, second?])
}

/// The system `matrix` (lower triangle) restricted to the vertices marked `keep`,
/// factored.
fn restricted(matrix: &SparseColMat<u32, f64>, keep: &[bool]) -> Result<Restricted, HeatError> {
    let mut index = vec![u32::MAX; keep.len()];
    let mut rows = Vec::new();
    for (v, _) in keep.iter().enumerate().filter(|(_, k)| **k) {
        index[v] = rows.len() as u32;
        rows.push(v as u32);
    }
    let (pattern, values) = (matrix.symbolic(), matrix.val());
    let mut kept = Vec::new();
    for col in (0..keep.len()).filter(|&c| keep[c]) {
        let range = pattern.col_ptr()[col] as usize..pattern.col_ptr()[col + 1] as usize;
        for at in range {
            let row = pattern.row_idx()[at] as usize;
            if keep[row] {
                kept.push(Triplet::new(index[row], index[col], values[at]));
            }
        }
    }
    let matrix = SparseColMat::try_new_from_triplets(rows.len(), rows.len(), &kept)
        .map_err(|e| HeatError::Factorisation("boundary heat", format!("{e:?}"), false))?;
    let llt = factor("boundary heat", &matrix)?;
    Ok(Restricted { llt, rows })
}

/// Solves in place with a factored matrix.
fn solve(llt: &Llt<u32, f64>, values: &mut [f64]) {
    if values.is_empty() {
        return;
    }
    let n = values.len();
    llt.solve_in_place(faer::MatMut::from_column_major_slice_mut(values, n, 1));
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Mesh;

    #[test]
    fn a_regular_tetrahedron_gives_its_three_neighbours_one_distance() {
        let mut mesh = Mesh::default();
        for p in [
            [1.0, 1.0, 1.0],
            [-1.0, -1.0, 1.0],
            [-1.0, 1.0, -1.0],
            [1.0, -1.0, -1.0],
        ] {
            mesh.push_vertex(p, [0.0, 1.0, 0.0], [0.0, 0.0]);
        }
        mesh.indices = vec![0, 1, 3, 0, 2, 1, 0, 3, 2, 1, 2, 3];
        let solver =
            HeatSolver::new(Triangulation::from_mesh(&mesh), HeatOptions::default()).unwrap();
        let d = solver.distances(&[0]);
        assert!(
            (d[1] - d[2]).abs() < 1e-9 && (d[2] - d[3]).abs() < 1e-9,
            "{d:?}"
        );
    }

    #[test]
    fn a_failed_factorisation_suggests_the_robust_option_only_when_it_was_off() {
        let plain = HeatError::Factorisation("heat", "NonPositivePivot".into(), false);
        let robust = HeatError::Factorisation("heat", "NonPositivePivot".into(), true);
        assert!(
            plain
                .to_string()
                .contains("the robust option handles poor triangles")
        );
        assert!(!robust.to_string().contains("the robust option handles"));
        assert!(robust.to_string().contains("could not repair"));
    }

    #[test]
    fn time_factors_outside_the_trusted_range_are_refused_before_any_work() {
        for factor in [0.0, -1.0, 1e-4, 2e6, f64::NAN, f64::INFINITY] {
            let options = HeatOptions {
                time_factor: factor,
                ..HeatOptions::default()
            };
            let mesh = crate::mesh::primitive("torus:8").expect("a primitive");
            let result = HeatSolver::new(Triangulation::from_mesh(&mesh), options);
            assert!(matches!(result, Err(HeatError::TimeFactor(_))), "{factor}");
        }
    }
}
