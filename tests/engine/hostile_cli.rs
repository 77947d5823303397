//! Hostile command lines (issue: no crash, no hang, no silent wrong result): sizes past
//! the device's limits, full and closed standard streams, counts that would allocate
//! without bound, values that used to give uniform images or wrong fields with exit 0,
//! outputs that would replace each other, and usage errors with the documented codes.

use crate::support::{gpu, root, run_veneer, temp_dir, veneer};
use std::io::Read;
use std::process::{Output, Stdio};
use std::time::{Duration, Instant};
use veneer::render::{GpuContext, MeshRenderer, MeshView};

/// The command's stderr as text.
fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// Asserts a refusal: exit `code`, a message containing `expected`, no panic.
fn assert_refused(output: &Output, code: i32, expected: &str) {
    let message = stderr(output);
    assert_eq!(output.status.code(), Some(code), "{message}");
    assert!(
        message.contains(expected),
        "expected '{expected}' in: {message}"
    );
    assert!(!message.contains("panicked"), "{message}");
}

/// A copy of a preset with one piece of its text replaced, in `dir`.
fn edited_preset(dir: &std::path::Path, preset: &str, from: &str, to: &str) -> String {
    let text = std::fs::read_to_string(root(&format!("graphs/{preset}.ron"))).expect("preset");
    assert!(text.contains(from), "{preset} has no '{from}'");
    let path = dir.join(format!("{preset}.ron"));
    std::fs::write(&path, text.replacen(from, to, 1)).expect("written");
    path.to_string_lossy().into_owned()
}

#[test]
fn a_full_stdout_or_stderr_is_an_error_not_a_panic() {
    let full = || {
        std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .expect("/dev/full")
    };
    let output = veneer()
        .args(["mesh", "torus"])
        .stdout(full())
        .output()
        .expect("runs");
    assert_refused(&output, 1, "cannot write to stdout");
    let output = veneer()
        .args(["check", "tests/missing.ron"])
        .current_dir(root(""))
        .stderr(full())
        .output()
        .expect("runs");
    assert_eq!(output.status.code(), Some(1));
}

#[test]
fn a_closed_pipe_ends_the_command_quietly() {
    // 80,000 lines of CSV: far more than a pipe holds, so the write meets the closed end.
    let mut child = veneer()
        .args([
            "geodesic",
            "torus:200",
            "--sources",
            "0",
            "--method",
            "dijkstra",
            "-o",
            "-",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("runs");
    let mut first = [0u8; 1];
    child
        .stdout
        .take()
        .expect("piped")
        .read_exact(&mut first)
        .expect("one byte");
    let output = child.wait_with_output().expect("finishes");
    let message = stderr(&output);
    assert_eq!(output.status.code(), Some(0), "{message}");
    assert!(
        !message.contains("panicked") && !message.contains("Broken pipe"),
        "{message}"
    );
}

#[test]
fn counts_from_the_command_line_are_bounded_before_anything_is_allocated() {
    let started = Instant::now();
    let output = run_veneer(&[
        "report",
        "--quick",
        "--repetitions",
        "4294967295",
        "-o",
        "target/never-report",
    ]);
    assert_refused(&output, 1, "--repetitions 4294967295: expected 1 to 1000");
    assert!(started.elapsed() < Duration::from_secs(10));
}

#[test]
fn heat_time_factors_that_give_wrong_fields_are_refused() {
    let csv = temp_dir("time-factor").join("field.csv");
    for factor in ["0", "1e30", "-1", "NaN"] {
        let output = run_veneer(&[
            "geodesic",
            "torus",
            "--sources",
            "0",
            &format!("--time-factor={factor}"),
            "-o",
            &csv.to_string_lossy(),
        ]);
        assert_refused(&output, 1, "is outside 1e-3 to 1e6");
        assert!(!csv.exists(), "{factor} wrote a field");
    }
}

#[test]
fn check_refuses_what_render_would_refuse_or_draw_uniform() {
    let dir = temp_dir("check-preview");
    let cases = [
        ("wood", "size: 9.0", "size: NaN", "preview size NaN"),
        ("wood", "center: (31.0", "center: (inf", "preview center"),
        (
            "sand_water",
            "sources: [29039]",
            "sources: [99999999]",
            "source vertex 99999999 does not exist",
        ),
        (
            "sand_water",
            "time_factor: 1.0",
            "time_factor: 1e30",
            "preview field 0: time factor",
        ),
    ];
    for (preset, from, to, expected) in cases {
        let graph = edited_preset(&dir, preset, from, to);
        assert_refused(&run_veneer(&["check", &graph]), 1, expected);
        let png = dir.join("never.png");
        let output = run_veneer(&[
            "render",
            &graph,
            "--size",
            "16",
            "-o",
            &png.to_string_lossy(),
        ]);
        assert_eq!(output.status.code(), Some(1), "{to}: {}", stderr(&output));
        assert!(!png.exists());
    }
}

#[test]
fn times_that_are_not_finite_are_refused() {
    for time in ["inf", "NaN", "-inf"] {
        let output = run_veneer(&[
            "render",
            "graphs/wood.ron",
            "--time",
            time,
            "--size",
            "8",
            "-o",
            "target/never.png",
        ]);
        assert_refused(&output, 1, "the time must be a finite number of seconds");
    }
}

#[test]
fn flat_rectangles_beyond_f32_are_refused() {
    for rect in ["0,0,1e39,50,0.5", "-3e38,0,3e38,1,0", "0,0,1,1,inf"] {
        let output = run_veneer(&[
            "render",
            "graphs/wood.ron",
            "--flat",
            rect,
            "--size",
            "8",
            "-o",
            "target/never.png",
        ]);
        assert_refused(&output, 1, "f32");
    }
}

#[test]
fn baking_into_a_mesh_without_uvs_bakes_into_an_atlas() {
    let dir = temp_dir("no-uvs");
    let mesh = dir.join("no_uvs.obj");
    std::fs::write(
        &mesh,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    )
    .expect("written");
    let output = run_veneer(&[
        "bake",
        "graphs/wood.ron",
        "--size",
        "64",
        "--mesh",
        &mesh.to_string_lossy(),
        "-o",
        &dir.to_string_lossy(),
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    // Four charts, one per face of the tetrahedron, with the background between them.
    let albedo = image::open(dir.join("wood_albedo.png"))
        .expect("a PNG")
        .to_rgb8();
    let black = albedo.pixels().filter(|p| p.0 == [0, 0, 0]).count();
    assert!(black > 0 && black < 64 * 64 / 2, "{black} black texels");
}

#[test]
fn bake_outputs_are_checked_before_any_rendering() {
    let dir = temp_dir("bake-outputs");
    for sub in ["a", "b"] {
        std::fs::create_dir_all(dir.join(sub)).expect("folder");
        std::fs::copy(root("graphs/marble.ron"), dir.join(sub).join("x.ron")).expect("copied");
    }
    let out = dir.join("out");
    std::fs::create_dir_all(&out).expect("folder");
    let (a, b) = (dir.join("a/x.ron"), dir.join("b/x.ron"));
    let started = Instant::now();
    let output = run_veneer(&[
        "bake",
        &a.to_string_lossy(),
        &b.to_string_lossy(),
        "--size",
        "8192",
        "-o",
        &out.to_string_lossy(),
    ]);
    assert_refused(&output, 1, "would write this file");
    assert_eq!(std::fs::read_dir(&out).expect("listed").count(), 0);
    let missing = dir.join("no such folder");
    let output = run_veneer(&[
        "bake",
        &a.to_string_lossy(),
        "--size",
        "8192",
        "-o",
        &missing.to_string_lossy(),
    ]);
    assert_refused(&output, 1, "does not exist; nothing was baked");
    // Bakes stream to disk with bounded memory: the disk is what bounds a huge EXR
    // (200,000² × 3 maps × 16 bytes: 1.7 TiB).
    let output = run_veneer(&[
        "bake",
        &a.to_string_lossy(),
        "--size",
        "200000",
        "--format",
        "exr",
        "-o",
        &out.to_string_lossy(),
    ]);
    assert_refused(&output, 1, "its disk has");
    assert_eq!(std::fs::read_dir(&out).expect("listed").count(), 0);
    // Refused before loading the GPU or rendering an 8192² map.
    assert!(
        started.elapsed() < Duration::from_secs(5),
        "{:?}",
        started.elapsed()
    );
}

#[test]
fn outputs_that_name_folders_are_explained() {
    let dir = temp_dir("folder-outputs");
    let slash = format!("{}/", dir.join("sub").display());
    let output = run_veneer(&["compile", "graphs/wood.ron", "-o", &slash]);
    assert_refused(&output, 1, "is a folder; give the output a file name");
    let file = dir.join("golden.png");
    std::fs::write(&file, b"not a folder").expect("written");
    let output = run_veneer(&[
        "snapshot",
        "graphs/wood.ron",
        "--golden",
        &file.to_string_lossy(),
    ]);
    assert_refused(
        &output,
        2,
        "is a file; it takes the folder of golden images",
    );
}

#[test]
fn usage_errors_exit_with_the_documented_codes() {
    assert_refused(&run_veneer(&["render", "graphs/wood.ron"]), 1, "--output");
    let exr = temp_dir("render-exr").join("wood.exr");
    let exr = exr.to_string_lossy();
    assert_refused(
        &run_veneer(&["render", "graphs/wood.ron", "-o", &exr]),
        1,
        "render writes PNG images, not .exr; name the output .png",
    );
    assert!(!std::path::Path::new(exr.as_ref()).exists());
    assert_refused(
        &run_veneer(&["no-such-command"]),
        1,
        "unrecognized subcommand",
    );
    assert_refused(&run_veneer(&["snapshot", "graphs/wood.ron"]), 2, "--golden");
    let help = run_veneer(&["--help"]);
    assert_eq!(help.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&help.stdout).contains("Usage"));
}

#[test]
fn mesh_views_past_the_readback_limit_render_in_tiles() {
    // A readback of 8193² RGBA passes the 256 MiB buffer limit.
    let png = temp_dir("big-mesh-view").join("view.png");
    let output = run_veneer(&[
        "render",
        "graphs/marble.ron",
        "--size",
        "8193",
        "-o",
        &png.to_string_lossy(),
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let image = image::open(&png).expect("a PNG");
    assert_eq!((image.width(), image.height()), (8193, 8193));
}

#[test]
fn meshes_past_the_buffer_limit_are_drawn_in_parts() {
    // A device whose largest buffer holds 1,000 vertices of 48 bytes: torus:64 (8,385
    // vertices) goes up in nine or more parts, and must look as it does in one.
    let small = GpuContext::with_limits(|limits| wgpu::Limits {
        max_buffer_size: 48_000,
        ..limits
    })
    .expect("a device with a small buffer limit");
    let graph = veneer::graph::load(&root("graphs/marble.ron")).expect("preset");
    let module = veneer::codegen::compile(&graph, &Default::default())
        .expect("compiles")
        .module;
    let mesh = veneer::mesh::preview_mesh("torus:64").expect("mesh");
    let view = MeshView::for_preview(&graph.preview);
    let render = |gpu: &GpuContext| {
        MeshRenderer::new(gpu, &module.source, module.uses)
            .expect("pipeline")
            .render(gpu, &mesh, &view, 128)
            .expect("renders")
    };
    let whole = render(gpu());
    let shaded = whole.iter().filter(|p| **p != whole[0]).count();
    assert!(
        shaded * 4 > whole.len(),
        "the torus covers a quarter of the view"
    );
    assert_nearly_equal(&render(&small), &whole);
}

/// Asserts that two renders of one view agree but for rounding at triangle edges: at
/// most 0.1% of pixels off by more than 2/255.
fn assert_nearly_equal(a: &[[u8; 4]], b: &[[u8; 4]]) {
    assert_eq!(a.len(), b.len());
    let differing = a
        .iter()
        .zip(b)
        .filter(|(p, q)| p.iter().zip(q.iter()).any(|(x, y)| x.abs_diff(*y) > 2))
        .count();
    assert!(
        differing * 1000 <= a.len(),
        "{differing} of {} pixels differ",
        a.len()
    );
}

#[test]
fn tiled_mesh_renders_match_whole_ones() {
    let graph = veneer::graph::load(&root("graphs/wood.ron")).expect("preset");
    let module = veneer::codegen::compile(&graph, &Default::default())
        .expect("compiles")
        .module;
    let renderer = MeshRenderer::new(gpu(), &module.source, module.uses).expect("pipeline");
    let mesh = veneer::mesh::preview_mesh(&graph.preview.mesh).expect("mesh");
    let view = MeshView::for_preview(&graph.preview);
    let whole = renderer
        .render_in_tiles(gpu(), &mesh, &view, 300, 300)
        .expect("renders");
    // Uneven tiles: 97, 97, 97 and 9 pixels a side.
    let tiled = renderer
        .render_in_tiles(gpu(), &mesh, &view, 300, 97)
        .expect("renders");
    assert_nearly_equal(&whole, &tiled);
}
