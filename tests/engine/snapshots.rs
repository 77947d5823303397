//! `veneer snapshot` and `veneer::snapshot`: a changed graph fails with a diff image and an
//! explanation, exit codes are 0/1/2, and time-dependent graphs render at the given time.

use crate::support::{gpu, root, snapshot_folder};
use std::path::{Path, PathBuf};
use std::process::Command;
use veneer::graph::{NodeKind, Value};
use veneer::render::{View, render_material};
use veneer::snapshot::{Outcome, Settings, beside, check};

/// A scratch folder holding a copy of marble.ron and its golden and sidecar.
fn scratch_with_marble(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("veneer-snapshot-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("golden")).expect("scratch folder");
    std::fs::copy(root("graphs/marble.ron"), dir.join("marble.ron")).expect("graph copied");
    for file in ["marble.png", "marble.snap.ron"] {
        std::fs::copy(snapshot_folder().join(file), dir.join("golden").join(file))
            .expect("golden copied");
    }
    dir
}

fn change_marble(path: &Path) {
    let mut graph = veneer::graph::load(path).expect("marble loads");
    veneer::graph::parameters::set(
        &mut graph,
        "vein_frequency",
        &veneer::graph::parameters::Given::Number(4.0),
    )
    .expect("marble exposes its vein frequency");
    veneer::graph::save(&graph, path).expect("saved");
}

fn snapshot_cli(dir: &Path, extra: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_veneer"))
        .current_dir(dir)
        .args(["snapshot", "marble.ron", "--golden", "golden"])
        .args(extra)
        .env_remove(veneer::snapshot::UPDATE_VARIABLE)
        .output()
        .expect("veneer runs")
}

#[test]
fn an_unchanged_graph_passes_and_a_changed_one_exits_1_naming_it_with_a_diff() {
    let dir = scratch_with_marble("cli");
    let output = snapshot_cli(&dir, &[]);
    assert_eq!(
        output.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&output.stdout)
    );
    change_marble(&dir.join("marble.ron"));
    let output = snapshot_cli(&dir, &[]);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert_eq!(output.status.code(), Some(1), "{stdout}");
    assert!(stdout.contains("marble.ron: DIFFERS"), "{stdout}");
    assert!(
        stdout.contains("the graph changed since the golden was made"),
        "{stdout}"
    );
    assert!(stdout.contains("PSNR"), "{stdout}");
    assert!(
        dir.join("golden/marble.diff.png").exists()
            && dir.join("golden/marble.actual.png").exists()
    );
    let output = snapshot_cli(&dir, &["--json"]);
    let summary: serde_json::Value =
        serde_json::from_slice(&output.stdout).expect("JSON on stdout");
    assert_eq!(summary[0]["status"], "differs");
    assert!(summary[0]["share_outside"].as_f64().unwrap() > 0.0);
    // A failing run says why on stderr, with --json too (the contract: no silent exit 1).
    assert_eq!(output.status.code(), Some(1));
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(message.contains("1 of 1 snapshots differ"), "{message}");
    let output = snapshot_cli(&dir, &["--update"]);
    assert_eq!(output.status.code(), Some(0));
    assert!(
        !dir.join("golden/marble.diff.png").exists(),
        "approving removes the leftovers"
    );
    assert_eq!(snapshot_cli(&dir, &[]).status.code(), Some(0));
}

#[test]
fn bad_input_exits_2() {
    let dir = scratch_with_marble("bad");
    std::fs::write(dir.join("marble.ron"), "(version: 1, nodes: [").expect("broken file");
    assert_eq!(snapshot_cli(&dir, &[]).status.code(), Some(2));
    let dir = scratch_with_marble("tolerance");
    assert_eq!(
        snapshot_cli(&dir, &["--tolerance", "share=7"])
            .status
            .code(),
        Some(2)
    );
}

#[test]
fn the_library_explains_a_missing_golden_and_writes_the_actual_render() {
    let dir = scratch_with_marble("missing");
    let golden = dir.join("golden/absent.png");
    let report = check(
        gpu(),
        &dir.join("marble.ron"),
        &golden,
        &Settings::default(),
        false,
    )
    .expect("runs");
    match report.outcome {
        Outcome::Mismatched { reasons, .. } => {
            assert!(reasons[0].contains("no golden"), "{reasons:?}")
        }
        other => panic!("expected a mismatch, got {other:?}"),
    }
    assert!(beside(&golden, "actual.png").exists());
}

#[test]
fn time_dependent_graphs_render_at_the_given_time() {
    let mut graph = veneer::graph::Graph::default();
    let time = graph.add("time", NodeKind::Time);
    let wave = graph.add("wave", NodeKind::SineBand);
    graph.connect(time, "time", wave, "x");
    graph.set_input(wave, "frequency", Value::Float(3.0));
    let material = graph.add("material", NodeKind::Material);
    graph.connect(wave, "band", material, "albedo");
    let compiled = veneer::codegen::compile(&graph, &Default::default()).expect("compiles");
    let render = |t| {
        render_material(gpu(), &compiled, &View::PreviewFlat, 16, t)
            .expect("renders")
            .pixels
    };
    assert_eq!(render(0.25), render(0.25));
    assert_ne!(render(0.25), render(0.75));
    let expected = (255.0 * (0.5 + 0.5 * (3.0f32 * 0.75).sin())).round() as u8;
    assert!(render(0.75).iter().all(|&v| v.abs_diff(expected) <= 1));
}

/// `veneer snapshot` of `graphs` against `golden` on GL (`extra` arguments after), as on
/// a machine without Vulkan.
fn snapshot_on_gl(graphs: &[&str], golden: &str, extra: &[&str]) -> String {
    let output = crate::support::veneer()
        .current_dir(root(""))
        .arg("snapshot")
        .args(graphs)
        .args(["--golden", golden, "--json"])
        .args(extra)
        .env("WGPU_BACKEND", "gl")
        .env_remove("MESA_EXTENSION_OVERRIDE")
        .env_remove(veneer::snapshot::UPDATE_VARIABLE)
        .output()
        .expect("veneer runs");
    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
    assert!(
        output.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    stdout
}

/// On a machine with only GL, `veneer snapshot graphs/*.ron --golden tests/snapshots`
/// passes: GL reads its own copies where the sine hash's bits differ (`llvmpipe-gl/`),
/// and the shared goldens elsewhere.
#[test]
fn the_cli_passes_the_shipped_goldens_on_gl() {
    let stdout = snapshot_on_gl(
        &["graphs/wood.ron", "graphs/wood_classic.ron"],
        "tests/snapshots",
        &[],
    );
    assert!(
        stdout.contains("llvmpipe-gl/wood.png"),
        "wood read GL's own golden: {stdout}"
    );
    assert!(
        stdout.contains("tests/snapshots/wood_classic.png"),
        "wood_classic read the shared golden: {stdout}"
    );
}

/// The texture graphs (float buffers) on GL too (the binary names Mesa's float render
/// targets for wgpu, gfx-rs/wgpu#2838): on their mesh and flat; the samplers' placements
/// round differently there, so pebbles and fish scales keep GL copies.
#[test]
fn the_texture_graphs_pass_their_goldens_on_gl() {
    let graphs: Vec<String> = crate::support::texture_graphs()
        .iter()
        .map(|path| path.display().to_string())
        .collect();
    let graphs: Vec<&str> = graphs.iter().map(String::as_str).collect();
    snapshot_on_gl(&graphs, "tests/snapshots/texture", &[]);
    let flat = snapshot_on_gl(
        &graphs,
        "tests/snapshots/texture/flat",
        &["--flat", "preview"],
    );
    assert!(flat.contains("flat/llvmpipe-gl/pebbles.png"), "{flat}");
}
