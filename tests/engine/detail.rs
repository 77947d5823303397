//! Footprint-aware detail: octaves finer than a pixel are left out, so a distant view is
//! closer to the truly filtered (supersampled) pattern than full evaluation, and a near
//! view is unchanged.

use crate::support::gpu;
use veneer::codegen::{CompileOptions, Detail};
use veneer::graph::{Basis, Graph, NodeKind, Value};
use veneer::nodes::{Combine, Fbm};
use veneer::render::{FlatRect, View, render_material};

fn fbm_graph() -> Graph {
    let mut graph = Graph::default();
    let fbm = graph.add(
        "fbm",
        NodeKind::Fbm(Fbm {
            basis: Basis::Gradient,
            octaves: 8,
            normalize: true,
            rotate: false,
            period: 0,
        }),
    );
    graph.set_input(fbm, "scale", Value::Float(1.0));
    show_in_grey(&mut graph, fbm, "value");
    graph
}

/// Wires `node`'s float output `pin` into the albedo as a grey.
fn show_in_grey(graph: &mut Graph, node: veneer::graph::NodeId, pin: &str) {
    let grey = graph.add(
        "grey",
        NodeKind::Combine(Combine {
            ty: veneer::graph::ValueType::Color,
        }),
    );
    for channel in ["x", "y", "z"] {
        graph.connect(node, pin, grey, channel);
    }
    let material = graph.add("material", NodeKind::Material);
    graph.connect(grey, "v", material, "albedo");
}

/// The WGSL `graph` compiles to with footprint-aware detail.
fn footprint_source(graph: &Graph) -> String {
    veneer::codegen::compile(graph, &CompileOptions::with_detail(Detail::Footprint))
        .unwrap()
        .module
        .source
}

fn render(graph: &Graph, extent: f64, size: u32, detail: Detail) -> Vec<f64> {
    let rect = FlatRect {
        x0: 0.0,
        z0: 0.0,
        x1: extent,
        z1: extent,
        y: 0.37,
    };
    let compiled = veneer::codegen::compile(graph, &CompileOptions::with_detail(detail)).unwrap();
    let image = render_material(gpu(), &compiled, &View::Flat(rect), size, 0.0).expect("renders");
    image
        .pixels
        .chunks_exact(3)
        .map(|p| f64::from(p[0]) / 255.0)
        .collect()
}

/// `pixels` (size·factor squared) averaged over factor×factor blocks.
fn box_down(pixels: &[f64], size: usize, factor: usize) -> Vec<f64> {
    let wide = size * factor;
    let mut out = vec![0.0; size * size];
    for (k, value) in pixels.iter().enumerate() {
        let (x, y) = (k % wide / factor, k / wide / factor);
        out[y * size + x] += value / (factor * factor) as f64;
    }
    out
}

fn mean_error(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).sum::<f64>() / a.len() as f64
}

/// Mean errors of a 64² flat render over `extent`, with full and footprint detail,
/// against the full render supersampled `factor`×`factor` and box-filtered down, and
/// between the two.
#[derive(Debug)]
struct DetailErrors {
    full: f64,
    footprint: f64,
    between: f64,
}

fn compare_detail(graph: &Graph, extent: f64, factor: usize) -> DetailErrors {
    let size = 64usize;
    let reference = box_down(
        &render(graph, extent, (size * factor) as u32, Detail::Full),
        size,
        factor,
    );
    let full = render(graph, extent, size as u32, Detail::Full);
    let footprint = render(graph, extent, size as u32, Detail::Footprint);
    let errors = DetailErrors {
        full: mean_error(&full, &reference),
        footprint: mean_error(&footprint, &reference),
        between: mean_error(&full, &footprint),
    };
    println!("extent {extent}: {errors:?}");
    errors
}

#[test]
fn far_away_the_footprint_is_nearer_the_filtered_pattern_and_near_by_it_changes_nothing() {
    let graph = fbm_graph();
    assert!(
        footprint_source(&graph).contains("veneer_octave_cutoff("),
        "the cutoff is computed"
    );

    let far = compare_detail(&graph, 400.0, 8);
    assert!(far.footprint < 0.5 * far.full, "far: {far:?}");
    let near = compare_detail(&graph, 0.5, 8);
    assert!(
        near.between < 0.01,
        "near: every octave is shown either way: {near:?}"
    );
}

/// Seed 004's flagstone joints, filtered over the pixel's footprint (its `fwidth`): far
/// away the mortar grid is nearer the supersampled pattern than the hard-edged one, and
/// near by (joints many pixels wide) the image barely changes.
#[test]
fn tile_joints_are_filtered_over_the_pixel_footprint() {
    let graph = veneer::graph::load(&crate::support::root("graphs/marble_tiles.ron")).unwrap();
    // The joints alone: the tiles' mask as the albedo, unblurred.
    let mut joints = Graph::default();
    let tiles_node = graph
        .nodes
        .iter()
        .find(|node| matches!(node.kind, NodeKind::Tiles))
        .expect("the preset has tiles");
    let tiles = joints.add("tiles", NodeKind::Tiles);
    for (pin, value) in &tiles_node.inputs {
        joints.set_input(tiles, pin, value.clone());
    }
    joints.set_input(tiles, "blur", Value::Float(0.0));
    show_in_grey(&mut joints, tiles, "mask");
    assert!(
        footprint_source(&joints).contains("fwidth("),
        "the footprint comes from fwidth"
    );
    // Far: joints (0.022 units) half a pixel wide; near: about five pixels. The reference
    // resolves the joints with 16×16 samples a pixel. (Filtered over [x, x + width], as
    // seed 004 writes it, half a pixel off centre, the far error was 0.045 against the
    // hard edges' 0.037; centred it is 0.0005.)
    let far = compare_detail(&joints, 2.5, 16);
    assert!(far.footprint < 0.5 * far.full, "far: {far:?}");
    let near = compare_detail(&joints, 0.3, 16);
    assert!(
        near.footprint <= near.full && near.between < 0.02,
        "near: {near:?}"
    );
}
