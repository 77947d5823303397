//! The classic wood preset (`graphs/wood_classic.ron`) against a transcription of seed
//! 001's fragment shader (the OpenGL Orange Book, §15.7, Listing 15.8), written from the
//! book's GLSL and not from the node code.
//!
//! The shader reads its noise from the book's 3D noise texture (§15.3, not part of the
//! seed): four octaves of Perlin noise, one a channel, of frequencies 4, 8, 16 and 32
//! across the texture and amplitudes ½, ¼, ⅛ and 1/16, each stored as
//! `(noise + 1) · amplitude · 128` in a byte. That texture is a basis, like a hash: the
//! transcription's `texture3D(Noise, p)` samples Veneer's gradient noise (in [0, 1], the
//! stored `(noise + 1) / 2`) at the same frequencies and amplitudes, so the comparison
//! checks the shader's formulas and constants, not the lattice. (The byte's 128/255 is
//! the texture's encoding and is taken as ½; its 8-bit steps and trilinear filtering
//! are the texture's too.)
//!
//! Veneer's surface position is the shader's `MCposition`: the vertex shader's `Scale`
//! (object size) is the application's, as is `LightIntensity` (the lighting), so the
//! albedo is compared with the shader's colour before `color *= LightIntensity`. Both
//! sides run in f64 and differ only by rounding (the graph sums the noise before the
//! ring distance), so the tolerance is 1e-9.

use crate::support::{Samples, root};
use veneer::eval::{Evaluator, Material, Surface};
use veneer::graph::{Graph, Value};
use veneer::nodes::formulas::noise;
use veneer::nodes::settings::Basis;

type V3 = [f64; 3];

/// §15.7.1's uniforms (the book's defaults; the seed's page lost the scalars' values,
/// which its text gives: RingFreq 4, GrainScale 27, GrainThreshold 0.5, LightGrains 1,
/// DarkGrains 0; Noisiness 3 is the book's).
#[derive(Clone, Copy, Debug)]
struct Uniforms {
    light_wood: V3,
    dark_wood: V3,
    ring_freq: f64,
    light_grains: f64,
    dark_grains: f64,
    grain_threshold: f64,
    noise_scale: V3,
    noisiness: f64,
    grain_scale: f64,
}

const BOOK: Uniforms = Uniforms {
    light_wood: [0.6, 0.3, 0.1],
    dark_wood: [0.4, 0.2, 0.07],
    ring_freq: 4.0,
    light_grains: 1.0,
    dark_grains: 0.0,
    grain_threshold: 0.5,
    noise_scale: [0.5, 0.1, 0.1],
    noisiness: 3.0,
    grain_scale: 27.0,
};

/// The book's noise texture at texture coordinate `p`: octave k in channel k.
fn noise_texture(p: V3) -> [f64; 4] {
    let (frequency, amplitude) = ([4.0, 8.0, 16.0, 32.0], [0.5, 0.25, 0.125, 0.0625]);
    [0, 1, 2, 3].map(|k| amplitude[k] * noise::basis(Basis::Gradient, p.map(|c| c * frequency[k])))
}

fn fract(x: f64) -> f64 {
    x - x.floor()
}

fn mix3(a: V3, b: V3, t: f64) -> V3 {
    [0, 1, 2].map(|i| a[i] * (1.0 - t) + b[i] * t)
}

/// Listing 15.8 up to `color *= LightIntensity`, at `MCposition`.
fn wood(u: &Uniforms, mc_position: V3) -> V3 {
    let texel = noise_texture([0, 1, 2].map(|i| mc_position[i] * u.noise_scale[i]));
    let mut noisevec: V3 = [0, 1, 2].map(|i| texel[i] * u.noisiness);
    let location: V3 = [0, 1, 2].map(|i| mc_position[i] + noisevec[i]);

    let mut dist = (location[0] * location[0] + location[2] * location[2]).sqrt();
    dist *= u.ring_freq;

    let mut r = fract(dist + noisevec[0] + noisevec[1] + noisevec[2]) * 2.0;
    if r > 1.0 {
        r = 2.0 - r;
    }
    let mut color = mix3(u.light_wood, u.dark_wood, r);

    r = fract((mc_position[0] + mc_position[2]) * u.grain_scale + 0.5);
    noisevec[2] *= r;
    if r < u.grain_threshold {
        color = [0, 1, 2].map(|i| color[i] + u.light_wood[i] * u.light_grains * noisevec[2]);
    } else {
        // The listing subtracts LightWood · DarkGrains (its text says DarkWood; the
        // code is what ran).
        color = [0, 1, 2].map(|i| color[i] - u.light_wood[i] * u.dark_grains * noisevec[2]);
    }
    color
}

fn preset() -> Graph {
    veneer::graph::load(&root("graphs/wood_classic.ron")).expect("preset loads")
}

/// Sets input `pin` of the preset's node labelled `label`.
fn set(graph: &mut Graph, label: &str, pin: &str, value: Value) {
    let id = graph
        .nodes
        .iter()
        .find(|node| node.label == label)
        .unwrap_or_else(|| panic!("the preset has a node labelled {label:?}"))
        .id;
    graph.set_input(id, pin, value);
}

/// What the comparison saw, to show that the samples reach both grain branches and
/// that the noise moves the pattern.
#[derive(Debug, Default)]
struct Seen {
    light_side: usize,
    noise_matters: usize,
}

/// The preset's albedo against the listing at 3,000 points of [−3, 3]³ (a sphere of
/// radius 1 under the vertex shader's `Scale` 2 spans [−2, 2]) and 1,000 of [−20, 20]³.
fn compare(graph: &Graph, u: &Uniforms, seed: u64) -> Seen {
    let evaluator = Evaluator::new(graph).expect("preset checks");
    let quiet = Uniforms {
        noisiness: 0.0,
        ..*u
    };
    let mut samples = Samples(seed);
    let (mut seen, mut worst) = (Seen::default(), 0.0_f64);
    for index in 0..4000 {
        let reach = if index < 3000 { 3.0 } else { 20.0 };
        let p = [0, 1, 2].map(|_| (samples.unit() * 2.0 - 1.0) * reach);
        let ours: Material<f64> = evaluator.eval(&Surface::<f64>::at(p));
        let book = wood(u, p);
        let error = (0..3)
            .map(|i| (ours.albedo[i] - book[i]).abs())
            .fold(0.0, f64::max);
        worst = worst.max(error);
        assert!(
            error <= 1e-9,
            "at {p:?}: the preset gives {:?}, Listing 15.8 {book:?}",
            ours.albedo
        );
        let grain = fract((p[0] + p[2]) * u.grain_scale + 0.5);
        seen.light_side += usize::from(grain < u.grain_threshold);
        let without_noise = wood(&quiet, p);
        seen.noise_matters +=
            usize::from((0..3).any(|i| (without_noise[i] - book[i]).abs() > 0.01));
    }
    eprintln!("wood_classic: largest difference from Listing 15.8 {worst:e}; {seen:?}");
    assert!(
        (1600..2400).contains(&seen.light_side),
        "both grain branches are sampled: {seen:?}"
    );
    seen
}

#[test]
fn wood_classic_matches_seed_001_listing_15_8() {
    let seen = compare(&preset(), &BOOK, 0x5eed_0001);
    assert!(seen.noise_matters > 2000, "the noise is wired: {seen:?}");
}

/// Noisiness 0 (the preset's `noisiness` multiplier at 0): the rings and grain alone,
/// the noise texture out of the comparison.
#[test]
fn wood_classic_without_noise_is_the_listings_bare_rings_and_grain() {
    let mut graph = preset();
    set(&mut graph, "noisiness", "b", Value::Vec3(0.0, 0.0, 0.0));
    let book = Uniforms {
        noisiness: 0.0,
        ..BOOK
    };
    compare(&graph, &book, 0x5eed_0010);
}

/// The grain's two branches with other weights and threshold than the book's defaults
/// (whose DarkGrains 0 hides the dark branch): the preset's labelled constants are the
/// listing's uniforms.
#[test]
fn wood_classic_grain_branches_follow_the_listing() {
    let mut graph = preset();
    set(&mut graph, "light grain amount", "b", Value::Float(0.35));
    set(&mut graph, "dark grain amount", "b", Value::Float(0.8));
    set(&mut graph, "dark side", "edge", Value::Float(0.3));
    let book = Uniforms {
        light_grains: 0.35,
        dark_grains: 0.8,
        grain_threshold: 0.3,
        ..BOOK
    };
    let evaluator = Evaluator::new(&graph).expect("preset checks");
    let mut samples = Samples(0x5eed_0011);
    let mut darkened = 0;
    for _ in 0..3000 {
        let p = [0, 1, 2].map(|_| samples.unit() * 6.0 - 3.0);
        let ours: Material<f64> = evaluator.eval(&Surface::<f64>::at(p));
        let expected = wood(&book, p);
        let error = (0..3)
            .map(|i| (ours.albedo[i] - expected[i]).abs())
            .fold(0.0, f64::max);
        assert!(
            error <= 1e-9,
            "at {p:?}: the preset gives {:?}, Listing 15.8 {expected:?}",
            ours.albedo
        );
        let without_dark_grains = Uniforms {
            dark_grains: 0.0,
            ..book
        };
        darkened += usize::from(expected[0] < wood(&without_dark_grains, p)[0] - 0.01);
    }
    assert!(
        darkened > 500,
        "the dark branch shows: {darkened} darker samples"
    );
}
