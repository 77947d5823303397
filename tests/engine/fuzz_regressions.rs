//! Inputs the fuzz targets in `fuzz/` once crashed on, replayed on every test run with
//! the targets' own checks: `tests/fuzz/<target>/` holds one file per finding.

use crate::support::root;
use veneer::codegen::{CompileError, CompileOptions, Detail, ParamMode, compile};

/// The files under `tests/fuzz/<target>/` (there is at least one: an empty or missing
/// folder would make the replay test nothing).
fn findings(target: &str) -> Vec<std::path::PathBuf> {
    let folder = root(&format!("tests/fuzz/{target}"));
    let mut paths: Vec<_> = std::fs::read_dir(&folder)
        .unwrap_or_else(|error| panic!("{}: {error}", folder.display()))
        .map(|entry| entry.expect("entry").path())
        .collect();
    assert!(!paths.is_empty(), "no findings in {}", folder.display());
    paths.sort();
    paths
}

#[test]
fn mesh_files_that_crashed_a_loader_load_or_are_refused() {
    for path in findings("mesh_load") {
        let bytes = std::fs::read(&path).expect("finding");
        for extension in ["obj", "stl", "ply", "glb"] {
            if let Ok(mesh) = veneer::mesh::from_bytes(extension, &bytes, None) {
                let count = mesh.positions.len();
                assert!(
                    mesh.indices.iter().all(|&i| (i as usize) < count),
                    "{path:?}"
                );
                veneer::mesh::analyse(&mesh);
            }
        }
    }
}

#[test]
fn graphs_that_crashed_the_compiler_compile_or_are_rejected_by_the_check() {
    for path in findings("compile").into_iter().chain(findings("graph_ron")) {
        let Ok(graph) = veneer::graph::load(&path) else {
            continue;
        };
        for (mode, detail) in [
            (ParamMode::Baked, Detail::Full),
            (ParamMode::Uniform, Detail::Footprint),
            (ParamMode::Storage, Detail::Footprint),
        ] {
            let options = CompileOptions {
                params: mode,
                detail,
            };
            if let Err(CompileError::Validation(error)) = compile(&graph, &options) {
                panic!("{}: naga rejected a checked graph: {error}", path.display());
            }
        }
    }
}

/// A mesh and sources the geodesic target once hung or ran out of memory on.
#[derive(serde::Deserialize)]
struct GeodesicFinding {
    positions: Vec<[f32; 3]>,
    indices: Vec<u32>,
    sources: Vec<u32>,
}

#[test]
fn meshes_that_hung_a_geodesic_method_give_fields_without_nan() {
    use veneer::geodesic::{HeatOptions, Method, distances};
    for path in findings("geodesic") {
        let text = std::fs::read_to_string(&path).expect("finding");
        let finding: GeodesicFinding = serde_json::from_str(&text).expect("finding parses");
        let mesh = veneer::mesh::Mesh::from_triangles(finding.positions, finding.indices);
        for method in [
            Method::Heat(HeatOptions::default()),
            Method::Heat(HeatOptions {
                robust: true,
                ..HeatOptions::default()
            }),
            Method::Exact,
            Method::Dijkstra,
        ] {
            let Ok(field) = distances(&mesh, &finding.sources, method, |_, _| {}) else {
                continue;
            };
            assert!(
                field.iter().all(|d| *d >= 0.0),
                "{path:?} {}: {field:?}",
                method.name()
            );
            assert!(
                finding.sources.iter().all(|&s| field[s as usize] == 0.0),
                "{path:?}"
            );
        }
    }
}
