//! Ambient occlusion at the vertices: the share of a cosine-weighted hemisphere of rays
//! about the normal that hit the mesh within a distance (1 open, 0 enclosed).

use super::rays::cosine_hemisphere;
use super::scene::{Scene, Vertex};

/// Rays are cast in batches of this many between checks of the confidence interval.
pub const BATCH: u32 = 16;

/// How a vertex's occlusion is sampled.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sampling {
    /// The most rays per vertex.
    pub samples: u32,
    /// How far a ray may travel before it counts as open, in units of the bounding radius.
    pub distance: f32,
    /// Stop early once the 95% confidence interval of the estimate is narrower than ±
    /// this (Laplace-smoothed binomial interval, checked every [`BATCH`] rays); `None`
    /// casts every ray.
    pub tolerance: Option<f32>,
}

/// A vertex's occlusion and the rays it took.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Estimate {
    /// Unoccluded share of the cosine-weighted hemisphere, 0 to 1.
    pub open: f32,
    /// Rays cast.
    pub rays: u32,
}

/// The 95% half-width of the estimate after `hits` of `rays`, smoothed so that no hit
/// yet does not read as certainty.
fn half_width(hits: u32, rays: u32) -> f32 {
    let share = (hits as f32 + 1.0) / (rays as f32 + 2.0);
    1.96 * (share * (1.0 - share) / rays as f32).sqrt()
}

/// The occlusion of one vertex.
pub fn occlusion_at(scene: &Scene, vertex: Vertex, sampling: Sampling) -> Estimate {
    let origin = vertex.origin(1.0);
    let mut hits = 0u32;
    let mut rays = 0u32;
    for direction in cosine_hemisphere(vertex.normal, vertex.index).take(sampling.samples as usize)
    {
        rays += 1;
        hits += u32::from(
            scene
                .bvh()
                .occluded(origin, direction.into(), sampling.distance),
        );
        if let Some(tolerance) = sampling.tolerance
            && rays.is_multiple_of(BATCH)
            && half_width(hits, rays) < tolerance
        {
            break;
        }
    }
    Estimate {
        open: 1.0 - hits as f32 / rays.max(1) as f32,
        rays,
    }
}

/// The occlusion of every vertex of the scene.
pub fn occlusion(
    scene: &Scene,
    sampling: Sampling,
    progress: impl FnMut(usize, usize),
) -> Vec<Estimate> {
    scene.per_vertex(|vertex| occlusion_at(scene, vertex, sampling), progress)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Mesh, primitive};

    const EVERY_RAY: Sampling = Sampling {
        samples: 4096,
        distance: 4.0,
        tolerance: None,
    };

    #[test]
    fn a_plane_under_nothing_is_open_everywhere() {
        let plane = primitive("plane").unwrap();
        let estimates = occlusion(&Scene::new(&plane), EVERY_RAY, |_, _| {});
        assert!(estimates.iter().all(|e| e.open == 1.0 && e.rays == 4096));
    }

    /// Three square walls of side 1 meeting at the origin, open towards +x, +y and +z,
    /// each a grid of `steps`² quads facing into the corner.
    fn inside_corner(steps: u32) -> Mesh {
        let mut mesh = Mesh::default();
        let walls: [([f32; 3], [f32; 3], [f32; 3]); 3] = [
            ([1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]),
            ([0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
            ([0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]),
        ];
        for (normal, a, b) in walls {
            mesh.push_grid(steps, steps, |u, v| {
                ([0, 1, 2].map(|k| a[k] * u + b[k] * v), normal)
            });
        }
        mesh
    }

    #[test]
    fn the_inside_corner_of_a_box_sees_one_octant() {
        let mut mesh = inside_corner(8);
        let corner = Vertex {
            index: 0,
            position: glam::Vec3A::ZERO,
            normal: glam::Vec3A::ONE.normalize(),
            lift: 1.0e-4,
        };
        // Scene::new moves the corner into the unit frame: place it there by hand.
        let scene = Scene::new(&mesh);
        let (centre, radius) = mesh.bounding_sphere();
        let position = (glam::DVec3::ZERO - centre) / radius;
        let estimate = occlusion_at(
            &scene,
            Vertex {
                position: position.as_vec3a(),
                ..corner
            },
            Sampling {
                samples: 4096,
                distance: 0.5,
                tolerance: None,
            },
        );
        // The cosine-weighted share of an octant about its diagonal: √3/4.
        let expected = 3.0f32.sqrt() / 4.0;
        assert!(
            (estimate.open - expected).abs() <= 0.02 * expected,
            "{} against {expected}",
            estimate.open
        );
        mesh.indices.clear();
        let empty = Scene::new(&mesh);
        assert_eq!(occlusion_at(&empty, corner, EVERY_RAY).open, 1.0);
    }

    #[test]
    fn sampling_stops_early_where_the_estimate_is_certain_and_not_where_it_is_not() {
        let torus = primitive("torus:24").unwrap();
        let scene = Scene::new(&torus);
        let adaptive = Sampling {
            samples: 1024,
            distance: 2.0,
            tolerance: Some(0.05),
        };
        let estimates = occlusion(&scene, adaptive, |_, _| {});
        let full = occlusion(
            &scene,
            Sampling {
                tolerance: None,
                ..adaptive
            },
            |_, _| {},
        );
        let rays: Vec<u32> = estimates.iter().map(|e| e.rays).collect();
        assert!(rays.iter().any(|&r| r < 1024) && rays.iter().any(|&r| r > 64));
        for (adaptive, full) in estimates.iter().zip(&full) {
            assert!((adaptive.open - full.open).abs() < 0.1);
        }
    }
}
