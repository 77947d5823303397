//! Mesh fields per texel of a UV layout, for bakes. Each texel whose centre a triangle
//! covers in the layout is a point of the surface (the centre's barycentric place in
//! that triangle): occlusion and thickness cast their rays from it as from a vertex,
//! with its interpolated normal and lift; the other fields are interpolated from the
//! vertices. A texel casts few rays, turned differently from its neighbours'; pooling
//! ([`Texels::pooled`]) averages each texel with the neighbours that lie on the same
//! surface (close in space, facing the same way), so a 5×5 neighbourhood of 16-ray
//! texels answers like some 400 rays while a crease or a chart's edge stays sharp.

use super::occlusion::{Sampling, occlusion_at};
use super::scene::{Scene, Vertex, in_steps};
use super::thickness::thickness_at;
use crate::mesh::Mesh;
use glam::{Vec2, Vec3A};

/// How far a covered texel's centre may lie outside its triangle, in barycentric
/// units, so texels on an edge shared by two triangles are never missed.
const EDGE_SLACK: f32 = 1.0e-5;

/// Neighbours pooled with a texel face within this cosine of its normal.
const SAME_FACING: f32 = 0.9;

/// Neighbours pooled with a texel lie within this many texel spacings of it per texel
/// of offset in the layout (a chart's neighbour in the layout, far on the surface, is not).
const SAME_SURFACE: f32 = 1.5;

/// The texels of a `size`² map a mesh's UV layout covers, as points of the surface.
pub struct Texels {
    /// The map's width and height in texels.
    pub size: u32,
    /// The covered texels' indices in the map (row by row from the top, v down), ascending.
    pub texels: Vec<u32>,
    /// Each covered texel's triangle and its centre's barycentric weights there.
    places: Vec<(u32, [f32; 3])>,
    /// Each covered texel as a point of the scene (unit frame).
    points: Vec<Vertex>,
    /// The distance on the surface between neighbouring texels, per covered texel
    /// (unit frame).
    spacing: Vec<f32>,
    /// Each texel's position in `texels`, `u32::MAX` where none covers it.
    slots: Vec<u32>,
}

/// The barycentric weights of `point` in the triangle `corners`, `None` when the
/// triangle has no area.
fn barycentric(corners: [Vec2; 3], point: Vec2) -> Option<[f32; 3]> {
    let [a, b, c] = corners;
    let area = (b - a).perp_dot(c - a);
    if area.abs() <= f32::EPSILON * (b - a).length() * (c - a).length() || !area.is_finite() {
        return None;
    }
    let wb = (point - a).perp_dot(c - a) / area;
    let wc = (b - a).perp_dot(point - a) / area;
    Some([1.0 - wb - wc, wb, wc])
}

impl Texels {
    /// The texels of a `size`² map that `mesh`'s triangles cover in its UV layout (where
    /// triangles overlap, the first in the mesh's order keeps the texel), as points of
    /// `scene` (built from `mesh`).
    pub fn new(mesh: &Mesh, scene: &Scene, size: u32) -> Texels {
        let n = size as usize;
        let scale = size as f32;
        let mut owner = vec![(u32::MAX, [0.0f32; 3]); n * n];
        let mut spacing_of = Vec::with_capacity(mesh.indices.len() / 3);
        for (triangle, corners) in mesh.indices.chunks_exact(3).enumerate() {
            let corners = [corners[0], corners[1], corners[2]];
            let uv = corners.map(|v| Vec2::from(mesh.uvs[v as usize]) * scale);
            let unit = corners.map(|v| scene.to_unit(mesh.positions[v as usize]));
            let layout_area = (uv[1] - uv[0]).perp_dot(uv[2] - uv[0]).abs();
            let surface_area = (unit[1] - unit[0]).cross(unit[2] - unit[0]).length();
            spacing_of.push((surface_area / layout_area.max(f32::MIN_POSITIVE)).sqrt());
            let low = uv.iter().fold(Vec2::INFINITY, |m, p| m.min(*p));
            let high = uv.iter().fold(Vec2::NEG_INFINITY, |m, p| m.max(*p));
            if !(low.is_finite() && high.is_finite()) {
                continue;
            }
            // The texels whose centres (x + ½, y + ½) lie within the triangle's bounds.
            let first = (low - 0.5).ceil().max(Vec2::ZERO).as_i64vec2();
            let last = (high - 0.5)
                .floor()
                .min(Vec2::splat(scale - 1.0))
                .as_i64vec2();
            for y in first.y..=last.y {
                for x in first.x..=last.x {
                    let texel = y as usize * n + x as usize;
                    if owner[texel].0 != u32::MAX {
                        continue;
                    }
                    let centre = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
                    if let Some(weights) = barycentric(uv, centre)
                        && weights.iter().all(|&w| w >= -EDGE_SLACK)
                    {
                        owner[texel] = (triangle as u32, weights.map(|w| w.max(0.0)));
                    }
                }
            }
        }
        let mut slots = vec![u32::MAX; n * n];
        let (mut texels, mut places) = (Vec::new(), Vec::new());
        for (texel, &(triangle, weights)) in owner.iter().enumerate() {
            if triangle != u32::MAX {
                slots[texel] = texels.len() as u32;
                texels.push(texel as u32);
                let total: f32 = weights.iter().sum();
                places.push((triangle, weights.map(|w| w / total)));
            }
        }
        let points = (texels.iter().zip(&places))
            .map(|(&texel, &(triangle, weights))| {
                scene.inside(corners_of(mesh, triangle), weights, texel)
            })
            .collect();
        let spacing = places
            .iter()
            .map(|&(t, _)| spacing_of[t as usize])
            .collect();
        Texels {
            size,
            texels,
            places,
            points,
            spacing,
            slots,
        }
    }

    /// `measure` at every covered texel's point, on every core; progress as
    /// `(texels done, texels)`.
    pub fn cast<T: Send>(
        &self,
        measure: impl Fn(Vertex) -> T + Sync,
        progress: impl FnMut(usize, usize),
    ) -> Vec<T> {
        in_steps(self.points.len(), |k| measure(self.points[k]), progress)
    }

    /// The open share of every covered texel's hemisphere ([`occlusion_at`]).
    pub fn occlusion(
        &self,
        scene: &Scene,
        sampling: Sampling,
        progress: impl FnMut(usize, usize),
    ) -> Vec<f32> {
        self.cast(|point| occlusion_at(scene, point, sampling).open, progress)
    }

    /// Every covered texel's thickness as a share of `distance` ([`thickness_at`]).
    pub fn thickness(
        &self,
        scene: &Scene,
        samples: u32,
        distance: f32,
        progress: impl FnMut(usize, usize),
    ) -> Vec<f32> {
        let share = |point| thickness_at(scene, point, samples, distance) / distance;
        self.cast(share, progress)
    }

    /// Per-vertex `values` of `mesh` interpolated at every covered texel.
    pub fn interpolated<const N: usize>(&self, mesh: &Mesh, values: &[[f32; N]]) -> Vec<[f32; N]> {
        (self.places.iter())
            .map(|&(triangle, weights)| {
                let corners = corners_of(mesh, triangle);
                std::array::from_fn(|k| {
                    (corners.iter().zip(weights))
                        .map(|(&v, w)| values[v as usize][k] * w)
                        .sum()
                })
            })
            .collect()
    }

    /// Each covered texel's point (unit frame) and unit normal.
    pub fn points(&self) -> impl Iterator<Item = (Vec3A, Vec3A)> + '_ {
        self.points
            .iter()
            .map(|point| (point.position, point.normal))
    }

    /// `values` (one per covered texel) averaged over each texel's neighbours up to
    /// `radius` texels away in the layout that lie on the same surface: facing within
    /// [`SAME_FACING`] of its normal and no farther on the surface than their offset
    /// allows ([`SAME_SURFACE`]). Radius 0 gives the values back.
    pub fn pooled(&self, values: &[f32], radius: u32) -> Vec<f32> {
        if radius == 0 {
            return values.to_vec();
        }
        let (n, reach) = (self.size as i64, i64::from(radius));
        in_steps(
            values.len(),
            |k| {
                let (texel, point) = (i64::from(self.texels[k]), self.points[k]);
                let (x, y) = (texel % n, texel / n);
                let farthest = SAME_SURFACE * (radius as f32 + 1.0) * self.spacing[k];
                let (mut sum, mut count) = (0.0f32, 0u32);
                for ny in (y - reach).max(0)..=(y + reach).min(n - 1) {
                    for nx in (x - reach).max(0)..=(x + reach).min(n - 1) {
                        let slot = self.slots[(ny * n + nx) as usize];
                        if slot == u32::MAX {
                            continue;
                        }
                        let other = self.points[slot as usize];
                        if other.normal.dot(point.normal) >= SAME_FACING
                            && other.position.distance(point.position) <= farthest
                        {
                            sum += values[slot as usize];
                            count += 1;
                        }
                    }
                }
                sum / count.max(1) as f32
            },
            |_, _| {},
        )
    }

    /// A `size`² image of `values` (one per covered texel), NaN where no texel is covered
    /// (as [`crate::bake::fill_uncovered`] takes it).
    pub fn image(&self, values: &[[f32; 4]]) -> Vec<[f32; 4]> {
        let mut image = vec![[f32::NAN; 4]; (self.size as usize).pow(2)];
        for (&texel, value) in self.texels.iter().zip(values) {
            image[texel as usize] = *value;
        }
        image
    }
}

/// The corners of triangle `triangle` of `mesh`.
fn corners_of(mesh: &Mesh, triangle: u32) -> [u32; 3] {
    let first = 3 * triangle as usize;
    [0, 1, 2].map(|k| mesh.indices[first + k])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::primitive;

    /// The plane's layout covers the whole map, each texel at its own place: the
    /// interpolated positions follow the texel centres.
    #[test]
    fn a_planes_texels_cover_the_map_and_sit_at_their_centres() {
        let plane = primitive("plane:4").unwrap();
        let scene = Scene::new(&plane);
        let texels = Texels::new(&plane, &scene, 16);
        assert_eq!(texels.texels.len(), 256);
        let positions: Vec<[f32; 3]> = plane.positions.clone();
        let at = texels.interpolated(&plane, &positions);
        let uv_of: Vec<[f32; 3]> = plane.uvs.iter().map(|uv| [uv[0], uv[1], 0.0]).collect();
        let uvs = texels.interpolated(&plane, &uv_of);
        for ((&texel, uv), position) in texels.texels.iter().zip(&uvs).zip(&at) {
            let (x, y) = (texel % 16, texel / 16);
            assert!((uv[0] - (x as f32 + 0.5) / 16.0).abs() < 1e-5);
            assert!((uv[1] - (y as f32 + 0.5) / 16.0).abs() < 1e-5);
            assert!(position[1].abs() < 1e-6);
        }
    }

    /// An open plane is open at every texel, and pooling keeps a constant constant.
    #[test]
    fn an_open_plane_is_open_at_every_texel() {
        let plane = primitive("plane:4").unwrap();
        let scene = Scene::new(&plane);
        let texels = Texels::new(&plane, &scene, 32);
        let sampling = Sampling {
            samples: 16,
            distance: 1.0,
            tolerance: None,
        };
        let open = texels.occlusion(&scene, sampling, |_, _| {});
        assert!(open.iter().all(|&v| v == 1.0));
        assert!(texels.pooled(&open, 2).iter().all(|&v| v == 1.0));
    }

    /// Pooling does not reach across a sharp crease: on a cube's atlas, texels of one
    /// face never average with another face's.
    #[test]
    fn pooling_stays_on_one_face_of_a_cube() {
        let cube = primitive("cube").unwrap().with_uv_atlas(64);
        let scene = Scene::new(&cube);
        let texels = Texels::new(&cube, &scene, 64);
        // A value per face: which axis its normal points along, and which way.
        let face: Vec<f32> = (texels.points())
            .map(|(_, normal)| {
                let axis = normal.abs().max_position() as f32;
                axis * 2.0 + f32::from(normal[normal.abs().max_position()] > 0.0)
            })
            .collect();
        assert_eq!(texels.pooled(&face, 2), face);
    }
}
