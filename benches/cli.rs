//! What the user waits for at the command line: `veneer render`, `bake` and `geodesic`
//! run end to end as processes (start-up, device, loading, compiling, drawing, writing),
//! each beside a baseline in the same run — the same command on a one-node material
//! (a constant colour: what the process costs before any material work), and for
//! distances the edge-path method, which does next to nothing but read the mesh.
//!
//! `cargo bench --bench cli`

use criterion::{Criterion, criterion_group, criterion_main};
use std::path::{Path, PathBuf};
use std::process::Command;

const GRAPHS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/graphs");

/// A material node with a constant albedo and nothing else.
const CONSTANT: &str = r#"(
    version: 1,
    name: "constant",
    nodes: [(id: 1, label: "material", kind: Material, inputs: {"albedo": Color(0.5, 0.4, 0.3)}, position: (0.0, 0.0))],
)"#;

/// Runs `veneer args` and panics with its stderr unless it succeeds.
fn veneer(args: &[&str]) {
    let output = Command::new(env!("CARGO_BIN_EXE_veneer"))
        .args(args)
        .output()
        .expect("veneer runs");
    assert!(
        output.status.success(),
        "veneer {args:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
}

fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("veneer-cli-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch folder");
    std::fs::write(dir.join("constant.ron"), CONSTANT).expect("baseline graph");
    dir
}

fn path(dir: &Path, name: &str) -> String {
    dir.join(name).to_string_lossy().into_owned()
}

fn render(c: &mut Criterion) {
    let dir = scratch();
    let out = path(&dir, "out.png");
    let mut group = c.benchmark_group("veneer render, 512² on the preview mesh, whole process");
    group.sample_size(10);
    for (label, graph) in [
        ("baseline: constant material", path(&dir, "constant.ron")),
        ("wood", format!("{GRAPHS}/wood.ron")),
        ("marble", format!("{GRAPHS}/marble.ron")),
        (
            "thesis C.2 (a heat field solved first)",
            format!("{GRAPHS}/thesis_c2_sand_water.ron"),
        ),
    ] {
        group.bench_function(label, |b| {
            b.iter(|| veneer(&["render", &graph, "--size", "512", "-o", &out]))
        });
    }
    group.finish();
}

fn bake(c: &mut Criterion) {
    let dir = scratch();
    let out = path(&dir, "maps");
    std::fs::create_dir_all(&out).expect("bake folder");
    let mut group =
        c.benchmark_group("veneer bake, 2048² albedo, normal and height PNG, whole process");
    group.sample_size(10);
    for (label, graph) in [
        ("baseline: constant material", path(&dir, "constant.ron")),
        ("marble", format!("{GRAPHS}/marble.ron")),
    ] {
        group.bench_function(label, |b| {
            b.iter(|| {
                veneer(&[
                    "bake",
                    &graph,
                    "--size",
                    "2048",
                    "--maps",
                    "albedo,normal,height",
                    "-o",
                    &out,
                ])
            })
        });
    }
    group.finish();
}

fn geodesic(c: &mut Criterion) {
    let dir = scratch();
    let mesh = path(&dir, "torus160.obj");
    veneer(&["mesh", "torus:160", "--weld", "1e-6", "--write", &mesh]);
    let out = path(&dir, "field.csv");
    let mut group =
        c.benchmark_group("veneer geodesic, torus:160 (102,400 triangles) from OBJ, whole process");
    group.sample_size(10);
    for (label, method) in [("baseline: dijkstra", "dijkstra"), ("heat", "heat")] {
        group.bench_function(label, |b| {
            b.iter(|| {
                veneer(&[
                    "geodesic",
                    &mesh,
                    "--sources",
                    "0",
                    "--method",
                    method,
                    "-o",
                    &out,
                ])
            })
        });
    }
    group.finish();
}

criterion_group!(benches, render, bake, geodesic);
criterion_main!(benches);
