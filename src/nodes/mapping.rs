//! Mapping: interpolating, switching, clamping, stepping and carrying values from one
//! range to another.

use super::cpu::Eval;
use super::emit::Emit;
use super::formulas::real::{Real, V3, map, splat};
use super::formulas::{ranges as map_range, shapes};
use super::interval::{self, Interval, Lanes};
use super::math::typed_settings;
use super::pins::{FLOAT, REQUIRED, Signature, f, input, output, splat as splat_default};
use super::ranges::{Ranges, lanewise};
use super::settings::{Basis, Setting, TYPES, choice};
use super::value::ValueType;
use super::{Catalogue, Category, Configure, Definition, Evaluate};
use serde::{Deserialize, Serialize};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather
            [$($units)* (Smoothstep, mapping) (Remap, mapping)]
            [$($configured)* (Mix, mapping) (Switch, mapping) (Clamp, mapping) (Step, mapping) (MapRange, mapping)]
            $($rest)*);
    };
}
pub(super) use kinds;

/// Linear interpolation `a (1 - factor) + b factor`, clamped to the finite range.
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
        let function = format!("veneer_mix_{}", self.ty.wgsl());
        io.single(format!(
            "{function}({}, {}, {})",
            io.input("a"),
            io.input("b"),
            io.input("factor")
        ));
        io.uses(&function);
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

/// One of three inputs, picked by `choice` rounded to the nearest (0: `a`, 1: `b`, 2:
/// `c`; below 0.5, and NaN, picks `a`, from 1.5 on `c`): Material Maker's and Substance
/// Designer's Switch, for a graph that offers variants behind one parameter.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Switch {
    pub ty: ValueType,
}

impl Definition for Switch {
    computed_in!(Category::Math, unchecked);
    fn title(&self) -> &'static str {
        "Switch"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["select", "choose", "if", "branch", "variant"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("a", self.ty, splat_default(self.ty, 0.0)).soft(0.0, 1.0),
                input("b", self.ty, splat_default(self.ty, 0.5)).soft(0.0, 1.0),
                input("c", self.ty, splat_default(self.ty, 1.0)).soft(0.0, 1.0),
                input("choice", FLOAT, f(0.0)).limits(0.0, 2.0),
            ],
            vec![output("result", self.ty)],
        )
    }
    fn emit(&self, io: &mut Emit) {
        let choice = io.input("choice");
        io.single(format!(
            "select(select({}, {}, {choice} >= 0.5), {}, {choice} >= 1.5)",
            io.input("a"),
            io.input("b"),
            io.input("c"),
        ));
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        // The inputs the choice can pick, joined.
        let choice = io.float("choice");
        let picked = [
            ("a", choice.lo < 0.5),
            ("b", choice.hi >= 0.5 && choice.lo < 1.5),
            ("c", choice.hi >= 1.5),
        ];
        picked
            .into_iter()
            .filter(|(_, possible)| *possible)
            .map(|(pin, _)| io.input(pin))
            .reduce(|joined, next| lanewise(&joined, &next, Interval::hull))
            .map_or_else(|| vec![io.input("a")], |joined| vec![joined])
    }
}

impl Evaluate for Switch {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let choice = io.float("choice");
        let pin = if choice >= R::c(1.5) {
            "c"
        } else if choice >= R::c(0.5) {
            "b"
        } else {
            "a"
        };
        vec![io.input(pin)]
    }
}

typed_settings!(Switch, TYPES, menu [("Switch", ValueType::Float), ("Switch colours", ValueType::Color)]);

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
        let (edge, x) = (io.input("edge"), io.input("x"));
        if io.filters_footprint() {
            let function = format!("veneer_step_filtered_{}", self.ty.wgsl());
            io.single(format!("{function}({edge}, {x})"));
            io.uses(&function);
        } else {
            io.single(format!("step({}({edge}), {x})", self.ty.wgsl()));
        }
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
        io.call(&io.band_limited("veneer_smoothstep"));
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

/// How [`MapRange`] carries a value across (Blender's Map Range modes).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum MapRangeMode {
    /// In proportion.
    Linear,
    /// In `steps` equal steps.
    Stepped,
    /// Through smoothstep (3t² − 2t³).
    Smooth,
    /// Through Perlin's smootherstep (6t⁵ − 15t⁴ + 10t³).
    Smoother,
}

impl MapRangeMode {
    /// Every mode, in menu order.
    pub const ALL: [MapRangeMode; 4] = [
        MapRangeMode::Linear,
        MapRangeMode::Stepped,
        MapRangeMode::Smooth,
        MapRangeMode::Smoother,
    ];

    /// Whether the result can leave the target range (and `clamp` applies).
    fn overshoots(self) -> bool {
        matches!(self, MapRangeMode::Linear | MapRangeMode::Stepped)
    }
}

/// Blender's Map Range: `x` carried from [from_min, from_max] to [to_min, to_max]
/// linearly, in steps, or smoothly; `clamp` keeps the linear and stepped results within
/// the target range. An empty source range gives to_min.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct MapRange {
    pub mode: MapRangeMode,
    pub clamp: bool,
}

impl Definition for MapRange {
    computed_in!(Category::Math, unchecked);
    fn title(&self) -> &'static str {
        "Map range"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &[
            "remap",
            "rescale",
            "fit",
            "quantize",
            "posterize",
            "smoothstep",
        ]
    }
    fn signature(&self) -> Signature {
        let mut inputs = vec![
            input("x", FLOAT, REQUIRED),
            input("from_min", FLOAT, f(0.0)),
            input("from_max", FLOAT, f(1.0)),
            input("to_min", FLOAT, f(0.0)),
            input("to_max", FLOAT, f(1.0)),
        ];
        if self.mode == MapRangeMode::Stepped {
            inputs.push(input("steps", FLOAT, f(4.0)).soft(1.0, 16.0));
        }
        Signature::new(inputs, vec![output("result", FLOAT)])
    }
    fn emit(&self, io: &mut Emit) {
        let function = match self.mode {
            MapRangeMode::Linear => "veneer_map_range_linear".to_string(),
            MapRangeMode::Stepped => io.band_limited("veneer_map_range_stepped"),
            MapRangeMode::Smooth => "veneer_map_range_smooth".to_string(),
            MapRangeMode::Smoother => "veneer_map_range_smoother".to_string(),
        };
        let clamp = if self.mode.overshoots() {
            format!(", {}", self.clamp)
        } else {
            String::new()
        };
        io.single(format!("{function}({}{clamp})", io.inputs().join(", ")));
        io.uses(&function);
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        let target = io.float("to_min").hull(io.float("to_max"));
        if self.clamp || !self.mode.overshoots() {
            return vec![interval::splat(target)];
        }
        let from_min = io.float("from_min");
        let mut t = io
            .float("x")
            .sub(from_min)
            .div(io.float("from_max").sub(from_min));
        if self.mode == MapRangeMode::Stepped {
            // floor(t (s + 1)) / s lies within (|t| (s + 1) + 1) / s of 0.
            let steps = io.float("steps");
            let reach = if steps.lo > 0.0 {
                (t.magnitude() * (steps.hi + 1.0) + 1.0) / steps.lo
            } else {
                3.0e38
            };
            t = Interval::new(-reach, reach);
        }
        let to_min = io.float("to_min");
        let result = to_min.add(t.mul(io.float("to_max").sub(to_min)));
        vec![interval::splat(result.hull(target))]
    }
}

impl Evaluate for MapRange {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let (x, from_min, from_max) = (io.float("x"), io.float("from_min"), io.float("from_max"));
        let (to_min, to_max) = (io.float("to_min"), io.float("to_max"));
        let result = match self.mode {
            MapRangeMode::Linear => {
                map_range::map_range_linear(x, from_min, from_max, to_min, to_max, self.clamp)
            }
            MapRangeMode::Stepped => map_range::map_range_stepped(
                x,
                from_min,
                from_max,
                to_min,
                to_max,
                io.float("steps"),
                self.clamp,
            ),
            MapRangeMode::Smooth => {
                map_range::map_range_smooth(x, from_min, from_max, to_min, to_max)
            }
            MapRangeMode::Smoother => {
                map_range::map_range_smoother(x, from_min, from_max, to_min, to_max)
            }
        };
        vec![splat(result)]
    }
}

impl Configure for MapRange {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        vec![
            choice("mode", &mut self.mode, &MapRangeMode::ALL),
            Setting::Toggle {
                label: "clamp",
                value: &mut self.clamp,
            },
        ]
    }
}

impl Catalogue for MapRange {
    fn menu() -> Vec<(String, Self)> {
        let mode = MapRangeMode::Linear;
        vec![("Map range".into(), MapRange { mode, clamp: true })]
    }
    fn examples() -> Vec<Self> {
        MapRangeMode::ALL
            .into_iter()
            .flat_map(|mode| [true, false].map(|clamp| MapRange { mode, clamp }))
            .collect()
    }
}
