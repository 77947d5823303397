//! Node kinds and their settings.
//!
//! A node's *settings* are the structural choices that change the generated code
//! (which noise basis, how many octaves, which operator). Its float-valued
//! parameters are input pins instead, so they can be wired or left as constants.

use super::value::ValueType;
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

/// Every kind of node Veneer knows, with its structural settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum NodeKind {
    /// Object-space position of the shaded point.
    Position,
    /// Unit object-space normal.
    Normal,
    /// Texture coordinates.
    Uv,
    /// Time in seconds.
    Time,
    /// One of the four distance fields of `VeneerSurface.fields`.
    Field { slot: u8 },
    /// A constant (its `value` input); also usable as a reroute point.
    Constant { ty: ValueType },
    /// `rotate(p * scale) + offset`, rotation in degrees about x, then y, then z.
    Transform,
    /// Coordinate along a direction: `(p - origin) · normalize(direction)`.
    Project,
    /// Cylindrical coordinates about an axis: axial t, radius r, angle θ.
    Cylindrical,
    /// `p + strength * (vector noise at p * scale)`, each component in [-1, 1].
    DomainWarp { basis: Basis },
    /// A single octave of lattice noise.
    Noise { basis: Basis },
    /// Fractal Brownian motion.
    Fbm {
        basis: Basis,
        octaves: u32,
        normalize: bool,
    },
    /// Sum of |noise| over octaves.
    Turbulence {
        basis: Basis,
        octaves: u32,
        normalize: bool,
    },
    /// Sum of signed noise over octaves.
    FractalSum {
        basis: Basis,
        octaves: u32,
        normalize: bool,
    },
    /// Cellular (Worley) noise; more than one octave makes it fractal.
    Worley {
        feature: WorleyFeature,
        metric: Metric,
        octaves: u32,
    },
    /// `0.5 + 0.5 * sin(frequency * x + distortion * turbulence)`.
    SineBand,
    /// A triangle wave of `x * frequency` going 0 → 1 → 0 each period.
    TriangleWave,
    /// Offset rows of tiles in the xz plane with antialiased mortar gaps.
    Tiles,
    /// Concentric rings about an axis: `0.5 + 0.5 * sin(2π * frequency * r)`.
    Rings,
    /// A propagation front over a distance field: 1 where `distance + noise` is below
    /// `threshold`, fading to 0 over `width` beyond it (seed 003).
    Front,
    /// Four values in nested rings around the sources of a distance field, each boundary
    /// a front of the same width and noise (seed 003's nested mixes).
    Layers { ty: ValueType },
    /// Lines where a value crosses multiples of `spacing`, `width` wide.
    Isolines,
    /// A relief of noise as a bump: minus `strength` times the noise gradient.
    NoiseBump { basis: Basis },
    /// A binary arithmetic operator.
    Math { op: MathOp, ty: ValueType },
    /// A unary operator.
    Unary { op: UnaryOp, ty: ValueType },
    /// Linear interpolation `a + (b - a) * factor`.
    Mix { ty: ValueType },
    /// Clamp every component between `min` and `max`.
    Clamp { ty: ValueType },
    /// 0 below `edge`, 1 from it on.
    Step { ty: ValueType },
    /// Hermite smoothstep, well defined when the edges are equal or reversed.
    Smoothstep,
    /// Linear map from [from_min, from_max] to [to_min, to_max].
    Remap,
    /// Length of a vector.
    Length { ty: ValueType },
    /// Dot product of two vectors.
    Dot { ty: ValueType },
    /// Unit vector in the same direction; zero stays zero.
    Normalize { ty: ValueType },
    /// Components of a vector.
    Split { ty: ValueType },
    /// A vector from components.
    Combine { ty: ValueType },
    /// A colour ramp over a factor, with several stops.
    ColorRamp {
        stops: Vec<RampStop>,
        interpolation: RampInterpolation,
    },
    /// The material output.
    Material,
}

/// Menu category of a node kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Category {
    Input,
    Coordinates,
    Noise,
    Fractal,
    Cellular,
    Pattern,
    Field,
    Math,
    Output,
}

impl NodeKind {
    /// A short human-readable name (used for default labels and messages).
    pub fn title(&self) -> &'static str {
        match self {
            NodeKind::Position => "Position",
            NodeKind::Normal => "Normal",
            NodeKind::Uv => "UV",
            NodeKind::Time => "Time",
            NodeKind::Field { .. } => "Distance field",
            NodeKind::Constant { .. } => "Constant",
            NodeKind::Transform => "Transform",
            NodeKind::Project => "Project",
            NodeKind::Cylindrical => "Cylindrical",
            NodeKind::DomainWarp { .. } => "Domain warp",
            NodeKind::Noise { .. } => "Noise",
            NodeKind::Fbm { .. } => "fBm",
            NodeKind::Turbulence { .. } => "Turbulence",
            NodeKind::FractalSum { .. } => "Fractal sum",
            NodeKind::Worley { .. } => "Worley",
            NodeKind::SineBand => "Sine band",
            NodeKind::TriangleWave => "Triangle wave",
            NodeKind::Tiles => "Tiles",
            NodeKind::Rings => "Rings",
            NodeKind::Math { .. } => "Math",
            NodeKind::Unary { .. } => "Unary",
            NodeKind::Mix { .. } => "Mix",
            NodeKind::Clamp { .. } => "Clamp",
            NodeKind::Step { .. } => "Step",
            NodeKind::Smoothstep => "Smoothstep",
            NodeKind::Remap => "Remap",
            NodeKind::Length { .. } => "Length",
            NodeKind::Dot { .. } => "Dot",
            NodeKind::Normalize { .. } => "Normalize",
            NodeKind::Split { .. } => "Split",
            NodeKind::Combine { .. } => "Combine",
            NodeKind::ColorRamp { .. } => "Colour ramp",
            NodeKind::Front => "Front",
            NodeKind::Layers { .. } => "Layers",
            NodeKind::Isolines => "Isolines",
            NodeKind::NoiseBump { .. } => "Noise bump",
            NodeKind::Material => "Material",
        }
    }

    /// The menu category.
    pub fn category(&self) -> Category {
        use NodeKind::*;
        match self {
            Position | Normal | Uv | Time | Field { .. } | Constant { .. } => Category::Input,
            Transform | Project | Cylindrical | DomainWarp { .. } => Category::Coordinates,
            Noise { .. } | NoiseBump { .. } => Category::Noise,
            Front | Layers { .. } | Isolines => Category::Field,
            Fbm { .. } | Turbulence { .. } | FractalSum { .. } => Category::Fractal,
            Worley { .. } => Category::Cellular,
            SineBand | TriangleWave | Tiles | Rings => Category::Pattern,
            Material => Category::Output,
            _ => Category::Math,
        }
    }

    /// For the three fractal kinds: their mode, basis, octave count and normalisation.
    pub fn fractal(&self) -> Option<(FractalMode, Basis, u32, bool)> {
        match *self {
            NodeKind::Fbm {
                basis,
                octaves,
                normalize,
            } => Some((FractalMode::Fbm, basis, octaves, normalize)),
            NodeKind::Turbulence {
                basis,
                octaves,
                normalize,
            } => Some((FractalMode::Turbulence, basis, octaves, normalize)),
            NodeKind::FractalSum {
                basis,
                octaves,
                normalize,
            } => Some((FractalMode::FractalSum, basis, octaves, normalize)),
            _ => None,
        }
    }
}

/// The most octaves a fractal node accepts.
pub const MAX_OCTAVES: u32 = 64;

/// The most octaves the editor's slider offers (more are allowed in files, up to `MAX_OCTAVES`).
pub const MAX_OCTAVES_UI: u32 = 16;

/// The most stops a colour ramp accepts: each stop is a line of shader code, and past a
/// few hundred a ramp only costs compile and shading time (a file with more is refused,
/// naming the node).
pub const MAX_RAMP_STOPS: usize = 256;
