//! Procedural primitives: sphere, cube, torus, plane, a genus-2 double torus and a
//! rock (a sphere with a noisy surface), each about unit size at the origin.

use super::Mesh;
use std::f32::consts::{PI, TAU};

/// Names accepted by [`primitive`].
pub const PRIMITIVES: [&str; 6] = ["sphere", "cube", "torus", "plane", "genus2", "rock"];

/// The largest level of detail of a primitive, measured on a 2-core machine with 24 GB:
/// `torus:512` (1,048,576 triangles) takes 0.5 s and 90 MB in `veneer mesh`, 6 s and
/// 1.5 GB in `veneer geodesic` (heat); `torus:1024` took 81 s and 6.2 GB to solve, and
/// `torus:4096` (the earlier cap, 67 million triangles) over a minute and 5–6 GB.
pub const MAX_DETAIL: u32 = 512;

/// What the most detailed primitives cost, for messages and help.
pub const DETAIL_COST: &str = "torus:512 is a million triangles: about 0.5 s and 90 MB \
    in `veneer mesh`, 6 s and 1.5 GB in `veneer geodesic` on a 2-core machine";

/// The largest level of detail of `genus2`, whose polygonisation grows with its cube.
pub const MAX_GENUS2_DETAIL: u32 = 256;

/// The primitive called `name`, if there is one. A name may carry a level of detail,
/// `torus:320` (segments across the smaller direction; the defaults are sphere 48,
/// cube 8, torus 48, plane 16, genus2 40 and rock 48), for refined meshes and
/// benchmarks. Every level of detail samples the same shape, so `rock:24` and
/// `rock:192` are a coarse and a fine mesh of one surface (for bakes from high to low).
pub fn primitive(name: &str) -> Option<Mesh> {
    let (base, detail) = match name.split_once(':') {
        Some((base, detail)) => (
            base,
            Some(
                detail
                    .parse::<u32>()
                    .ok()
                    .filter(|d| (1..=MAX_DETAIL).contains(d))?,
            ),
        ),
        None => (name, None),
    };
    let detail = |default: u32| detail.unwrap_or(default);
    match base {
        "sphere" => Some(sphere(2 * detail(48), detail(48))),
        "cube" => Some(cube(detail(8))),
        "torus" => Some(torus(0.7, 0.3, 2 * detail(48), detail(48))),
        "plane" => Some(plane(detail(16))),
        "rock" => Some(rock(2 * detail(48), detail(48))),
        // Marching tetrahedra cost the cube of the detail: capped where it stays seconds.
        "genus2" if detail(40) <= MAX_GENUS2_DETAIL => {
            Some(super::implicit::double_torus(1.0 / detail(40) as f32))
        }
        _ => None,
    }
}

/// A unit sphere of latitude-longitude quads (`segments` round, `rings` pole to pole;
/// the seam and pole vertices repeat, as a UV-mapped file would).
pub fn sphere(segments: u32, rings: u32) -> Mesh {
    let mut mesh = Mesh::default();
    mesh.push_grid(segments, rings, |u, v| {
        let (theta, phi) = (u * TAU, v * PI);
        let p = [phi.sin() * theta.cos(), phi.cos(), -phi.sin() * theta.sin()];
        (p, p)
    });
    mesh
}

/// How far the rock's surface lies from the origin in the unit direction `d`: 1 plus
/// four octaves of gradient noise, the finer octaves below what a coarse mesh holds.
fn rock_radius(d: glam::Vec3) -> f32 {
    use crate::nodes::{formulas::noise::signed, settings::Basis};
    let (mut sum, mut amplitude, mut frequency) = (0.0, 0.2, 1.2);
    for _ in 0..4 {
        let p = (d * frequency).to_array();
        sum += amplitude * signed(Basis::Gradient, p);
        amplitude *= 0.5;
        frequency *= 2.2;
    }
    1.0 + sum
}

/// The rock: [`sphere`]'s latitude-longitude grid (UVs and seam alike) pushed out to
/// [`rock_radius`], normals from the gradient of the implicit surface
/// `|p| − rock_radius(p/|p|)` by central differences (so the poles get theirs too). The
/// differences span the grid's own spacing, so a coarse mesh's normals follow the shape
/// it holds rather than point samples of bumps finer than its facets.
fn rock(segments: u32, rings: u32) -> Mesh {
    let surface = |p: glam::Vec3| p.length() - rock_radius(p.normalize());
    let h = PI / rings as f32;
    let mut mesh = sphere(segments, rings);
    for (position, normal) in mesh.positions.iter_mut().zip(&mut mesh.normals) {
        let d = glam::Vec3::from(*position);
        let p = d * rock_radius(d);
        let gradient = glam::Vec3::AXES.map(|axis| surface(p + axis * h) - surface(p - axis * h));
        *position = p.to_array();
        *normal = glam::Vec3::from(gradient).normalize_or(d).to_array();
    }
    mesh
}

/// A hollow ball: the unit sphere facing out around a sphere of radius `inner` facing
/// in, each of `segments` × `rings` quads — a wall of known thickness `1 − inner`.
pub fn shell(inner: f32, segments: u32, rings: u32) -> Mesh {
    let mut mesh = sphere(segments, rings);
    let inside = sphere(segments, rings);
    let offset = mesh.positions.len() as u32;
    for ((p, n), uv) in inside
        .positions
        .iter()
        .zip(&inside.normals)
        .zip(&inside.uvs)
    {
        mesh.push_vertex(p.map(|c| c * inner), n.map(|c| -c), *uv);
    }
    mesh.indices.extend(
        inside
            .indices
            .chunks_exact(3)
            .flat_map(|t| [t[0] + offset, t[2] + offset, t[1] + offset]),
    );
    mesh
}

/// A torus about the y axis with `segments` steps round the axis and `sides` round the
/// tube (the seam vertices repeat, as a UV-mapped file would).
pub fn torus(major: f32, minor: f32, segments: u32, sides: u32) -> Mesh {
    let mut mesh = Mesh::default();
    mesh.push_grid(segments, sides, |u, v| {
        let (theta, phi) = (u * TAU, -v * TAU);
        let normal = [phi.cos() * theta.cos(), phi.sin(), -phi.cos() * theta.sin()];
        let ring = major + minor * phi.cos();
        (
            [ring * theta.cos(), minor * phi.sin(), -ring * theta.sin()],
            normal,
        )
    });
    mesh
}

/// A cube from -0.7 to 0.7, one grid per face so the edges stay sharp.
fn cube(steps: u32) -> Mesh {
    let mut mesh = Mesh::default();
    let half = 0.7;
    // (normal, a, b) per face with a × b = normal; the grid runs v along a and u along b
    // so that its triangles wind counter-clockwise seen from outside.
    let faces: [([f32; 3], [f32; 3], [f32; 3]); 6] = [
        ([1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]),
        ([-1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]),
        ([0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]),
        ([0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
        ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
        ([0.0, 0.0, -1.0], [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
    ];
    for (n, a, b) in faces {
        mesh.push_grid(steps, steps, |u, v| {
            let (s, t) = ((v * 2.0 - 1.0) * half, (u * 2.0 - 1.0) * half);
            let p = [0, 1, 2].map(|k| n[k] * half + a[k] * s + b[k] * t);
            (p, n)
        });
    }
    mesh
}

/// A 2×2 plane in y = 0 facing up.
fn plane(steps: u32) -> Mesh {
    let mut mesh = Mesh::default();
    mesh.push_grid(steps, steps, |u, v| {
        ([u * 2.0 - 1.0, 0.0, v * 2.0 - 1.0], [0.0, 1.0, 0.0])
    });
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closed_primitives_wind_outwards_with_the_expected_volume() {
        let sphere = primitive("sphere").unwrap();
        assert!((sphere.signed_volume() - 4.0 / 3.0 * PI).abs() < 0.02);
        let cube = primitive("cube").unwrap();
        assert!((cube.signed_volume() - 1.4f32.powi(3)).abs() < 1e-3);
        let torus = primitive("torus").unwrap();
        assert!((torus.signed_volume() - 2.0 * PI * PI * 0.7 * 0.09).abs() < 0.01);
    }

    #[test]
    fn normals_are_unit_length() {
        for name in PRIMITIVES {
            let mesh = primitive(name).unwrap();
            assert!(
                mesh.normals
                    .iter()
                    .all(|n| (glam::Vec3::from(*n).length() - 1.0).abs() < 1e-4),
                "{name}"
            );
        }
    }

    /// Every level of detail samples one rock: `rock:24`'s vertices are among
    /// `rock:48`'s (the coarse grid's directions are a subset of the fine one's), and
    /// each normal faces out of the stone and agrees with the fine mesh's facets.
    #[test]
    fn the_rock_is_one_shape_at_every_detail() {
        let coarse = primitive("rock:24").unwrap();
        let fine = primitive("rock:48").unwrap();
        let near = |a: [f32; 3], b: [f32; 3]| glam::Vec3::from(a).distance(b.into()) < 1e-5;
        for &p in &coarse.positions {
            assert!(fine.positions.iter().any(|&q| near(p, q)), "{p:?}");
        }
        let radii = coarse
            .positions
            .iter()
            .map(|&p| glam::Vec3::from(p).length());
        let (low, high) = radii.fold((f32::MAX, 0.0f32), |(l, h), r| (l.min(r), h.max(r)));
        assert!(
            0.6 < low && low < 0.95 && 1.05 < high && high < 1.4,
            "{low} {high}"
        );
        for triangle in fine.indices.chunks(3) {
            let [a, b, c] =
                [0, 1, 2].map(|k| glam::Vec3::from(fine.positions[triangle[k] as usize]));
            let area = (b - a).cross(c - a);
            if area.length() < 1e-5 {
                continue; // a pole's degenerate triangle
            }
            let facet = area.normalize();
            for &k in triangle {
                let normal = glam::Vec3::from(fine.normals[k as usize]);
                assert!(normal.dot(fine.positions[k as usize].into()) > 0.0);
                assert!(normal.dot(facet) > 0.5, "{normal} against {facet}");
            }
        }
    }
}
