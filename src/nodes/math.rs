//! Math: arithmetic, interpolation, clamping and vector operations.

use super::coordinates::plain_catalogue;
use super::cpu::Eval;
use super::emit::Emit;
use super::formulas::real::{Real, V3, map, splat, zip};
use super::formulas::shapes;
use super::interval::{self, Interval, Lanes};
use super::pins::{FLOAT, REQUIRED, Signature, f, input, output, splat as splat_default};
use super::ranges::{Ranges, lanewise};
use super::settings::{Basis, MathOp, Setting, TYPES, UnaryOp, choice};
use super::value::ValueType;
use super::{Catalogue, Category, Configure, Definition, Evaluate};
use serde::{Deserialize, Serialize};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather
            [$($units)* (Smoothstep, math) (Remap, math)]
            [$($configured)* (Math, math) (Unary, math) (Mix, math) (Clamp, math) (Step, math)]
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

/// A binary arithmetic operator; division and power are safe (never NaN or Inf).
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
        let expression = match self.op {
            MathOp::Add => format!("{a} + {b}"),
            MathOp::Subtract => format!("{a} - {b}"),
            MathOp::Multiply => format!("{a} * {b}"),
            MathOp::Minimum => format!("min({a}, {b})"),
            MathOp::Maximum => format!("max({a}, {b})"),
            MathOp::Divide | MathOp::Power => {
                let stem = if self.op == MathOp::Divide {
                    "safe_div"
                } else {
                    "safe_pow"
                };
                let function = format!("veneer_{stem}_{}", self.ty.wgsl());
                io.uses(&function);
                format!("{function}({a}, {b})")
            }
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
fn power_range(base: Interval, exponent: Interval) -> Interval {
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
            MathOp::Add => a + b,
            MathOp::Subtract => a - b,
            MathOp::Multiply => a * b,
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

/// Linear interpolation `a + (b - a) * factor`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Mix {
    pub ty: ValueType,
}

impl Definition for Mix {
    computed_in!(Category::Math);
    fn title(&self) -> &'static str {
        "Mix"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["lerp", "blend", "interpolate", "mix rgb"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("a", self.ty, splat_default(self.ty, 0.0)).soft(0.0, 1.0),
                input("b", self.ty, splat_default(self.ty, 1.0)).soft(0.0, 1.0),
                input("factor", FLOAT, f(0.5)).soft(0.0, 1.0),
            ],
            vec![output("result", self.ty)],
        )
    }
    fn check(&self) -> Option<String> {
        None
    }
    fn emit(&self, io: &mut Emit) {
        io.single(format!(
            "mix({}, {}, {})",
            io.input("a"),
            io.input("b"),
            io.input("factor")
        ));
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        let factor = io.float("factor");
        vec![lanewise(&io.input("a"), &io.input("b"), |a, b| {
            a.add(b.sub(a).mul(factor))
        })]
    }
}

impl Evaluate for Mix {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        vec![shapes::mix3(
            io.input("a"),
            io.input("b"),
            io.float("factor"),
        )]
    }
}

typed_settings!(Mix, TYPES, menu [("Mix", ValueType::Float), ("Mix colours", ValueType::Color)]);

/// Clamp every component between `min` and `max`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Clamp {
    pub ty: ValueType,
}

impl Definition for Clamp {
    computed_in!(Category::Math);
    fn title(&self) -> &'static str {
        "Clamp"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["limit", "saturate", "minimum", "maximum"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("x", self.ty, REQUIRED),
                input("min", FLOAT, f(0.0)),
                input("max", FLOAT, f(1.0)),
            ],
            vec![output("result", self.ty)],
        )
    }
    fn check(&self) -> Option<String> {
        None
    }
    fn emit(&self, io: &mut Emit) {
        let t = self.ty.wgsl();
        io.single(format!(
            "min(max({}, {t}({})), {t}({}))",
            io.input("x"),
            io.input("min"),
            io.input("max")
        ));
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        let (low, high) = (io.float("min"), io.float("max"));
        vec![
            io.input("x").map(|x| {
                Interval::new(x.lo.max(low.lo).min(high.hi), x.hi.min(high.hi).max(low.lo))
            }),
        ]
    }
}

impl Evaluate for Clamp {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let (low, high) = (io.float("min"), io.float("max"));
        vec![map(io.input("x"), |x| x.max(low).min(high))]
    }
}

typed_settings!(Clamp, TYPES, menu[("Clamp", ValueType::Float)]);

/// 0 below `edge`, 1 from it on.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Step {
    pub ty: ValueType,
}

impl Definition for Step {
    computed_in!(Category::Math);
    fn title(&self) -> &'static str {
        "Step"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["threshold", "greater than", "compare", "mask"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("edge", FLOAT, f(0.5)).soft(0.0, 1.0),
                input("x", self.ty, REQUIRED),
            ],
            vec![output("result", self.ty)],
        )
    }
    fn check(&self) -> Option<String> {
        None
    }
    fn emit(&self, io: &mut Emit) {
        io.single(format!(
            "step({}({}), {})",
            self.ty.wgsl(),
            io.input("edge"),
            io.input("x")
        ));
    }
    fn ranges(&self, _: &mut Ranges) -> Vec<Lanes> {
        super::unit_range()
    }
}

impl Evaluate for Step {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let edge = io.float("edge");
        vec![map(io.input("x"), |x| R::step(edge, x))]
    }
}

typed_settings!(Step, TYPES, menu[("Step", ValueType::Float)]);

/// Hermite smoothstep, well defined when the edges are equal or reversed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Smoothstep;

impl Definition for Smoothstep {
    computed_in!(Category::Math);
    fn title(&self) -> &'static str {
        "Smoothstep"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["smooth", "ramp", "hermite", "threshold", "soft step"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("edge0", FLOAT, f(0.0)).soft(0.0, 1.0),
                input("edge1", FLOAT, f(1.0)).soft(0.0, 1.0),
                input("x", FLOAT, REQUIRED),
            ],
            vec![output("result", FLOAT)],
        )
    }
    fn check(&self) -> Option<String> {
        None
    }
    fn emit(&self, io: &mut Emit) {
        io.call("veneer_smoothstep");
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        match (io.constant("edge0"), io.constant("edge1")) {
            (Some(a), Some(b)) if a == b => io.warn(format!(
                "edge0 = edge1 = {a}: a hard step, not a smooth one"
            )),
            (Some(a), Some(b)) if a > b => io.warn(format!(
                "edge0 {a} > edge1 {b}: the ramp falls instead of rising"
            )),
            _ => {}
        }
        super::unit_range()
    }
}

impl Evaluate for Smoothstep {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        vec![splat(shapes::smoothstep(
            io.float("edge0"),
            io.float("edge1"),
            io.float("x"),
        ))]
    }
}

plain_catalogue!(Smoothstep);

/// Linear map from [from_min, from_max] to [to_min, to_max].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Remap;

impl Definition for Remap {
    computed_in!(Category::Math);
    fn title(&self) -> &'static str {
        "Remap"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["map range", "rescale", "fit", "normalize range"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("x", FLOAT, REQUIRED),
                input("from_min", FLOAT, f(0.0)),
                input("from_max", FLOAT, f(1.0)),
                input("to_min", FLOAT, f(0.0)),
                input("to_max", FLOAT, f(1.0)),
            ],
            vec![output("result", FLOAT)],
        )
    }
    fn check(&self) -> Option<String> {
        None
    }
    fn emit(&self, io: &mut Emit) {
        io.call("veneer_remap");
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        if let (Some(a), Some(b)) = (io.constant("from_min"), io.constant("from_max"))
            && a == b
        {
            io.warn(format!(
                "from_min = from_max = {a}: the result is to_min everywhere"
            ));
        }
        let (from_min, to_min) = (io.float("from_min"), io.float("to_min"));
        let t = io
            .float("x")
            .sub(from_min)
            .div(io.float("from_max").sub(from_min));
        vec![interval::splat(
            to_min.add(t.mul(io.float("to_max").sub(to_min))),
        )]
    }
}

impl Evaluate for Remap {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        vec![splat(shapes::remap(
            io.float("x"),
            io.float("from_min"),
            io.float("from_max"),
            io.float("to_min"),
            io.float("to_max"),
        ))]
    }
}

plain_catalogue!(Remap);
