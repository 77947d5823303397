//! Distance-field patterns (seed 003): fronts spreading over a field, nested layers,
//! isolines.

use super::cpu::Eval;
use super::emit::Emit;
use super::formulas::fields::{front, isolines};
use super::formulas::real::{Real, V3, splat};
use super::formulas::shapes::mix3;
use super::interval::{Interval, Lanes};
use super::pins::{FLOAT, REQUIRED, Signature, f, input, output, splat as splat_default};
use super::ranges::{Ranges, lanewise};
use super::settings::{Basis, Setting, TYPES, choice};
use super::value::ValueType;
use super::{Catalogue, Category, Configure, Definition, Evaluate};
use serde::{Deserialize, Serialize};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather
            [$($units)* (Front, fields) (Isolines, fields)]
            [$($configured)* (Layers, fields)]
            $($rest)*);
    };
}
pub(super) use kinds;

/// Warns when a front's width can be 0.
fn check_width(io: &mut Ranges) {
    if io.float("width").lo <= 0.0 {
        io.warn("the width can be 0: a hard front that aliases (stair-steps) on screen".into());
    }
}

/// A propagation front over a distance field: 1 where `distance + noise` is below
/// `threshold`, fading to 0 over `width` beyond it (seed 003).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Front;

impl Definition for Front {
    computed_in!(Category::Field, unchecked);
    fn title(&self) -> &'static str {
        "Front"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["geotexture", "spread", "threshold", "grow", "coverage"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("distance", FLOAT, REQUIRED),
                input("threshold", FLOAT, f(0.5)).limits(0.0, 1.0),
                input("width", FLOAT, f(0.05)).soft(0.0, 0.5),
                input("noise", FLOAT, f(0.0)).soft(-0.2, 0.2),
            ],
            vec![output("covered", FLOAT)],
        )
    }
    fn emit(&self, io: &mut Emit) {
        io.call("veneer_front");
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        check_width(io);
        super::unit_range()
    }
}

impl Evaluate for Front {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        vec![splat(front(
            io.float("distance"),
            io.float("threshold"),
            io.float("width"),
            io.float("noise"),
        ))]
    }
}

plain_catalogue!(Front);

/// Lines where a value crosses multiples of `spacing`, `width` wide.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Isolines;

impl Definition for Isolines {
    computed_in!(Category::Field, unchecked);
    fn title(&self) -> &'static str {
        "Isolines"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["contours", "level sets", "lines", "topographic"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("value", FLOAT, REQUIRED),
                input("spacing", FLOAT, f(0.1)).soft(0.0, 1.0),
                input("width", FLOAT, f(0.01)).soft(0.0, 0.1),
            ],
            vec![output("line", FLOAT)],
        )
    }
    fn emit(&self, io: &mut Emit) {
        io.call("veneer_isolines");
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        if io.float("spacing").lo <= 0.0 || io.float("width").lo <= 0.0 {
            io.warn("the spacing or the width can be 0: no lines there".into());
        }
        super::unit_range()
    }
}

impl Evaluate for Isolines {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        vec![splat(isolines(
            io.float("value"),
            io.float("spacing"),
            io.float("width"),
        ))]
    }
}

plain_catalogue!(Isolines);

/// Four values in nested rings around the sources of a distance field, each boundary a
/// front of the same width and noise (seed 003's nested mixes).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Layers {
    pub ty: ValueType,
}

/// The values of the layers, outermost first, and the edge each one ends at.
const LAYERS: [(&str, &str); 3] = [("third", "edge3"), ("second", "edge2"), ("inner", "edge1")];

impl Definition for Layers {
    computed_in!(Category::Field, unchecked);
    fn title(&self) -> &'static str {
        "Layers"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["geotexture", "nested", "bands", "zones", "mix"]
    }
    fn signature(&self) -> Signature {
        let ty = self.ty;
        Signature::new(
            vec![
                input("distance", FLOAT, REQUIRED),
                input("noise", FLOAT, f(0.0)).soft(-0.2, 0.2),
                input("width", FLOAT, f(0.02)).soft(0.0, 0.5),
                input("edge1", FLOAT, f(0.25)).soft(0.0, 1.0),
                input("edge2", FLOAT, f(0.5)).soft(0.0, 1.0),
                input("edge3", FLOAT, f(0.75)).soft(0.0, 1.0),
                input("inner", ty, splat_default(ty, 0.0)).soft(0.0, 1.0),
                input("second", ty, splat_default(ty, 0.33)).soft(0.0, 1.0),
                input("third", ty, splat_default(ty, 0.67)).soft(0.0, 1.0),
                input("outer", ty, splat_default(ty, 1.0)).soft(0.0, 1.0),
            ],
            vec![output("result", ty)],
        )
    }
    fn emit(&self, io: &mut Emit) {
        let front = |edge: &str| {
            format!(
                "veneer_front({}, {}, {}, {})",
                io.input("distance"),
                io.input(edge),
                io.input("width"),
                io.input("noise")
            )
        };
        let mixed = LAYERS
            .iter()
            .fold(io.input("outer").to_string(), |outside, (value, edge)| {
                format!("mix({outside}, {}, {})", io.input(value), front(edge))
            });
        io.single(mixed);
        io.uses("veneer_front");
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        check_width(io);
        let hull = |a: &str, b: &str| lanewise(&io.input(a), &io.input(b), Interval::hull);
        vec![lanewise(
            &hull("inner", "second"),
            &hull("third", "outer"),
            Interval::hull,
        )]
    }
}

impl Evaluate for Layers {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let (distance, width, noise) = (io.float("distance"), io.float("width"), io.float("noise"));
        let mixed = LAYERS
            .iter()
            .fold(io.input("outer"), |outside, (value, edge)| {
                mix3(
                    outside,
                    io.input(value),
                    front(distance, io.float(edge), width, noise),
                )
            });
        vec![mixed]
    }
}

impl Configure for Layers {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        vec![choice("type", &mut self.ty, &TYPES)]
    }
}

impl Catalogue for Layers {
    fn menu() -> Vec<(String, Self)> {
        vec![(
            "Layers (colour)".into(),
            Layers {
                ty: ValueType::Color,
            },
        )]
    }
    fn examples() -> Vec<Self> {
        TYPES.into_iter().map(|ty| Layers { ty }).collect()
    }
}
