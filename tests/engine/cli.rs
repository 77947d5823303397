//! The `veneer` binary: bad input exits 1 with a message naming the file position or the
//! node, never panics; good input works as DESIGN.md's CLI contract says.

use crate::support::run_veneer;
use std::process::Output;

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// Runs `veneer check` on a bad file and returns its message, asserting exit code 1.
fn check_fails(file: &str) -> String {
    let output = run_veneer(&["check", file]);
    assert_eq!(output.status.code(), Some(1), "{file}: {}", stderr(&output));
    let message = stderr(&output);
    assert!(!message.contains("panicked"), "{file} panicked: {message}");
    message
}

#[test]
fn malformed_ron_names_line_and_column() {
    let message = check_fails("tests/bad/malformed.ron");
    assert!(
        message.contains("tests/bad/malformed.ron:6:5:"),
        "{message}"
    );
}

#[test]
fn unknown_node_kind_names_line_and_column() {
    let message = check_fails("tests/bad/unknown_node.ron");
    assert!(
        message.contains("tests/bad/unknown_node.ron:5:"),
        "{message}"
    );
    assert!(message.contains("Swirl"), "{message}");
}

#[test]
fn cycle_names_its_nodes() {
    let message = check_fails("tests/bad/cycle.ron");
    assert!(message.contains("cycle"), "{message}");
    assert!(
        message.contains("'left'") && message.contains("'right'"),
        "{message}"
    );
}

#[test]
fn type_mismatch_names_the_node_and_types() {
    let message = check_fails("tests/bad/type_mismatch.ron");
    assert!(message.contains("node 'material' (#2)"), "{message}");
    assert!(
        message.contains("expects color") && message.contains("gives vec2"),
        "{message}"
    );
}

#[test]
fn check_passes_on_every_preset() {
    let mut args = vec!["check".to_string()];
    args.extend(
        crate::support::presets()
            .iter()
            .map(|p| p.display().to_string()),
    );
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let output = run_veneer(&args);
    assert!(output.status.success(), "{}", stderr(&output));
}

#[test]
fn compile_prints_validated_wgsl_with_the_contract() {
    let output = run_veneer(&["compile", "graphs/marble.ron"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let wgsl = String::from_utf8(output.stdout).expect("utf-8");
    assert!(wgsl.contains("struct VeneerSurface {") && wgsl.contains("struct VeneerMaterial {"));
    assert!(wgsl.contains("fn veneer_material(s: VeneerSurface) -> VeneerMaterial {"));
}

#[test]
fn render_writes_a_flat_png_of_the_requested_size() {
    let dir = std::env::temp_dir().join(format!("veneer-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let out = dir.join("wood.png");
    let out_arg = out.display().to_string();
    let output = run_veneer(&[
        "render",
        "graphs/wood.ron",
        "--flat",
        "0,0,50,50,0.5",
        "--size",
        "32",
        "-o",
        &out_arg,
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let image = image::open(&out).expect("a PNG");
    assert_eq!((image.width(), image.height()), (32, 32));
}

#[test]
fn bad_render_arguments_exit_1_without_writing() {
    let output = run_veneer(&[
        "render",
        "graphs/wood.ron",
        "--mesh",
        "teapot",
        "-o",
        "/nonexistent/x.png",
    ]);
    assert_eq!(output.status.code(), Some(1));
    assert!(
        stderr(&output).contains("teapot: unknown mesh"),
        "{}",
        stderr(&output)
    );
}
