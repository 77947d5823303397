//! The wood and marble presets against direct transcriptions of seed 000's Listings 4
//! and 5, rendered the same way (flat, 256×256): at least 99% of pixels within 2/255.

use crate::support::{difference, flat_rgb8, root};
use veneer::render::FlatRect;

/// Seed 000's hash, value noise and fBm, shared by both references.
pub const SEED_NOISE: &str = include_str!("reference/seed000_noise.wgsl");

fn compare_with_seed(preset: &str, reference: &str, rect: FlatRect) {
    let graph = veneer::graph::load(&root(&format!("graphs/{preset}.ron"))).expect("preset loads");
    let ours = veneer::codegen::compile(&graph, &Default::default())
        .expect("preset compiles")
        .module
        .source;
    let seed = format!(
        "{}\n{SEED_NOISE}\n{reference}",
        veneer::codegen::library::SURFACE
    );
    let (a, b) = (flat_rgb8(&ours, rect, 256), flat_rgb8(&seed, rect, 256));
    let diff = difference(&a, &b, 3, 2);
    assert!(
        diff.share_outside <= 0.01,
        "{preset}: {diff} against seed 000"
    );
}

#[test]
fn wood_matches_seed_000_listing_4() {
    let rect = FlatRect {
        x0: 0.0,
        z0: 0.0,
        x1: 50.0,
        z1: 50.0,
        y: 0.5,
    };
    compare_with_seed("wood", include_str!("reference/wood_seed000.wgsl"), rect);
}

#[test]
fn marble_matches_seed_000_listing_5() {
    let rect = FlatRect {
        x0: -10.0,
        z0: -10.0,
        x1: 10.0,
        z1: 10.0,
        y: 0.5,
    };
    compare_with_seed(
        "marble",
        include_str!("reference/marble_seed000.wgsl"),
        rect,
    );
}
