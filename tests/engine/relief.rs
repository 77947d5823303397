//! A material's height on the mesh: adaptive tessellation (the thesis's C.6.2–C.6.3,
//! refined on the CPU where the displacement needs it) brings a coarse mesh's displaced
//! render close to a finely meshed one, and bump-only shading keeps the silhouette.

use crate::support::{gpu, run_veneer, temp_dir};
use veneer::graph::{Tessellation, from_ron};
use veneer::render::{Relief, View, render_material_with};

/// Ripples along x on the preview plane: height 0.04·sin(25x).
const RIPPLES: &str = r#"(
    version: 1,
    preview: (mesh: "plane:4", center: (0.0, 0.0, 0.0), size: 1.0),
    nodes: [
        (id: 1, label: "position", kind: Position, inputs: {}, position: (0.0, 0.0)),
        (id: 2, label: "xyz", kind: Split(ty: Vec3), inputs: {}, position: (0.0, 0.0)),
        (id: 3, label: "phase", kind: Math(op: Multiply, ty: Float), inputs: {"b": Float(25.0)}, position: (0.0, 0.0)),
        (id: 4, label: "wave", kind: Unary(op: Sin, ty: Float), inputs: {}, position: (0.0, 0.0)),
        (id: 5, label: "height", kind: Math(op: Multiply, ty: Float), inputs: {"b": Float(0.04)}, position: (0.0, 0.0)),
        (id: 6, label: "material", kind: Material, inputs: {}, position: (0.0, 0.0)),
    ],
    wires: [
        (from: (node: 1, pin: "position"), to: (node: 2, pin: "v")),
        (from: (node: 2, pin: "x"), to: (node: 3, pin: "a")),
        (from: (node: 3, pin: "result"), to: (node: 4, pin: "x")),
        (from: (node: 4, pin: "result"), to: (node: 5, pin: "a")),
        (from: (node: 5, pin: "result"), to: (node: 6, pin: "height")),
    ],
)"#;

const SIZE: u32 = 128;

/// The ripples rendered on `mesh`, tessellated or not, as RGBA rows; and what
/// tessellation did.
fn ripples(mesh: &str, tessellation: Option<f64>, relief: Relief) -> (Vec<u8>, Option<usize>) {
    let mut graph = from_ron(RIPPLES).expect("test graph parses");
    graph.preview.mesh = mesh.into();
    graph.preview.tessellation = tessellation.map(|tolerance| Tessellation {
        tolerance,
        ..Tessellation::default()
    });
    let compiled = veneer::codegen::compile(&graph, &Default::default()).expect("compiles");
    let rendered = render_material_with(
        gpu(),
        &compiled,
        &View::Mesh(None),
        SIZE,
        0.0,
        veneer::render::MeshLook {
            relief,
            ..Default::default()
        },
    )
    .expect("renders");
    (
        rendered.image.pixels,
        rendered.tessellated.map(|t| t.triangles.1),
    )
}

/// Mean absolute difference of two RGBA images, per channel in 0–255.
fn mean_difference(a: &[u8], b: &[u8]) -> f64 {
    let total: u64 = a
        .iter()
        .zip(b)
        .map(|(x, y)| u64::from(x.abs_diff(*y)))
        .sum();
    total as f64 / a.len() as f64
}

#[test]
fn adaptive_tessellation_approaches_a_finely_meshed_displacement() {
    let (reference, _) = ripples("plane:256", None, Relief::Displaced);
    let (coarse, none) = ripples("plane:4", None, Relief::Displaced);
    assert_eq!(none, None);
    let (tessellated, triangles) = ripples("plane:4", Some(0.5), Relief::Displaced);
    let triangles = triangles.expect("the displaced plane is tessellated");
    let (before, after) = (
        mean_difference(&coarse, &reference),
        mean_difference(&tessellated, &reference),
    );
    assert!(
        after < before / 4.0,
        "tessellated {after:.2} vs coarse {before:.2} from the fine mesh"
    );
    // Leaner than the fine mesh's 131,072 triangles: only where the ripples need it
    // (they run along x, so edges along z stay whole).
    assert!(
        (32..131_072 / 2).contains(&triangles),
        "{triangles} triangles"
    );
}

#[test]
fn a_tighter_tolerance_refines_more() {
    let counts: Vec<usize> = [2.0, 0.5, 0.125]
        .map(|px| {
            ripples("plane:4", Some(px), Relief::Displaced)
                .1
                .expect("tessellated")
        })
        .to_vec();
    assert!(counts[0] < counts[1] && counts[1] < counts[2], "{counts:?}");
}

#[test]
fn bump_relief_leaves_the_mesh_unmoved_and_untessellated() {
    let (bump, tessellated) = ripples("plane:4", Some(0.5), Relief::Bump);
    assert_eq!(tessellated, None, "bump-only shading needs no refinement");
    let (displaced, _) = ripples("plane:256", None, Relief::Displaced);
    let (bump_fine, _) = ripples("plane:256", None, Relief::Bump);
    // The same shading without the moved vertices: the coarse and fine bump renders
    // agree (the relief is per pixel) where the displaced one does not.
    assert!(mean_difference(&bump, &bump_fine) < 1.0);
    assert!(mean_difference(&bump_fine, &displaced) > 1.0);
}

#[test]
fn the_cli_tessellates_on_request_and_says_so() {
    let dir = temp_dir("tessellate");
    let graph = dir.join("ripples.ron");
    std::fs::write(&graph, RIPPLES).expect("write the graph");
    let run = |extra: &[&str]| {
        let out = dir.join(format!("{}.png", extra.join("_")));
        let mut args = vec!["render", graph.to_str().unwrap(), "--size", "64", "-o"];
        args.push(out.to_str().unwrap());
        args.extend_from_slice(extra);
        let output = run_veneer(&args);
        assert!(output.status.success(), "{output:?}");
        (
            std::fs::read(out).expect("the image"),
            String::from_utf8_lossy(&output.stderr).into_owned(),
        )
    };
    let (plain, quiet) = run(&[]);
    assert!(quiet.is_empty(), "{quiet}");
    let (refined, said) = run(&["--tessellate", "0.5"]);
    assert!(said.contains("tessellated 32 triangles into"), "{said}");
    assert!(plain != refined, "tessellation changed nothing");
    let (off, _) = run(&["--tessellate", "off"]);
    assert!(
        off == plain,
        "--tessellate off differs from no tessellation"
    );
    let refused = run_veneer(&[
        "render",
        graph.to_str().unwrap(),
        "-o",
        "x.png",
        "--tessellate",
        "0",
    ]);
    assert_eq!(refused.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&refused.stderr).contains("at least"));
}
