//! Noise: one octave of lattice noise, and its gradient as a bump.

use super::cpu::Eval;
use super::emit::Emit;
use super::formulas::real::{Real, V3, scale, splat};
use super::formulas::{fields, noise};
use super::interval::{self, Interval, Lanes};
use super::pins::{FLOAT, POSITION, Signature, VEC3, f, input, output};
use super::ranges::Ranges;
use super::settings::{Basis, Setting, choice};
use super::{Catalogue, Category, Configure, Definition, Evaluate};
use serde::{Deserialize, Serialize};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather
            [$($units)*]
            [$($configured)* (Noise, noise) (NoiseBump, noise)]
            $($rest)*);
    };
}
pub(super) use kinds;

/// The basis choice both kinds offer.
fn basis_setting(basis: &mut Basis) -> Vec<Setting<'_>> {
    vec![choice("basis", basis, &Basis::ALL)]
}

/// A single octave of lattice noise.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Noise {
    pub basis: Basis,
}

impl Definition for Noise {
    fn title(&self) -> &'static str {
        "Noise"
    }
    fn category(&self) -> Category {
        Category::Noise
    }
    fn keywords(&self) -> &'static [&'static str] {
        &[
            "perlin", "value", "gradient", "simplex", "lattice", "texture",
        ]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("p", VEC3, POSITION),
                input("scale", FLOAT, f(1.0)).soft(0.0, 50.0),
            ],
            vec![output("value", FLOAT)],
        )
    }
    fn reads_surface(&self) -> bool {
        false
    }
    fn basis(&self) -> Option<Basis> {
        Some(self.basis)
    }
    fn check(&self) -> Option<String> {
        None
    }
    fn emit(&self, io: &mut Emit) {
        let function = format!("veneer_noise_{}", self.basis.suffix());
        io.single(format!(
            "{function}({} * {})",
            io.input("p"),
            io.input("scale")
        ));
        io.uses(&function);
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        let magnitude = io.reach("p") * io.float("scale").magnitude();
        io.lattice(Some(self.basis), magnitude);
        super::unit_range()
    }
}

impl Evaluate for Noise {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let p = scale(io.input("p"), io.float("scale"));
        vec![splat(noise::basis(self.basis, p))]
    }
}

impl Configure for Noise {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        basis_setting(&mut self.basis)
    }
}

impl Catalogue for Noise {
    fn menu() -> Vec<(String, Self)> {
        Basis::ALL
            .into_iter()
            .map(|basis| (format!("Noise ({})", basis.menu_name()), Noise { basis }))
            .collect()
    }
    fn examples() -> Vec<Self> {
        Basis::ALL
            .into_iter()
            .map(|basis| Noise { basis })
            .collect()
    }
}

/// A relief of noise as a bump: minus `strength` times the noise gradient.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct NoiseBump {
    pub basis: Basis,
}

impl Definition for NoiseBump {
    fn title(&self) -> &'static str {
        "Noise bump"
    }
    fn category(&self) -> Category {
        Category::Noise
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["bump", "normal", "relief", "roughness", "gradient"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("p", VEC3, POSITION),
                input("scale", FLOAT, f(1.0)).soft(0.0, 50.0),
                input("strength", FLOAT, f(0.05)).soft(0.0, 1.0),
            ],
            vec![output("bump", VEC3)],
        )
    }
    fn reads_surface(&self) -> bool {
        false
    }
    fn basis(&self) -> Option<Basis> {
        Some(self.basis)
    }
    fn check(&self) -> Option<String> {
        None
    }
    fn emit(&self, io: &mut Emit) {
        let function = format!("veneer_noise_bump_{}", self.basis.suffix());
        io.single(format!(
            "{function}({}, {}, {})",
            io.input("p"),
            io.input("scale"),
            io.input("strength")
        ));
        io.uses(&function);
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        let magnitude = io.reach("p") * io.float("scale").magnitude();
        io.lattice(Some(self.basis), magnitude);
        let reach = 4.0 * io.float("strength").magnitude();
        vec![interval::splat(Interval::new(-reach, reach))]
    }
}

impl Evaluate for NoiseBump {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        vec![fields::noise_bump(
            self.basis,
            io.input("p"),
            io.float("scale"),
            io.float("strength"),
        )]
    }
}

impl Configure for NoiseBump {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        basis_setting(&mut self.basis)
    }
}

impl Catalogue for NoiseBump {
    fn menu() -> Vec<(String, Self)> {
        Basis::ALL
            .into_iter()
            .map(|basis| {
                (
                    format!("Noise bump ({})", basis.menu_name()),
                    NoiseBump { basis },
                )
            })
            .collect()
    }
    fn examples() -> Vec<Self> {
        Basis::ALL
            .into_iter()
            .map(|basis| NoiseBump { basis })
            .collect()
    }
}
