//! Mesh fields on a ~100k-triangle torus (`torus:160`, 102,400 triangles), in one run:
//! - ambient occlusion at 16, 64 and 256 rays per vertex, and adaptive sampling (stop at
//!   a ±0.05 confidence interval, at most 256 rays), each with its mean and largest
//!   error against a 4,096-ray reference printed first;
//! - thickness at 64 rays;
//! - curvatures (cotangent Laplacian and angle defect) and convexity's smoothing;
//! - occlusion baked per texel into a 1024² layout of `torus:158` (99,856 triangles,
//!   every texel covered): 8 rays pooled ±3 texels (the bake's default) against the
//!   baseline of 64 rays per texel alone, their errors against 1,024 rays per texel
//!   (at 384²) printed first.
//!
//! `cargo bench --bench mesh_fields -- texel` runs the texel part alone.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use veneer::mesh_fields::{self, Sampling, Scene};

/// Mean and largest absolute difference.
fn errors(values: &[f32], reference: &[f32]) -> (f32, f32) {
    let differences: Vec<f32> = values
        .iter()
        .zip(reference)
        .map(|(a, b)| (a - b).abs())
        .collect();
    let mean = differences.iter().sum::<f32>() / differences.len().max(1) as f32;
    (mean, differences.iter().copied().fold(0.0, f32::max))
}

fn fields(c: &mut Criterion) {
    let mesh = veneer::mesh::primitive("torus:160").expect("primitive");
    let scene = Scene::new(&mesh);
    let sampling = |samples, tolerance| Sampling {
        samples,
        distance: 0.5,
        tolerance,
    };
    let open = |sampling| -> (Vec<f32>, f64) {
        let estimates = mesh_fields::occlusion(&scene, sampling, |_, _| {});
        let rays: u64 = estimates.iter().map(|e| u64::from(e.rays)).sum();
        (
            estimates.iter().map(|e| e.open).collect(),
            rays as f64 / estimates.len() as f64,
        )
    };
    let (reference, _) = open(sampling(4096, None));
    let variants = [
        ("16 rays", sampling(16, None)),
        ("64 rays", sampling(64, None)),
        ("256 rays", sampling(256, None)),
        (
            "adaptive ±0.05, at most 256 rays",
            sampling(256, Some(0.05)),
        ),
    ];
    for (label, sampling) in variants {
        let (values, rays) = open(sampling);
        let (mean, largest) = errors(&values, &reference);
        println!(
            "occlusion, {label}: {rays:.1} rays per vertex, error against 4,096 rays: mean {mean:.4}, largest {largest:.4}"
        );
    }
    let mut group = c.benchmark_group(format!(
        "mesh fields torus:160 ({} triangles, {} vertices)",
        mesh.triangle_count(),
        mesh.positions.len()
    ));
    group.sample_size(10);
    group.bench_function("hierarchy build", |b| {
        b.iter(|| Scene::new(black_box(&mesh)))
    });
    for (label, sampling) in variants {
        group.bench_function(format!("occlusion, {label}"), |b| {
            b.iter(|| mesh_fields::occlusion(&scene, sampling, |_, _| {}))
        });
    }
    group.bench_function("thickness, 64 rays", |b| {
        b.iter(|| mesh_fields::thickness(&scene, 64, 1.0, |_, _| {}))
    });
    let (welded, _) = veneer::geodesic::welded_for_distances(&mesh);
    group.bench_function("curvatures", |b| {
        b.iter(|| mesh_fields::curvatures(black_box(&welded)))
    });
    group.bench_function("convexity, radius 0.05", |b| {
        b.iter(|| mesh_fields::convexity(&welded, 0.05).expect("factors"))
    });
    group.finish();
}

/// Occlusion per texel: the pooled default against more rays alone.
fn texels(c: &mut Criterion) {
    let mesh = veneer::mesh::primitive("torus:158").expect("primitive");
    let scene = Scene::new(&mesh);
    let sampling = |samples| Sampling {
        samples,
        distance: 0.5,
        tolerance: None,
    };
    let bake = |texels: &mesh_fields::Texels, rays, pooling| {
        texels.pooled(
            &texels.occlusion(&scene, sampling(rays), |_, _| {}),
            pooling,
        )
    };
    let variants = [("8 rays pooled ±3 texels", 8, 3), ("64 rays alone", 64, 0)];
    // Errors at 384², where a reference of 1,024 rays per texel takes seconds.
    let small = mesh_fields::Texels::new(&mesh, &scene, 384);
    let reference = bake(&small, 1024, 0);
    for (label, rays, pooling) in variants {
        let (mean, largest) = errors(&bake(&small, rays, pooling), &reference);
        println!(
            "occlusion per texel at 384², {label}: error against 1,024 rays: mean {mean:.4}, largest {largest:.4}"
        );
    }
    let texels = mesh_fields::Texels::new(&mesh, &scene, 1024);
    let mut group = c.benchmark_group(format!(
        "texel occlusion torus:158 ({} triangles) at 1024²",
        mesh.triangle_count()
    ));
    group.sample_size(10);
    for (label, rays, pooling) in variants {
        group.bench_function(label, |b| b.iter(|| bake(&texels, rays, pooling)));
    }
    group.finish();
}

criterion_group!(benches, fields, texels);
criterion_main!(benches);
