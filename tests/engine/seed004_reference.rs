//! The flagstone preset (`graphs/marble_tiles.ron`) against a transcription of seed
//! 004's final fragment shader (Christian Marten's "Building a better marble": step 2's
//! `marble_color`, step 3's `turbulence` and step 4's `main`), written from the GLSL and
//! not from the node code.
//!
//! The seed's `noise` is Stefan Gustavson's Perlin noise in [−1, 1]; the transcription
//! calls Veneer's gradient noise in its signed form (`2n − 1`, what the preset's
//! `Turbulence` and `Remap` nodes use) in its place, so the comparison checks the
//! shader's formulas and constants, not the lattice.
//!
//! Two changes are Veneer's own and the comparison makes them explicitly:
//! - **Joints filtered centred on the pixel** (README, "Level of detail"): the seed
//!   box-filters the joints over `[pos, pos + fw]`, Veneer over `[pos − fw/2, pos + fw/2]`.
//! - **The filter width is a width in metres** (`blur`, or the footprint's `fwidth` with
//!   `--detail footprint`), which the `Tiles` node divides by the tile size; the seed adds
//!   `fwidth(vertexPosMC)`, in metres, to `pos`, in tiles. The seed's window of `fw`
//!   tiles is Veneer's `blur` of `fw · 1.1` m. (The CPU evaluator has no footprint: the
//!   preset's fixed `blur` of 0.01 m is the filter width it sees.)
//!
//! Both sides run in f64 and differ only by rounding, so the tolerance is 1e-9.

use crate::support::{Samples, root};
use veneer::eval::{Evaluator, Material, Surface};
use veneer::graph::{Graph, Value};
use veneer::nodes::formulas::noise;
use veneer::nodes::settings::Basis;

type V3 = [f64; 3];

/// The seed's definition of tiles, in metres.
const TILE_SIZE: V3 = [1.1, 1.0, 1.1];
const TILE_PCT: V3 = [0.98, 1.0, 0.98];

/// The preset's `blur` (metres).
const PRESET_BLUR: f64 = 0.01;

fn fract(x: f64) -> f64 {
    x - x.floor()
}

fn noise(p: V3) -> f64 {
    noise::signed(Basis::Gradient, p)
}

/// Step 3's `turbulence`.
fn turbulence(p: V3, num_freq: u32) -> f64 {
    let (mut val, mut freq) = (0.0, 1.0);
    for _ in 0..num_freq {
        val += (noise(p.map(|c| c * freq)) / freq).abs();
        freq *= 2.07;
    }
    val
}

/// Step 2's `marble_color`, for −1 < x < 1.
fn marble_color(x: f64) -> V3 {
    let mut x = 0.5 * (x + 1.0);
    x = x.sqrt();
    x = x.sqrt();
    x = x.sqrt();
    let mut col = [0.2 + 0.75 * x; 3];
    col[2] *= 0.95;
    col
}

/// `#define Integral(x, p, np) ((floor(x)*(p)) + max(fract (x) - (np), 0.0))`.
fn integral(x: f64, p: f64, np: f64) -> f64 {
    x.floor() * p + (fract(x) - np).max(0.0)
}

/// How the joints are filtered.
#[derive(Clone, Copy, Debug)]
enum Joints {
    /// No filter: the limit of the seed's box filter as `fw` goes to 0 (marble where
    /// `fract(pos) > 1 − tilePct`).
    Hard,
    /// The seed's box filter of width `fw` (tiles), centred on the pixel as Veneer does.
    Centred(V3),
}

/// Step 4's `main` at `vertexPosMC`, up to `gl_FragColor`: the colour, and the
/// joints' mix factor (`isMarble.x*isMarble.z`).
fn flagstone(vertex_pos_mc: V3, joints: Joints) -> (V3, f64) {
    let mut tpos: V3 = [0, 1, 2].map(|i| vertex_pos_mc[i] / TILE_SIZE[i]);
    if fract(tpos[0] * 0.5) > 0.5 {
        tpos[2] += 0.5;
    }
    let pos = tpos.map(fract);

    let roughness = 4;
    let tile_id = tpos.map(f64::ceil);
    let asc = 3.0 * noise(tile_id.map(|c| 2.3 * c));

    const PI: f64 = 3.1415;
    let amplitude = 6.0;
    let mut t = 2.0 * PI * (vertex_pos_mc[0] + (asc * vertex_pos_mc[2])) / TILE_SIZE[0];
    t += amplitude * turbulence(vertex_pos_mc, roughness);
    t = t.sin();
    let marble_colour = marble_color(t);

    let is_marble = |k: usize| {
        let (p, np) = (TILE_PCT[k], 1.0 - TILE_PCT[k]);
        match joints {
            Joints::Hard => f64::from(u8::from(pos[k] > np)),
            Joints::Centred(fw) => {
                // Veneer's change: the window [pos − fw/2, pos + fw/2], not [pos, pos + fw].
                let pos = pos[k] - fw[k] * 0.5;
                (integral(pos + fw[k], p, np) - integral(pos, p, np)) / fw[k]
            }
        }
    };
    let factor = is_marble(0) * is_marble(2);
    // mix(vec3(0.2, 0.2, 0.2), marbleColor, factor)
    let colour = [0, 1, 2].map(|i| 0.2 * (1.0 - factor) + marble_colour[i] * factor);
    (colour, factor)
}

impl Samples {
    /// A point with x and z in about [−5.5, 5.5] m (ten tiles each way) and y in
    /// [−2.5, 2.5] (the seed's tile id counts layers of 1 m in y too); half of them
    /// within a few hundredths of a tile of a joint, across x or along z.
    fn point(&mut self) -> V3 {
        let y = self.unit() * 5.0 - 2.5;
        let mut tx = self.unit() * 10.0 - 5.0;
        let mut tz = self.unit() * 10.0 - 5.0;
        let near = self.unit() * 0.06 - 0.02;
        match (self.unit() * 4.0) as usize {
            0 => tx = tx.floor() + near,
            1 => {
                let shift = if fract(tx * 0.5) > 0.5 { 0.5 } else { 0.0 };
                tz = (tz + shift).floor() + near - shift;
            }
            _ => {}
        }
        [tx * TILE_SIZE[0], y, tz * TILE_SIZE[2]]
    }
}

fn preset() -> Graph {
    veneer::graph::load(&root("graphs/marble_tiles.ron")).expect("preset loads")
}

/// The preset's albedo against the seed at 4,000 points; returns how many fell in the
/// mortar (wholly or in part) and how many on a joint's blurred edge (partly mortar).
fn compare(graph: &Graph, joints: Joints, seed: u64) -> (usize, usize) {
    let evaluator = Evaluator::new(graph).expect("preset checks");
    let mut samples = Samples(seed);
    let (mut mortar, mut edges, mut worst) = (0, 0, 0.0_f64);
    for _ in 0..4000 {
        let p = samples.point();
        let ours: Material<f64> = evaluator.eval(&Surface::<f64>::at(p));
        let (seed, factor) = flagstone(p, joints);
        let error = (0..3)
            .map(|i| (ours.albedo[i] - seed[i]).abs())
            .fold(0.0, f64::max);
        worst = worst.max(error);
        assert!(
            error <= 1e-9,
            "at {p:?} ({joints:?}): the preset gives {:?}, seed 004 {seed:?}",
            ours.albedo
        );
        mortar += usize::from(factor < 1.0);
        edges += usize::from(factor > 0.0 && factor < 1.0);
    }
    eprintln!("marble_tiles ({joints:?}): largest difference from seed 004 {worst:e}");
    (mortar, edges)
}

#[test]
fn marble_tiles_matches_seed_004() {
    let fw = PRESET_BLUR / TILE_SIZE[0];
    let (mortar, edges) = compare(&preset(), Joints::Centred([fw, 0.0, fw]), 0x5eed_0004);
    assert!(
        mortar > 500 && edges > 200,
        "{mortar} mortar samples, {edges} on edges"
    );
}

/// The preset with its blur at 0 (and no footprint) has the seed's joints unfiltered.
#[test]
fn marble_tiles_without_blur_has_the_seeds_hard_joints() {
    let mut graph = preset();
    let tiles = graph
        .nodes
        .iter()
        .find(|node| node.label == "flagstones")
        .expect("the preset's tiles")
        .id;
    graph.set_input(tiles, "blur", Value::Float(0.0));
    let (mortar, edges) = compare(&graph, Joints::Hard, 0x5eed_0040);
    assert!(
        mortar > 500 && edges == 0,
        "{mortar} mortar samples, {edges} on edges"
    );
}
