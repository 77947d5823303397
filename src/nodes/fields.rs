//! Distance-field patterns (seed 003): fronts spreading over a field, nested layers,
//! isolines.

use super::cpu::Eval;
use super::emit::Emit;
use super::formulas::fields::{front, isolines};
use super::formulas::real::{Real, V3, splat};
use super::formulas::shapes::mix3;
use super::interval::{Interval, Lanes};
use super::pins::{FLOAT, InputPin, REQUIRED, Signature, f, input, output, splat as splat_default};
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
        check_width_message(io);
    }
}

/// The warning for a front whose width can be 0.
fn check_width_message(io: &mut Ranges) {
    io.warn("the width can be 0: a hard front that aliases (stair-steps) on screen".into());
}

/// The two pins that place a front's transition relative to its threshold and width
/// (appended after the first release; their defaults keep older graphs' looks).
fn placement_pins() -> [InputPin; 2] {
    [
        input("centre", FLOAT, f(0.5)).soft(-1.0, 2.0),
        input("softness", FLOAT, f(0.5)).soft(0.0, 2.0),
    ]
}

/// A propagation front over a distance field: 1 near the sources, fading to 0 where
/// `distance + noise` passes `threshold`, as `formulas::fields::front` places it
/// (seed 003 §5.2.4 and appendix C).
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
            ]
            .into_iter()
            .chain(placement_pins())
            .collect(),
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
            io.float("centre"),
            io.float("softness"),
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
/// front (seed 003's nested mixes) with the same noise and placement; one width for
/// every boundary, or one each (`separate_widths`, as appendix C's C.4 has them).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Layers {
    pub ty: ValueType,
    /// A width pin per boundary (`width1` … `width3`) instead of one `width`. Graph
    /// files leave it out when off.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub separate_widths: bool,
}

/// The values of the layers, outermost first, with the edge each one ends at and the
/// width pin of that edge when the widths are separate.
const LAYERS: [(&str, &str, &str); 3] = [
    ("third", "edge3", "width3"),
    ("second", "edge2", "width2"),
    ("inner", "edge1", "width1"),
];

impl Layers {
    /// The pin holding the width of the boundary whose own width pin is `own`.
    fn width_pin(&self, own: &'static str) -> &'static str {
        if self.separate_widths { own } else { "width" }
    }
}

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
        let width = |name| input(name, FLOAT, f(0.02)).soft(0.0, 0.5);
        let widths = if self.separate_widths {
            vec![width("width1"), width("width2"), width("width3")]
        } else {
            vec![width("width")]
        };
        let mut inputs = vec![
            input("distance", FLOAT, REQUIRED),
            input("noise", FLOAT, f(0.0)).soft(-0.2, 0.2),
        ];
        inputs.extend(widths);
        inputs.extend([
            input("edge1", FLOAT, f(0.25)).soft(0.0, 1.0),
            input("edge2", FLOAT, f(0.5)).soft(0.0, 1.0),
            input("edge3", FLOAT, f(0.75)).soft(0.0, 1.0),
            input("inner", ty, splat_default(ty, 0.0)).soft(0.0, 1.0),
            input("second", ty, splat_default(ty, 0.33)).soft(0.0, 1.0),
            input("third", ty, splat_default(ty, 0.67)).soft(0.0, 1.0),
            input("outer", ty, splat_default(ty, 1.0)).soft(0.0, 1.0),
        ]);
        inputs.extend(placement_pins());
        Signature::new(inputs, vec![output("result", ty)])
    }
    fn emit(&self, io: &mut Emit) {
        let front = |edge: &str, width: &str| {
            format!(
                "veneer_front({}, {}, {}, {}, {}, {})",
                io.input("distance"),
                io.input(edge),
                io.input(width),
                io.input("noise"),
                io.input("centre"),
                io.input("softness")
            )
        };
        let mix = format!("veneer_mix_{}", self.ty.wgsl());
        let mixed = LAYERS.iter().fold(
            io.input("outer").to_string(),
            |outside, (value, edge, width)| {
                let covered = front(edge, self.width_pin(width));
                format!("{mix}({outside}, {}, {covered})", io.input(value))
            },
        );
        io.single(mixed);
        io.uses("veneer_front");
        io.uses(&mix);
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        if LAYERS
            .iter()
            .any(|(_, _, width)| io.float(self.width_pin(width)).lo <= 0.0)
        {
            check_width_message(io);
        }
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
        let (distance, noise) = (io.float("distance"), io.float("noise"));
        let (centre, softness) = (io.float("centre"), io.float("softness"));
        let mixed = LAYERS
            .iter()
            .fold(io.input("outer"), |outside, (value, edge, width)| {
                let width = io.float(self.width_pin(width));
                let covered = front(distance, io.float(edge), width, noise, centre, softness);
                mix3(outside, io.input(value), covered)
            });
        vec![mixed]
    }
}

impl Configure for Layers {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        vec![
            choice("type", &mut self.ty, &TYPES),
            Setting::Toggle {
                label: "separate widths",
                value: &mut self.separate_widths,
            },
        ]
    }
}

impl Catalogue for Layers {
    fn menu() -> Vec<(String, Self)> {
        vec![(
            "Layers (colour)".into(),
            Layers {
                ty: ValueType::Color,
                separate_widths: false,
            },
        )]
    }
    fn examples() -> Vec<Self> {
        TYPES
            .into_iter()
            .flat_map(|ty| {
                [false, true].map(|separate_widths| Layers {
                    ty,
                    separate_widths,
                })
            })
            .collect()
    }
}
