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
