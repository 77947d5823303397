//! The vertex numbering of a mesh file. Loaders may split a file's vertices (an OBJ
//! vertex with two texture coordinates becomes two mesh vertices) or reorder them, but
//! distance fields, their sources and picking count vertices as the file lists them.
//!
//! Per format, the file's vertices are: OBJ — its `v` lines; PLY — the `vertex`
//! elements; glTF/GLB — the entries of the POSITION accessors of the scene's triangle
//! primitives, one primitive after another, nodes depth first in the order the scene
//! and each node list them (a mesh that several nodes use counts once per node; for a
//! single primitive, simply its accessor's order); STL, which repeats every corner in
//! each facet — each distinct position (bit for bit) in the order it first appears,
//! facet by facet; a primitive — its own vertices. Vertices no triangle uses count too
//! (they are never reached).

use super::Mesh;

/// Where the vertices of a mesh came from in its file, for loaders that split or
/// reorder them (OBJ).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FileVertices {
    /// The file vertex each mesh vertex was read from.
    pub of_vertex: Vec<u32>,
    /// How many vertices the file lists, including those no triangle uses.
    pub count: usize,
}

impl Mesh {
    /// How many vertices the mesh's file lists (the mesh's own count when its vertices
    /// are the file's).
    pub fn file_vertex_count(&self) -> usize {
        self.file_vertices
            .as_ref()
            .map_or(self.positions.len(), |file| file.count)
    }

    /// The file vertex that mesh vertex `vertex` was read from.
    pub fn file_vertex(&self, vertex: u32) -> u32 {
        self.file_vertices
            .as_ref()
            .map_or(vertex, |file| file.of_vertex[vertex as usize])
    }

    /// For every vertex of the file, a mesh vertex read from it (the first) when a
    /// triangle uses it, else `None`.
    pub fn vertices_of_file(&self) -> Vec<Option<u32>> {
        let mut sites = vec![None; self.file_vertex_count()];
        for &vertex in &self.indices {
            let site = &mut sites[self.file_vertex(vertex) as usize];
            *site = Some(site.map_or(vertex, |first: u32| first.min(vertex)));
        }
        sites
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn split_vertices_lead_back_to_their_file_vertex_and_unused_ones_to_none() {
        let mut mesh = Mesh::from_triangles(vec![[0.0; 3]; 4], vec![0, 1, 2, 2, 1, 3]);
        assert_eq!(mesh.file_vertex_count(), 4);
        assert_eq!(
            mesh.vertices_of_file(),
            [Some(0), Some(1), Some(2), Some(3)]
        );
        // Mesh vertices 0 and 3 both came from file vertex 2; file vertex 1 is unused.
        mesh.file_vertices = Some(FileVertices {
            of_vertex: vec![2, 0, 3, 2],
            count: 4,
        });
        assert_eq!(mesh.file_vertex(3), 2);
        assert_eq!(mesh.vertices_of_file(), [Some(1), None, Some(0), Some(2)]);
    }
}
