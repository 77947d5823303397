//! Noise: one octave of lattice noise, and its gradient as a bump.

use super::cpu::Eval;
use super::emit::Emit;
use super::formulas::real::{Real, V3, scale, splat};
use super::formulas::{fields, gabor, noise};
use super::interval::{self, Interval, Lanes};
use super::pins::{COLOR, FLOAT, POINT, SCALE, Signature, VEC3, f, input, output, v3};
use super::ranges::Ranges;
use super::settings::{Basis, Setting, check_period, choice, no_period, period, period_setting};
use super::{Catalogue, Category, Configure, Definition, Evaluate};
use serde::{Deserialize, Serialize};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather
            [$($units)* (WhiteNoise, noise) (ValueGradientNoise, noise) (Gabor, noise)]
            [$($configured)* (Noise, noise) (NoiseBump, noise)]
            $($rest)*);
    };
}
pub(super) use kinds;

/// A single octave of lattice noise, repeating every `period` cells when it has one.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Noise {
    pub basis: Basis,
    /// How many lattice cells the noise repeats over along x, y and z (0: it never
    /// repeats). Graph files leave it out when 0.
    #[serde(default, skip_serializing_if = "no_period")]
    pub period: u32,
}

impl Definition for Noise {
    fn title(&self) -> &'static str {
        "Noise"
    }
    computed_in!(@parts Category::Noise, |self| Some(self.basis));
    fn keywords(&self) -> &'static [&'static str] {
        &[
            "perlin", "value", "gradient", "simplex", "lattice", "texture", "seamless", "tileable",
            "periodic",
        ]
    }
    fn signature(&self) -> Signature {
        Signature::new(vec![POINT, SCALE], vec![output("value", FLOAT)])
    }
    fn check(&self) -> Option<String> {
        check_period(self.period, Some(self.basis))
    }
    fn emit(&self, io: &mut Emit) {
        let q = format!("{} * {}", io.input("p"), io.input("scale"));
        periodic_call(
            io,
            &format!("veneer_noise_{}", self.basis.suffix()),
            q,
            self.period,
        );
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        io.sampled(Some(self.basis));
        super::unit_range()
    }
}

/// One output: library function `function` of `arguments`, or with a period (the
/// setting; 0 for none) its `_periodic` variant with the period appended.
pub(super) fn periodic_call(io: &mut Emit, function: &str, arguments: String, setting: u32) {
    let (function, arguments) = match period(setting) {
        None => (function.to_string(), arguments),
        Some(cells) => (
            format!("{function}_periodic"),
            format!("{arguments}, {cells}i"),
        ),
    };
    io.single(format!("{function}({arguments})"));
    io.uses(&function);
}

impl Evaluate for Noise {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let p = scale(io.input("p"), io.float("scale"));
        vec![splat(noise::repeating(self.basis, p, period(self.period)))]
    }
}

impl Configure for Noise {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        vec![
            choice("basis", &mut self.basis, &Basis::ALL),
            period_setting(&mut self.period),
        ]
    }
}

impl Catalogue for Noise {
    fn menu() -> Vec<(String, Self)> {
        Basis::ALL
            .into_iter()
            .map(|basis| {
                let name = format!("Noise ({})", basis.menu_name());
                (name, Noise { basis, period: 0 })
            })
            .collect()
    }
    /// Every basis, infinite and repeating every 6 cells.
    fn examples() -> Vec<Self> {
        [0, 6]
            .into_iter()
            .flat_map(|period| Basis::ALL.map(|basis| Noise { basis, period }))
            .collect()
    }
}

/// A relief of noise as a bump: minus `strength` times the noise gradient.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct NoiseBump {
    pub basis: Basis,
    /// How many lattice cells the noise repeats over (0: it never repeats); left out of
    /// graph files when 0.
    #[serde(default, skip_serializing_if = "no_period")]
    pub period: u32,
}

impl Definition for NoiseBump {
    fn title(&self) -> &'static str {
        "Noise bump"
    }
    computed_in!(@parts Category::Noise, |self| Some(self.basis));
    fn check(&self) -> Option<String> {
        check_period(self.period, Some(self.basis))
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["bump", "normal", "relief", "roughness", "gradient"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                POINT,
                SCALE,
                input("strength", FLOAT, f(0.05)).soft(0.0, 1.0),
            ],
            vec![output("bump", VEC3)],
        )
    }
    fn emit(&self, io: &mut Emit) {
        let arguments = format!(
            "{}, {}, {}",
            io.input("p"),
            io.input("scale"),
            io.input("strength")
        );
        periodic_call(
            io,
            &format!("veneer_noise_bump_{}", self.basis.suffix()),
            arguments,
            self.period,
        );
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        io.sampled(Some(self.basis));
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
            period(self.period),
        )]
    }
}

basis_choice!(NoiseBump, "Noise bump");

/// White noise (seed 003 §3.2): one random value per lattice cell of `p * scale`, and a
/// random colour whose red is that value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WhiteNoise;

impl Definition for WhiteNoise {
    computed_in!(Category::Noise, unchecked);
    fn title(&self) -> &'static str {
        "White noise"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["random", "hash", "per cell", "cell colour", "dither"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![POINT, SCALE],
            vec![output("value", FLOAT), output("color", COLOR)],
        )
    }
    fn emit(&self, io: &mut Emit) {
        io.uses("veneer_white_noise_color");
        io.bind(
            "vec3f",
            format!(
                "veneer_white_noise_color({} * {})",
                io.input("p"),
                io.input("scale")
            ),
        );
        let name = io.name();
        io.outputs(vec![format!("{name}.x"), name.to_string()]);
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        io.sampled(None);
        vec![interval::splat(Interval::UNIT); 2]
    }
}

impl Evaluate for WhiteNoise {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let color = gabor::white_noise_color(scale(io.input("p"), io.float("scale")));
        vec![splat(color[0]), color]
    }
}

plain_catalogue!(WhiteNoise);

/// Value-gradient noise (seed 003 §3.2): the mean of PCG value noise and gradient noise,
/// in [0, 1].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ValueGradientNoise;

impl Definition for ValueGradientNoise {
    computed_in!(Category::Noise, unchecked);
    fn title(&self) -> &'static str {
        "Value-gradient noise"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["perlin", "value", "gradient", "lattice", "texture"]
    }
    fn signature(&self) -> Signature {
        Signature::new(vec![POINT, SCALE], vec![output("value", FLOAT)])
    }
    fn emit(&self, io: &mut Emit) {
        io.single(format!(
            "veneer_noise_value_gradient({} * {})",
            io.input("p"),
            io.input("scale")
        ));
        io.uses("veneer_noise_value_gradient");
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        io.sampled(None);
        super::unit_range()
    }
}

impl Evaluate for ValueGradientNoise {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let p = scale(io.input("p"), io.float("scale"));
        vec![splat(gabor::value_gradient(p))]
    }
}

plain_catalogue!(ValueGradientNoise);

/// Gabor noise (Lagae et al. 2009, sparse convolution of Gabor kernels, as Blender's
/// Gabor texture): stripes of `frequency` per unit, all along `orientation` when
/// `anisotropy` is 1, in random directions when it is 0 (or the orientation is zero).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gabor;

impl Definition for Gabor {
    computed_in!(Category::Noise, unchecked);
    fn title(&self) -> &'static str {
        "Gabor noise"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &[
            "sparse convolution",
            "anisotropic",
            "brushed",
            "fibres",
            "stripes",
            "noise",
        ]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                POINT,
                SCALE,
                input("frequency", FLOAT, f(2.0)).soft(0.0, 10.0),
                input("anisotropy", FLOAT, f(1.0)).limits(0.0, 1.0),
                input("orientation", VEC3, v3(1.0, 0.0, 0.0)),
            ],
            vec![output("value", FLOAT)],
        )
    }
    fn emit(&self, io: &mut Emit) {
        io.single(format!(
            "veneer_gabor({} * {}, {}, {}, {})",
            io.input("p"),
            io.input("scale"),
            io.input("frequency"),
            io.input("anisotropy"),
            io.input("orientation")
        ));
        io.uses("veneer_gabor");
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        io.sampled(None);
        super::unit_range()
    }
}

impl Evaluate for Gabor {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        vec![splat(gabor::gabor(
            scale(io.input("p"), io.float("scale")),
            io.float("frequency"),
            io.float("anisotropy"),
            io.input("orientation"),
        ))]
    }
}

plain_catalogue!(Gabor);
