//! Inputs: what the surface provides at the shaded point, and constants.

use super::cpu::Eval;
use super::emit::Emit;
use super::formulas::real::{Real, V3, splat};
use super::interval::{self, Interval, Lanes};
use super::pins::{Signature, input, output, splat as splat_default};
use super::ranges::Ranges;
use super::settings::{Basis, Setting, TYPES, choice};
use super::value::ValueType;
use super::{Catalogue, Category, Configure, Definition, Evaluate};
use serde::{Deserialize, Serialize};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather
            [$($units)* (Position, inputs) (Normal, inputs) (Uv, inputs) (Time, inputs)]
            [$($configured)* (Field, inputs) (Constant, inputs)]
            $($rest)*);
    };
}
pub(super) use kinds;

/// A surface input with one output read straight from `VeneerSurface`.
macro_rules! surface_input {
    ($(#[$doc:meta])* $kind:ident, $title:literal, [$($keyword:literal),*], $pin:literal, $ty:expr,
     $wgsl:literal, |$s:ident| $value:expr, $range:expr) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct $kind;

        impl Definition for $kind {
            fn title(&self) -> &'static str {
                $title
            }
            fn category(&self) -> Category {
                Category::Input
            }
            fn keywords(&self) -> &'static [&'static str] {
                &[$($keyword),*]
            }
            fn signature(&self) -> Signature {
                Signature::new(vec![], vec![output($pin, $ty)])
            }
            fn reads_surface(&self) -> bool {
                true
            }
            fn basis(&self) -> Option<Basis> {
                None
            }
            fn check(&self) -> Option<String> {
                None
            }
            fn emit(&self, io: &mut Emit) {
                io.outputs(vec![$wgsl.into()]);
            }
            fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
                let range: fn(&Ranges) -> Lanes = $range;
                vec![range(io)]
            }
        }

        impl Evaluate for $kind {
            fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
                let $s = io.surface;
                vec![$value]
            }
        }

        impl Catalogue for $kind {
            fn menu() -> Vec<(String, Self)> {
                vec![($title.into(), $kind)]
            }
            fn examples() -> Vec<Self> {
                vec![$kind]
            }
        }
    };
}

surface_input!(
    /// Object-space position of the shaded point.
    Position, "Position", ["coordinates", "location", "object", "vector"], "position",
    ValueType::Vec3, "s.position", |s| s.position, |io| io.positions
);
surface_input!(
    /// Unit object-space normal.
    Normal, "Normal", ["direction", "geometry"], "normal", ValueType::Vec3, "s.normal",
    |s| s.normal, |_| interval::splat(Interval::new(-1.0, 1.0))
);
surface_input!(
    /// Texture coordinates.
    Uv, "UV", ["texture coordinate", "uv map"], "uv", ValueType::Vec2, "s.uv",
    |s| [s.uv[0], s.uv[1], R::c(0.0)], |_| interval::splat(Interval::UNIT)
);
surface_input!(
    /// Time in seconds.
    Time, "Time", ["animation", "seconds", "frame"], "time", ValueType::Float, "s.time",
    |s| splat(s.time), |_| interval::splat(Interval::new(0.0, f64::INFINITY))
);

/// One of the four distance fields of `VeneerSurface.fields`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Field {
    pub slot: u32,
}

impl Definition for Field {
    fn title(&self) -> &'static str {
        "Distance field"
    }
    fn category(&self) -> Category {
        Category::Input
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["geodesic", "distance", "geotexture"]
    }
    fn signature(&self) -> Signature {
        Signature::new(vec![], vec![output("distance", ValueType::Float)])
    }
    fn reads_surface(&self) -> bool {
        true
    }
    fn basis(&self) -> Option<Basis> {
        None
    }
    fn check(&self) -> Option<String> {
        (self.slot > 3)
            .then(|| format!("field slot {} is out of range (expected 0 to 3)", self.slot))
    }
    fn emit(&self, io: &mut Emit) {
        let lane = ["x", "y", "z", "w"][self.slot as usize % 4];
        io.outputs(vec![format!("s.fields.{lane}")]);
    }
    fn ranges(&self, _: &mut Ranges) -> Vec<Lanes> {
        super::unit_range()
    }
}

impl Evaluate for Field {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        vec![splat(io.surface.fields[self.slot as usize % 4])]
    }
}

impl Configure for Field {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        vec![Setting::Count {
            label: "field slot",
            value: &mut self.slot,
            range: 0..=3,
        }]
    }
}

impl Catalogue for Field {
    fn menu() -> Vec<(String, Self)> {
        vec![("Distance field".into(), Field { slot: 0 })]
    }
    fn examples() -> Vec<Self> {
        vec![Field { slot: 0 }, Field { slot: 3 }]
    }
}

/// A constant (its `value` input); also usable as a reroute point.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Constant {
    pub ty: ValueType,
}

impl Definition for Constant {
    computed_in!(Category::Input, unchecked);
    fn title(&self) -> &'static str {
        "Constant"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &[
            "value", "number", "vector", "colour", "color", "rgb", "reroute",
        ]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![input("value", self.ty, splat_default(self.ty, 0.0))],
            vec![output("value", self.ty)],
        )
    }
    fn emit(&self, io: &mut Emit) {
        io.single(io.input("value").to_string());
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        vec![io.input("value")]
    }
}

impl Evaluate for Constant {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        vec![io.input("value")]
    }
}

impl Configure for Constant {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        vec![choice("type", &mut self.ty, &TYPES)]
    }
}

impl Catalogue for Constant {
    fn menu() -> Vec<(String, Self)> {
        [
            ("Value", ValueType::Float),
            ("Vector", ValueType::Vec3),
            ("Colour", ValueType::Color),
            ("Vector 2", ValueType::Vec2),
            ("Reroute", ValueType::Vec3),
        ]
        .into_iter()
        .map(|(name, ty)| (name.to_string(), Constant { ty }))
        .collect()
    }
    fn examples() -> Vec<Self> {
        TYPES.into_iter().map(|ty| Constant { ty }).collect()
    }
}
