//! Mesh files: every format loads with outward triangles and unit normals, broken files
//! are errors naming the file, and `veneer render --mesh FILE` draws them.

use crate::support::root;
use veneer::mesh::load;

#[test]
fn every_format_loads_closed_outward_meshes_with_unit_normals() {
    // A regular tetrahedron of edge 2√2 has volume 8/3; the cube of side 2 has 8.
    for (file, triangles, volume) in [
        ("tetrahedron.obj", 4, 8.0 / 3.0),
        ("tetrahedron.stl", 4, 8.0 / 3.0),
        ("tetrahedron.gltf", 4, 8.0 / 3.0),
        ("cube_quads.ply", 12, 8.0),
    ] {
        let mesh = load(&root(&format!("tests/meshes/{file}"))).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(mesh.triangle_count(), triangles, "{file}");
        assert!(
            (mesh.signed_volume() - volume).abs() < 1e-4,
            "{file}: volume {}",
            mesh.signed_volume()
        );
        assert!(
            mesh.normals
                .iter()
                .all(|n| (glam::Vec3::from(*n).length() - 1.0).abs() < 1e-5),
            "{file}"
        );
    }
}

#[test]
fn gltf_node_transforms_are_applied_and_fitting_undoes_them() {
    let mesh = load(&root("tests/meshes/tetrahedron.gltf")).expect("loads");
    let mean_x = mesh.positions.iter().map(|p| p[0]).sum::<f32>() / mesh.positions.len() as f32;
    assert!(
        (mean_x - 5.0).abs() < 1e-5,
        "the node's translation moves it to x = 5"
    );
    let fitted = mesh.fitted_to_unit_sphere();
    let radius = fitted
        .positions
        .iter()
        .map(|p| glam::Vec3::from(*p).length())
        .fold(0.0f32, f32::max);
    assert!((radius - 1.0).abs() < 1e-5);
}

#[test]
fn broken_files_are_errors_that_name_the_file() {
    for (file, expected) in [
        (
            "bad_index.obj",
            "line 4: a face refers to vertex 9, but the file has 3",
        ),
        ("truncated.stl", ""),
        ("missing.obj", ""),
        ("tetrahedron.xyz", "unknown mesh format 'xyz'"),
    ] {
        let path = root(&format!("tests/meshes/{file}"));
        let error = load(&path).expect_err(file).to_string();
        assert!(error.starts_with(&path.display().to_string()), "{error}");
        assert!(error.contains(expected), "{error}");
    }
}

/// `veneer render graphs/marble.ron --mesh mesh` into `out`.
fn render_mesh(mesh: &std::path::Path, out: &std::path::Path) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_veneer"))
        .current_dir(root(""))
        .args(["render", "graphs/marble.ron", "--size", "64", "--mesh"])
        .arg(mesh)
        .arg("-o")
        .arg(out)
        .output()
        .expect("veneer runs")
}

#[test]
fn render_draws_a_mesh_file() {
    let dir = std::env::temp_dir().join(format!("veneer-mesh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let out = dir.join("tetra.png");
    assert!(
        render_mesh(&root("tests/meshes/tetrahedron.obj"), &out)
            .status
            .success()
    );
    let image = image::open(&out).expect("a PNG").to_rgba8();
    let background = *image.get_pixel(0, 0);
    assert!(
        image.pixels().filter(|p| **p != background).count() > 500,
        "the tetrahedron covers the middle"
    );
}

/// The tetrahedron scaled to the ends of the f32 range (coordinates ±3e38, or ±1e-40,
/// below the smallest normal f32) renders as the tetrahedron does: fitting to the unit
/// sphere works in f64 (before: an empty image, exit 0). A mesh whose vertices all
/// coincide is refused, naming the file, rather than drawn as nothing.
#[test]
fn render_fits_meshes_at_the_ends_of_the_f32_range_and_refuses_one_with_no_extent() {
    let dir = std::env::temp_dir().join(format!("veneer-mesh-range-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let original = std::fs::read_to_string(root("tests/meshes/tetrahedron.obj")).expect("reads");
    let scaled = |factor: f64| {
        original
            .lines()
            .map(|line| match line.strip_prefix("v ") {
                Some(coordinates) => {
                    let scaled: Vec<String> = coordinates
                        .split_whitespace()
                        .map(|c| format!("{:e}", c.parse::<f64>().expect("a number") * factor))
                        .collect();
                    format!("v {}", scaled.join(" "))
                }
                None => line.to_string(),
            })
            .collect::<Vec<_>>()
            .join("\n")
    };
    let reference = dir.join("reference.png");
    assert!(
        render_mesh(&root("tests/meshes/tetrahedron.obj"), &reference)
            .status
            .success()
    );
    let reference = image::open(&reference).expect("a PNG").to_rgb8().into_raw();
    for (name, factor) in [("huge", 3.0e38), ("tiny", 1.0e-40)] {
        let mesh = dir.join(format!("{name}.obj"));
        std::fs::write(&mesh, scaled(factor)).expect("written");
        let out = dir.join(format!("{name}.png"));
        let output = render_mesh(&mesh, &out);
        assert!(
            output.status.success(),
            "{}",
            String::from_utf8_lossy(&output.stderr)
        );
        let image = image::open(&out).expect("a PNG").to_rgb8().into_raw();
        let diff = crate::support::difference(&image, &reference, 3, 2);
        assert!(diff.share_outside < 0.01, "{name}: {diff}");
        let report = std::process::Command::new(env!("CARGO_BIN_EXE_veneer"))
            .args(["mesh"])
            .arg(&mesh)
            .output()
            .expect("veneer runs");
        let report = String::from_utf8_lossy(&report.stdout);
        assert!(
            report.contains("4 triangles, 0 degenerate"),
            "{name}: {report}"
        );
    }
    let point = dir.join("point.obj");
    std::fs::write(&point, "v 1e-40 0 0\nv 1e-40 0 0\nv 1e-40 0 0\nf 1 2 3\n").expect("written");
    let out = dir.join("point.png");
    let output = render_mesh(&point, &out);
    let message = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{message}");
    assert!(
        message.contains("point.obj") && message.contains("no area"),
        "{message}"
    );
    assert!(!out.exists(), "nothing is written");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_mesh_command_reports_defects_before_and_after_welding() {
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_veneer"))
        .current_dir(root(""))
        .args(["mesh", "tests/meshes/cube_quads.ply", "--weld", "0.001"])
        .output()
        .expect("veneer runs");
    assert!(output.status.success());
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("8 vertices, 12 triangles, 0 degenerate, 0 boundary edges, 0 non-manifold edges, 1 components"), "{stdout}");
    let bad = std::process::Command::new(env!("CARGO_BIN_EXE_veneer"))
        .current_dir(root(""))
        .args(["mesh", "tests/meshes/truncated.stl"])
        .output()
        .expect("veneer runs");
    assert_eq!(bad.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("truncated.stl"));
}

#[test]
fn geodesic_writes_one_distance_per_file_vertex_with_inf_where_unreached() {
    let dir = std::env::temp_dir().join(format!("veneer-geodesic-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("folder");
    // Two tetrahedra apart: the second is never reached from vertex 0 of the first.
    let tetrahedron =
        std::fs::read_to_string(root("tests/meshes/tetrahedron.obj")).expect("fixture");
    let moved: String = tetrahedron
        .lines()
        .filter(|l| l.starts_with("v "))
        .map(|l| {
            let c: Vec<f32> = l[2..]
                .split_whitespace()
                .map(|x| x.parse().unwrap())
                .collect();
            format!("v {} {} {}\n", c[0] + 10.0, c[1], c[2])
        })
        .collect();
    let faces: String = tetrahedron
        .lines()
        .filter(|l| l.starts_with("f "))
        .map(|l| {
            let i: Vec<u32> = l[2..]
                .split_whitespace()
                .map(|x| x.parse().unwrap())
                .collect();
            format!("f {} {} {}\n", i[0] + 4, i[1] + 4, i[2] + 4)
        })
        .collect();
    let file = dir.join("two.obj");
    std::fs::write(&file, format!("{tetrahedron}{moved}{faces}")).expect("written");
    let csv = dir.join("field.csv");
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_veneer"))
        .args([
            "geodesic",
            file.to_str().unwrap(),
            "--sources",
            "0",
            "--normalize",
            "-o",
            csv.to_str().unwrap(),
        ])
        .status()
        .expect("veneer runs");
    assert!(status.success());
    let lines: Vec<String> = std::fs::read_to_string(&csv)
        .expect("csv")
        .lines()
        .map(String::from)
        .collect();
    assert_eq!(lines.len(), 8, "one line per vertex of the file");
    assert_eq!(lines[0], "0");
    let near: Vec<f64> = lines[1..4].iter().map(|l| l.parse().unwrap()).collect();
    assert!(
        near.iter().all(|&d| (d - 1.0).abs() < 1e-9),
        "every edge of a regular tetrahedron is equally long: {near:?}"
    );
    assert!(lines[4..].iter().all(|l| l == "inf"), "{lines:?}");
}
