//! Thickness at the vertices: how far the mesh goes on inwards, the mean over a cone of
//! rays about the inward normal of each ray's distance to the mesh's far side,
//! projected onto the normal (so a slab of thickness `d` reads `d` whatever the cone).

use super::rays::cone;
use super::scene::{Scene, Vertex};

/// The half-angle of the cone of rays (30°).
pub const CONE_HALF_ANGLE: f32 = std::f32::consts::FRAC_PI_6;

/// The thickness below one vertex, in units of the bounding radius; rays that leave
/// the mesh without meeting its far side (an open mesh) count as `distance`.
pub fn thickness_at(scene: &Scene, vertex: Vertex, samples: u32, distance: f32) -> f32 {
    let inward = -vertex.normal;
    let origin = vertex.origin(-1.0);
    let total: f32 = cone(inward, CONE_HALF_ANGLE, vertex.index)
        .take(samples as usize)
        .map(|direction| {
            scene
                .bvh()
                .nearest(origin, direction.into(), distance)
                // Depth below the vertex itself: the ray started `lift` below it.
                .map_or(distance, |hit| {
                    (vertex.lift + hit.distance * direction.dot(inward)).min(distance)
                })
        })
        .sum();
    total / samples.max(1) as f32
}

/// The thickness of every vertex of the scene.
pub fn thickness(
    scene: &Scene,
    samples: u32,
    distance: f32,
    progress: impl FnMut(usize, usize),
) -> Vec<f32> {
    scene.per_vertex(
        |vertex| thickness_at(scene, vertex, samples, distance),
        progress,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shell;

    #[test]
    fn a_shell_is_as_thick_as_its_wall() {
        let mesh = shell(0.9, 128, 64);
        let scene = Scene::new(&mesh);
        let outer = mesh.positions.len() / 2;
        let values = thickness(&scene, 256, 1.0, |_, _| {});
        // From either side the wall is 0.1 thick along the normal; rays off the normal
        // see it a little thicker from outside, a little thinner from inside.
        for (v, &value) in values.iter().enumerate() {
            let side = if v < outer { "outer" } else { "inner" };
            assert!((value - 0.1).abs() <= 0.003, "{side} vertex {v}: {value}");
        }
    }

    #[test]
    fn rays_that_leave_an_open_mesh_count_as_the_distance() {
        let plane = crate::mesh::primitive("plane").unwrap();
        let values = thickness(&Scene::new(&plane), 16, 0.75, |_, _| {});
        assert!(values.iter().all(|&t| t == 0.75));
    }
}
