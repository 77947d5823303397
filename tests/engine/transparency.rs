//! A material's alpha on the mesh: cut-out surfaces show the mesh's inside through their
//! holes (back faces drawn and lit from their side), and blended surfaces (the thesis's
//! figure 5.7) show what is behind them in proportion to their alpha.

use crate::support::gpu;
use veneer::graph::{AlphaMode, Graph, NodeId, Value, from_ron};
use veneer::render::{View, render_material};

const SIZE: u32 = 96;
/// The preview's background (linear RGB 0.12, 0.13, 0.15 as 8-bit).
fn is_background(pixel: &[u8]) -> bool {
    let background = veneer::render::MeshView::for_preview(&Default::default()).background;
    pixel[..3]
        .iter()
        .zip(background)
        .all(|(&p, b)| p.abs_diff((b * 255.0).round() as u8) <= 1)
}

/// A red-glowing, otherwise black sphere whose alpha is `alpha` (a RON input source:
/// a constant, or the z of the position through `1 - step(0.7, z)`).
fn sphere(alpha: &str, mode: AlphaMode) -> Graph {
    let text = format!(
        r#"(
    version: 1,
    preview: (mesh: "sphere:32", center: (0.0, 0.0, 0.0), size: 1.0),
    nodes: [
        (id: 1, label: "position", kind: Position, inputs: {{}}, position: (0.0, 0.0)),
        (id: 2, label: "xyz", kind: Split(ty: Vec3), inputs: {{}}, position: (0.0, 0.0)),
        (id: 3, label: "in front", kind: Step(ty: Float), inputs: {{"edge": Float(0.7)}}, position: (0.0, 0.0)),
        (id: 4, label: "kept", kind: Unary(op: OneMinus, ty: Float), inputs: {{}}, position: (0.0, 0.0)),
        (id: 5, label: "material", kind: Material, inputs: {{
            "albedo": Color(0.0, 0.0, 0.0), "specular": Color(0.0, 0.0, 0.0),
            "emission": Color(1.0, 0.0, 0.0), {alpha}
        }}, position: (0.0, 0.0)),
    ],
    wires: [
        (from: (node: 1, pin: "position"), to: (node: 2, pin: "v")),
        (from: (node: 2, pin: "z"), to: (node: 3, pin: "x")),
        (from: (node: 3, pin: "result"), to: (node: 4, pin: "x")),
    ],
)"#
    );
    let mut graph = from_ron(&text).expect("test graph parses");
    graph.alpha = mode;
    graph
}

fn render(graph: &Graph) -> Vec<u8> {
    let compiled = veneer::codegen::compile(graph, &Default::default()).expect("compiles");
    render_material(gpu(), &compiled, &View::Mesh(None), SIZE, 0.0)
        .expect("renders")
        .pixels
}

/// The sphere with the cap facing the camera (z > 0.7) cut away: `kept` wired to the
/// alpha.
fn holed(mode: AlphaMode) -> Graph {
    let mut graph = sphere(r#""alpha": Float(1.0)"#, mode);
    graph.connect(NodeId(4), "result", NodeId(5), "alpha");
    graph
}

#[test]
fn through_a_cut_out_hole_the_inside_shows() {
    // Lit green over the glow, so that the inside, lit from its side, looks other than
    // the outside.
    let lit = |mut graph: Graph| {
        graph.set_input(NodeId(5), "albedo", Value::Color(0.0, 0.6, 0.0));
        render(&graph)
    };
    let whole = lit(sphere(r#""alpha": Float(1.0)"#, AlphaMode::default()));
    let cut = lit(holed(AlphaMode::default()));
    let inside: Vec<usize> = (0..whole.len() / 4)
        .filter(|&k| !is_background(&whole[4 * k..]))
        .collect();
    assert!(inside.len() > 1000, "{} sphere pixels", inside.len());
    // The hole faces the camera: through it the inside of the far side shows (glowing
    // red), never the background (as it would with back faces culled).
    let background = inside
        .iter()
        .filter(|&&k| is_background(&cut[4 * k..]))
        .count();
    // The hole is there: a good part of the sphere's picture changed.
    let changed = inside
        .iter()
        .filter(|&&k| whole[4 * k..4 * k + 3] != cut[4 * k..4 * k + 3])
        .count();
    assert!(
        changed * 10 > inside.len(),
        "{changed} of {} pixels changed",
        inside.len()
    );
    // With back faces culled, the hole would show the background all over; only rim
    // pixels (partly covered by the hole's edge and the silhouette) may.
    assert!(
        background * 50 < changed,
        "{background} of {changed} pixels in the hole show the background"
    );
}

#[test]
fn opaque_mode_ignores_the_alpha() {
    let whole = render(&sphere(r#""alpha": Float(1.0)"#, AlphaMode::default()));
    assert_eq!(render(&holed(AlphaMode::Opaque)), whole);
    assert_eq!(
        render(&sphere(r#""alpha": Float(0.1)"#, AlphaMode::Opaque)),
        whole
    );
}

#[test]
fn a_blended_surface_shows_what_is_behind_in_proportion() {
    let half = render(&sphere(r#""alpha": Float(0.5)"#, AlphaMode::Blend));
    let whole = render(&sphere(r#""alpha": Float(1.0)"#, AlphaMode::Blend));
    let background = veneer::render::MeshView::for_preview(&Default::default()).background;
    let centre = 4 * ((SIZE / 2) * SIZE + SIZE / 2) as usize;
    assert_eq!(&whole[centre..centre + 3], &[255, 0, 0]);
    // Front (red, 0.5) over the back face (red, 0.5) over the background.
    let expected = [0, 1, 2].map(|c| {
        let red = if c == 0 { 1.0 } else { 0.0 };
        255.0 * (0.75 * red + 0.25 * background[c])
    });
    for c in 0..3 {
        let got = f32::from(half[centre + c]);
        assert!(
            (got - expected[c]).abs() <= 2.0,
            "channel {c}: {got} vs {}",
            expected[c]
        );
    }
    // Away from the sphere the background is untouched, and the image stays opaque.
    assert!(is_background(&half[..4]));
    assert!(half.chunks_exact(4).all(|p| p[3] == 255));
}

#[test]
fn blended_renders_are_the_same_each_time() {
    let graph = holed(AlphaMode::Blend);
    assert_eq!(render(&graph), render(&graph));
}

#[test]
fn alpha_cutoffs_outside_0_to_1_are_refused() {
    let graph = sphere(r#""alpha": Float(1.0)"#, AlphaMode::Mask { cutoff: 1.5 });
    let error = veneer::codegen::compile(&graph, &Default::default()).unwrap_err();
    assert!(error.to_string().contains("alpha cutoff 1.5"), "{error}");
}
