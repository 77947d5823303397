//! The mesh the solvers see and the two numberings around it: the vertices of the mesh
//! as loaded (split at seams, which the renderer needs) and the vertices of its file
//! (which field sources and `veneer geodesic`'s output count, see
//! [`crate::mesh::FileVertices`]).

use super::welded_for_distances;
use crate::mesh::Mesh;

/// A mesh welded for the solvers, with the welded vertex of every vertex of the mesh
/// and of its file.
pub struct WeldedMesh {
    /// The welded mesh.
    pub mesh: Mesh,
    /// The welded vertex of every vertex of the mesh as loaded.
    pub of_vertex: Vec<u32>,
    /// The welded vertex of every vertex of the file; `None` for those no triangle uses.
    pub of_file_vertex: Vec<Option<u32>>,
}

impl WeldedMesh {
    /// Welds `mesh` ([`welded_for_distances`]) and follows its file's vertices there.
    pub fn new(mesh: &Mesh) -> WeldedMesh {
        let (welded, of_vertex) = welded_for_distances(mesh);
        let of_file_vertex = mesh
            .vertices_of_file()
            .into_iter()
            .map(|vertex| vertex.map(|v| of_vertex[v as usize]))
            .collect();
        WeldedMesh {
            mesh: welded,
            of_vertex,
            of_file_vertex,
        }
    }

    /// Source vertices counted in the file's numbering (in range: see
    /// [`super::check_field_sources`]) as welded vertices. Sources no triangle uses are
    /// left out: they reach nothing but themselves.
    pub fn sources(&self, file_sources: &[u32]) -> Vec<u32> {
        file_sources
            .iter()
            .filter_map(|&s| self.of_file_vertex.get(s as usize).copied().flatten())
            .collect()
    }

    /// A field over the welded vertices, solved from `file_sources`, for every vertex of
    /// the file: infinite where no triangle uses the vertex, 0 at the sources themselves.
    pub fn in_file_order(&self, field: &[f64], file_sources: &[u32]) -> Vec<f64> {
        let mut ordered: Vec<f64> = self
            .of_file_vertex
            .iter()
            .map(|vertex| vertex.map_or(f64::INFINITY, |v| field[v as usize]))
            .collect();
        for &source in file_sources {
            if let Some(distance) = ordered.get_mut(source as usize) {
                *distance = 0.0;
            }
        }
        ordered
    }
}
