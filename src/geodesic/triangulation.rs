//! The surface as geodesic solvers see it: triangles, the length of each of their edges
//! and which triangle lies across each edge. Everything else (angles, areas, a flat
//! layout of each triangle) follows from the lengths, so the same code serves the mesh
//! as given and its intrinsic Delaunay retriangulation.

use crate::mesh::Mesh;
use glam::DVec2;
use std::collections::HashMap;

/// Marks a half-edge with no triangle across it (a boundary or non-manifold edge).
pub const NO_TWIN: u32 = u32::MAX;

/// Triangles with edge lengths and adjacency. Half-edge `3·f + k` runs from corner `k`
/// of triangle `f` to corner `k + 1`; its length is `lengths[f][k]`.
#[derive(Clone, Debug)]
pub struct Triangulation {
    /// Vertex count (vertices no triangle uses are allowed; they are never reached).
    pub vertex_count: usize,
    /// Three vertex indices per triangle, counter-clockwise.
    pub faces: Vec<[u32; 3]>,
    /// `lengths[f][k]` is the length of the edge from corner `k` to corner `k + 1`.
    pub lengths: Vec<[f64; 3]>,
    /// The opposite half-edge across each half-edge, or [`NO_TWIN`].
    pub twins: Vec<u32>,
}

/// The triangle of half-edge `h` and its corner.
pub fn split(h: u32) -> (usize, usize) {
    ((h / 3) as usize, (h % 3) as usize)
}

/// The half-edge of triangle `f` starting at corner `k`.
pub fn half_edge(f: usize, k: usize) -> u32 {
    (3 * f + k % 3) as u32
}

/// The area of a triangle from its side lengths (Kahan's stable Heron
/// formula); 0 when the lengths violate the triangle inequality.
pub fn area_from_lengths(a: f64, b: f64, c: f64) -> f64 {
    let mut sides = [a, b, c];
    sides.sort_by(|x, y| y.total_cmp(x));
    let [a, b, c] = sides;
    let product = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
    if product > 0.0 {
        0.25 * product.sqrt()
    } else {
        0.0
    }
}

impl Triangulation {
    /// The triangles of `mesh` (best welded first) with their 3D edge lengths in f64.
    /// Triangles with a repeated vertex are left out; an edge is paired with the one
    /// triangle across it only when exactly two consistently oriented triangles share it.
    pub fn from_mesh(mesh: &Mesh) -> Triangulation {
        let position = |i: u32| glam::DVec3::from(mesh.positions[i as usize].map(f64::from));
        let faces: Vec<[u32; 3]> = mesh
            .indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .filter(|[a, b, c]| a != b && b != c && a != c)
            .collect();
        let lengths = faces
            .iter()
            .map(|face| [0, 1, 2].map(|k| position(face[k]).distance(position(face[(k + 1) % 3]))))
            .collect();
        let twins = pair_half_edges(&faces);
        Triangulation {
            vertex_count: mesh.positions.len(),
            faces,
            lengths,
            twins,
        }
    }

    /// The vertex a half-edge starts from.
    pub fn tail(&self, h: u32) -> u32 {
        let (f, k) = split(h);
        self.faces[f][k]
    }

    /// The vertex a half-edge points to.
    pub fn head(&self, h: u32) -> u32 {
        let (f, k) = split(h);
        self.faces[f][(k + 1) % 3]
    }

    /// The length of half-edge `h`.
    pub fn length(&self, h: u32) -> f64 {
        let (f, k) = split(h);
        self.lengths[f][k]
    }

    /// The area of triangle `f`.
    pub fn area(&self, f: usize) -> f64 {
        let [a, b, c] = self.lengths[f];
        area_from_lengths(a, b, c)
    }

    /// The cotangent of the angle at corner `(k + 2) % 3` of triangle `f`, the corner
    /// across from edge `k`; `None` for a triangle with no area.
    pub fn cotan_across(&self, f: usize, k: usize) -> Option<f64> {
        let area = self.area(f);
        let l = self.lengths[f];
        let (opposite, a, b) = (l[k], l[(k + 1) % 3], l[(k + 2) % 3]);
        (area > 0.0).then(|| (a * a + b * b - opposite * opposite) / (4.0 * area))
    }

    /// Triangle `f` laid flat: corner 0 at the origin, corner 1 on the positive x axis,
    /// corner 2 above it.
    pub fn layout(&self, f: usize) -> [DVec2; 3] {
        [
            DVec2::ZERO,
            DVec2::new(self.lengths[f][0], 0.0),
            self.apex(f, 0),
        ]
    }

    /// The corner of triangle `f` across from its edge `k`, in that edge's frame: the
    /// edge from the origin along the positive x axis, the triangle above.
    pub fn apex(&self, f: usize, k: usize) -> DVec2 {
        let l = self.lengths[f];
        let (length, l_bc, l_ca) = (l[k], l[(k + 1) % 3], l[(k + 2) % 3]);
        let x = (length * length + l_ca * l_ca - l_bc * l_bc) / (2.0 * length);
        DVec2::new(x, (l_ca * l_ca - x * x).max(0.0).sqrt())
    }

    /// The mean length over all half-edges (0 for no triangles).
    pub fn mean_edge_length(&self) -> f64 {
        let total: f64 = self.lengths.iter().flatten().sum();
        if self.faces.is_empty() {
            0.0
        } else {
            total / (3 * self.faces.len()) as f64
        }
    }

    /// How many vertices some triangle uses.
    pub fn used_vertex_count(&self) -> usize {
        let mut used = vec![false; self.vertex_count];
        for &v in self.faces.iter().flatten() {
            used[v as usize] = true;
        }
        used.iter().filter(|&&u| u).count()
    }

    /// Whether each vertex lies on a boundary (or non-manifold) edge.
    pub fn boundary_vertices(&self) -> Vec<bool> {
        let mut boundary = vec![false; self.vertex_count];
        for (h, &twin) in self.twins.iter().enumerate() {
            if twin == NO_TWIN {
                boundary[self.tail(h as u32) as usize] = true;
                boundary[self.head(h as u32) as usize] = true;
            }
        }
        boundary
    }

    /// The connected component of each vertex (through shared triangles), as a
    /// representative vertex; vertices in no triangle get a component of their own.
    pub fn components(&self) -> Vec<usize> {
        crate::mesh::vertex_components(self.vertex_count, self.faces.iter().copied())
    }

    /// The sum of the corner angles at each vertex (2π on a flat interior vertex, more
    /// at a saddle).
    pub fn angle_sums(&self) -> Vec<f64> {
        let mut sums = vec![0.0; self.vertex_count];
        for (f, face) in self.faces.iter().enumerate() {
            for k in 0..3 {
                sums[face[k] as usize] += self.corner_angle(f, k);
            }
        }
        sums
    }

    /// The angle of triangle `f` at its vertex `k`, between edges `k` and `k + 2` (across
    /// from edge `k + 1`); 0 where the lengths give none.
    pub fn corner_angle(&self, f: usize, k: usize) -> f64 {
        let l = self.lengths[f];
        let (a, b, opposite) = (l[k], l[(k + 2) % 3], l[(k + 1) % 3]);
        let cos = ((a * a + b * b - opposite * opposite) / (2.0 * a * b)).clamp(-1.0, 1.0);
        if cos.is_finite() { cos.acos() } else { 0.0 }
    }
}

/// Pairs each half-edge with the reverse half-edge of the one other triangle on its edge;
/// edges on one triangle, on three or more, or shared by two triangles running the same
/// way stay unpaired.
fn pair_half_edges(faces: &[[u32; 3]]) -> Vec<u32> {
    let mut by_edge: HashMap<(u32, u32), Vec<u32>> = HashMap::with_capacity(faces.len() * 3);
    for (f, face) in faces.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (face[k], face[(k + 1) % 3]);
            by_edge
                .entry((a.min(b), a.max(b)))
                .or_default()
                .push(half_edge(f, k));
        }
    }
    let mut twins = vec![NO_TWIN; faces.len() * 3];
    let tail = |h: u32| {
        let (f, k) = split(h);
        faces[f][k]
    };
    for sharing in by_edge.values() {
        if let [first, second] = sharing[..]
            && tail(first) != tail(second)
        {
            twins[first as usize] = second;
            twins[second as usize] = first;
        }
    }
    twins
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// The unit square in the xz plane as two triangles sharing a diagonal.
    pub(in crate::geodesic) fn square() -> Triangulation {
        let mut mesh = Mesh::default();
        mesh.push_grid(1, 1, |u, v| ([u, 0.0, v], [0.0, 1.0, 0.0]));
        Triangulation::from_mesh(&mesh)
    }

    #[test]
    fn lengths_areas_and_pairing_of_a_split_square() {
        let square = square();
        assert_eq!(square.faces.len(), 2);
        let total: f64 = (0..2).map(|f| square.area(f)).sum();
        assert!((total - 1.0).abs() < 1e-12);
        assert_eq!(square.twins.iter().filter(|&&t| t != NO_TWIN).count(), 2);
        assert!(square.boundary_vertices().iter().all(|&b| b));
        let [p0, p1, p2] = square.layout(0);
        assert!((p1 - p0).length() - square.lengths[0][0] < 1e-12);
        assert!(((p2 - p1).length() - square.lengths[0][1]).abs() < 1e-12);
        assert!(((p0 - p2).length() - square.lengths[0][2]).abs() < 1e-12);
    }

    #[test]
    fn heron_is_zero_for_flat_or_impossible_triangles() {
        assert_eq!(area_from_lengths(1.0, 2.0, 3.0), 0.0);
        assert_eq!(area_from_lengths(1.0, 1.0, 3.0), 0.0);
        assert!((area_from_lengths(3.0, 4.0, 5.0) - 6.0).abs() < 1e-12);
        assert!(area_from_lengths(1.0, 1.0, 1.0e-9) > 0.0);
    }
}
