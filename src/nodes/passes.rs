//! What node kinds declare about passes: the buffer a sampled input is rendered into
//! (its resolution, format and edge mode) and the texel-space stages a kind runs over
//! its buffer before it reads it (a separable blur's first axis, a jump flood's steps).

use super::formulas::buffers::Image;
use super::interval::Interval;
use serde::{Deserialize, Serialize};

/// What a buffer read beyond its edges sees.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum EdgeMode {
    /// The opposite edge: the buffer repeats (a tile).
    #[default]
    Wrap,
    /// The nearest edge texel.
    Clamp,
    /// The buffer reflected at each edge.
    Mirror,
}

impl EdgeMode {
    /// Every edge mode, in menu order.
    pub const ALL: [EdgeMode; 3] = [EdgeMode::Wrap, EdgeMode::Clamp, EdgeMode::Mirror];

    /// The mode's number in WGSL (`veneer_edge_index`).
    pub fn wgsl(self) -> &'static str {
        match self {
            EdgeMode::Wrap => "0u",
            EdgeMode::Clamp => "1u",
            EdgeMode::Mirror => "2u",
        }
    }
}

/// How a buffer stores its four lanes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum BufferFormat {
    /// 8 bits per lane, values clamped to [0, 1]: masks and colours, a quarter of the memory.
    Unorm8,
    /// 16-bit floats: heights and colours with headroom, half the memory.
    Float16,
    /// 32-bit floats: exact intermediate values.
    #[default]
    Float32,
}

impl BufferFormat {
    /// Every format, in menu order.
    pub const ALL: [BufferFormat; 3] = [
        BufferFormat::Unorm8,
        BufferFormat::Float16,
        BufferFormat::Float32,
    ];

    /// Bytes per texel (four lanes).
    pub fn texel_bytes(self) -> u64 {
        match self {
            BufferFormat::Unorm8 => 4,
            BufferFormat::Float16 => 8,
            BufferFormat::Float32 => 16,
        }
    }

    /// `value` as the format stores it (rounded to 8 bits or a half float).
    pub fn quantise(self, value: f32) -> f32 {
        match self {
            BufferFormat::Unorm8 => (value.clamp(0.0, 1.0) * 255.0).round() / 255.0,
            BufferFormat::Float16 => half::f16::from_f32(value).to_f32(),
            BufferFormat::Float32 => value,
        }
    }
}

/// A buffer's resolution relative to the output it feeds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum Resolution {
    /// The output's.
    #[default]
    Inherit,
    /// Twice the output's (sharper neighbourhoods, four times the memory).
    Double,
    /// Half the output's.
    Half,
    /// A fixed size (the buffer node's `size`).
    Absolute,
}

impl Resolution {
    /// Every choice, in menu order.
    pub const ALL: [Resolution; 4] = [
        Resolution::Inherit,
        Resolution::Double,
        Resolution::Half,
        Resolution::Absolute,
    ];
}

/// How a buffer is read between its texels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum Filter {
    #[default]
    Bilinear,
    /// Catmull-Rom over 4×4 texels.
    Bicubic,
}

impl Filter {
    /// Every filter, in menu order.
    pub const ALL: [Filter; 2] = [Filter::Bilinear, Filter::Bicubic];

    /// The library function reading a buffer this way (`veneer_buffer_bilinear(t, edge,
    /// uv)`, `veneer_buffer_bicubic(…)`).
    pub fn wgsl(self) -> &'static str {
        match self {
            Filter::Bilinear => "veneer_buffer_bilinear",
            Filter::Bicubic => "veneer_buffer_bicubic",
        }
    }

    /// `image` read at domain coordinate `uv` this way (the CPU twin of [`Filter::wgsl`]).
    pub fn read(self, image: &Image, uv: [f64; 2]) -> [f64; 4] {
        match self {
            Filter::Bilinear => image.bilinear(uv),
            Filter::Bicubic => image.bicubic(uv),
        }
    }

    /// The range of what this filter reads from texels within `lane`: Catmull-Rom
    /// overshoots by at most an eighth of the span each way.
    pub fn range(self, lane: Interval) -> Interval {
        match self {
            Filter::Bilinear => lane,
            Filter::Bicubic => {
                let reach = 0.125 * (lane.hi - lane.lo);
                Interval::new(lane.lo - reach, lane.hi + reach)
            }
        }
    }
}

/// The largest side a buffer may have, in texels (the resource limit every adapter
/// Veneer renders on offers for a 2D texture).
pub const MAX_BUFFER_SIZE: u32 = 8192;

/// How one buffer is stored: what a cut of the graph renders into.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct BufferSpec {
    pub resolution: Resolution,
    /// The side in texels when `resolution` is absolute.
    pub size: u32,
    pub format: BufferFormat,
    pub edge: EdgeMode,
}

impl BufferSpec {
    /// The buffer's side in texels when the output it feeds is `output` texels square.
    pub fn texels(&self, output: u32) -> u32 {
        let side = match self.resolution {
            Resolution::Inherit => output,
            Resolution::Double => output.saturating_mul(2),
            Resolution::Half => output.div_ceil(2),
            Resolution::Absolute => self.size,
        };
        side.clamp(1, MAX_BUFFER_SIZE)
    }
}

/// The side up to which step `k` of a doubling scan (windows of 2ᵏ texels: the flood
/// fill's, the reduction's) changes nothing: step 0 starts the scan, step k > 0 reaches
/// 2ᵏ texels, past every texel of a buffer of that side.
pub fn doubling_step_reach(k: u32) -> u32 {
    if k == 0 { 0 } else { 1 << k }
}

/// One texel-space pass a node runs over its sampled input's buffer: every texel of a
/// new buffer (of the same size and edge mode, in f32) computed from the previous one.
pub struct Stage {
    /// What the pass is, for labels and reports ("blur, x axis").
    pub label: String,
    /// The WGSL expression of the texel's value (a `vec4f`): it reads the previous
    /// buffer through the arguments `SOURCE` (replaced by the texture and its edge
    /// mode) or the texture alone, `SOURCE_TEXTURE`, and the texel's index
    /// `texel: vec2i`.
    pub wgsl: String,
    /// The library items the expression calls.
    pub library: Vec<&'static str>,
    /// On a buffer at most this many texels a side the stage leaves every texel as it
    /// was (a scan step longer than the buffer), so a renderer may copy its source
    /// instead of running it; 0 when it always computes.
    pub unchanged_up_to: u32,
    /// The same on the CPU: the texel's value from the previous image.
    pub cpu: Box<dyn Fn(&Image, [i64; 2]) -> [f64; 4] + Send + Sync>,
}

impl std::fmt::Debug for Stage {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.debug_struct("Stage")
            .field("label", &self.label)
            .field("wgsl", &self.wgsl)
            .finish_non_exhaustive()
    }
}
