//! The geodesic solvers on arbitrary small meshes (any connectivity: slivers, repeated
//! vertices, non-manifold edges, several components) and sources: every method returns
//! a field or an error, never a panic or a hang; no distance is NaN or negative, and
//! sources are at distance 0.

#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use veneer::geodesic::{HeatOptions, Method, distances};
use veneer::mesh::Mesh;

#[derive(Arbitrary, Debug)]
struct FuzzMesh {
    /// Coordinates on a grid of 1/64, so that coincident and collinear points are common.
    positions: Vec<[i16; 3]>,
    triangles: Vec<[u8; 3]>,
    sources: Vec<u8>,
    time_factor: u8,
}

fuzz_target!(|fuzz: FuzzMesh| {
    let count = fuzz.positions.len().min(64);
    if count == 0 || fuzz.triangles.is_empty() || fuzz.sources.is_empty() {
        return;
    }
    let positions: Vec<[f32; 3]> = fuzz.positions[..count]
        .iter()
        .map(|p| p.map(|c| f32::from(c) / 64.0))
        .collect();
    let indices: Vec<u32> = fuzz
        .triangles
        .iter()
        .take(128)
        .flat_map(|t| t.map(|i| u32::from(i) % count as u32))
        .collect();
    let sources: Vec<u32> = fuzz
        .sources
        .iter()
        .map(|&s| u32::from(s) % count as u32)
        .collect();
    let mesh = Mesh::from_triangles(positions, indices);
    let time_factor = 2f64.powi(i32::from(fuzz.time_factor % 24) - 12);
    for method in [
        Method::Heat(HeatOptions {
            time_factor,
            robust: false,
        }),
        Method::Heat(HeatOptions {
            time_factor,
            robust: true,
        }),
        Method::Exact,
        Method::Dijkstra,
    ] {
        let Ok(field) = distances(&mesh, &sources, method, |_, _| {}) else {
            continue;
        };
        assert_eq!(field.len(), count);
        assert!(
            field.iter().all(|d| *d >= 0.0),
            "{}: a NaN or negative distance: {field:?}",
            method.name()
        );
        assert!(
            sources.iter().all(|&s| field[s as usize] == 0.0),
            "{}: a source is not at 0",
            method.name()
        );
    }
});
