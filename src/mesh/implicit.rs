//! Surfaces of implicit functions (where `f(p) = 0`, inside where negative) turned
//! into welded triangle meshes by marching tetrahedra: each grid cube is cut into six
//! tetrahedra along its main diagonal (so neighbouring cubes agree on their shared
//! faces) and each tetrahedron crossed by the surface gives one or two triangles. The
//! vertices on each grid edge are shared, so the result is closed and manifold. The
//! triangles are uneven (slivers included), which is what the geodesic tests want.

use super::Mesh;
use glam::Vec3;
use std::collections::HashMap;

/// The six tetrahedra of a cube around its diagonal from corner 0 to corner 7; corner
/// `c` sits at offset `(c & 1, c >> 1 & 1, c >> 2 & 1)`.
const TETRAHEDRA: [[usize; 4]; 6] = [
    [0, 1, 3, 7],
    [0, 3, 2, 7],
    [0, 2, 6, 7],
    [0, 6, 4, 7],
    [0, 4, 5, 7],
    [0, 5, 1, 7],
];

/// The surface `f = 0` inside the box `[min, max]`, sampled every `step`.
pub fn polygonize(f: impl Fn(Vec3) -> f32, min: Vec3, max: Vec3, step: f32) -> Mesh {
    let counts = ((max - min) / step).ceil().as_uvec3() + 1;
    let index = |i: u32, j: u32, k: u32| (i + counts.x * (j + counts.y * k)) as usize;
    let point = |i: u32, j: u32, k: u32| min + Vec3::new(i as f32, j as f32, k as f32) * step;
    // Values exactly 0 would put several surface vertices on one grid point.
    let values: Vec<f32> = (0..counts.z)
        .flat_map(|k| (0..counts.y).flat_map(move |j| (0..counts.x).map(move |i| (i, j, k))))
        .map(|(i, j, k)| {
            let value = f(point(i, j, k));
            if value.abs() < 1.0e-7 { 1.0e-7 } else { value }
        })
        .collect();
    let mut builder = Builder {
        mesh: Mesh::default(),
        on_edge: HashMap::new(),
    };
    for k in 0..counts.z - 1 {
        for j in 0..counts.y - 1 {
            for i in 0..counts.x - 1 {
                let corners: [(usize, Vec3); 8] = std::array::from_fn(|c| {
                    let (di, dj, dk) = ((c & 1) as u32, (c >> 1 & 1) as u32, (c >> 2 & 1) as u32);
                    (index(i + di, j + dj, k + dk), point(i + di, j + dj, k + dk))
                });
                for tetrahedron in TETRAHEDRA {
                    let samples =
                        tetrahedron.map(|c| (corners[c].0, corners[c].1, values[corners[c].0]));
                    builder.tetrahedron(samples);
                }
            }
        }
    }
    let mut mesh = builder.mesh;
    mesh.normals = mesh
        .positions
        .iter()
        .map(|&p| gradient(&f, Vec3::from(p), step * 0.25).to_array())
        .collect();
    mesh
}

/// The unit normal of the surface at `p`, by central differences.
fn gradient(f: &impl Fn(Vec3) -> f32, p: Vec3, h: f32) -> Vec3 {
    let d = |axis: Vec3| f(p + axis * h) - f(p - axis * h);
    Vec3::new(d(Vec3::X), d(Vec3::Y), d(Vec3::Z)).normalize_or(Vec3::Y)
}

struct Builder {
    mesh: Mesh,
    /// The surface vertex on each crossed grid edge (keyed by its two sample indices).
    on_edge: HashMap<(usize, usize), u32>,
}

impl Builder {
    /// The triangles of one tetrahedron given its corners as (sample index, position,
    /// value).
    fn tetrahedron(&mut self, corners: [(usize, Vec3, f32); 4]) {
        let (inside, outside): (Vec<_>, Vec<_>) = corners.iter().partition(|c| c.2 < 0.0);
        let outward = centroid(&outside) - centroid(&inside);
        match (inside.len(), outside.len()) {
            (1, 3) | (3, 1) => {
                let (lone, others) = if inside.len() == 1 {
                    (inside[0], &outside)
                } else {
                    (outside[0], &inside)
                };
                let v = others
                    .iter()
                    .map(|o| self.crossing(lone, o))
                    .collect::<Vec<_>>();
                self.triangle([v[0], v[1], v[2]], outward);
            }
            (2, 2) => {
                let [a, b] = [inside[0], inside[1]];
                let [c, d] = [outside[0], outside[1]];
                // The crossings go round the quad in the order a–c, a–d, b–d, b–c.
                let quad = [
                    self.crossing(a, c),
                    self.crossing(a, d),
                    self.crossing(b, d),
                    self.crossing(b, c),
                ];
                self.triangle([quad[0], quad[1], quad[2]], outward);
                self.triangle([quad[0], quad[2], quad[3]], outward);
            }
            _ => {}
        }
    }

    /// The surface vertex between two samples of opposite sign.
    fn crossing(&mut self, a: &(usize, Vec3, f32), b: &(usize, Vec3, f32)) -> u32 {
        let key = (a.0.min(b.0), a.0.max(b.0));
        if let Some(&vertex) = self.on_edge.get(&key) {
            return vertex;
        }
        // Kept off the samples, so that no two surface vertices coincide.
        let t = (a.2 / (a.2 - b.2)).clamp(0.01, 0.99);
        let position = a.1.lerp(b.1, t);
        let vertex = self
            .mesh
            .push_vertex(position.to_array(), [0.0, 1.0, 0.0], [0.0, 0.0]);
        self.on_edge.insert(key, vertex);
        vertex
    }

    /// Adds a triangle, wound counter-clockwise seen from the `outward` side.
    fn triangle(&mut self, [a, b, c]: [u32; 3], outward: Vec3) {
        let p = |v: u32| Vec3::from(self.mesh.positions[v as usize]);
        let normal = (p(b) - p(a)).cross(p(c) - p(a));
        let ordered = if normal.dot(outward) >= 0.0 {
            [a, b, c]
        } else {
            [a, c, b]
        };
        self.mesh.indices.extend_from_slice(&ordered);
    }
}

fn centroid(corners: &[&(usize, Vec3, f32)]) -> Vec3 {
    corners.iter().map(|c| c.1).sum::<Vec3>() / corners.len().max(1) as f32
}

/// A genus-2 surface: two tori about the y axis, side by side and smoothly joined in
/// the middle, fitting the unit sphere; `step` is the grid spacing.
pub fn double_torus(step: f32) -> Mesh {
    let (major, minor, offset) = (0.42, 0.16, 0.46);
    let torus = |p: Vec3, x: f32| {
        let ring = glam::Vec2::new(p.x - x, p.z).length() - major;
        glam::Vec2::new(ring, p.y).length() - minor
    };
    let smooth_min = |a: f32, b: f32, k: f32| {
        let h = (0.5 + 0.5 * (b - a) / k).clamp(0.0, 1.0);
        b + (a - b) * h - k * h * (1.0 - h)
    };
    let f = |p: Vec3| smooth_min(torus(p, -offset), torus(p, offset), 0.08);
    let extent = Vec3::new(
        offset + major + minor + 0.05,
        minor + 0.05,
        major + minor + 0.05,
    );
    polygonize(f, -extent, extent, step)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::analyse;

    #[test]
    fn the_double_torus_is_closed_manifold_and_of_genus_two() {
        let mesh = double_torus(0.05);
        let report = analyse(&mesh);
        assert_eq!(
            (
                report.boundary_edges,
                report.non_manifold_edges,
                report.components
            ),
            (0, 0, 1),
            "{report}"
        );
        let edges = mesh.indices.len() / 2;
        let euler = mesh.positions.len() as i64 - edges as i64 + mesh.triangle_count() as i64;
        assert_eq!(euler, -2, "V - E + F = 2 - 2g with g = 2");
        assert!(mesh.signed_volume() > 0.0, "wound outwards");
    }

    #[test]
    fn a_sphere_polygonizes_to_the_right_volume() {
        let mesh = polygonize(
            |p| p.length() - 0.8,
            Vec3::splat(-1.0),
            Vec3::splat(1.0),
            0.05,
        );
        let expected = 4.0 / 3.0 * std::f32::consts::PI * 0.8f32.powi(3);
        assert!((mesh.signed_volume() - expected).abs() < 0.02 * expected);
    }
}
