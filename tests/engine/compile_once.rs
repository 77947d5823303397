//! `veneer render`, `bake` and `snapshot` check and emit each graph exactly once. The
//! commands run in-process through the binary's own command-line module (compiled into
//! this test, as the `cli_args` fuzz target does), and the compiler's per-thread counts
//! say how many graphs they checked and how many modules they emitted.

use crate::support::{root, temp_dir};
use std::ffi::OsString;
use veneer::codegen::counts::{self, CompileCounts};

// The CLI lives in the binary crate, not in the library.
#[allow(dead_code, unexpected_cfgs)]
#[path = "../../src/cli/mod.rs"]
mod cli;

/// Runs `veneer <args>` in-process and returns the checks and emissions it made.
fn counted(args: &[&str]) -> CompileCounts {
    let args: Vec<OsString> = std::iter::once("veneer")
        .chain(args.iter().copied())
        .map(OsString::from)
        .collect();
    let parsed = cli::parse_from(&args).expect("the command line parses");
    let before = counts::current();
    if let Err(cli::Failure(message, code)) = cli::execute(parsed) {
        panic!("{args:?} failed with exit code {code}: {message}");
    }
    counts::current() - before
}

fn path(relative: &str) -> String {
    root(relative).display().to_string()
}

fn once_each(graphs: u64) -> CompileCounts {
    CompileCounts {
        checks: graphs,
        emissions: graphs,
    }
}

#[test]
fn render_checks_and_emits_its_graph_once() {
    let dir = temp_dir("compile-once-render");
    let image = dir.join("waves.png").display().to_string();
    let mesh = [
        "render",
        &path("graphs/waves.ron"),
        "-o",
        &image,
        "--size",
        "16",
    ];
    assert_eq!(counted(&mesh), once_each(1), "on its mesh");
    let flat = [
        "render",
        &path("graphs/wood.ron"),
        "-o",
        &image,
        "--size",
        "16",
        "--flat",
        "-1,-1,1,1,0",
        "--detail",
        "footprint",
    ];
    assert_eq!(counted(&flat), once_each(1), "flat, footprint-aware");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bake_checks_and_emits_each_graph_once() {
    let dir = temp_dir("compile-once-bake");
    let out = dir.display().to_string();
    let args = [
        "bake",
        &path("graphs/wood.ron"),
        &path("graphs/marble.ron"),
        "--size",
        "16",
        "--maps",
        "albedo,normal,height",
        "-o",
        &out,
        "--json",
    ];
    assert_eq!(counted(&args), once_each(2));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn snapshot_checks_and_emits_each_graph_once() {
    let dir = temp_dir("compile-once-snapshot");
    let golden = dir.display().to_string();
    let (wood, marble) = (path("graphs/wood.ron"), path("graphs/marble.ron"));
    let update = [
        "snapshot", &wood, &marble, "--golden", &golden, "--size", "16", "--update", "--json",
    ];
    assert_eq!(counted(&update), once_each(2), "writing goldens");
    let compare = [
        "snapshot", &wood, &marble, "--golden", &golden, "--size", "16", "--json",
    ];
    assert_eq!(counted(&compare), once_each(2), "comparing with them");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn errors_tell_a_graph_error_from_a_render_failure() {
    use veneer::codegen::{CompileError, CompileOptions, ParamMode};
    use veneer::render::{RenderError, View};
    let dir = temp_dir("typed-errors");
    let error = veneer::snapshot::check(
        crate::support::gpu(),
        &root("tests/bad/cycle.ron"),
        &dir.join("cycle.png"),
        &Default::default(),
        true,
    )
    .expect_err("a cycle does not compile");
    assert!(
        matches!(
            error,
            veneer::snapshot::SnapshotError::Compile {
                error: CompileError::Check(_),
                ..
            }
        ),
        "{error:?}"
    );
    // The editor's uniform-parameter modules are refused before any GPU work.
    let graph = veneer::graph::load(&root("graphs/wood.ron")).expect("preset");
    let uniform =
        veneer::codegen::compile(&graph, &CompileOptions::with_params(ParamMode::Uniform))
            .expect("compiles");
    let render = veneer::render::render_material(
        crate::support::gpu(),
        &uniform,
        &View::PreviewFlat,
        8,
        0.0,
    );
    assert!(matches!(render, Err(RenderError::Invalid(_))), "{render:?}");
    let settings = veneer::bake::BakeSettings {
        surface: veneer::bake::BakeSurface::Plane(None),
        size: 8,
        maps: vec![veneer::bake::Map::Albedo],
        format: veneer::bake::Format::Png8,
        normal: veneer::bake::NormalConvention::OpenGl,
        time: 0.0,
    };
    let baked = veneer::bake::bake(
        crate::support::gpu(),
        &uniform,
        &settings,
        &dir.join("wood"),
        |_, _| true,
    );
    assert!(
        matches!(
            baked,
            Err(veneer::bake::BakeError::Render(RenderError::Invalid(_)))
        ),
        "{baked:?}"
    );
    assert!(!dir.join("cycle.png").exists() && !dir.join("wood_albedo.png").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
