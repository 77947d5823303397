//! Footprint detail: octaves finer than a pixel are left out and periodic and thresholding
//! patterns are box-filtered over the pixel, so a distant view is closer to the truly
//! filtered (supersampled) pattern than full evaluation, and a near view is unchanged.
//! The materials are the report's level-of-detail cases, one per band-limited node kind.

use crate::support::gpu;
use veneer::codegen::{CompileOptions, Detail};
use veneer::graph::{Graph, NodeKind, Value};
use veneer::render::{View, render_material};
use veneer::report::level_of_detail::{DetailCase, box_down, cases, shown_in_grey, view};

/// The WGSL `graph` compiles to with footprint detail.
fn footprint_source(graph: &Graph) -> String {
    veneer::codegen::compile(graph, &CompileOptions::with_detail(Detail::Footprint))
        .unwrap()
        .module
        .source
}

fn render(graph: &Graph, width: f64, size: u32, detail: Detail) -> Vec<[f64; 3]> {
    let compiled = veneer::codegen::compile(graph, &CompileOptions::with_detail(detail)).unwrap();
    let rect = view(graph, width);
    let image = render_material(gpu(), &compiled, &View::Flat(rect), size, 0.0).expect("renders");
    image
        .pixels
        .chunks_exact(3)
        .map(|p| [0, 1, 2].map(|c| f64::from(p[c]) / 255.0))
        .collect()
}

fn mean_error(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    let sum: f64 = a
        .iter()
        .zip(b)
        .map(|(x, y)| (0..3).map(|c| (x[c] - y[c]).abs()).sum::<f64>() / 3.0)
        .sum();
    sum / a.len() as f64
}

/// Mean errors of a 64² flat render `width` wide, with full and footprint detail,
/// against the full render supersampled `factor`×`factor` and box-filtered down, and
/// between the two.
#[derive(Debug)]
struct DetailErrors {
    full: f64,
    footprint: f64,
    between: f64,
}

fn compare_detail(graph: &Graph, width: f64, factor: usize) -> DetailErrors {
    let size = 64usize;
    let reference = box_down(
        &render(graph, width, (size * factor) as u32, Detail::Full),
        size,
        factor,
    );
    let full = render(graph, width, size as u32, Detail::Full);
    let footprint = render(graph, width, size as u32, Detail::Footprint);
    DetailErrors {
        full: mean_error(&full, &reference),
        footprint: mean_error(&footprint, &reference),
        between: mean_error(&full, &footprint),
    }
}

fn case(name: &str) -> DetailCase {
    cases()
        .into_iter()
        .find(|case| case.name == name)
        .unwrap_or_else(|| panic!("no level-of-detail case {name}"))
}

/// Every node kind the footprint filters, at its farthest view (2.5 periods or cells a
/// pixel, still resolved by the reference's 8×8 samples): the footprint render is at most half as far from the 64-sample
/// reference as the full one. Thresholds of Voronoi distances do less well (at most
/// 0.8×): once cells are under a pixel, the distance's screen-space derivative jumps
/// from cell to cell, so the step is filtered over a width that is itself noise. At the
/// nearest view (about six pixels a period, joints and edges a pixel or less) the
/// footprint render is no farther from the reference than the full one.
#[test]
fn far_away_each_band_limited_kind_is_nearer_the_filtered_pattern_and_near_by_no_worse() {
    let mut failures = Vec::new();
    for case in cases() {
        let far = compare_detail(&case.graph, case.widths[2], 8);
        let near = compare_detail(&case.graph, case.widths[0], 8);
        println!("{}: far {far:?}, near {near:?}", case.name);
        let cellular = matches!(
            case.graph.nodes[0].kind,
            NodeKind::WorleyEdge | NodeKind::Worley(_)
        );
        let bound = if cellular { 0.8 } else { 0.5 };
        if far.footprint > bound * far.full {
            failures.push(format!("{} far: {far:?}", case.name));
        }
        if near.footprint > near.full + 0.002 {
            failures.push(format!("{} near: {near:?}", case.name));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The report's wood at a distance (a view 100× its preview, 180 units wide): the
/// footprint error is at most half the full-detail error (the number).
#[test]
fn woods_rings_at_a_distance_are_filtered() {
    let wood = case("wood");
    let source = footprint_source(&wood.graph);
    assert!(
        source.contains("veneer_sine_band_filtered("),
        "the rings are filtered"
    );
    assert!(
        source.contains("veneer_smoothstep_filtered("),
        "their threshold too"
    );
    let far = compare_detail(&wood.graph, wood.widths[1], 8);
    println!("wood at {}: {far:?}", wood.widths[1]);
    assert!(far.footprint <= 0.5 * far.full, "{far:?}");
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
        joints.set_input(tiles, pin, *value);
    }
    joints.set_input(tiles, "blur", Value::Float(0.0));
    shown_in_grey(&mut joints, tiles, "mask");
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

/// Inside a sampler's local frame (run per instance, where screen-space derivatives are
/// undefined) nodes draw in full: no derivative is taken there. Pebbles with its ground's
/// fBm also placed per pebble as the pebbles' colour.
#[test]
fn nodes_a_sampler_places_take_no_derivatives() {
    let mut graph =
        veneer::graph::load(&crate::support::root("graphs/texture/pebbles.ron")).unwrap();
    let id = |label: &str| graph.nodes.iter().find(|n| n.label == label).unwrap().id;
    let (ground, pebbles) = (id("ground"), id("pebbles"));
    graph.connect(ground, "value", pebbles, "pattern_colour");
    let source = footprint_source(&graph);
    assert!(
        source.contains("veneer_octave_cutoff("),
        "the ground filters where shaded"
    );
    let mut placed_ground = false;
    for (start, _) in source.match_indices("fn veneer_local_") {
        let body = &source[start..];
        let body = &body[..body.find("\n}\n").expect("the function ends")];
        placed_ground |= body.contains("veneer_fbm_");
        assert!(
            !body.contains("fwidth(")
                && !body.contains("dpdx(")
                && !body.contains("_filtered(")
                && !body.contains("veneer_octave_cutoff("),
            "{body}"
        );
    }
    assert!(placed_ground, "the ground's fBm is placed per pebble");
}
