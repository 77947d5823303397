//! Image nodes: kinds with a sampled input, which read their upstream at other points
//! than the one being shaded. The compiler renders each sampled input into a buffer
//! (a pass) and hands the node the buffer's arguments (`texture, edge`) in place of an
//! expression; the node reads it at the point's domain coordinate `s.uv` and around it.

use super::cpu::Eval;
use super::emit::Emit;
use super::formulas::buffers::Image;
use super::formulas::real::{Real, V3};
use super::interval::{Interval, Lanes};
use super::passes::{BufferFormat, BufferSpec, EdgeMode, Filter, Resolution, Stage};
use super::pins::{FLOAT, Signature, VEC2, VEC3, f, input, output, v2};
use super::ranges::Ranges;
use super::settings::{Basis, Setting, TYPES, choice};
use super::value::ValueType;
use super::{Catalogue, Category, Configure, Definition, Evaluate};
use serde::{Deserialize, Serialize};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather
            [$($units)*]
            [$($configured)* (Buffer, sampled) (Blur, sampled) (HeightToNormal, sampled) (Warp, sampled)]
            $($rest)*);
    };
}
pub(super) use kinds;

/// The parts of a definition every image node shares: it reads the surface (its
/// domain coordinate), samples no lattice, and checks nothing of its settings.
macro_rules! image_node {
    () => {
        fn category(&self) -> Category {
            Category::Image
        }
        fn reads_surface(&self) -> bool {
            true
        }
        fn basis(&self) -> Option<Basis> {
            None
        }
    };
}

pub(super) use image_node;

/// The lanes of a buffer texel as a value of type `ty` (a float in all three lanes).
pub(super) fn typed<R: Real>(texel: [f64; 4], ty: ValueType) -> V3<R> {
    match ty {
        ValueType::Float => [texel[0]; 3].map(R::c),
        ValueType::Vec2 => [texel[0], texel[1], 0.0].map(R::c),
        ValueType::Vec3 | ValueType::Color => [texel[0], texel[1], texel[2]].map(R::c),
    }
}

/// The WGSL swizzle taking a value of type `ty` from a buffer's `vec4f`.
pub(super) fn swizzle(ty: ValueType) -> &'static str {
    ["x", "xy", "xyz"][ty.width() - 1]
}

/// Reads the buffer of `pin` at the point, by `filter`, as the node's one output.
fn read_buffer(io: &mut Emit, pin: &str, filter: Filter, offset: Option<String>) {
    let function = filter.wgsl();
    let uv = offset.map_or("s.uv".to_string(), |offset| format!("s.uv + {offset}"));
    let ty = io.pins()[super::pins::pin_index(io.pins(), pin)].ty;
    io.single(format!(
        "{function}({}, {uv}).{}",
        io.input(pin),
        swizzle(ty)
    ));
    io.uses(function);
}

/// A value kept in a buffer and read back at the point, bilinearly or bicubically: how
/// a graph sets the resolution, format and edge mode of the buffer behind a cut (every
/// sampled input wired to a Buffer reads this buffer), or caches an expensive upstream.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Buffer {
    pub ty: ValueType,
    pub resolution: Resolution,
    /// The side in texels when `resolution` is `Absolute`.
    pub size: u32,
    pub format: BufferFormat,
    pub edge: EdgeMode,
    pub filter: Filter,
}

impl Default for Buffer {
    fn default() -> Buffer {
        Buffer {
            ty: ValueType::Float,
            resolution: Resolution::Inherit,
            size: 512,
            format: BufferFormat::Float32,
            edge: EdgeMode::Wrap,
            filter: Filter::Bilinear,
        }
    }
}

impl Definition for Buffer {
    image_node!();
    fn title(&self) -> &'static str {
        "Buffer"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["cache", "bitmap", "render target", "resolution", "texture"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![input("value", self.ty, f(0.0)).sampled()],
            vec![output("value", self.ty)],
        )
    }
    fn check(&self) -> Option<String> {
        let limit = super::passes::MAX_BUFFER_SIZE;
        (self.resolution == Resolution::Absolute && !(1..=limit).contains(&self.size))
            .then(|| format!("size {} is out of range (1 to {limit} texels)", self.size))
    }
    fn emit(&self, io: &mut Emit) {
        read_buffer(io, "value", self.filter, None);
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        let lanes = io.input("value").map(|lane| {
            let lane = self.filter.range(lane);
            match self.format {
                BufferFormat::Unorm8 => lane.clamp(0.0, 1.0),
                BufferFormat::Float16 | BufferFormat::Float32 => lane,
            }
        });
        vec![lanes]
    }
    fn buffer(&self) -> Option<BufferSpec> {
        Some(BufferSpec {
            resolution: self.resolution,
            size: self.size,
            format: self.format,
            edge: self.edge,
        })
    }
}

impl Evaluate for Buffer {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let texel = self.filter.read(io.image("value"), io.domain());
        vec![typed(texel, self.ty)]
    }
}

impl Configure for Buffer {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        let Buffer {
            ty,
            resolution,
            size,
            format,
            edge,
            filter,
        } = self;
        let mut settings = vec![choice("type", ty, &TYPES)];
        settings.extend(buffer_settings(resolution, size, format, edge, filter));
        settings
    }
}

/// The settings of a buffer: its resolution (and size when absolute), format, edge mode
/// and filter, for every node that makes one.
pub(super) fn buffer_settings<'a>(
    resolution: &'a mut Resolution,
    size: &'a mut u32,
    format: &'a mut BufferFormat,
    edge: &'a mut EdgeMode,
    filter: &'a mut Filter,
) -> Vec<Setting<'a>> {
    vec![
        choice("resolution", resolution, &Resolution::ALL),
        Setting::Count {
            label: "size (absolute)",
            value: size,
            range: 1..=4096,
        },
        choice("format", format, &BufferFormat::ALL),
        choice("edges", edge, &EdgeMode::ALL),
        choice("filter", filter, &Filter::ALL),
    ]
}

impl Catalogue for Buffer {
    fn menu() -> Vec<(String, Self)> {
        vec![
            ("Buffer".into(), Buffer::default()),
            (
                "Buffer colours".into(),
                Buffer {
                    ty: ValueType::Color,
                    ..Buffer::default()
                },
            ),
        ]
    }
    fn examples() -> Vec<Self> {
        let mut examples: Vec<Buffer> = TYPES
            .into_iter()
            .map(|ty| Buffer {
                ty,
                ..Buffer::default()
            })
            .collect();
        examples.push(Buffer {
            resolution: Resolution::Half,
            format: BufferFormat::Float16,
            edge: EdgeMode::Mirror,
            filter: Filter::Bicubic,
            ..Buffer::default()
        });
        examples.push(Buffer {
            resolution: Resolution::Absolute,
            size: 24,
            format: BufferFormat::Unorm8,
            edge: EdgeMode::Clamp,
            ..Buffer::default()
        });
        examples
    }
}

/// What a blur's radius is measured in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum RadiusUnit {
    /// Texels of the buffer: the same blur in texels at every resolution.
    #[default]
    Texels,
    /// Domain units (the tile is 1 wide): the same picture at every resolution.
    Domain,
}

impl RadiusUnit {
    const ALL: [RadiusUnit; 2] = [RadiusUnit::Texels, RadiusUnit::Domain];
}

/// The most texels a blur reaches on each side.
pub const MAX_BLUR_RADIUS: f64 = 1024.0;

/// A Gaussian blur, in two passes (x, then y: its cost grows with the radius, not its
/// square): `radius` is three standard deviations, in texels or domain units.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Blur {
    pub ty: ValueType,
    pub unit: RadiusUnit,
}

impl Definition for Blur {
    image_node!();
    fn title(&self) -> &'static str {
        "Blur"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["gaussian", "soften", "smooth", "filter"]
    }
    fn signature(&self) -> Signature {
        let radius = match self.unit {
            RadiusUnit::Texels => input("radius", FLOAT, f(4.0)).soft(0.0, 64.0),
            RadiusUnit::Domain => input("radius", FLOAT, f(0.01)).soft(0.0, 0.1),
        };
        Signature::new(
            vec![
                input("image", self.ty, f(0.0)).sampled(),
                radius.at_least(0.0),
            ],
            vec![output("result", self.ty)],
        )
    }
    fn check(&self) -> Option<String> {
        None
    }
    fn emit(&self, io: &mut Emit) {
        read_buffer(io, "image", Filter::Bilinear, None);
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        // A weighted mean of the input's values.
        vec![io.input("image")]
    }
    fn stages(&self, constant: &dyn Fn(&str) -> Option<f64>) -> Result<Vec<Stage>, String> {
        let radius = constant("radius")
            .ok_or("the radius must be a constant: the blur runs once over the whole buffer")?;
        if !radius.is_finite() || radius < 0.0 {
            return Err(format!("radius {radius} must be finite and not negative"));
        }
        let unit = self.unit;
        let axis = |label: &str, axis: [i64; 2]| {
            // The radius in texels of the buffer, along this axis.
            let texels = match unit {
                RadiusUnit::Texels => super::emit::float_literal(radius),
                RadiusUnit::Domain => format!(
                    "{} * f32(textureDimensions(SOURCE_TEXTURE).{})",
                    super::emit::float_literal(radius),
                    if axis[0] == 1 { "x" } else { "y" }
                ),
            };
            Stage {
                label: format!("blur, {label} axis"),
                wgsl: format!(
                    "veneer_blur_axis(SOURCE, texel, vec2i({}, {}), min({texels}, {}))",
                    axis[0],
                    axis[1],
                    super::emit::float_literal(MAX_BLUR_RADIUS)
                ),
                library: vec!["veneer_blur_axis"],
                unchanged_up_to: 0,
                cpu: Box::new(move |image: &Image, texel| {
                    let side = if axis[0] == 1 {
                        image.width
                    } else {
                        image.height
                    };
                    let texels = match unit {
                        RadiusUnit::Texels => radius,
                        RadiusUnit::Domain => f64::from((radius as f32) * side as f32),
                    };
                    image.blur_axis(texel, axis, texels.min(MAX_BLUR_RADIUS))
                }),
            }
        };
        Ok(vec![axis("x", [1, 0]), axis("y", [0, 1])])
    }
}

impl Evaluate for Blur {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        vec![typed(io.image("image").bilinear(io.domain()), self.ty)]
    }
}

impl Configure for Blur {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        vec![
            choice("type", &mut self.ty, &TYPES),
            choice("radius in", &mut self.unit, &RadiusUnit::ALL),
        ]
    }
}

impl Catalogue for Blur {
    fn menu() -> Vec<(String, Self)> {
        vec![
            (
                "Blur".into(),
                Blur {
                    ty: ValueType::Float,
                    unit: RadiusUnit::Texels,
                },
            ),
            (
                "Blur colours".into(),
                Blur {
                    ty: ValueType::Color,
                    unit: RadiusUnit::Texels,
                },
            ),
        ]
    }
    fn examples() -> Vec<Self> {
        let mut examples: Vec<Blur> = TYPES
            .into_iter()
            .map(|ty| Blur {
                ty,
                unit: RadiusUnit::Texels,
            })
            .collect();
        examples.push(Blur {
            ty: ValueType::Float,
            unit: RadiusUnit::Domain,
        });
        examples
    }
}

/// Which way a normal map's green channel points.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum NormalConvention {
    /// y up the image (OpenGL, Blender, glTF).
    #[default]
    OpenGl,
    /// y down the image (DirectX, Unreal).
    DirectX,
}

impl NormalConvention {
    const ALL: [NormalConvention; 2] = [NormalConvention::OpenGl, NormalConvention::DirectX];

    fn y_sign(self) -> f64 {
        match self {
            NormalConvention::OpenGl => 1.0,
            NormalConvention::DirectX => -1.0,
        }
    }
}

/// The tangent-space normal of a height buffer: Sobel differences one texel apart,
/// slopes per domain unit scaled by `strength` (wire it to the material's normal).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct HeightToNormal {
    pub convention: NormalConvention,
}

impl Definition for HeightToNormal {
    image_node!();
    fn title(&self) -> &'static str {
        "Height to normal"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["normal map", "sobel", "bump", "derivative", "slope"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("height", FLOAT, f(0.0)).sampled(),
                input("strength", FLOAT, f(0.02)).soft(0.0, 0.2),
            ],
            vec![output("normal", VEC3)],
        )
    }
    fn check(&self) -> Option<String> {
        None
    }
    fn emit(&self, io: &mut Emit) {
        io.single(format!(
            "veneer_height_normal({}, s.uv, {}, {})",
            io.input("height"),
            io.input("strength"),
            super::emit::float_literal(self.convention.y_sign())
        ));
        io.uses("veneer_height_normal");
    }
    fn ranges(&self, _: &mut Ranges) -> Vec<Lanes> {
        let signed = Interval::new(-1.0, 1.0);
        vec![[signed, signed, Interval::new(0.0, 1.0)]]
    }
}

impl Evaluate for HeightToNormal {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let strength = io.float("strength").to_f64();
        let image = io.image("height");
        vec![image.height_normal(io.domain(), strength, self.convention.y_sign())]
    }
}

impl Configure for HeightToNormal {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        vec![choice(
            "convention",
            &mut self.convention,
            &NormalConvention::ALL,
        )]
    }
}

impl Catalogue for HeightToNormal {
    fn menu() -> Vec<(String, Self)> {
        vec![(
            "Height to normal".into(),
            HeightToNormal {
                convention: NormalConvention::OpenGl,
            },
        )]
    }
    fn examples() -> Vec<Self> {
        NormalConvention::ALL
            .into_iter()
            .map(|convention| HeightToNormal { convention })
            .collect()
    }
}

/// A buffer read at the point moved by `amount × vector` (a domain warp of an image:
/// wire a noise or a gradient to `vector`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Warp {
    pub ty: ValueType,
}

impl Definition for Warp {
    image_node!();
    fn title(&self) -> &'static str {
        "Warp"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["displace", "offset", "distort", "image warp"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("image", self.ty, f(0.0)).sampled(),
                input("vector", VEC2, v2(0.0, 0.0)),
                input("amount", FLOAT, f(0.05)).soft(0.0, 0.5),
            ],
            vec![output("result", self.ty)],
        )
    }
    fn check(&self) -> Option<String> {
        None
    }
    fn emit(&self, io: &mut Emit) {
        let offset = format!(
            "veneer_finite_vec2f({} * {})",
            io.input("amount"),
            io.input("vector")
        );
        io.uses("veneer_finite_vec2f");
        read_buffer(io, "image", Filter::Bilinear, Some(offset));
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        vec![io.input("image")]
    }
}

impl Evaluate for Warp {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let amount = io.float("amount");
        let vector = io.input("vector");
        let [u, v] = io.domain();
        let offset = [vector[0], vector[1]].map(|lane| {
            let moved = (amount * lane).to_f64() as f32;
            f64::from(moved.clamp(-f32::MAX, f32::MAX))
        });
        let at = [
            f64::from((u as f32) + offset[0] as f32),
            f64::from((v as f32) + offset[1] as f32),
        ];
        vec![typed(io.image("image").bilinear(at), self.ty)]
    }
}

super::math::typed_settings!(Warp, TYPES, menu [("Warp", ValueType::Float), ("Warp colours", ValueType::Color)]);
