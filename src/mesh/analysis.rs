//! Mesh hygiene: welding duplicate vertices and reporting what geodesic solvers care
//! about — degenerate (zero-area) triangles, boundary and non-manifold edges, and
//! connected components.

use super::Mesh;
use std::collections::{BTreeMap, HashMap};

/// What a mesh is made of and what is wrong with it.
#[derive(Clone, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct MeshReport {
    pub vertices: usize,
    pub triangles: usize,
    /// Triangles with (near) zero area or a repeated vertex.
    pub degenerate_triangles: usize,
    /// Edges used by one triangle only (the mesh has holes or is open).
    pub boundary_edges: usize,
    /// Edges shared by more than two triangles.
    pub non_manifold_edges: usize,
    /// Separately connected pieces (vertices no triangle uses are not counted).
    pub components: usize,
}

impl std::fmt::Display for MeshReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} vertices, {} triangles, {} degenerate, {} boundary edges, {} non-manifold edges, {} components",
            self.vertices,
            self.triangles,
            self.degenerate_triangles,
            self.boundary_edges,
            self.non_manifold_edges,
            self.components
        )
    }
}

impl MeshReport {
    /// What a geodesic solver should warn about, one sentence each (empty for a clean,
    /// closed, connected mesh).
    pub fn problems(&self) -> Vec<String> {
        let mut problems = Vec::new();
        if self.degenerate_triangles > 0 {
            problems.push(format!(
                "{} degenerate (zero-area) triangles; paths cannot cross them (the robust heat method mollifies them)",
                self.degenerate_triangles
            ));
        }
        if self.boundary_edges > 0 {
            problems.push(format!(
                "{} boundary edges: the surface is open",
                self.boundary_edges
            ));
        }
        if self.non_manifold_edges > 0 {
            problems.push(format!(
                "{} non-manifold edges, treated as boundaries",
                self.non_manifold_edges
            ));
        }
        if self.components > 1 {
            problems.push(format!(
                "{} separate components: vertices of components without a source stay unreached (inf)",
                self.components
            ));
        }
        problems
    }
}

/// A position in f64, where no difference or cross product of f32 positions overflows
/// or underflows.
fn wide(p: [f32; 3]) -> glam::DVec3 {
    glam::DVec3::from(p.map(f64::from))
}

/// Twice the area of `triangle` (three indices into `positions`), in f64.
pub(super) fn double_area(positions: &[[f32; 3]], triangle: &[u32]) -> f64 {
    let [a, b, c] = [0, 1, 2].map(|k| wide(positions[triangle[k] as usize]));
    (b - a).cross(c - a).length()
}

/// Whether a triangle is degenerate: a repeated index, or an area below `1e-12` of the
/// squared size of the mesh (`scale²`).
fn degenerate(mesh: &Mesh, triangle: &[u32], scale: f64) -> bool {
    let [a, b, c] = [triangle[0], triangle[1], triangle[2]];
    a == b || b == c || a == c || double_area(&mesh.positions, triangle) <= 1.0e-12 * scale * scale
}

/// The largest side of the bounding box.
fn extent(mesh: &Mesh) -> f64 {
    let (min, max) = mesh.positions.iter().fold(
        (glam::DVec3::splat(f64::MAX), glam::DVec3::splat(f64::MIN)),
        |(lo, hi), p| (lo.min(wide(*p)), hi.max(wide(*p))),
    );
    (max - min).max_element().max(0.0)
}

/// Finds the representative of `x`, compressing the path.
fn find(parents: &mut [usize], mut x: usize) -> usize {
    while parents[x] != x {
        parents[x] = parents[parents[x]];
        x = parents[x];
    }
    x
}

/// The connected component of each of `count` vertices through `triangles`, as the
/// index of a representative vertex; vertices in no triangle are their own component.
pub fn vertex_components(
    count: usize,
    triangles: impl IntoIterator<Item = [u32; 3]>,
) -> Vec<usize> {
    let mut parents: Vec<usize> = (0..count).collect();
    for triangle in triangles {
        for k in 1..3 {
            let (a, b) = (
                find(&mut parents, triangle[0] as usize),
                find(&mut parents, triangle[k] as usize),
            );
            parents[a] = b;
        }
    }
    (0..count).map(|v| find(&mut parents, v)).collect()
}

/// Reports the structure and defects of `mesh`.
pub fn analyse(mesh: &Mesh) -> MeshReport {
    let scale = extent(mesh);
    let mut edges: BTreeMap<(u32, u32), u32> = BTreeMap::new();
    let mut used = vec![false; mesh.positions.len()];
    let mut degenerate_triangles = 0;
    for triangle in mesh.indices.chunks_exact(3) {
        if degenerate(mesh, triangle, scale) {
            degenerate_triangles += 1;
        }
        for k in 0..3 {
            let (a, b) = (triangle[k], triangle[(k + 1) % 3]);
            if a != b {
                *edges.entry((a.min(b), a.max(b))).or_default() += 1;
            }
            used[a as usize] = true;
        }
    }
    let triangles = mesh.indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]);
    let roots = vertex_components(mesh.positions.len(), triangles);
    let components = (0..roots.len())
        .filter(|&v| used[v] && roots[v] == v)
        .count();
    MeshReport {
        vertices: mesh.positions.len(),
        triangles: mesh.triangle_count(),
        degenerate_triangles,
        boundary_edges: edges.values().filter(|&&n| n == 1).count(),
        non_manifold_edges: edges.values().filter(|&&n| n > 2).count(),
        components,
    }
}

/// Merges vertices closer than `tolerance` (per axis, on a grid), so that triangles split
/// at seams share their vertices again, and drops the triangles that collapse. Returns the
/// welded mesh (normals recomputed) and, for every original vertex, its welded index.
pub fn weld(mesh: &Mesh, tolerance: f32) -> (Mesh, Vec<u32>) {
    let cell = tolerance.max(f32::MIN_POSITIVE);
    let mut index: HashMap<[i64; 3], u32> = HashMap::new();
    let mut welded = Mesh::default();
    let mut remap = Vec::with_capacity(mesh.positions.len());
    for (k, position) in mesh.positions.iter().enumerate() {
        let key = position.map(|c| (f64::from(c) / f64::from(cell)).round() as i64);
        let next = welded.positions.len() as u32;
        let target = *index.entry(key).or_insert_with(|| {
            welded.positions.push(*position);
            welded
                .uvs
                .push(mesh.uvs.get(k).copied().unwrap_or([0.0; 2]));
            next
        });
        remap.push(target);
    }
    // Triangles whose corners merged have no area left: drop them.
    welded.indices = mesh
        .indices
        .chunks_exact(3)
        .map(|t| [0, 1, 2].map(|k| remap[t[k] as usize]))
        .filter(|[a, b, c]| a != b && b != c && a != c)
        .flatten()
        .collect();
    welded.normals = super::vertex_normals(&welded.positions, &welded.indices);
    (welded, remap)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::primitive;

    #[test]
    fn welding_the_cube_joins_its_faces_into_one_closed_piece() {
        let cube = primitive("cube").unwrap();
        let before = analyse(&cube);
        assert_eq!(before.components, 6, "each face is its own grid");
        assert!(before.boundary_edges > 0);
        let (welded, remap) = weld(&cube, 1.0e-5);
        assert_eq!(remap.len(), cube.positions.len());
        let after = analyse(&welded);
        assert_eq!(
            (
                after.components,
                after.boundary_edges,
                after.non_manifold_edges
            ),
            (1, 0, 0),
            "{after}"
        );
        assert_eq!(
            after.vertices,
            6 * 81 - 12 * 9 + 8,
            "shared edge rows and corners merge"
        );
        assert!((welded.signed_volume() - cube.signed_volume()).abs() < 1e-5);
    }

    #[test]
    fn the_sphere_welds_its_seam_and_poles_and_the_plane_is_open() {
        let (sphere, _) = weld(&primitive("sphere").unwrap(), 1.0e-5);
        let report = analyse(&sphere);
        assert_eq!(
            (
                report.components,
                report.boundary_edges,
                report.non_manifold_edges
            ),
            (1, 0, 0),
            "{report}"
        );
        assert_eq!(
            report.degenerate_triangles, 0,
            "the triangles collapsed at the poles are dropped"
        );
        assert_eq!(report.triangles, 96 * 48 * 2 - 2 * 96);
        let plane = analyse(&primitive("plane").unwrap());
        assert_eq!(plane.boundary_edges, 4 * 16);
    }

    #[test]
    fn non_manifold_edges_degenerate_triangles_and_components_are_counted() {
        let mut mesh = Mesh::default();
        for p in [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, 1.0],
            [5.0, 5.0, 5.0],
            [6.0, 5.0, 5.0],
            [7.0, 5.0, 5.0],
        ] {
            mesh.push_vertex(p, [0.0, 1.0, 0.0], [0.0, 0.0]);
        }
        // Three triangles on the edge 0-1 (non-manifold), and a collinear sliver apart.
        mesh.indices = vec![0, 1, 2, 1, 0, 3, 0, 1, 4, 5, 6, 7];
        let report = analyse(&mesh);
        assert_eq!(report.non_manifold_edges, 1, "{report}");
        assert_eq!(report.degenerate_triangles, 1, "{report}");
        assert_eq!(report.components, 2, "{report}");
    }
}
