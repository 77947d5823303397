//! What the ray-cast mesh fields share: the mesh moved into a unit frame (centred, its
//! bounding sphere of radius 1, so huge or tiny coordinates cast rays as well as unit
//! ones), a hierarchy over its triangles, and a loop over the vertices on every core
//! that reports progress.

use crate::mesh::{Bvh, Mesh};
use glam::{DVec3, Vec3A};
use rayon::prelude::*;

/// How far a ray's origin is lifted off the surface, as a share of the mean length of
/// the edges at its vertex: enough that the triangles around the vertex, tilted a
/// little by a scan's noise or a coarse polygonisation, do not occlude it (the bias
/// other bakers leave to the user), small enough that a real crease still does.
const LIFT: f32 = 0.05;

/// The least lift, in units of the bounding radius (a vertex in no triangle).
const LEAST_LIFT: f32 = 1.0e-5;

/// Points per step of the loops (progress is reported between steps).
const STEP: usize = 4096;

/// A mesh ready for rays.
pub struct Scene {
    bvh: Bvh,
    positions: Vec<Vec3A>,
    normals: Vec<Vec3A>,
    /// How far rays from each vertex start off the surface.
    lifts: Vec<f32>,
    /// Three vertex indices per triangle, as in the mesh.
    indices: Vec<u32>,
    frame: Frame,
}

/// A unit frame: mesh points minus `centre`, times `scale`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    pub centre: DVec3,
    pub scale: f64,
}

/// A vertex as a ray-cast field sees it.
#[derive(Clone, Copy, Debug)]
pub struct Vertex {
    /// Its index in the mesh.
    pub index: u32,
    /// Its position in the unit frame.
    pub position: Vec3A,
    /// Its unit normal (the mesh's own, so hard edges keep their faces' normals).
    pub normal: Vec3A,
    /// How far its rays start off the surface.
    pub lift: f32,
}

impl Vertex {
    /// Where a ray leaving the surface on the `side` of the normal (+1 out, −1 in)
    /// starts.
    pub fn origin(&self, side: f32) -> [f32; 3] {
        (self.position + self.normal * (side * self.lift)).into()
    }
}

/// `point` moved by `-centre` and scaled by `scale`, computed in f64.
fn unit_point(point: [f32; 3], centre: DVec3, scale: f64) -> glam::Vec3 {
    ((DVec3::from(point.map(f64::from)) - centre) * scale).as_vec3()
}

/// The lift of every vertex: [`LIFT`] times the mean length of its edges.
fn lifts(positions: &[[f32; 3]], indices: &[u32]) -> Vec<f32> {
    let mut sums = vec![(0.0f32, 0u32); positions.len()];
    for triangle in indices.chunks_exact(3) {
        for k in 0..3 {
            let (a, b) = (triangle[k] as usize, triangle[(k + 1) % 3] as usize);
            let length = Vec3A::from(positions[a]).distance(Vec3A::from(positions[b]));
            if length.is_finite() {
                for end in [a, b] {
                    sums[end].0 += length;
                    sums[end].1 += 1;
                }
            }
        }
    }
    sums.into_iter()
        .map(|(total, count)| (LIFT * total / count.max(1) as f32).max(LEAST_LIFT))
        .collect()
}

impl Scene {
    /// `mesh` in its unit frame, with its hierarchy built.
    pub fn new(mesh: &Mesh) -> Scene {
        let (centre, radius) = mesh.bounding_sphere();
        let scale = if radius > 0.0 { 1.0 / radius } else { 1.0 };
        Scene::in_frame(mesh, Frame { centre, scale })
    }

    /// `mesh` in the unit frame of another scene (so that two meshes meet as they do in
    /// their files), with its hierarchy built.
    pub fn in_frame(mesh: &Mesh, frame: Frame) -> Scene {
        let Frame { centre, scale } = frame;
        let unit: Vec<[f32; 3]> = mesh
            .positions
            .iter()
            .map(|&p| unit_point(p, centre, scale).to_array())
            .collect();
        let bvh = Bvh::new(&unit, &mesh.indices);
        let normals = (0..unit.len())
            .map(|v| {
                let normal = mesh.normals.get(v).copied().unwrap_or([0.0, 1.0, 0.0]);
                Vec3A::from(normal).normalize_or(Vec3A::Y)
            })
            .collect();
        Scene {
            bvh,
            lifts: lifts(&unit, &mesh.indices),
            positions: unit.into_iter().map(Vec3A::from).collect(),
            normals,
            indices: mesh.indices.clone(),
            frame,
        }
    }

    /// The hierarchy, in the unit frame.
    pub fn bvh(&self) -> &Bvh {
        &self.bvh
    }

    /// The scene's unit frame.
    pub fn frame(&self) -> Frame {
        self.frame
    }

    /// The unit normal at `hit`, interpolated between its triangle's vertices.
    pub fn normal_at(&self, hit: &crate::mesh::Hit) -> Vec3A {
        let corners = &self.indices[3 * hit.triangle as usize..][..3];
        let [b, c] = hit.barycentric;
        let normal = self.normals[corners[0] as usize] * (1.0 - b - c)
            + self.normals[corners[1] as usize] * b
            + self.normals[corners[2] as usize] * c;
        normal.normalize_or(self.normals[corners[0] as usize])
    }

    /// `mesh`'s point `position` (mesh units) in the unit frame.
    pub fn to_unit(&self, position: [f32; 3]) -> Vec3A {
        unit_point(position, self.frame.centre, self.frame.scale).into()
    }

    /// The point at `weights` (barycentric, summing to 1) in the triangle of `corners`,
    /// as a ray-cast field sees it: position, normal and lift interpolated; `index`
    /// seeds its ray directions.
    pub fn inside(&self, corners: [u32; 3], weights: [f32; 3], index: u32) -> Vertex {
        let mix = |values: &[Vec3A]| {
            (corners.iter().zip(weights))
                .fold(Vec3A::ZERO, |sum, (&v, w)| sum + values[v as usize] * w)
        };
        let lift = (corners.iter().zip(weights)).map(|(&v, w)| self.lifts[v as usize] * w);
        let normal = mix(&self.normals);
        Vertex {
            index,
            position: mix(&self.positions),
            normal: normal.normalize_or(self.normals[corners[0] as usize]),
            lift: lift.sum::<f32>().max(LEAST_LIFT),
        }
    }

    /// `measure` of every vertex, worked out on every core, in vertex order; progress
    /// as `(vertices done, vertices)`.
    pub fn per_vertex<T: Send>(
        &self,
        measure: impl Fn(Vertex) -> T + Sync,
        progress: impl FnMut(usize, usize),
    ) -> Vec<T> {
        let vertex = |v: usize| Vertex {
            index: v as u32,
            position: self.positions[v],
            normal: self.normals[v],
            lift: self.lifts[v],
        };
        in_steps(self.positions.len(), |v| measure(vertex(v)), progress)
    }
}

/// `measure` of `0..count`, worked out on every core, in order, a step at a time;
/// progress as `(done, count)` after each step.
pub fn in_steps<T: Send>(
    count: usize,
    measure: impl Fn(usize) -> T + Sync,
    mut progress: impl FnMut(usize, usize),
) -> Vec<T> {
    let mut values = Vec::with_capacity(count);
    for start in (0..count).step_by(STEP) {
        let end = (start + STEP).min(count);
        values.par_extend((start..end).into_par_iter().map(&measure));
        progress(end, count);
    }
    values
}
