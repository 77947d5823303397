//! Patterns: bands, waves, tiles and rings.

use super::coordinates::axis_reach;
use super::cpu::Eval;
use super::emit::Emit;
use super::formulas::real::{Real, V3, splat};
use super::formulas::shapes;
use super::interval::{self, Interval, Lanes};
use super::pins::{
    FLOAT, POINT, REQUIRED, Signature, VEC2, VEC3, f, input, output, pin_index, v2, v3,
};
use super::ranges::Ranges;
use super::settings::Basis;
use super::{Catalogue, Category, Definition, Evaluate};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather
            [$($units)* (SineBand, patterns) (TriangleWave, patterns) (Tiles, patterns) (Rings, patterns)]
            [$($configured)*]
            $($rest)*);
    };
}
pub(super) use kinds;

/// `0.5 + 0.5 * sin(frequency * x + distortion * turbulence)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SineBand;

impl Definition for SineBand {
    computed_in!(Category::Pattern, unchecked);
    fn title(&self) -> &'static str {
        "Sine band"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["wave", "stripes", "bands", "marble", "wood"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("x", FLOAT, REQUIRED),
                input("frequency", FLOAT, f(1.0)).soft(0.0, 50.0),
                input("distortion", FLOAT, f(1.0)).soft(0.0, 20.0),
                input("turbulence", FLOAT, f(0.0)),
            ],
            vec![output("band", FLOAT)],
        )
    }
    fn emit(&self, io: &mut Emit) {
        io.call(&io.band_limited("veneer_sine_band"));
    }
    fn ranges(&self, _: &mut Ranges) -> Vec<Lanes> {
        super::unit_range()
    }
}

impl Evaluate for SineBand {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        vec![splat(shapes::sine_band(
            io.float("x"),
            io.float("frequency"),
            io.float("distortion"),
            io.float("turbulence"),
        ))]
    }
}

plain_catalogue!(SineBand);

/// A triangle wave of `x * frequency` going 0 → 1 → 0 each period.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleWave;

impl Definition for TriangleWave {
    computed_in!(Category::Pattern, unchecked);
    fn title(&self) -> &'static str {
        "Triangle wave"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["wave", "sawtooth", "ping pong", "stripes"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("x", FLOAT, REQUIRED),
                input("frequency", FLOAT, f(1.0)).soft(0.0, 50.0),
            ],
            vec![output("value", FLOAT)],
        )
    }
    fn emit(&self, io: &mut Emit) {
        io.call(&io.band_limited("veneer_triangle_wave"));
    }
    fn ranges(&self, _: &mut Ranges) -> Vec<Lanes> {
        super::unit_range()
    }
}

impl Evaluate for TriangleWave {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        vec![splat(shapes::triangle_wave(
            io.float("x"),
            io.float("frequency"),
        ))]
    }
}

plain_catalogue!(TriangleWave);

/// Offset rows of tiles in the xz plane with antialiased mortar gaps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tiles;

impl Definition for Tiles {
    computed_in!(Category::Pattern, unchecked);
    fn title(&self) -> &'static str {
        "Tiles"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["bricks", "flagstones", "grid", "checker", "mortar"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                POINT,
                input("size", VEC2, v2(1.0, 1.0)).soft(0.0, 10.0),
                input("gap", VEC2, v2(0.02, 0.02)).limits(0.0, 1.0),
                input("row_offset", FLOAT, f(0.5)).limits(0.0, 1.0),
                input("blur", FLOAT, f(0.0)).soft(0.0, 0.1),
            ],
            vec![
                output("mask", FLOAT),
                output("cell", VEC2),
                output("local", VEC2),
            ],
        )
    }
    fn emit(&self, io: &mut Emit) {
        io.uses("veneer_tiles");
        let mut inputs = io.inputs().to_vec();
        if io.filters_footprint() {
            // Seed 004's antialiasing: the mortar box-filtered over the pixel's footprint
            // (its `fwidth`), or over `blur` where that is wider.
            io.uses("veneer_plane_footprint");
            let blur = io.input("blur");
            inputs[pin_index(io.pins(), "blur")] =
                format!("max({blur}, veneer_plane_footprint({}))", io.input("p"));
        }
        io.bind(
            "veneer_tiles_result",
            format!("veneer_tiles({})", inputs.join(", ")),
        );
        let name = io.name();
        io.outputs(
            ["mask", "cell", "local"]
                .map(|c| format!("{name}.{c}"))
                .to_vec(),
        );
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        let p = io.input("p");
        let cells = [p[0], p[2], Interval::point(0.0)];
        vec![
            interval::splat(Interval::UNIT),
            cells.map(|lane| Interval::new(lane.lo.floor() - 2.0, lane.hi.ceil() + 2.0)),
            interval::splat(Interval::UNIT),
        ]
    }
}

impl Evaluate for Tiles {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let (mask, cell, local) = shapes::tiles(
            io.input("p"),
            io.input("size"),
            io.input("gap"),
            io.float("row_offset"),
            io.float("blur"),
        );
        let zero = R::c(0.0);
        vec![
            splat(mask),
            [cell[0], cell[1], zero],
            [local[0], local[1], zero],
        ]
    }
}

plain_catalogue!(Tiles);

/// Concentric rings about an axis: `0.5 + 0.5 * sin(2π * frequency * r)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rings;

impl Definition for Rings {
    computed_in!(Category::Pattern, unchecked);
    fn title(&self) -> &'static str {
        "Rings"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["wood", "concentric", "circles", "growth rings"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                POINT,
                input("origin", VEC3, v3(0.0, 0.0, 0.0)).soft(-10.0, 10.0),
                input("axis", VEC3, v3(0.0, 1.0, 0.0)),
                input("frequency", FLOAT, f(1.0)).soft(0.0, 50.0),
            ],
            vec![output("value", FLOAT)],
        )
    }
    fn emit(&self, io: &mut Emit) {
        io.call(&io.band_limited("veneer_rings"));
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        axis_reach(io, "origin", "axis");
        super::unit_range()
    }
}

impl Evaluate for Rings {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        vec![splat(shapes::rings(
            io.input("p"),
            io.input("origin"),
            io.input("axis"),
            io.float("frequency"),
        ))]
    }
}

plain_catalogue!(Rings);
