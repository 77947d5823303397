//! The heat method on dirty meshes: when the plain method's matrices cannot be factored
//! (near-degenerate triangles on scans round its cotangent Laplacian into an indefinite
//! matrix), the robust variant — mollified lengths, intrinsic Delaunay triangulation,
//! whose Laplacian has no negative weights — takes over, and the result says so.

use super::heat::{HeatError, HeatSolver};
use super::triangulation::Triangulation;
use crate::graph::HeatOptions;
use crate::mesh::Mesh;

/// The robust heat method standing in for the plain one, which could not be set up.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error(
    "the plain heat method could not factor the {matrix} matrix ({reason}); used the robust heat method instead"
)]
pub struct Fallback {
    /// The matrix that could not be factored.
    pub matrix: &'static str,
    /// The factorisation's reason.
    pub reason: String,
}

/// A heat solver for `mesh` with `options`; when the plain method cannot factor its
/// matrices, the robust one, and why it was needed. Fails only when the robust method
/// fails too (or the options are invalid).
pub fn heat_solver(
    mesh: &Mesh,
    options: HeatOptions,
) -> Result<(HeatSolver, Option<Fallback>), HeatError> {
    match HeatSolver::new(Triangulation::from_mesh(mesh), options) {
        Err(HeatError::Factorisation(matrix, reason, _)) if !options.robust => {
            let robust = HeatOptions {
                robust: true,
                ..options
            };
            let solver = HeatSolver::new(Triangulation::from_mesh(mesh), robust)?;
            Ok((solver, Some(Fallback { matrix, reason })))
        }
        solved => solved.map(|solver| (solver, None)),
    }
}
