//! Math: arithmetic, interpolation, clamping and vector operations.

use super::cpu::Eval;
use super::emit::Emit;
use super::formulas::real::{Real, V3, finite, map, zip};
use super::formulas::shapes;
use super::interval::{Interval, Lanes};
use super::pins::{REQUIRED, Signature, input, output, splat as splat_default};
use super::ranges::{Ranges, lanewise};
use super::settings::{Basis, MathOp, Setting, TYPES, UnaryOp, choice};
use super::value::ValueType;
use super::{Catalogue, Category, Configure, Definition, Evaluate};
use serde::{Deserialize, Serialize};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather
            [$($units)*]
            [$($configured)* (Math, math) (Unary, math)]
            $($rest)*);
    };
}
pub(super) use kinds;

/// The settings and catalogue of a kind whose only setting is its value type, chosen
/// from `$types`, and its menu entries.
macro_rules! typed_settings {
    ($kind:ident, $types:expr, menu [$(($name:literal, $ty:expr)),*]) => {
        impl Configure for $kind {
            fn settings(&mut self) -> Vec<Setting<'_>> {
                vec![choice("type", &mut self.ty, &$types)]
            }
        }

        impl Catalogue for $kind {
            fn menu() -> Vec<(String, Self)> {
                vec![$(($name.into(), $kind { ty: $ty })),*]
            }
            fn examples() -> Vec<Self> {
                $types.into_iter().map(|ty| $kind { ty }).collect()
            }
        }
    };
}
pub(super) use typed_settings;

/// A binary arithmetic operator; every result is finite for finite operands (sums,
/// differences and products clamp to the finite range; division and power are safe).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Math {
    pub op: MathOp,
    pub ty: ValueType,
}

impl Definition for Math {
    computed_in!(Category::Math);
    fn title(&self) -> &'static str {
        "Math"
    }
    /// The operation ("Divide", "Sin"), as the add-node menu names it.
    fn shown_title(&self) -> String {
        format!("{:?}", self.op)
    }
    fn keywords(&self) -> &'static [&'static str] {
        &[
            "add",
            "subtract",
            "multiply",
            "divide",
            "power",
            "minimum",
            "maximum",
            "arithmetic",
        ]
    }
    fn signature(&self) -> Signature {
        let identity = match self.op {
            MathOp::Multiply | MathOp::Divide | MathOp::Power => 1.0,
            _ => 0.0,
        };
        Signature::new(
            vec![
                input("a", self.ty, splat_default(self.ty, 0.0)),
                input("b", self.ty, splat_default(self.ty, identity)),
            ],
            vec![output("result", self.ty)],
        )
    }
    fn check(&self) -> Option<String> {
        None
    }
    fn emit(&self, io: &mut Emit) {
        let (a, b) = (io.input("a"), io.input("b"));
        let ty = self.ty.wgsl();
        let mut library = |stem: &str| {
            let function = format!("veneer_{stem}_{ty}");
            io.uses(&function);
            function
        };
        // Sums, differences and products can overflow: clamped to the finite range.
        let expression = match self.op {
            MathOp::Add => format!("{}({a} + {b})", library("finite")),
            MathOp::Subtract => format!("{}({a} - {b})", library("finite")),
            MathOp::Multiply => format!("{}({a} * {b})", library("finite")),
            MathOp::Minimum => format!("min({a}, {b})"),
            MathOp::Maximum => format!("max({a}, {b})"),
            MathOp::Divide => format!("{}({a}, {b})", library("safe_div")),
            MathOp::Power => format!("{}({a}, {b})", library("safe_pow")),
        };
        io.single(expression);
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        let (a, b) = (io.input("a"), io.input("b"));
        let result = match self.op {
            MathOp::Add => lanewise(&a, &b, Interval::add),
            MathOp::Subtract => lanewise(&a, &b, Interval::sub),
            MathOp::Multiply => lanewise(&a, &b, Interval::mul),
            MathOp::Minimum => {
                lanewise(&a, &b, |a, b| Interval::new(a.lo.min(b.lo), a.hi.min(b.hi)))
            }
            MathOp::Maximum => {
                lanewise(&a, &b, |a, b| Interval::new(a.lo.max(b.lo), a.hi.max(b.hi)))
            }
            MathOp::Divide => {
                if b.iter().any(|lane| lane.contains(0.0)) {
                    io.warn("the divisor may be 0 there: the result is 0".into());
                }
                lanewise(&a, &b, Interval::div)
            }
            MathOp::Power => {
                if a.iter().any(|lane| lane.lo < 0.0) {
                    io.warn("the base may be negative, where a power is undefined: the result is 0 there".into());
                }
                lanewise(&a, &b, power_range)
            }
        };
        vec![result]
    }
}

/// The range of `veneer_safe_pow` over a base and an exponent range.
pub(super) fn power_range(base: Interval, exponent: Interval) -> Interval {
    let base = base.clamp(0.0, f64::MAX);
    let corners = [
        base.lo.powf(exponent.lo),
        base.lo.powf(exponent.hi),
        base.hi.powf(exponent.lo),
        base.hi.powf(exponent.hi),
    ];
    let corners = corners.map(|c| if c.is_nan() { 0.0 } else { c.min(3.0e38) });
    Interval::new(
        0.0f64.min(corners.iter().copied().fold(f64::INFINITY, f64::min)),
        corners.iter().copied().fold(0.0, f64::max),
    )
}

impl Evaluate for Math {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        vec![zip(io.input("a"), io.input("b"), |a, b| match self.op {
            MathOp::Add => finite(a + b),
            MathOp::Subtract => finite(a - b),
            MathOp::Multiply => finite(a * b),
            MathOp::Divide => shapes::safe_div(a, b),
            MathOp::Power => shapes::safe_pow(a, b),
            MathOp::Minimum => a.min(b),
            MathOp::Maximum => a.max(b),
        })]
    }
}

impl Configure for Math {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        vec![
            choice("operation", &mut self.op, &MathOp::ALL),
            choice("type", &mut self.ty, &TYPES),
        ]
    }
}

impl Catalogue for Math {
    fn menu() -> Vec<(String, Self)> {
        MathOp::ALL
            .into_iter()
            .map(|op| {
                let ty = ValueType::Float;
                (format!("{op:?}"), Math { op, ty })
            })
            .collect()
    }
    fn examples() -> Vec<Self> {
        TYPES
            .into_iter()
            .flat_map(|ty| MathOp::ALL.map(|op| Math { op, ty }))
            .collect()
    }
}

/// A unary operator, applied per component.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Unary {
    pub op: UnaryOp,
    pub ty: ValueType,
}

impl Definition for Unary {
    computed_in!(Category::Math);
    fn title(&self) -> &'static str {
        "Unary"
    }
    /// The operation ("Divide", "Sin"), as the add-node menu names it.
    fn shown_title(&self) -> String {
        format!("{:?}", self.op)
    }
    fn keywords(&self) -> &'static [&'static str] {
        &[
            "absolute",
            "fraction",
            "floor",
            "sine",
            "cosine",
            "negate",
            "invert",
            "one minus",
        ]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![input("x", self.ty, REQUIRED)],
            vec![output("result", self.ty)],
        )
    }
    fn check(&self) -> Option<String> {
        None
    }
    fn emit(&self, io: &mut Emit) {
        let x = io.input("x");
        io.single(match self.op {
            UnaryOp::Abs => format!("abs({x})"),
            UnaryOp::Fract => format!("fract({x})"),
            UnaryOp::Floor => format!("floor({x})"),
            UnaryOp::Sin => format!("sin({x})"),
            UnaryOp::Cos => format!("cos({x})"),
            UnaryOp::Negate => format!("-({x})"),
            UnaryOp::OneMinus => format!("1.0 - {x}"),
        });
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        vec![io.input("x").map(|x| match self.op {
            UnaryOp::Abs => Interval::new(
                if x.contains(0.0) {
                    0.0
                } else {
                    x.lo.abs().min(x.hi.abs())
                },
                x.magnitude(),
            ),
            UnaryOp::Fract => Interval::UNIT,
            UnaryOp::Floor => Interval::new(x.lo.floor(), x.hi.floor()),
            UnaryOp::Sin | UnaryOp::Cos => Interval::new(-1.0, 1.0),
            UnaryOp::Negate => Interval::new(-x.hi, -x.lo),
            UnaryOp::OneMinus => Interval::new(1.0 - x.hi, 1.0 - x.lo),
        })]
    }
}

impl Evaluate for Unary {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        vec![map(io.input("x"), |x| match self.op {
            UnaryOp::Abs => x.abs(),
            UnaryOp::Fract => x.fract(),
            UnaryOp::Floor => x.floor(),
            UnaryOp::Sin => x.sin(),
            UnaryOp::Cos => x.cos(),
            UnaryOp::Negate => -x,
            UnaryOp::OneMinus => R::c(1.0) - x,
        })]
    }
}

impl Configure for Unary {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        vec![
            choice("operation", &mut self.op, &UnaryOp::ALL),
            choice("type", &mut self.ty, &TYPES),
        ]
    }
}

impl Catalogue for Unary {
    fn menu() -> Vec<(String, Self)> {
        UnaryOp::ALL
            .into_iter()
            .map(|op| {
                let ty = ValueType::Float;
                (format!("{op:?}"), Unary { op, ty })
            })
            .collect()
    }
    fn examples() -> Vec<Self> {
        TYPES
            .into_iter()
            .flat_map(|ty| UnaryOp::ALL.map(|op| Unary { op, ty }))
            .collect()
    }
}
