//! The settings node kinds share: the structural choices that change the generated
//! code (which noise basis, how many octaves, which operator), and how the inspector
//! offers them. A node's float-valued parameters are input pins instead, so they can be
//! wired or left as constants.

use serde::{Deserialize, Serialize};

/// The lattice noise a noise, fractal or warp node is built on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum Basis {
    /// Value noise hashed with `fract(sin(dot(p, k)) * 43758.5453)`, as in seed 000.
    /// Cheap, but differs between GPUs and degrades at large coordinates.
    ValueSine,
    /// Value noise hashed with the integer PCG3D hash: bit-identical on CPU and GPU.
    ValuePcg,
    /// Improved Perlin gradient noise (PCG-hashed gradients), in about [-1, 1].
    Gradient,
    /// 3D simplex noise (PCG-hashed gradients), in about [-1, 1].
    Simplex,
}

impl Basis {
    /// All bases, in menu order.
    pub const ALL: [Basis; 4] = [
        Basis::ValueSine,
        Basis::ValuePcg,
        Basis::Gradient,
        Basis::Simplex,
    ];

    /// The basis as the add-node menu names it.
    pub fn menu_name(self) -> &'static str {
        match self {
            Basis::ValueSine => "value, sine hash",
            Basis::ValuePcg => "value, PCG hash",
            Basis::Gradient => "gradient",
            Basis::Simplex => "simplex",
        }
    }

    /// The suffix of this basis' WGSL library function (`veneer_noise_<suffix>`).
    pub fn suffix(self) -> &'static str {
        match self {
            Basis::ValueSine => "value_sine",
            Basis::ValuePcg => "value_pcg",
            Basis::Gradient => "gradient",
            Basis::Simplex => "simplex",
        }
    }
}

/// How a fractal node combines its octaves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum FractalMode {
    /// Sum of the basis in its natural range (value noise in [0, 1]).
    Fbm,
    /// Sum of |signed noise|, Perlin's turbulence.
    Turbulence,
    /// Sum of signed noise, Perlin's fractal sum.
    FractalSum,
}

impl FractalMode {
    /// Name used in generated identifiers.
    pub fn name(self) -> &'static str {
        match self {
            FractalMode::Fbm => "fbm",
            FractalMode::Turbulence => "turbulence",
            FractalMode::FractalSum => "fractal_sum",
        }
    }
}

/// Which Worley feature a cellular node outputs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum WorleyFeature {
    F1,
    F2,
    F3,
    F2MinusF1,
}

/// Where a Worley node puts each cell's feature point.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum FeaturePoints {
    /// Inside the cell: its centre moved by up to `jitter` / 2 per axis, by a PCG hash.
    #[default]
    Hashed,
    /// The GeoTextures thesis's (seed 003, appendix B's `gpuCellNoise3D`): the cell's
    /// corner moved along (1, 1, 1) by signed simplex noise at the corner times `jitter`
    /// (the thesis's `noiseScale`); past 0.5 points leave their cell, beyond the 27 cells
    /// searched, and the pattern shows the thesis's seams.
    Simplex,
}

impl FeaturePoints {
    /// Graph files leave the placement out when it is the usual one.
    pub fn is_hashed(&self) -> bool {
        *self == FeaturePoints::Hashed
    }
}

/// The distance metric of a cellular node.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum Metric {
    Euclidean,
    Manhattan,
    Chebyshev,
}

/// Binary arithmetic operators; division and power are safe (never NaN or Inf).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum MathOp {
    Add,
    Subtract,
    Multiply,
    Divide,
    Power,
    Minimum,
    Maximum,
}

impl MathOp {
    /// All operators, in menu order.
    pub const ALL: [MathOp; 7] = [
        MathOp::Add,
        MathOp::Subtract,
        MathOp::Multiply,
        MathOp::Divide,
        MathOp::Power,
        MathOp::Minimum,
        MathOp::Maximum,
    ];
}

/// Unary operators, applied per component.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum UnaryOp {
    Abs,
    Fract,
    Floor,
    Sin,
    Cos,
    Negate,
    OneMinus,
}

impl UnaryOp {
    /// All operators, in menu order.
    pub const ALL: [UnaryOp; 7] = [
        UnaryOp::Abs,
        UnaryOp::Fract,
        UnaryOp::Floor,
        UnaryOp::Sin,
        UnaryOp::Cos,
        UnaryOp::Negate,
        UnaryOp::OneMinus,
    ];
}

/// How a colour ramp blends between stops.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum RampInterpolation {
    #[default]
    Linear,
    Constant,
}

/// One stop of a colour ramp.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct RampStop {
    pub position: f64,
    pub color: (f64, f64, f64),
}

/// The most octaves a fractal node accepts.
pub const MAX_OCTAVES: u32 = 64;

/// The most octaves the editor's slider offers (more are allowed in files, up to `MAX_OCTAVES`).
pub const MAX_OCTAVES_UI: u32 = 16;

/// The longest period, in lattice cells, a noise may repeat over: the periodic noises
/// wrap cells in i32 and sample points near the origin, exact in f32 well past this.
pub const MAX_PERIOD: u32 = 65536;

/// A noise's period (how many lattice cells it repeats over) as the inspector offers it.
pub fn period_setting(value: &mut u32) -> Setting<'_> {
    Setting::Count {
        label: "period (cells, 0: none)",
        value,
        range: 0..=1024,
    }
}

/// What is wrong with a noise's `period` over `basis`, if anything: too long, or not a
/// multiple of the basis' lattice step (3 for simplex noise).
pub fn check_period(period: u32, basis: Option<Basis>) -> Option<String> {
    let step = basis.map_or(1, crate::nodes::formulas::noise::period_step) as u32;
    if period > MAX_PERIOD {
        Some(format!(
            "period {period} is out of range (expected 0 for none, or up to {MAX_PERIOD} cells)"
        ))
    } else if !period.is_multiple_of(step) {
        Some(format!(
            "period {period}: simplex noise repeats only over a multiple of {step} cells (its lattice is skewed); try {} or another basis",
            (period / step).max(1) * step
        ))
    } else {
        None
    }
}

/// The period a noise's setting asks for (0: none).
pub fn period(setting: u32) -> crate::nodes::formulas::noise::Period {
    (setting > 0).then_some(setting.min(MAX_PERIOD) as i32)
}

/// Graph files leave a noise's period out when it has none.
pub fn no_period(setting: &u32) -> bool {
    *setting == 0
}

/// The most stops a colour ramp accepts: each stop is a line of shader code, and past a
/// few hundred a ramp only costs compile and shading time (a file with more is refused,
/// naming the node).
pub const MAX_RAMP_STOPS: usize = 256;

/// One structural setting as the inspector offers it: the family files list their
/// settings once, and the inspector draws whatever they list.
pub enum Setting<'a> {
    /// One of a few values.
    Choice {
        label: &'static str,
        value: Box<dyn Choose + 'a>,
    },
    /// A whole number within a range (octaves, a field slot).
    Count {
        label: &'static str,
        value: &'a mut u32,
        range: std::ops::RangeInclusive<u32>,
    },
    /// A file's path, relative to the graph's folder, chosen in a file dialog or typed.
    File {
        label: &'static str,
        value: &'a mut String,
        /// The extensions the dialog offers (lower case, without the dot).
        extensions: &'static [&'static str],
    },
    /// On or off.
    Toggle {
        label: &'static str,
        value: &'a mut bool,
    },
    /// The stops of a colour ramp and how it blends between them.
    Ramp {
        stops: &'a mut Vec<RampStop>,
        interpolation: &'a mut RampInterpolation,
    },
}

/// A choice among named values.
pub trait Choose {
    /// The names of the values, in menu order.
    fn names(&self) -> Vec<String>;
    /// The index of the current value.
    fn selected(&self) -> usize;
    /// Makes value `index` the current one.
    fn select(&mut self, index: usize);
}

struct Chooser<'a, T: 'static> {
    value: &'a mut T,
    options: &'static [T],
}

impl<T: Copy + PartialEq + std::fmt::Debug> Choose for Chooser<'_, T> {
    fn names(&self) -> Vec<String> {
        self.options.iter().map(|o| format!("{o:?}")).collect()
    }
    fn selected(&self) -> usize {
        self.options
            .iter()
            .position(|o| o == self.value)
            .unwrap_or(0)
    }
    fn select(&mut self, index: usize) {
        if let Some(option) = self.options.get(index) {
            *self.value = *option;
        }
    }
}

/// A setting choosing `value` among `options` (named as their `Debug` spelling, which
/// is also how graph files spell them).
pub fn choice<'a, T: Copy + PartialEq + std::fmt::Debug>(
    label: &'static str,
    value: &'a mut T,
    options: &'static [T],
) -> Setting<'a> {
    Setting::Choice {
        label,
        value: Box::new(Chooser { value, options }),
    }
}

/// Every Worley feature, in menu order.
pub const WORLEY_FEATURES: [WorleyFeature; 4] = [
    WorleyFeature::F1,
    WorleyFeature::F2,
    WorleyFeature::F3,
    WorleyFeature::F2MinusF1,
];

/// Every feature-point placement, in menu order.
pub const FEATURE_POINTS: [FeaturePoints; 2] = [FeaturePoints::Hashed, FeaturePoints::Simplex];

/// Every distance metric, in menu order.
pub const METRICS: [Metric; 3] = [Metric::Euclidean, Metric::Manhattan, Metric::Chebyshev];

/// Every ramp interpolation, in menu order.
pub const RAMP_INTERPOLATIONS: [RampInterpolation; 2] =
    [RampInterpolation::Linear, RampInterpolation::Constant];

/// Every value type.
pub const TYPES: [super::value::ValueType; 4] = [
    super::value::ValueType::Float,
    super::value::ValueType::Vec2,
    super::value::ValueType::Vec3,
    super::value::ValueType::Color,
];

/// The vector types.
pub const VECTORS: [super::value::ValueType; 3] = [
    super::value::ValueType::Vec2,
    super::value::ValueType::Vec3,
    super::value::ValueType::Color,
];
