//! Veneer's own ray-casting hierarchy (`mesh/bvh.rs`) against two well-kept crates,
//! `parry3d` (a `TriMesh`'s own hierarchy) and `bvh` (a SAH tree whose leaves are
//! triangles, tested here two-sided), on the rays ambient occlusion casts: 16
//! cosine-distributed rays from each vertex, lifted 0.001 off the surface, on
//! `torus:160` (102,400 triangles, rays up to 0.5) and `genus2:60` (153,588 triangles
//! with slivers, rays up to 1.5, more of them blocked). For each it times the build
//! (one thread each), any-hit queries (the occlusion test) and nearest-hit queries
//! (thickness, high-to-low bakes) on all cores, after printing how many rays each finds
//! blocked and how the nearest hits compare, so that the three are seen to answer the
//! same question.
//!
//! `cargo bench --bench ray_casting --features compare-ray-casting`

use criterion::{Criterion, criterion_group, criterion_main};
use glam::Vec3;
use rayon::prelude::*;
use std::hint::black_box;

/// The meshes and how far their rays run.
const SCENES: [(&str, f32); 2] = [("torus:160", 0.5), ("genus2:60", 1.5)];

/// One ray: origin, unit direction and how far it runs.
type Ray = (Vec3, Vec3, f32);

/// An any-hit query, and a nearest-hit query's distance, under a label.
type Blocked<'a> = (&'static str, &'a (dyn Fn(Ray) -> bool + Sync));
type Nearest<'a> = (&'static str, &'a (dyn Fn(Ray) -> Option<f32> + Sync));

/// 16 cosine-distributed directions around each vertex normal, from a fixed generator.
fn occlusion_rays(mesh: &veneer::mesh::Mesh, limit: f32) -> Vec<Ray> {
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut uniform = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    let mut rays = Vec::new();
    for (position, normal) in mesh.positions.iter().zip(&mesh.normals) {
        let normal = Vec3::from(*normal);
        let (tangent, bitangent) = normal.any_orthonormal_pair();
        for _ in 0..16 {
            let (r, angle) = (uniform().sqrt(), uniform() * std::f32::consts::TAU);
            let (x, y) = (r * angle.cos(), r * angle.sin());
            let z = (1.0 - r * r).max(0.0).sqrt();
            let direction = (tangent * x + bitangent * y + normal * z).normalize();
            rays.push((Vec3::from(*position) + normal * 1.0e-3, direction, limit));
        }
    }
    rays
}

/// The three hierarchies over one mesh, each answering both queries.
struct Hierarchies {
    own: veneer::mesh::Bvh,
    parry: parry3d::shape::TriMesh,
    crate_bvh: crate_bvh::Scene,
}

impl Hierarchies {
    fn new(mesh: &veneer::mesh::Mesh) -> Hierarchies {
        Hierarchies {
            own: veneer::mesh::Bvh::new(&mesh.positions, &mesh.indices),
            parry: parry_mesh(mesh),
            crate_bvh: crate_bvh::Scene::new(mesh),
        }
    }
}

fn parry_mesh(mesh: &veneer::mesh::Mesh) -> parry3d::shape::TriMesh {
    let vertices = (mesh.positions.iter())
        .map(|&[x, y, z]| parry3d::math::Vector::new(x, y, z))
        .collect();
    let triangles = (mesh.indices.chunks_exact(3))
        .map(|t| [t[0], t[1], t[2]])
        .collect();
    parry3d::shape::TriMesh::new(vertices, triangles).expect("a valid triangle mesh")
}

fn parry_ray((origin, direction, _): Ray) -> parry3d::query::Ray {
    let v = |v: Vec3| parry3d::math::Vector::new(v.x, v.y, v.z);
    parry3d::query::Ray::new(v(origin), v(direction))
}

fn parry_blocked(mesh: &parry3d::shape::TriMesh, ray: Ray) -> bool {
    use parry3d::query::RayCast;
    mesh.intersects_local_ray(&parry_ray(ray), ray.2)
}

fn parry_nearest(mesh: &parry3d::shape::TriMesh, ray: Ray) -> Option<f32> {
    use parry3d::query::RayCast;
    mesh.cast_local_ray(&parry_ray(ray), ray.2, false)
}

/// The `bvh` crate: triangles as its shapes, a query that respects the ray's limit, and a
/// two-sided Möller–Trumbore test on the candidates it returns.
mod crate_bvh {
    use super::Ray;
    use bvh::aabb::{Aabb, Bounded, IntersectsAabb};
    use bvh::bounding_hierarchy::BHShape;
    use nalgebra::{Point3, Vector3};

    pub struct Triangle {
        corners: [Point3<f32>; 3],
        node: usize,
    }

    impl Bounded<f32, 3> for Triangle {
        fn aabb(&self) -> Aabb<f32, 3> {
            let [a, b, c] = self.corners;
            Aabb::empty().grow(&a).grow(&b).grow(&c)
        }
    }

    impl BHShape<f32, 3> for Triangle {
        fn set_bh_node_index(&mut self, index: usize) {
            self.node = index;
        }
        fn bh_node_index(&self) -> usize {
            self.node
        }
    }

    /// A ray that meets a box only if it enters it before `limit`.
    struct Limited {
        ray: bvh::ray::Ray<f32, 3>,
        limit: f32,
    }

    impl IntersectsAabb<f32, 3> for Limited {
        fn intersects_aabb(&self, aabb: &Aabb<f32, 3>) -> bool {
            (self.ray.intersection_slice_for_aabb(aabb)).is_some_and(|(near, _)| near <= self.limit)
        }
    }

    pub struct Scene {
        hierarchy: bvh::bvh::Bvh<f32, 3>,
        triangles: Vec<Triangle>,
    }

    impl Scene {
        pub fn new(mesh: &veneer::mesh::Mesh) -> Scene {
            let corner = |i: u32| Point3::from(mesh.positions[i as usize]);
            let mut triangles: Vec<Triangle> = (mesh.indices.chunks_exact(3))
                .map(|t| Triangle {
                    corners: [corner(t[0]), corner(t[1]), corner(t[2])],
                    node: 0,
                })
                .collect();
            let hierarchy = bvh::bvh::Bvh::build(&mut triangles);
            Scene {
                hierarchy,
                triangles,
            }
        }

        /// The distances at which the ray meets each candidate triangle, from either side.
        fn hits(&self, (origin, direction, limit): Ray) -> impl Iterator<Item = f32> + '_ {
            let ray = bvh::ray::Ray::new(
                Point3::from(origin.to_array()),
                Vector3::from(direction.to_array()),
            );
            let query = Limited { ray, limit };
            let candidates: Vec<&Triangle> = self.hierarchy.traverse(&query, &self.triangles);
            candidates.into_iter().filter_map(move |triangle| {
                let [a, b, c] = &triangle.corners;
                let front = query.ray.intersects_triangle(a, b, c).distance;
                let back = query.ray.intersects_triangle(a, c, b).distance;
                let distance = front.min(back);
                (distance <= limit).then_some(distance)
            })
        }

        pub fn blocked(&self, ray: Ray) -> bool {
            self.hits(ray).next().is_some()
        }

        pub fn nearest(&self, ray: Ray) -> Option<f32> {
            self.hits(ray).min_by(f32::total_cmp)
        }
    }
}

fn compare(c: &mut Criterion) {
    for (name, limit) in SCENES {
        compare_on(c, name, limit);
    }
}

fn compare_on(c: &mut Criterion, name: &str, limit: f32) {
    let mesh = veneer::mesh::primitive(name).expect("primitive");
    let rays = occlusion_rays(&mesh, limit);
    let hierarchies = Hierarchies::new(&mesh);
    let own_blocked = |(origin, direction, limit): Ray| {
        (hierarchies.own).occluded(origin.to_array(), direction.to_array(), limit)
    };
    let own_nearest = |(origin, direction, limit): Ray| {
        (hierarchies
            .own
            .nearest(origin.to_array(), direction.to_array(), limit))
        .map(|hit| hit.distance)
    };
    let parry_blocked = |ray| parry_blocked(&hierarchies.parry, ray);
    let parry_nearest = |ray| parry_nearest(&hierarchies.parry, ray);
    let bvh_blocked = |ray| hierarchies.crate_bvh.blocked(ray);
    let bvh_nearest = |ray| hierarchies.crate_bvh.nearest(ray);
    let blocked: [Blocked; 3] = [
        ("veneer mesh/bvh.rs", &own_blocked),
        ("parry3d TriMesh", &parry_blocked),
        ("bvh crate", &bvh_blocked),
    ];
    let nearest: [Nearest; 3] = [
        ("veneer mesh/bvh.rs", &own_nearest),
        ("parry3d TriMesh", &parry_nearest),
        ("bvh crate", &bvh_nearest),
    ];
    let reference: Vec<Option<f32>> = rays.par_iter().map(|&ray| own_nearest(ray)).collect();
    for ((label, blocked), (_, nearest)) in blocked.iter().zip(&nearest) {
        let count = rays.par_iter().filter(|&&ray| blocked(ray)).count();
        let (disagree, largest) = (rays.par_iter().zip(&reference))
            .map(|(&ray, expected)| match (nearest(ray), expected) {
                (Some(a), Some(b)) => (0usize, (a - b).abs()),
                (None, None) => (0, 0.0),
                _ => (1, 0.0),
            })
            .reduce(|| (0, 0.0), |a, b| (a.0 + b.0, a.1.max(b.1)));
        println!(
            "{name}, {label}: {count} of {} rays blocked; nearest hit: {disagree} rays disagree with veneer's on hit or miss, distances within {largest:.2e}",
            rays.len()
        );
    }
    let mut group = c.benchmark_group(format!(
        "ray casting {name} ({} triangles, {} rays up to {limit})",
        mesh.triangle_count(),
        rays.len()
    ));
    group.sample_size(10);
    group.bench_function("build, veneer mesh/bvh.rs", |b| {
        b.iter(|| veneer::mesh::Bvh::new(black_box(&mesh.positions), &mesh.indices))
    });
    group.bench_function("build, parry3d TriMesh", |b| {
        b.iter(|| parry_mesh(black_box(&mesh)))
    });
    group.bench_function("build, bvh crate", |b| {
        b.iter(|| crate_bvh::Scene::new(black_box(&mesh)))
    });
    for (label, blocked) in blocked {
        group.bench_function(format!("any hit, {label}"), |b| {
            b.iter(|| rays.par_iter().filter(|&&ray| blocked(ray)).count())
        });
    }
    for (label, nearest) in nearest {
        group.bench_function(format!("nearest hit, {label}"), |b| {
            b.iter(|| rays.par_iter().filter_map(|&ray| nearest(ray)).count())
        });
    }
    group.finish();
}

criterion_group!(benches, compare);
criterion_main!(benches);
