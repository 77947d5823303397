//! Fractals: sums of octaves of lattice noise (fBm, turbulence, fractal sum).

use super::cpu::Eval;
use super::emit::{Emit, float_literal};
use super::formulas::real::{Real, V3, scale, splat};
use super::formulas::{noise, octaves, shapes};
use super::interval::{Interval, Lanes};
use super::pins::{FLOAT, POINT, SCALE, Signature, f, input, output};
use super::ranges::Ranges;
use super::settings::{
    Basis, FractalMode, MAX_OCTAVES, MAX_OCTAVES_UI, Setting, check_period, choice, no_period,
    period, period_setting,
};
use super::{Catalogue, Category, Configure, Definition, Evaluate};
use serde::{Deserialize, Serialize};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather
            [$($units)*]
            [$($configured)* (Fbm, fractal) (Turbulence, fractal) (FractalSum, fractal)]
            $($rest)*);
    };
}
pub(super) use kinds;

/// The message for an octave count outside 1..=MAX_OCTAVES (shared with Worley).
pub(super) fn check_octaves(octaves: u32) -> Option<String> {
    (octaves == 0 || octaves > MAX_OCTAVES)
        .then(|| format!("octaves {octaves} is out of range (expected 1 to {MAX_OCTAVES})"))
}

/// The three fractal kinds differ only in how they sum octaves.
macro_rules! fractal_kind {
    ($(#[$doc:meta])* $kind:ident, $mode:expr, $title:literal, amplitude $amplitude:literal,
     menu octaves $octaves:literal, [$($keyword:literal),*]) => {
        $(#[$doc])*
        #[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
        #[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
        pub struct $kind {
            pub basis: Basis,
            pub octaves: u32,
            pub normalize: bool,
            /// Each octave turned by a fixed irrational rotation, so that no octave's
            /// lattice lines up with the next (fewer directional artefacts). Graph
            /// files leave it out when off.
            #[serde(default, skip_serializing_if = "std::ops::Not::not")]
            pub rotate: bool,
            /// How many lattice cells the sum repeats over along x, y and z (0: it
            /// never repeats); each octave spans a whole number of cells over it.
            /// Graph files leave it out when 0.
            #[serde(default, skip_serializing_if = "no_period")]
            pub period: u32,
        }

        impl Definition for $kind {
            fn title(&self) -> &'static str {
                $title
            }
            fn category(&self) -> Category {
                Category::Fractal
            }
            fn keywords(&self) -> &'static [&'static str] {
                &[$($keyword),*]
            }
            fn signature(&self) -> Signature {
                signature($amplitude)
            }
            fn reads_surface(&self) -> bool {
                false
            }
            fn basis(&self) -> Option<Basis> {
                Some(self.basis)
            }
            fn check(&self) -> Option<String> {
                check_octaves(self.octaves)
                    .or_else(|| check_period(self.period, Some(self.basis)))
                    .or_else(|| (self.rotate && self.period > 0).then(|| {
                        "rotated octaves cannot repeat over a period: turn off 'rotate octaves' or set the period to 0".to_string()
                    }))
            }
            fn emit(&self, io: &mut Emit) {
                emit($mode, self.basis, self.octaves, self.normalize, self.rotate, self.period, io);
            }
            fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
                ranges($mode, self.basis, self.octaves, self.normalize, io)
            }
        }

        impl Evaluate for $kind {
            fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
                let p = scale(io.input("p"), io.float("scale"));
                let shape = [io.float("lacunarity"), io.float("gain"), io.float("amplitude")];
                // Every octave: the CPU has no pixel footprint.
                let cutoff = R::c(1.0e9);
                let (basis, octaves, normalize) = (self.basis, self.octaves, self.normalize);
                vec![splat(if self.rotate {
                    octaves::fractal_rotated($mode, basis, p, octaves, shape, normalize, cutoff)
                } else {
                    let period = period(self.period);
                    shapes::fractal($mode, basis, p, octaves, shape, normalize, cutoff, period)
                })]
            }
        }

        impl Configure for $kind {
            fn settings(&mut self) -> Vec<Setting<'_>> {
                vec![
                    choice("basis", &mut self.basis, &Basis::ALL),
                    Setting::Count {
                        label: "octaves",
                        value: &mut self.octaves,
                        range: 1..=MAX_OCTAVES_UI,
                    },
                    Setting::Toggle {
                        label: "normalize",
                        value: &mut self.normalize,
                    },
                    Setting::Toggle {
                        label: "rotate octaves",
                        value: &mut self.rotate,
                    },
                    period_setting(&mut self.period),
                ]
            }
        }

        impl Catalogue for $kind {
            fn menu() -> Vec<(String, Self)> {
                Basis::ALL
                    .into_iter()
                    .map(|basis| {
                        let settings = $kind { basis, octaves: $octaves, normalize: false, rotate: false, period: 0 };
                        (format!("{} ({})", $title, basis.menu_name()), settings)
                    })
                    .collect()
            }
            fn examples() -> Vec<Self> {
                Basis::ALL
                    .into_iter()
                    .flat_map(|basis| {
                        [(3, false, false, 0), (4, true, false, 0), (4, false, true, 0), (3, true, false, 6)].map(
                            |(octaves, normalize, rotate, period)| $kind {
                                basis,
                                octaves,
                                normalize,
                                rotate,
                                period,
                            },
                        )
                    })
                    .collect()
            }
        }
    };
}

fractal_kind!(
    /// Fractal Brownian motion: octaves of the basis in its natural range.
    Fbm, FractalMode::Fbm, "fBm", amplitude 0.5, menu octaves 5,
    ["fractal", "brownian", "clouds", "musgrave", "noise", "octaves"]
);
fractal_kind!(
    /// Perlin's turbulence: a sum of |signed noise| over octaves.
    Turbulence, FractalMode::Turbulence, "Turbulence", amplitude 1.0, menu octaves 4,
    ["fractal", "perlin", "billow", "marble", "octaves"]
);
fractal_kind!(
    /// Perlin's fractal sum: signed noise over octaves.
    FractalSum, FractalMode::FractalSum, "Fractal sum", amplitude 1.0, menu octaves 4,
    ["fractal", "perlin", "signed", "octaves"]
);

fn signature(amplitude: f64) -> Signature {
    Signature::new(
        vec![
            POINT,
            SCALE,
            input("lacunarity", FLOAT, f(2.0)).soft(1.0, 4.0),
            input("gain", FLOAT, f(0.5)).limits(0.0, 1.0),
            input("amplitude", FLOAT, f(amplitude)).soft(0.0, 2.0),
        ],
        vec![output("value", FLOAT)],
    )
}

/// The call of a fractal kind's library function; `period` is the setting (0: none).
fn emit(
    mode: FractalMode,
    basis: Basis,
    octaves: u32,
    normalize: bool,
    rotate: bool,
    period_setting: u32,
    io: &mut Emit,
) {
    let turned = if rotate { "_rotated" } else { "" };
    let function = format!("veneer_{}{turned}_{}", mode.name(), basis.suffix());
    let q = format!("{} * {}", io.input("p"), io.input("scale"));
    let lacunarity = io.input("lacunarity");
    let cutoff = if io.filters_footprint() {
        io.uses("veneer_octave_cutoff");
        format!("veneer_octave_cutoff({q}, {lacunarity})")
    } else {
        float_literal(1.0e9)
    };
    let arguments = format!(
        "{q}, {octaves}, {lacunarity}, {}, {}, {normalize}, {cutoff}",
        io.input("gain"),
        io.input("amplitude")
    );
    match period(period_setting) {
        None => {
            io.single(format!("{function}({arguments})"));
            io.uses(&function);
        }
        Some(cells) => {
            let step = noise::period_step(basis);
            let function = format!("{function}_periodic");
            io.single(format!("{function}({arguments}, {cells}i, {step}i)"));
            io.uses(&function);
        }
    }
}

fn ranges(
    mode: FractalMode,
    basis: Basis,
    octaves: u32,
    normalize: bool,
    io: &mut Ranges,
) -> Vec<Lanes> {
    let (lacunarity, gain, amplitude) = (
        io.float("lacunarity"),
        io.float("gain"),
        io.float("amplitude"),
    );
    if gain.lo >= 1.0 {
        io.warn(format!(
            "gain {} ≥ 1: octaves grow instead of fading, the sum does not converge",
            gain.lo
        ));
    }
    if lacunarity.hi <= 1.0 {
        io.warn(format!(
            "lacunarity {} ≤ 1: octaves do not get finer",
            lacunarity.hi
        ));
    }
    let top = lacunarity.magnitude().max(1.0).powi(octaves as i32 - 1);
    let magnitude = io.reach("p") * io.float("scale").magnitude() * top;
    if !top.is_finite() || top > f64::from(f32::MAX) {
        io.warn(format!(
            "{octaves} octaves at lacunarity {}: the top frequency overflows f32",
            lacunarity.hi
        ));
    } else {
        io.lattice(Some(basis), magnitude);
    }
    let sum: f64 = (0..octaves)
        .map(|k| amplitude.magnitude() * gain.magnitude().powi(k as i32))
        .sum();
    let sum = if sum.is_finite() {
        sum
    } else {
        f64::from(f32::MAX)
    };
    let range = match (mode, normalize) {
        (FractalMode::Fbm | FractalMode::Turbulence, true) => {
            Interval::new(-1.0, 1.0).hull(Interval::UNIT)
        }
        (FractalMode::FractalSum, true) => Interval::new(-1.0, 1.0),
        (_, false) => Interval::new(-sum, sum),
    };
    vec![super::interval::splat(range)]
}
