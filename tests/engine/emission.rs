//! The material's `emission` (seed 003's ambient glow): the CPU evaluator returns it,
//! and the lit preview adds it to the lit colour, so a black, unshiny surface that
//! emits shows the emitted colour wherever it is, lit or not.

use crate::support::gpu;
use veneer::eval::{Evaluator, Surface};
use veneer::graph::{Graph, NodeKind, Value};
use veneer::render::{View, render_material};

const GLOW: (f64, f64, f64) = (0.6, 0.3, 0.1);

/// A black, non-specular material emitting `emission` (none: the input left unset).
fn glowing(emission: Option<(f64, f64, f64)>) -> Graph {
    let mut graph = Graph::default();
    let material = graph.add("material", NodeKind::Material);
    graph.set_input(material, "albedo", Value::Color(0.0, 0.0, 0.0));
    graph.set_input(material, "specular", Value::Color(0.0, 0.0, 0.0));
    if let Some((r, g, b)) = emission {
        graph.set_input(material, "emission", Value::Color(r, g, b));
    }
    graph
}

/// The sphere's mesh render as RGBA rows, 64×64.
fn render(graph: &Graph) -> Vec<u8> {
    let compiled = veneer::codegen::compile(graph, &Default::default()).expect("compiles");
    let image = render_material(
        gpu(),
        &compiled,
        &View::Mesh(Some("sphere".into())),
        64,
        0.0,
    )
    .expect("renders");
    assert_eq!(image.channels, 4);
    image.pixels
}

#[test]
fn the_evaluator_returns_the_emission_and_black_by_default() {
    let surface = Surface::<f64>::at([0.1, 0.2, 0.3]);
    let lit = Evaluator::new(&glowing(Some(GLOW)))
        .expect("checks")
        .eval(&surface);
    assert_eq!(lit.emission, [GLOW.0, GLOW.1, GLOW.2]);
    let plain = Evaluator::new(&glowing(None))
        .expect("checks")
        .eval(&surface);
    assert_eq!(plain.emission, [0.0; 3]);
}

#[test]
fn the_preview_adds_the_emission_to_the_lit_colour_on_both_sides_of_the_light() {
    let dark = render(&glowing(None));
    let glow = render(&glowing(Some(GLOW)));
    // Two rows through the sphere's middle, across its lit and its unlit side, inside
    // its outline (about 24 pixels in radius), where no pixel is partly background.
    let mut on_sphere = 0;
    for y in [30, 34] {
        for x in 12..52 {
            let at = (y * 64 + x) * 4;
            let (before, after) = (&dark[at..at + 3], &glow[at..at + 3]);
            if before == after {
                continue; // the background, untouched
            }
            on_sphere += 1;
            assert!(
                before.iter().all(|&c| c <= 2),
                "a black, unshiny sphere is black at ({x}, {y}): {before:?}"
            );
            assert!(
                after[0] > after[1] && after[1] > after[2] && after[0] >= 100,
                "the emission shows at ({x}, {y}): {after:?}"
            );
        }
    }
    assert!(
        on_sphere >= 40,
        "the rows cross the sphere ({on_sphere} pixels)"
    );
}

#[test]
fn the_emission_strength_multiplies_the_emission_in_the_preview() {
    let mut strong = glowing(Some((0.2, 0.1, 0.05)));
    let material = strong.material().unwrap().id;
    strong.set_input(material, "emission_strength", Value::Float(3.0));
    let weak = render(&glowing(Some((0.2, 0.1, 0.05))));
    let strong = render(&strong);
    // At the sphere's centre, black and unshiny: the emission alone, 3× as bright.
    let at = |image: &[u8]| image[(32 * 64 + 32) * 4] as f32;
    assert!(
        (at(&strong) - 3.0 * at(&weak)).abs() <= 2.0,
        "{} vs {}",
        at(&strong),
        at(&weak)
    );
}
