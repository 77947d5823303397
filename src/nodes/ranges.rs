//! The interface through which a node kind propagates value ranges for the lint: its
//! input intervals by pin name, the range of surface positions, and the hazards it
//! finds.

use super::interval::{Interval, Lanes, max_length};
use super::pins::InputPin;
use super::settings::Basis;

/// Past this coordinate magnitude the sine hash's neighbouring lattice cells start to
/// repeat in f32 (measured on the CPU: 0.25% of neighbours repeat at 10⁶ as everywhere
/// closer, 1% at 2·10⁶, half at 4·10⁶; see `formulas::noise`'s `sine_hash_precision`).
pub const SINE_HASH_SAFE_COORDINATE: f64 = 1.0e6;

/// Past this magnitude f32 coordinates are spaced more than 1 apart, so lattice noise
/// turns into a stair of repeated cells.
pub const F32_LATTICE_LIMIT: f64 = 1.6777216e7;

/// A node's view of range propagation.
pub struct Ranges<'a> {
    pins: &'a [InputPin],
    inputs: &'a [Lanes],
    /// The range of surface positions.
    pub positions: Lanes,
    /// The range of each lane of the bitmap the node reads (an Image node), when known.
    bitmap: Option<[Interval; 4]>,
    warnings: Vec<String>,
}

impl<'a> Ranges<'a> {
    /// A node with these input pins and ranges, over `positions`.
    pub fn new(pins: &'a [InputPin], inputs: &'a [Lanes], positions: Lanes) -> Ranges<'a> {
        Ranges {
            pins,
            inputs,
            positions,
            bitmap: None,
            warnings: Vec::new(),
        }
    }

    /// The same node reading a bitmap whose lanes span `lanes`.
    pub fn with_bitmap(self, lanes: [Interval; 4]) -> Ranges<'a> {
        Ranges {
            bitmap: Some(lanes),
            ..self
        }
    }

    /// The range of each lane of the bitmap the node reads, when the lint knows it.
    pub fn bitmap(&self) -> Option<[Interval; 4]> {
        self.bitmap
    }

    /// The range of input pin `pin`. A name the kind does not have is a bug in its
    /// definition (the registry test lints every kind).
    pub fn input(&self, pin: &str) -> Lanes {
        self.inputs[super::pins::pin_index(self.pins, pin)]
    }

    /// The range of float input pin `pin`.
    pub fn float(&self, pin: &str) -> Interval {
        self.input(pin)[0]
    }

    /// The value of float input `pin` when it is one constant.
    pub fn constant(&self, pin: &str) -> Option<f64> {
        let lane = self.float(pin);
        (lane.lo == lane.hi).then_some(lane.lo)
    }

    /// The largest length a vec3 input can have.
    pub fn reach(&self, pin: &str) -> f64 {
        max_length(&self.input(pin), 3)
    }

    /// Records a hazard on the node.
    pub fn warn(&mut self, message: String) {
        self.warnings.push(message);
    }

    /// Records the hazards of lattice noise sampled up to `magnitude`, hashed with
    /// `basis` (`None`: the PCG hash).
    pub fn lattice(&mut self, basis: Option<Basis>, magnitude: f64) {
        if magnitude > F32_LATTICE_LIMIT {
            self.warn(format!(
                "samples noise at coordinates up to {magnitude:.3e}, past f32's integer precision ({F32_LATTICE_LIMIT:.3e}): the pattern degrades into blocks"
            ));
        } else if basis == Some(Basis::ValueSine) && magnitude > SINE_HASH_SAFE_COORDINATE {
            self.warn(format!(
                "uses the sine hash at coordinates up to {magnitude:.3e}; past {SINE_HASH_SAFE_COORDINATE:.0e} f32 can no longer tell neighbouring cells apart (use the PCG hash)"
            ));
        }
    }

    /// Records the hazards of lattice noise sampled at input `p` times input `scale`.
    pub fn sampled(&mut self, basis: Option<Basis>) {
        let magnitude = self.reach("p") * self.float("scale").magnitude();
        self.lattice(basis, magnitude);
    }

    /// The hazards found.
    pub fn finish(self) -> Vec<String> {
        self.warnings
    }
}

/// `f` applied lane by lane to two ranges.
pub fn lanewise(a: &Lanes, b: &Lanes, f: impl Fn(Interval, Interval) -> Interval) -> Lanes {
    [f(a[0], b[0]), f(a[1], b[1]), f(a[2], b[2])]
}
