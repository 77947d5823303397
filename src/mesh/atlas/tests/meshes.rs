//! Meshes without texture coordinates for the atlas tests.

use crate::mesh::Mesh;
use glam::DVec3;

/// A lumpy closed surface like a scan: a cube of `n` × `n` squares a side blown up into a
/// sphere, pushed in and out by bumps and by noise of 0.3% of its radius, written as an
/// OBJ of `v` and `f` lines only.
pub fn lumpy_obj(n: i32) -> Mesh {
    use std::fmt::Write;
    let mut index: std::collections::HashMap<[i32; 3], usize> = Default::default();
    let (mut obj, mut faces) = (String::new(), String::new());
    let mut vertex = |p: [i32; 3], obj: &mut String| -> usize {
        let count = index.len();
        *index.entry(p).or_insert_with(|| {
            let d = (DVec3::from(p.map(f64::from)) / f64::from(n) * 2.0 - 1.0).normalize();
            let noise = ((d.x * 12.9898 + d.y * 78.233 + d.z * 37.719).sin() * 43758.5453).fract();
            let r = 1.0
                + 0.15 * (3.0 * d.x + 1.0).sin() * (2.0 * d.y).sin()
                + 0.1 * (5.0 * d.z + 2.0 * d.y).sin() * (4.0 * d.x).cos()
                + 0.02 * (17.0 * d.x + 13.0 * d.y + 11.0 * d.z).sin()
                + 0.003 * noise;
            let _ = writeln!(obj, "v {} {} {}", r * d.x, r * d.y, r * d.z);
            count + 1
        })
    };
    for axis in 0..3 {
        // Along the two other axes in cyclic order, so that u × v is +axis.
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        for outward in [false, true] {
            for a in 0..n {
                for b in 0..n {
                    let corner = |da: i32, db: i32| {
                        let mut p = [0; 3];
                        p[axis] = if outward { n } else { 0 };
                        (p[u], p[v]) = (a + da, b + db);
                        p
                    };
                    let mut quad = [corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)];
                    if !outward {
                        quad.reverse();
                    }
                    let [p, q, r, s] = quad.map(|c| vertex(c, &mut obj));
                    let _ = writeln!(faces, "f {p} {q} {r}\nf {p} {r} {s}");
                }
            }
        }
    }
    obj.push_str(&faces);
    crate::mesh::from_bytes("obj", obj.as_bytes(), None).expect("the OBJ reads")
}

/// Triangles facing every way, none sharing an edge: more charts than a small texture
/// has room for with gaps.
pub fn triangle_soup(count: u32) -> Mesh {
    let mut positions = Vec::new();
    for k in 0..count {
        let angle = f64::from(k) * 2.399963;
        let height = 1.0 - 2.0 * (f64::from(k) + 0.5) / f64::from(count);
        let centre = DVec3::new(
            angle.cos() * (1.0 - height * height).sqrt(),
            height,
            angle.sin() * (1.0 - height * height).sqrt(),
        );
        let (a, b) = centre.any_orthonormal_pair();
        for corner in [centre + 0.05 * a, centre + 0.05 * b, centre - 0.05 * a] {
            positions.push(corner.as_vec3().to_array());
        }
    }
    let indices = (0..3 * count).collect();
    Mesh::from_triangles(positions, indices)
}
