//! Per-vertex tangent frames from a mesh's UV layout, as glTF's `TANGENT` attribute
//! carries them: xyz along +u, w the sign that makes cross(normal, xyz) · w point up the
//! texture image (towards -v), the direction the green channel of an OpenGL-convention
//! normal map points. The preview's fragment frame (`shaders/render_tangent.wgsl`) is the
//! same frame, found per pixel.

use super::Mesh;
use glam::Vec3;

/// One tangent per vertex: the triangles' uv gradients summed (weighted by their area in
/// uv space, Lengyel's method), made orthogonal to the unit normal and unit. A vertex
/// whose triangles have no uv extent gets the frame built round its normal alone
/// (normal × +z, or +x where the normal is along z), with w = 1.
pub fn vertex_tangents(mesh: &Mesh, normals: &[Vec3]) -> Vec<[f32; 4]> {
    let count = mesh.positions.len();
    let mut along_u = vec![Vec3::ZERO; count];
    let mut up_image = vec![Vec3::ZERO; count];
    for triangle in mesh.indices.chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|k| triangle[k] as usize);
        let p = [a, b, c].map(|i| Vec3::from(mesh.positions[i]));
        let t = [a, b, c].map(|i| glam::Vec2::from(mesh.uvs[i]));
        let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
        let (d1, d2) = (t[1] - t[0], t[2] - t[0]);
        // Signed doubled uv area; its sign keeps mirrored islands' frames mirrored.
        let det = d1.x * d2.y - d2.x * d1.y;
        if det.abs() < 1e-20 || !det.is_finite() {
            continue;
        }
        let u = (e1 * d2.y - e2 * d1.y) * det.signum();
        let v = (e2 * d1.x - e1 * d2.x) * det.signum();
        for i in [a, b, c] {
            along_u[i] += u;
            up_image[i] -= v;
        }
    }
    (0..count)
        .map(|i| {
            let n = normals[i];
            let t = along_u[i] - n * n.dot(along_u[i]);
            match t.try_normalize() {
                Some(t) => {
                    let w = if n.cross(t).dot(up_image[i]) < 0.0 {
                        -1.0
                    } else {
                        1.0
                    };
                    t.extend(w).to_array()
                }
                None => frame_round(n).extend(1.0).to_array(),
            }
        })
        .collect()
}

/// The unit normals glTF requires: each vertex's normal made unit, +y where it has none.
pub fn unit_normals(mesh: &Mesh) -> Vec<Vec3> {
    (mesh.normals.iter())
        .map(|n| Vec3::from(*n).try_normalize().unwrap_or(Vec3::Y))
        .collect()
}

/// The tangent of the frame built round a unit normal alone.
fn frame_round(normal: Vec3) -> Vec3 {
    normal.cross(Vec3::Z).try_normalize().unwrap_or(Vec3::X)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit square in the plane y = 0 with u along +x and v along +z: the tangent is +x
    /// and cross(normal, tangent) · w is -z, up the image.
    #[test]
    fn a_plane_s_frame_is_u_and_up_the_image() {
        let mut mesh = Mesh::from_triangles(
            vec![
                [0.0, 0.0, 0.0],
                [0.0, 0.0, 1.0],
                [1.0, 0.0, 1.0],
                [1.0, 0.0, 0.0],
            ],
            vec![0, 1, 2, 0, 2, 3],
        );
        mesh.uvs = vec![[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]];
        let normals = unit_normals(&mesh);
        assert!(normals.iter().all(|n| n.abs_diff_eq(Vec3::Y, 1e-6)));
        for tangent in vertex_tangents(&mesh, &normals) {
            let t = Vec3::new(tangent[0], tangent[1], tangent[2]);
            assert!(t.abs_diff_eq(Vec3::X, 1e-6), "{tangent:?}");
            let bitangent = Vec3::Y.cross(t) * tangent[3];
            assert!(bitangent.abs_diff_eq(Vec3::NEG_Z, 1e-6), "{tangent:?}");
        }
        // Mirrored in u, the tangent turns round and w keeps the bitangent up the image.
        mesh.uvs.iter_mut().for_each(|uv| uv[0] = 1.0 - uv[0]);
        for tangent in vertex_tangents(&mesh, &normals) {
            let t = Vec3::new(tangent[0], tangent[1], tangent[2]);
            assert!(t.abs_diff_eq(Vec3::NEG_X, 1e-6), "{tangent:?}");
            assert!((Vec3::Y.cross(t) * tangent[3]).abs_diff_eq(Vec3::NEG_Z, 1e-6));
        }
    }

    /// Without a UV layout every tangent is still unit and orthogonal to its normal.
    #[test]
    fn no_layout_gives_frames_round_the_normal() {
        let mesh = crate::mesh::primitives::sphere(12, 8);
        let mut flat = mesh.clone();
        flat.uvs.iter_mut().for_each(|uv| *uv = [0.0; 2]);
        let normals = unit_normals(&flat);
        for (tangent, n) in vertex_tangents(&flat, &normals).iter().zip(&normals) {
            let t = Vec3::new(tangent[0], tangent[1], tangent[2]);
            assert!((t.length() - 1.0).abs() < 1e-5 && t.dot(*n).abs() < 1e-5);
            assert_eq!(tangent[3], 1.0);
        }
    }
}
