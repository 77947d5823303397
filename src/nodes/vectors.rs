//! Vectors: lengths, dot products, directions, and components taken apart and put
//! together.

use super::cpu::Eval;
use super::emit::Emit;
use super::formulas::real::{self, Real, V3, safe_normalize, splat};
use super::interval::{self, Interval, Lanes, max_length};
use super::math::typed_settings;
use super::pins::{COMPONENTS, FLOAT, REQUIRED, Signature, f, input, output};
use super::ranges::Ranges;
use super::settings::{Basis, Setting, VECTORS, choice};
use super::value::ValueType;
use super::{Catalogue, Category, Configure, Definition, Evaluate};
use serde::{Deserialize, Serialize};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather
            [$($units)*]
            [$($configured)* (Length, vectors) (Dot, vectors) (Normalize, vectors) (Split, vectors)
                (Combine, vectors)]
            $($rest)*);
    };
}
pub(super) use kinds;

/// The message for a vector-only kind given a float.
fn vector_only(ty: ValueType) -> Option<String> {
    (ty == ValueType::Float)
        .then(|| format!("type {ty} is not a vector (expected vec2, vec3 or color)"))
}

/// Length of a vector (of any finite one, clamped to the finite range).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Length {
    pub ty: ValueType,
}

impl Definition for Length {
    computed_in!(Category::Math);
    fn title(&self) -> &'static str {
        "Length"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["magnitude", "norm", "distance", "vector"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![input("v", self.ty, REQUIRED)],
            vec![output("length", FLOAT)],
        )
    }
    fn check(&self) -> Option<String> {
        vector_only(self.ty)
    }
    fn emit(&self, io: &mut Emit) {
        let function = format!("veneer_length_{}", self.ty.wgsl());
        io.single(format!("{function}({})", io.input("v")));
        io.uses(&function);
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        let longest = max_length(&io.input("v"), self.ty.width());
        vec![interval::splat(Interval::new(0.0, longest))]
    }
}

impl Evaluate for Length {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        vec![splat(real::finite_length(io.input("v"), self.ty.width()))]
    }
}

typed_settings!(Length, VECTORS, menu[("Length", ValueType::Vec3)]);

/// Dot product of two vectors (each product clamped to ±1e38, so it cannot overflow).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Dot {
    pub ty: ValueType,
}

impl Definition for Dot {
    computed_in!(Category::Math);
    fn title(&self) -> &'static str {
        "Dot"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["dot product", "scalar product", "vector", "facing"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![input("a", self.ty, REQUIRED), input("b", self.ty, REQUIRED)],
            vec![output("dot", FLOAT)],
        )
    }
    fn check(&self) -> Option<String> {
        vector_only(self.ty)
    }
    fn emit(&self, io: &mut Emit) {
        let function = format!("veneer_dot_{}", self.ty.wgsl());
        io.single(format!("{function}({}, {})", io.input("a"), io.input("b")));
        io.uses(&function);
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        let width = self.ty.width();
        let bound = max_length(&io.input("a"), width) * max_length(&io.input("b"), width);
        vec![interval::splat(Interval::new(-bound, bound))]
    }
}

impl Evaluate for Dot {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        vec![splat(real::finite_dot(
            io.input("a"),
            io.input("b"),
            self.ty.width(),
        ))]
    }
}

typed_settings!(Dot, VECTORS, menu[("Dot", ValueType::Vec3)]);

/// Unit vector in the same direction; zero stays zero.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Normalize {
    pub ty: ValueType,
}

impl Definition for Normalize {
    computed_in!(Category::Math);
    fn title(&self) -> &'static str {
        "Normalize"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["unit vector", "direction", "vector"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![input("v", self.ty, REQUIRED)],
            vec![output("unit", self.ty)],
        )
    }
    fn check(&self) -> Option<String> {
        vector_only(self.ty)
    }
    fn emit(&self, io: &mut Emit) {
        let function = format!("veneer_safe_normalize_{}", self.ty.wgsl());
        io.single(format!("{function}({})", io.input("v")));
        io.uses(&function);
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        let v = io.input("v");
        if v[..self.ty.width()].iter().all(|lane| lane.contains(0.0)) {
            io.warn(
                "the vector may be zero, where it has no direction: the result is 0 there".into(),
            );
        }
        vec![interval::splat(Interval::new(-1.0, 1.0))]
    }
}

impl Evaluate for Normalize {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        vec![safe_normalize(io.input("v"), self.ty.width())]
    }
}

typed_settings!(Normalize, VECTORS, menu[("Normalize", ValueType::Vec3)]);

/// Components of a vector.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Split {
    pub ty: ValueType,
}

impl Definition for Split {
    computed_in!(Category::Math);
    fn title(&self) -> &'static str {
        "Split"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["separate", "components", "xyz", "rgb", "channels"]
    }
    fn signature(&self) -> Signature {
        let outputs = COMPONENTS[..self.ty.width()]
            .iter()
            .map(|name| output(name, FLOAT))
            .collect();
        Signature::new(vec![input("v", self.ty, REQUIRED)], outputs)
    }
    fn check(&self) -> Option<String> {
        vector_only(self.ty)
    }
    fn emit(&self, io: &mut Emit) {
        io.bind(self.ty.wgsl(), io.input("v").to_string());
        let name = io.name();
        io.outputs(
            COMPONENTS[..self.ty.width()]
                .iter()
                .map(|c| format!("{name}.{c}"))
                .collect(),
        );
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        let v = io.input("v");
        (0..self.ty.width())
            .map(|k| interval::splat(v[k]))
            .collect()
    }
}

impl Evaluate for Split {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let v = io.input("v");
        (0..self.ty.width()).map(|k| splat(v[k])).collect()
    }
}

typed_settings!(Split, VECTORS, menu[("Split", ValueType::Vec3)]);

/// A vector from components.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Combine {
    pub ty: ValueType,
}

impl Definition for Combine {
    computed_in!(Category::Math);
    fn title(&self) -> &'static str {
        "Combine"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["join", "components", "xyz", "rgb", "vector", "colour"]
    }
    fn signature(&self) -> Signature {
        let inputs = COMPONENTS[..self.ty.width()]
            .iter()
            .map(|name| input(name, FLOAT, f(0.0)))
            .collect();
        Signature::new(inputs, vec![output("v", self.ty)])
    }
    fn check(&self) -> Option<String> {
        vector_only(self.ty)
    }
    fn emit(&self, io: &mut Emit) {
        io.single(format!("{}({})", self.ty.wgsl(), io.inputs().join(", ")));
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        let z = if self.ty.width() == 3 {
            io.float("z")
        } else {
            Interval::point(0.0)
        };
        vec![[io.float("x"), io.float("y"), z]]
    }
}

impl Evaluate for Combine {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let z = if self.ty.width() == 3 {
            io.float("z")
        } else {
            R::c(0.0)
        };
        vec![[io.float("x"), io.float("y"), z]]
    }
}

typed_settings!(Combine, VECTORS, menu [("Combine", ValueType::Vec3), ("Combine colour", ValueType::Color)]);
