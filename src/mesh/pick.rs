//! Picking a vertex of a mesh with a ray (a click on the preview).

use super::Mesh;
use glam::Vec3;

/// The vertex nearest to where the ray `origin + t·direction` (t > 0) first hits the
/// mesh, or `None` when it misses every triangle.
pub fn pick_vertex(mesh: &Mesh, origin: Vec3, direction: Vec3) -> Option<u32> {
    let position = |i: u32| Vec3::from(mesh.positions[i as usize]);
    let mut best: Option<(f32, [u32; 3])> = None;
    for triangle in mesh.indices.chunks_exact(3) {
        let corners = [triangle[0], triangle[1], triangle[2]];
        if let Some(t) = ray_hits_triangle(origin, direction, corners.map(position))
            && best.is_none_or(|(nearest, _)| t < nearest)
        {
            best = Some((t, corners));
        }
    }
    let (t, corners) = best?;
    let hit = origin + direction * t;
    corners.into_iter().min_by(|&a, &b| {
        position(a)
            .distance(hit)
            .total_cmp(&position(b).distance(hit))
    })
}

/// Möller–Trumbore: the ray parameter where it crosses the triangle (either side).
fn ray_hits_triangle(origin: Vec3, direction: Vec3, [a, b, c]: [Vec3; 3]) -> Option<f32> {
    let (ab, ac) = (b - a, c - a);
    let p = direction.cross(ac);
    let det = ab.dot(p);
    if det.abs() < 1.0e-12 {
        return None;
    }
    let to_origin = origin - a;
    let u = to_origin.dot(p) / det;
    let q = to_origin.cross(ab);
    let v = direction.dot(q) / det;
    let t = ac.dot(q) / det;
    (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0).then_some(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ray_down_the_z_axis_picks_the_sphere_vertex_facing_it() {
        let sphere = crate::mesh::primitive("sphere").unwrap();
        let picked = pick_vertex(&sphere, Vec3::new(0.0, 0.0, 5.0), Vec3::NEG_Z).unwrap();
        let p = Vec3::from(sphere.positions[picked as usize]);
        assert!(p.distance(Vec3::Z) < 0.05, "{p}");
        assert_eq!(
            pick_vertex(&sphere, Vec3::new(3.0, 0.0, 5.0), Vec3::NEG_Z),
            None
        );
    }
}
