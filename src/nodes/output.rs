//! The material output.

use super::cpu::Eval;
use super::emit::Emit;
use super::formulas::real::{Real, V3};
use super::interval::Lanes;
use super::pins::{COLOR, FLOAT, Signature, VEC3, f, input, rgb, v3};
use super::ranges::Ranges;
use super::settings::Basis;
use super::{Catalogue, Category, Definition, Evaluate};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather [$($units)* (Material, output)] [$($configured)*] $($rest)*);
    };
}
pub(super) use kinds;

/// The material output: what `veneer_material` returns (`VeneerMaterial`, one field
/// per input in pin order).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material;

impl Definition for Material {
    fn title(&self) -> &'static str {
        "Material"
    }
    fn category(&self) -> Category {
        Category::Output
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["output", "shader", "surface", "bsdf"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("albedo", COLOR, rgb(0.8, 0.8, 0.8)).limits(0.0, 1.0),
                input("alpha", FLOAT, f(1.0)).limits(0.0, 1.0),
                input("specular", COLOR, rgb(0.04, 0.04, 0.04)).limits(0.0, 1.0),
                input("shininess", FLOAT, f(32.0)).soft(1.0, 256.0),
                input("bump", VEC3, v3(0.0, 0.0, 0.0)),
                input("height", FLOAT, f(0.0)).soft(-0.2, 0.2),
                input("emission", COLOR, rgb(0.0, 0.0, 0.0)).soft(0.0, 1.0),
                // Appended for metallic-roughness materials (glTF 2.0's channels).
                input("metallic", FLOAT, f(0.0)).limits(0.0, 1.0),
                input("roughness", FLOAT, f(0.5)).limits(0.0, 1.0),
                input("normal", VEC3, v3(0.0, 0.0, 1.0)).limits(-1.0, 1.0),
                input("emission_strength", FLOAT, f(1.0)).soft(0.0, 10.0),
                input("occlusion", FLOAT, f(1.0)).limits(0.0, 1.0),
            ],
            vec![],
        )
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
        io.statement("return VeneerMaterial(".into());
        for (pin, expression) in io.pins().iter().zip(io.inputs()) {
            io.statement(format!("    {expression}, // {}", pin.name));
        }
        io.statement(");".into());
    }
    fn ranges(&self, _: &mut Ranges) -> Vec<Lanes> {
        Vec::new()
    }
}

impl Evaluate for Material {
    /// No outputs: the evaluator reads the material's inputs by name.
    fn eval<R: Real>(&self, _: &Eval<R>) -> Vec<V3<R>> {
        Vec::new()
    }
}

plain_catalogue!(Material);
