//! Geodesic fields count vertices as the mesh file lists them: OBJ, PLY, STL and glTF
//! files whose vertices are out of first-use order, split at UV seams or used by no
//! triangle, against an independent Dijkstra over the file's own numbering and against
//! the same mesh listed in first-use order; graph fields and picking in that numbering;
//! and the plain heat method handing a dirty mesh it cannot factor to the robust one.

use crate::support::{temp_dir, veneer};
use glam::DVec3;
use std::path::{Path, PathBuf};
use veneer::geodesic::{self, HeatOptions, HeatSolver, Method, Triangulation};
use veneer::graph::FieldSource;

/// Triangles over vertices in a file's numbering (some vertices used by none).
#[derive(Clone, Debug)]
struct FileMesh {
    positions: Vec<[f32; 3]>,
    triangles: Vec<[u32; 3]>,
}

impl FileMesh {
    /// Whether a triangle uses each vertex.
    fn used(&self) -> Vec<bool> {
        let mut used = vec![false; self.positions.len()];
        for &v in self.triangles.iter().flatten() {
            used[v as usize] = true;
        }
        used
    }

    /// The first vertex a triangle uses above or below (`x`, `z`).
    fn at(&self, x: f32, z: f32) -> u32 {
        let used = self.used();
        (0..self.positions.len())
            .find(|&v| used[v] && [self.positions[v][0], self.positions[v][2]] == [x, z])
            .expect("a used vertex there") as u32
    }
}

/// A bumpy 7×7-vertex grid listed in a scrambled order, with vertices no triangle uses
/// (one on top of a used vertex), then a separate square of two triangles and a last
/// unused vertex.
fn scan() -> FileMesh {
    let n = 6;
    let grid: Vec<[f32; 3]> = (0..=n)
        .flat_map(|j| (0..=n).map(move |i| (i as f32 / n as f32, j as f32 / n as f32)))
        .map(|(x, z)| [x, 0.2 * (3.0 * x).sin() * (2.0 * z).cos(), z])
        .collect();
    let count = grid.len();
    let mut positions = Vec::new();
    let mut file_of_grid = vec![0u32; count];
    for slot in 0..count {
        // 20 is prime to 49: every grid vertex once, far from first-use order.
        let k = (slot * 20 + 7) % count;
        match slot {
            0 => positions.push([0.5, 2.0, 0.5]),
            17 => positions.push(grid[k]),
            _ => {}
        }
        file_of_grid[k] = positions.len() as u32;
        positions.push(grid[k]);
    }
    let mut triangles = Vec::new();
    let row = n + 1;
    for j in 0..n {
        for i in 0..n {
            let a = j * row + i;
            let [a, b, c, d] = [a, a + 1, a + row, a + row + 1].map(|k| file_of_grid[k]);
            triangles.extend([[a, c, b], [b, c, d]]);
        }
    }
    let base = positions.len() as u32;
    positions.extend([
        [3.0, 0.0, 0.0],
        [4.0, 0.0, 0.0],
        [3.0, 0.0, 1.0],
        [4.0, 0.5, 1.0],
    ]);
    triangles.extend([[base, base + 2, base + 1], [base + 1, base + 2, base + 3]]);
    positions.push([9.0, 9.0, 9.0]);
    FileMesh {
        positions,
        triangles,
    }
}

/// Shortest paths along the triangles' edges over the file's own numbering: 0 at the
/// sources (used or not), `inf` where no path leads.
fn dijkstra(mesh: &FileMesh, sources: &[u32]) -> Vec<f64> {
    let point = |v: u32| DVec3::from(mesh.positions[v as usize].map(f64::from));
    let mut distance = vec![f64::INFINITY; mesh.positions.len()];
    for &s in sources {
        distance[s as usize] = 0.0;
    }
    let mut settled = vec![false; distance.len()];
    while let Some(v) = (0..distance.len())
        .filter(|&v| !settled[v] && distance[v].is_finite())
        .min_by(|&a, &b| distance[a].total_cmp(&distance[b]))
    {
        settled[v] = true;
        for t in mesh.triangles.iter().filter(|t| t.contains(&(v as u32))) {
            for &w in t {
                let via = distance[v] + point(v as u32).distance(point(w));
                if via < distance[w as usize] {
                    distance[w as usize] = via;
                }
            }
        }
    }
    distance
}

/// The mesh renumbered in the order its triangles first use the vertices (unused ones
/// left out), and the new number of every vertex.
fn first_use(mesh: &FileMesh) -> (FileMesh, Vec<Option<u32>>) {
    let mut number = vec![None; mesh.positions.len()];
    let mut positions = Vec::new();
    for &v in mesh.triangles.iter().flatten() {
        number[v as usize].get_or_insert_with(|| {
            positions.push(mesh.positions[v as usize]);
            positions.len() as u32 - 1
        });
    }
    let triangles = mesh
        .triangles
        .iter()
        .map(|t| t.map(|v| number[v as usize].expect("used")))
        .collect();
    (
        FileMesh {
            positions,
            triangles,
        },
        number,
    )
}

/// OBJ text; with `seams`, every corner has a texture coordinate of its own (so every
/// corner is a vertex of its own when loaded) and every other triangle counts back
/// from the last vertex.
fn obj(mesh: &FileMesh, seams: bool) -> String {
    let mut text = String::from("# scrambled\n");
    for p in &mesh.positions {
        text += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    let count = mesh.positions.len() as i64;
    for (t, triangle) in mesh.triangles.iter().enumerate() {
        let corners: Vec<String> = (0..3)
            .map(|k| {
                let v = i64::from(triangle[k]);
                let written = if seams && t % 2 == 1 {
                    v - count
                } else {
                    v + 1
                };
                match seams {
                    true => {
                        text += &format!("vt {} {}\n", k as f32 / 3.0, t as f32 / 100.0);
                        format!("{written}/-1")
                    }
                    false => written.to_string(),
                }
            })
            .collect();
        text += &format!("f {}\n", corners.join(" "));
    }
    text
}

/// ASCII PLY text.
fn ply(mesh: &FileMesh) -> String {
    let mut text = format!(
        "ply\nformat ascii 1.0\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
        mesh.positions.len(),
        mesh.triangles.len()
    );
    for p in &mesh.positions {
        text += &format!("{} {} {}\n", p[0], p[1], p[2]);
    }
    for t in &mesh.triangles {
        text += &format!("3 {} {} {}\n", t[0], t[1], t[2]);
    }
    text
}

/// ASCII STL of the triangles, last first, and the mesh as the STL file numbers it:
/// each distinct position in the order it first appears.
fn stl(mesh: &FileMesh) -> (String, FileMesh) {
    let mut text = String::from("solid scan\n");
    let mut numbered = FileMesh {
        positions: Vec::new(),
        triangles: Vec::new(),
    };
    for t in mesh.triangles.iter().rev() {
        text += " facet normal 0 0 0\n  outer loop\n";
        let corners = t.map(|v| {
            let p = mesh.positions[v as usize];
            text += &format!("   vertex {} {} {}\n", p[0], p[1], p[2]);
            match numbered.positions.iter().position(|q| *q == p) {
                Some(k) => k as u32,
                None => {
                    numbered.positions.push(p);
                    numbered.positions.len() as u32 - 1
                }
            }
        });
        numbered.triangles.push(corners);
        text += "  endloop\n endfacet\n";
    }
    text += "endsolid scan\n";
    (text, numbered)
}

/// A GLB file with the vertices before `split` in one node's mesh and the rest in a
/// second node's (each its own POSITION accessor; no triangle may span both).
fn glb(mesh: &FileMesh, split: u32) -> Vec<u8> {
    let mut binary: Vec<u8> = Vec::new();
    let (mut accessors, mut views, mut meshes) = (Vec::new(), Vec::new(), Vec::new());
    for (part, range) in [(0, 0..split), (1, split..mesh.positions.len() as u32)] {
        let positions = &mesh.positions[range.start as usize..range.end as usize];
        let indices: Vec<u32> = mesh
            .triangles
            .iter()
            .filter(|t| range.contains(&t[0]))
            .flat_map(|t| t.map(|v| v - range.start))
            .collect();
        let [min, max] = [f32::min, f32::max].map(|pick| {
            (0..3)
                .map(|k| positions.iter().map(|p| p[k]).reduce(pick).unwrap())
                .collect::<Vec<f32>>()
        });
        for (bytes, accessor) in [
            (
                positions
                    .iter()
                    .flatten()
                    .flat_map(|c| c.to_le_bytes())
                    .collect::<Vec<u8>>(),
                format!(
                    r#"{{"componentType":5126,"count":{},"type":"VEC3","min":{min:?},"max":{max:?}"#,
                    positions.len()
                ),
            ),
            (
                indices.iter().flat_map(|i| i.to_le_bytes()).collect(),
                format!(
                    r#"{{"componentType":5125,"count":{},"type":"SCALAR""#,
                    indices.len()
                ),
            ),
        ] {
            views.push(format!(
                r#"{{"buffer":0,"byteOffset":{},"byteLength":{}}}"#,
                binary.len(),
                bytes.len()
            ));
            accessors.push(format!(r#"{accessor},"bufferView":{}}}"#, views.len() - 1));
            binary.extend(bytes);
        }
        meshes.push(format!(
            r#"{{"primitives":[{{"attributes":{{"POSITION":{}}},"indices":{}}}]}}"#,
            2 * part,
            2 * part + 1
        ));
    }
    let mut json = format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0,1]}}],"nodes":[{{"mesh":0}},{{"mesh":1}}],"meshes":[{}],"accessors":[{}],"bufferViews":[{}],"buffers":[{{"byteLength":{}}}]}}"#,
        meshes.join(","),
        accessors.join(","),
        views.join(","),
        binary.len()
    )
    .into_bytes();
    json.resize(json.len().next_multiple_of(4), b' ');
    binary.resize(binary.len().next_multiple_of(4), 0);
    let mut file = Vec::new();
    let total = 12 + 8 + json.len() + 8 + binary.len();
    for word in [0x4654_6C67, 2, total as u32, json.len() as u32, 0x4E4F_534A] {
        file.extend(u32::to_le_bytes(word));
    }
    file.extend(&json);
    file.extend(u32::to_le_bytes(binary.len() as u32));
    file.extend(u32::to_le_bytes(0x004E_4942));
    file.extend(&binary);
    file
}

/// Runs `veneer geodesic FILE --sources ... --method METHOD` and reads its columns; the
/// command must succeed.
fn geodesic_cli(file: &Path, sources: &[Vec<u32>], method: &str) -> Vec<Vec<f64>> {
    let csv = file.with_extension(format!("{method}.csv"));
    let mut command = veneer();
    command
        .arg("geodesic")
        .arg(file)
        .args(["--method", method, "-o"])
        .arg(&csv);
    for set in sources {
        let list: Vec<String> = set.iter().map(u32::to_string).collect();
        command.args(["--sources", &list.join(",")]);
    }
    let output = command.output().expect("veneer runs");
    assert!(
        output.status.success(),
        "{}: {}",
        file.display(),
        String::from_utf8_lossy(&output.stderr)
    );
    let text = std::fs::read_to_string(&csv).expect("the field was written");
    let rows: Vec<Vec<f64>> = text
        .lines()
        .map(|line| {
            line.split(',')
                .map(|d| d.parse().expect("a number or inf"))
                .collect()
        })
        .collect();
    (0..sources.len())
        .map(|k| rows.iter().map(|row| row[k]).collect())
        .collect()
}

/// Asserts two fields agree vertex by vertex within `tolerance` (relative above 1).
fn assert_fields_match(what: &str, got: &[f64], expected: &[f64], tolerance: f64) {
    assert_eq!(
        got.len(),
        expected.len(),
        "{what}: one line per file vertex"
    );
    for (v, (&g, &e)) in got.iter().zip(expected).enumerate() {
        let same =
            (g.is_infinite() && e.is_infinite()) || (g - e).abs() <= tolerance * e.abs().max(1.0);
        assert!(same, "{what}: vertex {v} has {g}, expected {e}");
    }
}

/// Every format's file of the scrambled scan, with the mesh in that file's numbering.
fn files(dir: &Path) -> Vec<(PathBuf, FileMesh)> {
    let mesh = scan();
    let (stl_text, stl_mesh) = stl(&mesh);
    let write = |name: &str, bytes: &[u8]| {
        let path = dir.join(name);
        std::fs::write(&path, bytes).expect("written");
        path
    };
    vec![
        (
            write("plain.obj", obj(&mesh, false).as_bytes()),
            mesh.clone(),
        ),
        (
            write("seams.obj", obj(&mesh, true).as_bytes()),
            mesh.clone(),
        ),
        (write("scan.ply", ply(&mesh).as_bytes()), mesh.clone()),
        (write("scan.stl", stl_text.as_bytes()), stl_mesh),
        (
            write("scan.glb", &glb(&mesh, mesh.positions.len() as u32 - 5)),
            mesh,
        ),
    ]
}

#[test]
fn every_format_gives_one_line_per_file_vertex_in_the_files_order() {
    let dir = temp_dir("geodesic-files");
    for (path, mesh) in files(&dir) {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let loaded = veneer::mesh::load(&path).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(loaded.file_vertex_count(), mesh.positions.len(), "{name}");
        if name == "seams.obj" {
            assert_eq!(
                loaded.positions.len(),
                3 * mesh.triangles.len(),
                "split at seams"
            );
        }
        let used = mesh.used();
        let unused = (0..used.len() as u32).find(|&v| !used[v as usize]);
        let sources = vec![
            vec![mesh.at(0.0, 0.0), mesh.at(4.0, 1.0)],
            [mesh.at(0.5, 0.5)].into_iter().chain(unused).collect(),
        ];
        let expected: Vec<Vec<f64>> = sources.iter().map(|set| dijkstra(&mesh, set)).collect();
        let got = geodesic_cli(&path, &sources, "dijkstra");
        for (k, (got, expected)) in got.iter().zip(&expected).enumerate() {
            assert_fields_match(&format!("{name} dijkstra, field {k}"), got, expected, 1e-9);
        }
        // The same mesh listed in first-use order, solved by the other methods.
        let (ordered, number) = first_use(&mesh);
        let reference = dir.join(format!("{name}.first-use.obj"));
        std::fs::write(&reference, obj(&ordered, false)).expect("written");
        let renumbered: Vec<Vec<u32>> = sources
            .iter()
            .map(|set| set.iter().filter_map(|&s| number[s as usize]).collect())
            .collect();
        for method in ["heat", "exact"] {
            let got = geodesic_cli(&path, &sources, method);
            let reference = geodesic_cli(&reference, &renumbered, method);
            for k in 0..sources.len() {
                let expected: Vec<f64> = (0..mesh.positions.len())
                    .map(|v| match number[v] {
                        _ if sources[k].contains(&(v as u32)) => 0.0,
                        Some(n) => reference[k][n as usize],
                        None => f64::INFINITY,
                    })
                    .collect();
                assert_fields_match(
                    &format!("{name} {method}, field {k}"),
                    &got[k],
                    &expected,
                    1e-7,
                );
            }
        }
    }
}

#[test]
fn graph_fields_and_picking_count_vertices_as_the_file_does() {
    let dir = temp_dir("geodesic-file-fields");
    let mesh = scan();
    let path = dir.join("seams.obj");
    std::fs::write(&path, obj(&mesh, true)).expect("written");
    let mut loaded = veneer::mesh::load(&path).expect("loads");
    let source = mesh.at(0.5, 0.5);
    let field = FieldSource {
        sources: vec![source],
        method: Method::Dijkstra,
    };
    let notes = geodesic::attach_fields(
        &mut loaded,
        std::slice::from_ref(&field),
        [true, false, false, false],
        |_, _| {},
    )
    .expect("solves");
    assert!(notes.is_empty(), "{notes:?}");
    let expected = dijkstra(&mesh, &[source]);
    let farthest = geodesic::max_finite(&expected);
    for (vertex, values) in loaded.fields.iter().enumerate() {
        let distance = expected[loaded.file_vertex(vertex as u32) as usize];
        let normalised = if distance.is_finite() {
            distance / farthest
        } else {
            1.0
        };
        assert!(
            (f64::from(values[0]) - normalised).abs() < 1e-5,
            "vertex {vertex}"
        );
    }
    // The last vertex of the file is unused but exists; one past it does not.
    let count = mesh.positions.len() as u32;
    for (vertex, ok) in [(count - 1, true), (count, false)] {
        let field = FieldSource {
            sources: vec![vertex],
            ..field.clone()
        };
        let result = geodesic::attach_fields(
            &mut loaded,
            &[field],
            [true, false, false, false],
            |_, _| {},
        );
        assert_eq!(result.is_ok(), ok, "source {vertex}: {result:?}");
    }
    // A click straight down onto a grid vertex picks that vertex of the file.
    let target = mesh.positions[mesh.at(4.0 / 6.0, 2.0 / 6.0) as usize];
    let picked = veneer::mesh::pick_vertex(
        &loaded,
        glam::Vec3::new(target[0], 3.0, target[2]),
        glam::Vec3::NEG_Y,
    )
    .expect("a hit");
    assert_eq!(loaded.file_vertex(picked), mesh.at(target[0], target[2]));
}

/// An open grid with a near-degenerate cap triangle and a tall triangle on one of its
/// edges (a non-manifold edge of four triangles), a zero-area triangle hanging off a
/// corner and a separate square: the plain heat method's Poisson matrix does not factor.
fn dirty_scan() -> FileMesh {
    let n = 3;
    let mut positions: Vec<[f32; 3]> = (0..=n)
        .flat_map(|j| (0..=n).map(move |i| [i as f32 / 3.0, 0.0, j as f32 / 3.0]))
        .collect();
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i;
            triangles.extend([[a, a + n + 1, a + 1], [a + 1, a + n + 1, a + n + 2]]);
        }
    }
    let (a, b) = (4, 5);
    positions[a as usize][1] = 0.020_173_883;
    positions[b as usize][1] = 0.021_593_327;
    let mut add = |p: [f32; 3]| {
        positions.push(p);
        positions.len() as u32 - 1
    };
    let cap = add([0.023_163_013, 0.020_272_52, 1.0 / 3.0]);
    let tall = add([1.0 / 6.0, 0.5, 1.0 / 3.0]);
    let (near, far) = (add([-0.5, 0.0, 0.0]), add([-1.0, 0.0, 0.0]));
    let square = [
        [5.0, 0.0, 0.0],
        [6.0, 0.0, 0.0],
        [5.0, 0.0, 1.0],
        [6.0, 0.0, 1.0],
    ]
    .map(&mut add);
    triangles.extend([[a, b, cap], [a, b, tall], [0, near, far]]);
    triangles.extend([
        [square[0], square[2], square[1]],
        [square[1], square[2], square[3]],
    ]);
    FileMesh {
        positions,
        triangles,
    }
}

#[test]
fn the_heat_method_falls_back_to_robust_where_the_plain_one_cannot_factor() {
    let mesh = dirty_scan();
    let path = temp_dir("geodesic-dirty").join("dirty.obj");
    std::fs::write(&path, obj(&mesh, false)).expect("written");
    let loaded = veneer::mesh::load(&path).expect("loads");
    let welded = geodesic::WeldedMesh::new(&loaded);
    let report = veneer::mesh::analyse(&welded.mesh);
    assert!(
        report.non_manifold_edges > 0
            && report.degenerate_triangles > 0
            && report.boundary_edges > 0
            && report.components == 2,
        "{report}"
    );
    let plain = HeatOptions::default();
    assert!(
        HeatSolver::new(Triangulation::from_mesh(&welded.mesh), plain).is_err(),
        "the plain heat method must fail to factor this mesh for the test to mean anything"
    );
    let solved = geodesic::fields(
        &welded.mesh,
        &[welded.sources(&[0])],
        Method::Heat(plain),
        |_, _| {},
    )
    .expect("the robust method takes over");
    assert!(solved.fallback.is_some());
    assert_eq!(
        solved.method,
        Method::Heat(HeatOptions {
            robust: true,
            ..plain
        })
    );

    let csv = path.with_extension("csv");
    let output = veneer()
        .arg("geodesic")
        .arg(&path)
        .args(["--sources", "0", "--method", "heat", "-o"])
        .arg(&csv)
        .output()
        .expect("veneer runs");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    assert!(
        stderr.contains("warning: ") && stderr.contains("used the robust heat method instead"),
        "{stderr}"
    );
    let field: Vec<f64> = std::fs::read_to_string(&csv)
        .expect("written")
        .lines()
        .map(|line| line.parse().expect("a number or inf"))
        .collect();
    let reached = dijkstra(&mesh, &[0]);
    assert_eq!(field.len(), mesh.positions.len());
    for (v, (&d, &r)) in field.iter().zip(&reached).enumerate() {
        assert_eq!(
            d.is_finite(),
            r.is_finite(),
            "vertex {v}: {d} (edge path {r})"
        );
        assert!(
            d >= 0.0 && d <= 1.5 * r + 0.05,
            "vertex {v}: {d}, edge path {r}"
        );
    }
}
