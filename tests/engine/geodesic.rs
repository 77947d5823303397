//! Geodesic distances against closed forms and against each other: the exact method on
//! flat and spherical surfaces, the heat method and the edge baseline against the exact
//! one on a torus and a genus-2 surface, several sources, and broken meshes.

use veneer::geodesic::{self, HeatOptions, HeatSolver, Method, Triangulation};
use veneer::mesh::{self, Mesh};

use veneer::geodesic::relative_errors as relative_error;

fn welded(mesh: &Mesh) -> Mesh {
    geodesic::welded_for_distances(mesh).0
}

fn solve(mesh: &Mesh, sources: &[u32], method: Method) -> Vec<f64> {
    geodesic::distances(mesh, sources, method, |_, _| {}).expect("solvable")
}

const HEAT: Method = Method::Heat(HeatOptions {
    time_factor: 1.0,
    robust: false,
    refine: true,
});
const ROBUST: Method = Method::Heat(HeatOptions {
    time_factor: 1.0,
    robust: true,
    refine: true,
});
/// The heat method on the mesh's own triangles, as before refinement.
const UNREFINED: Method = Method::Heat(HeatOptions {
    time_factor: 1.0,
    robust: false,
    refine: false,
});

#[test]
fn distances_on_a_sphere_follow_great_circles() {
    let sphere = welded(&mesh::sphere(64, 32));
    let source = 0u32; // the north pole
    let north = glam::DVec3::from(sphere.positions[0].map(f64::from));
    let great_circle: Vec<f64> = sphere
        .positions
        .iter()
        .map(|p| {
            glam::DVec3::from(p.map(f64::from))
                .normalize()
                .dot(north.normalize())
                .clamp(-1.0, 1.0)
                .acos()
        })
        .collect();
    // The mesh is inscribed, so even exact polyhedral distances run short of the sphere's.
    for (method, bound) in [
        (Method::Exact, 0.01),
        (HEAT, 0.02),
        (Method::Dijkstra, 0.05),
    ] {
        let field = solve(&sphere, &[source], method);
        let (mean, _) = relative_error(&field, &great_circle, 0.2);
        assert!(
            mean < bound,
            "{}: mean relative error {mean}",
            method.name()
        );
    }
}

#[test]
fn the_exact_method_is_exact_on_a_plane_with_uneven_triangles() {
    let mut mesh = Mesh::default();
    mesh.push_grid(20, 13, |u, v| {
        // Irregular spacing: the grid lines bunch towards two sides.
        ([u * u * 3.0, 0.0, v.powf(1.5) * 2.0], [0.0, 1.0, 0.0])
    });
    let source = 7 * 21 + 10;
    let at = |v: usize| glam::DVec2::new(mesh.positions[v][0] as f64, mesh.positions[v][2] as f64);
    let exact = solve(&mesh, &[source as u32], Method::Exact);
    let straight: Vec<f64> = (0..mesh.positions.len())
        .map(|v| at(v).distance(at(source)))
        .collect();
    for v in 0..mesh.positions.len() {
        assert!(
            (exact[v] - straight[v]).abs() < 1e-5,
            "vertex {v}: {} vs {}",
            exact[v],
            straight[v]
        );
    }
    // The plane is open: the heat method averages its Neumann and Dirichlet solutions.
    let (heat, _) = relative_error(&solve(&mesh, &[source as u32], HEAT), &straight, 0.3);
    println!("open plane: heat {heat:.4}");
    assert!(heat < 0.05, "heat on an open plane: {heat}");
}

#[test]
fn heat_and_baseline_stay_within_their_bounds_of_the_exact_distance() {
    let torus = welded(&mesh::torus(0.7, 0.3, 96, 48));
    let genus2 = mesh::double_torus(0.04);
    for (name, mesh, heat_bound, robust_bound) in [
        ("torus", &torus, 0.025, 0.025),
        ("genus 2", &genus2, 0.05, 0.03),
    ] {
        let exact = solve(mesh, &[3], Method::Exact);
        let near = 0.1 * geodesic::max_finite(&exact);
        let (heat, _) = relative_error(&solve(mesh, &[3], HEAT), &exact, near);
        let (robust, _) = relative_error(&solve(mesh, &[3], ROBUST), &exact, near);
        let (edges, _) = relative_error(&solve(mesh, &[3], Method::Dijkstra), &exact, near);
        println!("{name}: heat {heat:.4}, robust {robust:.4}, dijkstra {edges:.4}");
        assert!(heat < heat_bound, "{name}: heat {heat}");
        assert!(robust < robust_bound, "{name}: robust heat {robust}");
        assert!(edges > 0.0 && edges < 0.15, "{name}: dijkstra {edges}");
    }
}

#[test]
fn several_sources_give_the_minimum_of_their_fields() {
    let torus = welded(&mesh::torus(0.7, 0.3, 48, 24));
    let sources = [5u32, 400, 777];
    for (method, tolerance) in [
        (Method::Exact, 1e-9),
        (Method::Dijkstra, 1e-12),
        (HEAT, 0.06),
    ] {
        let together = solve(&torus, &sources, method);
        let apart: Vec<Vec<f64>> = sources
            .iter()
            .map(|&s| solve(&torus, &[s], method))
            .collect();
        let scale = geodesic::max_finite(&together);
        for v in 0..torus.positions.len() {
            let minimum = apart.iter().map(|f| f[v]).fold(f64::INFINITY, f64::min);
            assert!(
                (together[v] - minimum).abs() <= tolerance * scale,
                "{}: vertex {v}: {} vs {minimum}",
                method.name(),
                together[v]
            );
        }
    }
}

#[test]
fn re_solving_with_new_sources_reuses_the_factorisation() {
    let torus = welded(&mesh::torus(0.7, 0.3, 48, 24));
    let solver = HeatSolver::new(Triangulation::from_mesh(&torus), HeatOptions::default()).unwrap();
    let first = solver.distances(&[0]);
    let second = solver.distances(&[100]);
    assert_eq!(first[0], 0.0);
    assert_eq!(second[100], 0.0);
    assert!(
        first[100] > 0.0 && (first[100] - second[0]).abs() < 0.05 * first[100],
        "symmetric"
    );
}

/// A flat square grid whose interior vertices are pushed about by up to `jitter` of a
/// cell (deterministically), making obtuse triangles and slivers.
fn jittered_grid(n: u32, jitter: f32) -> Mesh {
    let mut mesh = Mesh::default();
    mesh.push_grid(n, n, |u, v| ([u, 0.0, v], [0.0, 1.0, 0.0]));
    let mut state = 0x2545_f491u32;
    let mut random = move || {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        state as f32 / u32::MAX as f32 - 0.5
    };
    for p in &mut mesh.positions {
        let interior = p[0] > 0.0 && p[0] < 1.0 && p[2] > 0.0 && p[2] < 1.0;
        if interior {
            p[0] += random() * 2.0 * jitter / n as f32;
            p[2] += random() * 2.0 * jitter / n as f32;
        }
    }
    mesh
}

#[test]
fn the_intrinsic_delaunay_refinement_repairs_what_obtuse_triangles_spoil() {
    let grid = jittered_grid(40, 0.3);
    let center = (20 * 41 + 20) as u32;
    let exact = solve(&grid, &[center], Method::Exact);
    let (unrefined, _) = relative_error(&solve(&grid, &[center], UNREFINED), &exact, 0.1);
    for method in [HEAT, ROBUST] {
        let (refined, _) = relative_error(&solve(&grid, &[center], method), &exact, 0.1);
        println!(
            "jittered grid: unrefined heat {unrefined:.4}, {} {refined:.4}",
            method.name()
        );
        assert!(
            refined < 0.75 * unrefined,
            "unrefined {unrefined}, refined {refined}"
        );
    }
}

#[test]
fn stiff_and_slack_time_steps_stay_finite_and_bounded() {
    let torus = welded(&mesh::torus(0.7, 0.3, 64, 32));
    let exact = solve(&torus, &[0], Method::Exact);
    let farthest = geodesic::max_finite(&exact);
    for exponent in -3..=3 {
        let time_factor = 10f64.powi(exponent);
        for robust in [false, true] {
            let method = Method::Heat(HeatOptions {
                time_factor,
                robust,
                ..HeatOptions::default()
            });
            let field = solve(&torus, &[0], method);
            assert!(
                field
                    .iter()
                    .all(|d| d.is_finite() && *d >= 0.0 && *d <= 3.0 * farthest),
                "t = {time_factor}·h²"
            );
            let (mean, _) = relative_error(&field, &exact, 0.1 * farthest);
            println!("t = 1e{exponent}·h², robust {robust}: mean relative error {mean:.4}");
        }
    }
}

#[test]
fn meshes_past_the_refinement_limit_are_solved_unrefined_and_say_so() {
    for (name, skipped) in [("torus:64", false), ("torus:256", true)] {
        let torus = welded(&mesh::primitive(name).expect("a primitive"));
        let used = torus.positions.len();
        assert_eq!(
            used > geodesic::REFINE_UP_TO,
            skipped,
            "{name}: {used} vertices"
        );
        let solver = HeatSolver::new(Triangulation::from_mesh(&torus), HeatOptions::default())
            .expect("factors");
        let setup = solver.setup();
        assert_eq!(setup.refinement_skipped, skipped, "{name}");
        assert_eq!(setup.added_vertices == 0, skipped, "{name}");
        // Attached to a preview, the field says so (the editor shows the note).
        let mut preview = mesh::primitive(name).expect("a primitive");
        let field = veneer::graph::FieldSource {
            sources: vec![0],
            method: Method::Heat(HeatOptions::default()),
        };
        let notes = geodesic::attach_fields(
            &mut preview,
            &[field],
            [true, false, false, false],
            |_, _| {},
        )
        .expect("solves");
        let said = notes.iter().any(|note| note.contains("solved unrefined"));
        assert_eq!(said, skipped, "{name}: {notes:?}");
    }
}

#[test]
fn far_from_the_origin_the_field_is_the_same() {
    let mut near = welded(&mesh::torus(0.7, 0.3, 48, 24));
    for p in &mut near.positions {
        *p = p.map(|c| c * 1000.0);
    }
    let mut far = near.clone();
    for p in &mut far.positions {
        p[0] += 1.0e6;
    }
    // The positions are f32: a million units out, each is rounded by up to 0.03 (of
    // edges 80 long), which moves the field by less than 10⁻³ of its size. Refinement
    // splits the edges longer than the mean, so that rounding may split an edge in one
    // mesh and not in the other: the two fields then differ by the method's own error
    // (its mean on this torus is under 1%), not by a loss of precision.
    for (method, tolerance) in [(UNREFINED, 1e-3), (Method::Exact, 1e-3), (HEAT, 1e-2)] {
        let (a, b) = (solve(&near, &[7], method), solve(&far, &[7], method));
        let scale = geodesic::max_finite(&a);
        let worst = a
            .iter()
            .zip(&b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max);
        assert!(
            worst < tolerance * scale,
            "{}: {worst} of {scale}",
            method.name()
        );
    }
}

#[test]
fn a_broken_mesh_gets_finite_distances_where_reached_and_warnings_naming_its_defects() {
    // An open grid, a zero-area triangle hanging off its corner, and a second grid apart.
    let mut mesh = Mesh::default();
    mesh.push_grid(8, 8, |u, v| ([u, 0.0, v], [0.0, 1.0, 0.0]));
    let a = mesh.push_vertex([-0.5, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0]);
    let b = mesh.push_vertex([-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0]);
    mesh.indices.extend([0, a, b]);
    let apart = mesh.positions.len();
    mesh.push_grid(4, 4, |u, v| ([u + 5.0, 0.0, v], [0.0, 1.0, 0.0]));
    let obj = crate::support::temp_dir("broken-mesh").join("broken.obj");
    std::fs::write(&obj, mesh.to_obj()).unwrap();
    for method in ["heat", "exact", "dijkstra"] {
        for robust in [false, true] {
            let csv = obj.with_extension(format!("{method}{robust}.csv"));
            let mut command = crate::support::veneer();
            command
                .args([
                    "geodesic",
                    obj.to_str().unwrap(),
                    "--sources",
                    "40",
                    "--method",
                    method,
                    "-o",
                ])
                .arg(&csv);
            if robust {
                command.arg("--robust");
            }
            let output = command.output().unwrap();
            assert!(
                output.status.success(),
                "{}",
                String::from_utf8_lossy(&output.stderr)
            );
            let stderr = String::from_utf8_lossy(&output.stderr);
            for defect in [
                "1 degenerate",
                "boundary edges",
                "2 separate components",
                "unreached",
            ] {
                assert!(
                    stderr.contains(defect),
                    "{method}: no `{defect}` in {stderr}"
                );
            }
            let values: Vec<f64> = std::fs::read_to_string(&csv)
                .unwrap()
                .lines()
                .map(|l| l.parse().unwrap())
                .collect();
            assert_eq!(values.len(), mesh.positions.len());
            assert!(
                values[..apart].iter().all(|d| d.is_finite()),
                "{method}: reached vertices are finite"
            );
            assert!(
                values[apart..].iter().all(|d| d.is_infinite()),
                "{method}: the far grid is unreached"
            );
            let along = values[b as usize] - values[0];
            assert!(
                (along - 1.0).abs() < 1e-4,
                "{method}: along the flat triangle's edge {along}"
            );
        }
    }
}

#[test]
fn fields_and_relief_are_computed_only_where_a_material_uses_them() {
    let sand = veneer::graph::load(&crate::support::root("graphs/water_lava.ron")).unwrap();
    let uses = veneer::codegen::compile(&sand, &Default::default())
        .unwrap()
        .uses();
    assert_eq!(uses.fields, [true, true, false, false]);
    assert!(!uses.displacement);
    let wood = veneer::graph::load(&crate::support::root("graphs/wood.ron")).unwrap();
    let wood_uses = veneer::codegen::compile(&wood, &Default::default())
        .unwrap()
        .uses();
    assert_eq!(wood_uses.fields, [false; 4], "no field node, no field");

    let mut mesh = veneer::mesh::primitive(&sand.preview.mesh).unwrap();
    geodesic::attach_fields(&mut mesh, &sand.preview.fields, wood_uses.fields, |_, _| {}).unwrap();
    assert!(
        mesh.fields.is_empty(),
        "nothing solved when nothing reads a field"
    );
    geodesic::attach_fields(&mut mesh, &sand.preview.fields, uses.fields, |_, _| {}).unwrap();
    assert_eq!(mesh.fields.len(), mesh.positions.len());
    for slot in 0..2 {
        let values: Vec<f32> = mesh.fields.iter().map(|f| f[slot]).collect();
        assert!(
            values.iter().all(|v| (0.0..=1.0).contains(v)),
            "slot {slot} normalised"
        );
        assert!(values.iter().any(|&v| v == 0.0) && values.iter().any(|&v| v == 1.0));
    }
    assert!(
        mesh.fields.iter().all(|f| f[2] == 0.0 && f[3] == 0.0),
        "unused slots read 0"
    );

    let waves = veneer::graph::load(&crate::support::root("graphs/waves.ron")).unwrap();
    assert!(
        veneer::codegen::compile(&waves, &Default::default())
            .unwrap()
            .uses()
            .displacement
    );
    let moss = veneer::graph::load(&crate::support::root("graphs/moss_granite.ron")).unwrap();
    assert!(
        veneer::codegen::compile(&moss, &Default::default())
            .unwrap()
            .uses()
            .bump
    );
    assert!(
        !wood_uses.bump && !wood_uses.displacement,
        "no bump, no height: no relief work in the renderer"
    );
}

#[test]
fn geotexture_fronts_move_with_time_and_bad_sources_are_named() {
    let dir = crate::support::temp_dir("fronts");
    let render = |graph: &std::path::Path, time: &str, out: &str| {
        crate::support::veneer()
            .args([
                "render",
                graph.to_str().unwrap(),
                "--size",
                "64",
                "--time",
                time,
                "-o",
            ])
            .arg(dir.join(out))
            .output()
            .unwrap()
    };
    let sand = crate::support::root("graphs/sand_water.ron");
    assert!(render(&sand, "0", "early.png").status.success());
    assert!(render(&sand, "4", "late.png").status.success());
    let (early, late) = (
        std::fs::read(dir.join("early.png")).unwrap(),
        std::fs::read(dir.join("late.png")).unwrap(),
    );
    assert_ne!(early, late, "the sand front advances");

    let text = std::fs::read_to_string(&sand)
        .unwrap()
        .replace("sources: [29039]", "sources: [99999999]");
    let broken = dir.join("broken.ron");
    std::fs::write(&broken, text).unwrap();
    let output = render(&broken, "0", "broken.png");
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("field 0: source vertex 99999999 does not exist"),
        "{stderr}"
    );
    assert!(!dir.join("broken.png").exists(), "no half-made image");
}
