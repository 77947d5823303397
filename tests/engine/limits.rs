//! Inputs past the machine's limits: images larger than memory or the adapter allows,
//! meshes of a million triangles, primitives whose detail would take hours. Each gets a
//! clear message and exit code 1 or works; none runs out of memory or hangs.

use crate::support::{run_veneer, temp_dir};
use std::process::Output;

/// Asserts exit code 1 with a message containing every one of `words`.
fn refused(output: &Output, words: &[&str]) {
    let message = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{message}");
    assert!(!message.contains("panicked"), "{message}");
    for word in words {
        assert!(message.contains(word), "'{word}' not in: {message}");
    }
}

#[test]
fn images_larger_than_memory_are_refused_before_any_work() {
    let dir = temp_dir("huge-images");
    let png = dir.join("huge.png");
    let png = png.to_str().expect("utf-8 path");
    // 200,000² pixels of four f32 are 596 GiB: no machine here has that.
    let flat = run_veneer(&[
        "render",
        "graphs/wood.ron",
        "--flat",
        "-1,-1,1,1,0",
        "--size",
        "200000",
        "-o",
        png,
    ]);
    refused(
        &flat,
        &["200000×200000 image needs about", "GiB", "smaller size"],
    );
    let bake = run_veneer(&[
        "bake",
        "graphs/wood.ron",
        "--size",
        "200000",
        "-o",
        dir.to_str().unwrap(),
    ]);
    // Refused for its disk space (checked first, with the outputs) or its memory.
    refused(&bake, &["GiB"]);
    // Mesh views render in tiles: their limit is memory too.
    let mesh = run_veneer(&["render", "graphs/wood.ron", "--size", "200000", "-o", png]);
    refused(&mesh, &["200000×200000 image needs about"]);
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        0,
        "nothing written"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_million_triangle_mesh_is_analysed_and_rendered() {
    let report = run_veneer(&["mesh", "torus:512", "--json"]);
    assert!(
        report.status.success(),
        "{}",
        String::from_utf8_lossy(&report.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&report.stdout).expect("json");
    assert_eq!(json[0]["report"]["triangles"], 2 * 1024 * 512);
    let dir = temp_dir("million");
    let png = dir.join("torus.png");
    let render = run_veneer(&[
        "render",
        "graphs/wood.ron",
        "--mesh",
        "torus:512",
        "--size",
        "128",
        "-o",
        png.to_str().unwrap(),
    ]);
    assert!(
        render.status.success(),
        "{}",
        String::from_utf8_lossy(&render.stderr)
    );
    assert_eq!(image::open(&png).expect("png").width(), 128);
    std::fs::remove_dir_all(&dir).unwrap();
}
