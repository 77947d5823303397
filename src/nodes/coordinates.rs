//! Coordinates: transforming, projecting and warping the point that patterns read.

use super::cpu::Eval;
use super::emit::{Emit, value_literal};
use super::formulas::real::{Real, V3, splat};
use super::formulas::shapes;
use super::interval::{self, Interval, Lanes, max_length};
use super::pins::{FLOAT, POINT, Signature, VEC3, f, input, output, v3};
use super::ranges::{Ranges, lanewise};
use super::settings::{Basis, Setting, check_period, choice, no_period, period};
use super::value::Value;
use super::{Catalogue, Category, Configure, Definition, Evaluate};
use serde::{Deserialize, Serialize};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather
            [$($units)* (Transform, coordinates) (Project, coordinates) (Cylindrical, coordinates)]
            [$($configured)* (DomainWarp, coordinates)]
            $($rest)*);
    };
}
pub(super) use kinds;

/// The distance from `origin` a point can have, warning when `axis` can be zero (shared
/// by the kinds that measure along or around an axis).
pub(super) fn axis_reach(io: &mut Ranges, origin: &str, axis: &str) -> f64 {
    let relative = lanewise(&io.input("p"), &io.input(origin), Interval::sub);
    if io.reach(axis) == 0.0 {
        io.warn("the direction or axis is the zero vector: every point maps to 0".into());
    }
    max_length(&relative, 3)
}

/// `rotate(p * scale) + offset`, rotation in degrees about x, then y, then z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform;

impl Definition for Transform {
    fn title(&self) -> &'static str {
        "Transform"
    }
    computed_in!(Category::Coordinates, unchecked);
    fn keywords(&self) -> &'static [&'static str] {
        &["mapping", "scale", "rotate", "translate", "offset"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                POINT,
                input("scale", VEC3, v3(1.0, 1.0, 1.0)).soft(0.0, 10.0),
                input("rotation", VEC3, v3(0.0, 0.0, 0.0)).soft(-180.0, 180.0),
                input("offset", VEC3, v3(0.0, 0.0, 0.0)).soft(-10.0, 10.0),
            ],
            vec![output("p", VEC3)],
        )
    }
    fn emit(&self, io: &mut Emit) {
        let (p, scale, rotation, offset) = (
            io.input("p"),
            io.input("scale"),
            io.input("rotation"),
            io.input("offset"),
        );
        if rotation == value_literal(&Value::Vec3(0.0, 0.0, 0.0)) {
            io.uses("veneer_scale_offset");
            io.single(format!("veneer_scale_offset({p}, {scale}, {offset})"));
        } else {
            io.uses("veneer_transform");
            io.single(format!(
                "veneer_transform({p}, {scale}, {rotation}, {offset})"
            ));
        }
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        let scaled = lanewise(&io.input("p"), &io.input("scale"), Interval::mul);
        let unrotated = io
            .input("rotation")
            .iter()
            .all(|lane| lane.lo == 0.0 && lane.hi == 0.0);
        let rotated = if unrotated {
            scaled
        } else {
            let radius = max_length(&scaled, 3);
            interval::splat(Interval::new(-radius, radius))
        };
        vec![lanewise(&rotated, &io.input("offset"), Interval::add)]
    }
}

impl Evaluate for Transform {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        vec![shapes::transform(
            io.input("p"),
            io.input("scale"),
            io.input("rotation"),
            io.input("offset"),
        )]
    }
}

plain_catalogue!(Transform);

/// Coordinate along a direction: `(p - origin) · normalize(direction)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Project;

impl Definition for Project {
    fn title(&self) -> &'static str {
        "Project"
    }
    computed_in!(Category::Coordinates, unchecked);
    fn keywords(&self) -> &'static [&'static str] {
        &["gradient", "linear", "axis", "along", "direction"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                POINT,
                input("origin", VEC3, v3(0.0, 0.0, 0.0)).soft(-10.0, 10.0),
                input("direction", VEC3, v3(1.0, 0.0, 0.0)),
            ],
            vec![output("x", FLOAT)],
        )
    }
    fn emit(&self, io: &mut Emit) {
        io.uses("veneer_project");
        io.single(format!(
            "veneer_project({}, {}, {})",
            io.input("p"),
            io.input("origin"),
            io.input("direction")
        ));
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        let radius = axis_reach(io, "origin", "direction");
        vec![interval::splat(Interval::new(-radius, radius))]
    }
}

impl Evaluate for Project {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        vec![splat(shapes::project(
            io.input("p"),
            io.input("origin"),
            io.input("direction"),
        ))]
    }
}

plain_catalogue!(Project);

/// Cylindrical coordinates about an axis: axial t, radius r, angle θ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cylindrical;

impl Definition for Cylindrical {
    fn title(&self) -> &'static str {
        "Cylindrical"
    }
    computed_in!(Category::Coordinates, unchecked);
    fn keywords(&self) -> &'static [&'static str] {
        &["polar", "radius", "angle", "radial", "cylinder"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                POINT,
                input("origin", VEC3, v3(0.0, 0.0, 0.0)).soft(-10.0, 10.0),
                input("axis", VEC3, v3(0.0, 1.0, 0.0)),
            ],
            vec![
                output("t", FLOAT),
                output("r", FLOAT),
                output("theta", FLOAT),
            ],
        )
    }
    fn emit(&self, io: &mut Emit) {
        io.uses("veneer_cylindrical");
        io.bind(
            "vec3f",
            format!(
                "veneer_cylindrical({}, {}, {})",
                io.input("p"),
                io.input("origin"),
                io.input("axis")
            ),
        );
        let name = io.name();
        io.outputs(["x", "y", "z"].map(|c| format!("{name}.{c}")).to_vec());
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        let radius = axis_reach(io, "origin", "axis");
        let pi = std::f64::consts::PI;
        vec![
            interval::splat(Interval::new(-radius, radius)),
            interval::splat(Interval::new(0.0, radius)),
            interval::splat(Interval::new(-pi, pi)),
        ]
    }
}

impl Evaluate for Cylindrical {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        shapes::cylindrical(io.input("p"), io.input("origin"), io.input("axis"))
            .map(splat)
            .to_vec()
    }
}

plain_catalogue!(Cylindrical);

/// `p + strength * (vector noise at p * scale)`, each component in [-1, 1].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct DomainWarp {
    pub basis: Basis,
    /// How many lattice cells the warping noise repeats over (0: it never repeats), so
    /// that a periodic pattern at the warped point still repeats; left out of graph
    /// files when 0.
    #[serde(default, skip_serializing_if = "no_period")]
    pub period: u32,
}

impl Definition for DomainWarp {
    fn title(&self) -> &'static str {
        "Domain warp"
    }
    computed_in!(@parts Category::Coordinates, |self| Some(self.basis));
    fn check(&self) -> Option<String> {
        check_period(self.period, Some(self.basis))
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["distort", "displace", "warp", "noise"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                POINT,
                input("strength", FLOAT, f(1.0)).soft(0.0, 4.0),
                input("scale", FLOAT, f(1.0)).soft(0.0, 20.0),
            ],
            vec![output("p", VEC3)],
        )
    }
    fn emit(&self, io: &mut Emit) {
        let arguments = format!(
            "{}, {}, {}",
            io.input("p"),
            io.input("strength"),
            io.input("scale")
        );
        let function = format!("veneer_warp_{}", self.basis.suffix());
        super::noise::periodic_call(io, &function, arguments, self.period);
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        io.sampled(Some(self.basis));
        let reach = io.float("strength").magnitude();
        vec![
            io.input("p")
                .map(|lane| lane.add(Interval::new(-reach, reach))),
        ]
    }
}

impl Evaluate for DomainWarp {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        vec![shapes::warp(
            self.basis,
            io.input("p"),
            io.float("strength"),
            io.float("scale"),
            period(self.period),
        )]
    }
}

basis_choice!(DomainWarp, "Domain warp");
