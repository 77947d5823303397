//! Image operations: nodes that read a buffer around the point (see `sampled.rs` for
//! how buffers come to be): directional and slope blur, directional and slope warp,
//! edges, curvature and ambient occlusion from a height, 2D transforms of a buffer and
//! making a buffer tileable.

use super::cpu::Eval;
use super::emit::Emit;
use super::formulas::image_ops::{directional_warp_uv, transform_2d_uv};
use super::formulas::real::{Real, V3};
use super::interval::{Interval, Lanes, splat};
use super::passes::Filter;
use super::pins::{FLOAT, Signature, VEC2, f, input, output, v2};
use super::ranges::Ranges;
use super::sampled::{image_node, swizzle, typed};
use super::settings::{Basis, Setting, TYPES, choice};
use super::value::ValueType;
use super::{Catalogue, Category, Configure, Definition, Evaluate};
use serde::{Deserialize, Serialize};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather
            [$($units)* (EdgeDetect, image_ops) (Curvature, image_ops)]
            [$($configured)* (DirectionalBlur, image_ops) (SlopeBlur, image_ops)
                (HeightOcclusion, image_ops) (Transform2D, image_ops) (MakeTileable, image_ops)
                (DirectionalWarp, image_ops) (SlopeWarp, image_ops)]
            $($rest)*);
    };
}
pub(super) use kinds;

/// The default number of reads along a blur's line.
const BLUR_SAMPLES: u32 = 24;

/// The range of reads a line blur may take (its quality against its cost).
const BLUR_SAMPLE_RANGE: std::ops::RangeInclusive<u32> = 2..=256;

/// The reads of `samples` as a WGSL literal.
fn count_literal(samples: u32) -> String {
    format!("{samples}u")
}

/// Emits `function(<image>, s.uv, arguments…)` swizzled to `ty`, as the node's output.
fn emit_image_call(io: &mut Emit, function: &str, ty: ValueType, arguments: &[&str]) {
    let mut call = format!("{function}({}, s.uv", io.input("image"));
    for argument in arguments {
        call.push_str(", ");
        call.push_str(argument);
    }
    io.single(format!("{call}).{}", swizzle(ty)));
    io.uses(function);
}

/// A blur along a straight line through the point: `length` domain units long at
/// `angle` degrees from +u, the mean of `samples` reads (motion blur, streaks).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct DirectionalBlur {
    pub ty: ValueType,
    pub samples: u32,
}

impl Definition for DirectionalBlur {
    image_node!();
    fn title(&self) -> &'static str {
        "Directional blur"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["motion blur", "streak", "smear", "line blur"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("image", self.ty, f(0.0)).sampled(),
                input("angle", FLOAT, f(0.0)).soft(0.0, 180.0),
                input("length", FLOAT, f(0.05))
                    .soft(0.0, 0.25)
                    .at_least(0.0),
            ],
            vec![output("result", self.ty)],
        )
    }
    fn check(&self) -> Option<String> {
        check_samples(self.samples)
    }
    fn emit(&self, io: &mut Emit) {
        let samples = count_literal(self.samples);
        let (angle, length) = (
            io.input("angle").to_string(),
            io.input("length").to_string(),
        );
        let arguments = [angle.as_str(), length.as_str(), samples.as_str()];
        emit_image_call(io, "veneer_directional_blur", self.ty, &arguments);
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        vec![io.input("image")]
    }
}

impl Evaluate for DirectionalBlur {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let (angle, length) = (io.float("angle").to_f64(), io.float("length").to_f64());
        let image = io.image("image");
        let texel = image.directional_blur(io.domain(), angle, length, self.samples);
        vec![typed(texel, self.ty)]
    }
}

/// Why a line blur's read count is refused, if it is.
fn check_samples(samples: u32) -> Option<String> {
    (!BLUR_SAMPLE_RANGE.contains(&samples)).then(|| {
        format!(
            "samples {samples} is out of range ({} to {})",
            BLUR_SAMPLE_RANGE.start(),
            BLUR_SAMPLE_RANGE.end()
        )
    })
}

/// The settings of a line blur: its type and its reads.
fn line_blur_settings<'a>(ty: &'a mut ValueType, samples: &'a mut u32) -> Vec<Setting<'a>> {
    vec![
        choice("type", ty, &TYPES),
        Setting::Count {
            label: "samples",
            value: samples,
            range: BLUR_SAMPLE_RANGE,
        },
    ]
}

impl Configure for DirectionalBlur {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        line_blur_settings(&mut self.ty, &mut self.samples)
    }
}

impl Catalogue for DirectionalBlur {
    fn menu() -> Vec<(String, Self)> {
        vec![(
            "Directional blur".into(),
            DirectionalBlur {
                ty: ValueType::Float,
                samples: BLUR_SAMPLES,
            },
        )]
    }
    fn examples() -> Vec<Self> {
        let mut examples: Vec<DirectionalBlur> = TYPES
            .into_iter()
            .map(|ty| DirectionalBlur {
                ty,
                samples: BLUR_SAMPLES,
            })
            .collect();
        examples.push(DirectionalBlur {
            ty: ValueType::Float,
            samples: 2,
        });
        examples
    }
}

/// Slope blur (Substance's grunge workhorse): the image smeared along the slope of a
/// second buffer, downhill for a positive `intensity`, over intensity × slope domain
/// units: steep places streak, flat ones stay sharp.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct SlopeBlur {
    pub ty: ValueType,
    pub samples: u32,
}

impl Definition for SlopeBlur {
    image_node!();
    fn title(&self) -> &'static str {
        "Slope blur"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["grunge", "smear", "gradient blur", "erosion"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("image", self.ty, f(0.0)).sampled(),
                input("slope", FLOAT, f(0.0)).sampled(),
                input("intensity", FLOAT, f(0.005)).soft(-0.02, 0.02),
            ],
            vec![output("result", self.ty)],
        )
    }
    fn check(&self) -> Option<String> {
        check_samples(self.samples)
    }
    fn emit(&self, io: &mut Emit) {
        let call = format!(
            "veneer_slope_blur({}, {}, s.uv, {}, {})",
            io.input("image"),
            io.input("slope"),
            io.input("intensity"),
            count_literal(self.samples)
        );
        io.single(format!("{call}.{}", swizzle(self.ty)));
        io.uses("veneer_slope_blur");
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        vec![io.input("image")]
    }
}

impl Evaluate for SlopeBlur {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let intensity = io.float("intensity").to_f64();
        let (image, slope) = (io.image("image"), io.image("slope"));
        let texel = image.slope_blur(slope, io.domain(), intensity, self.samples);
        vec![typed(texel, self.ty)]
    }
}

impl Configure for SlopeBlur {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        line_blur_settings(&mut self.ty, &mut self.samples)
    }
}

impl Catalogue for SlopeBlur {
    fn menu() -> Vec<(String, Self)> {
        vec![
            (
                "Slope blur".into(),
                SlopeBlur {
                    ty: ValueType::Float,
                    samples: BLUR_SAMPLES,
                },
            ),
            (
                "Slope blur colours".into(),
                SlopeBlur {
                    ty: ValueType::Color,
                    samples: BLUR_SAMPLES,
                },
            ),
        ]
    }
    fn examples() -> Vec<Self> {
        TYPES
            .into_iter()
            .map(|ty| SlopeBlur {
                ty,
                samples: BLUR_SAMPLES,
            })
            .collect()
    }
}

/// The edges of a buffer: the length of its Sobel gradient (taps `width` texels apart)
/// times `strength`, from 0 on flat ground to 1 on a sharp step.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct EdgeDetect;

impl Definition for EdgeDetect {
    image_node!();
    fn title(&self) -> &'static str {
        "Edge detect"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["sobel", "outline", "contour", "gradient magnitude"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("image", FLOAT, f(0.0)).sampled(),
                input("width", FLOAT, f(1.0)).soft(0.0, 8.0).at_least(0.0),
                input("strength", FLOAT, f(4.0)).soft(0.0, 16.0),
            ],
            vec![output("edges", FLOAT)],
        )
    }
    fn check(&self) -> Option<String> {
        None
    }
    fn emit(&self, io: &mut Emit) {
        let call = format!(
            "veneer_edge_detect({}, s.uv, {}, {})",
            io.input("image"),
            io.input("width"),
            io.input("strength")
        );
        io.single(call);
        io.uses("veneer_edge_detect");
    }
    fn ranges(&self, _: &mut Ranges) -> Vec<Lanes> {
        vec![splat(Interval::UNIT)]
    }
}

impl Evaluate for EdgeDetect {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let (width, strength) = (io.float("width").to_f64(), io.float("strength").to_f64());
        let edges = io.image("image").edge_detect(io.domain(), width, strength);
        vec![[R::c(edges); 3]]
    }
}

impl Catalogue for EdgeDetect {
    fn menu() -> Vec<(String, Self)> {
        vec![("Edge detect".into(), EdgeDetect)]
    }
    fn examples() -> Vec<Self> {
        vec![EdgeDetect]
    }
}

/// The curvature of a height buffer: 0.5 where flat, brighter on ridges and bumps,
/// darker in hollows (edge wear and dirt masks).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Curvature;

impl Definition for Curvature {
    image_node!();
    fn title(&self) -> &'static str {
        "Curvature"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["laplacian", "convexity", "edge wear", "cavity"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("height", FLOAT, f(0.0)).sampled(),
                input("radius", FLOAT, f(0.01))
                    .soft(0.0, 0.05)
                    .at_least(0.0),
                input("strength", FLOAT, f(8.0)).soft(0.0, 64.0),
            ],
            vec![output("curvature", FLOAT)],
        )
    }
    fn check(&self) -> Option<String> {
        None
    }
    fn emit(&self, io: &mut Emit) {
        let call = format!(
            "veneer_curvature({}, s.uv, {}, {})",
            io.input("height"),
            io.input("radius"),
            io.input("strength")
        );
        io.single(call);
        io.uses("veneer_curvature");
    }
    fn ranges(&self, _: &mut Ranges) -> Vec<Lanes> {
        vec![splat(Interval::UNIT)]
    }
}

impl Evaluate for Curvature {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let (radius, strength) = (io.float("radius").to_f64(), io.float("strength").to_f64());
        let curvature = io.image("height").curvature(io.domain(), radius, strength);
        vec![[R::c(curvature); 3]]
    }
}

impl Catalogue for Curvature {
    fn menu() -> Vec<(String, Self)> {
        vec![("Curvature".into(), Curvature)]
    }
    fn examples() -> Vec<Self> {
        vec![Curvature]
    }
}

/// Ambient occlusion from a height buffer, horizon-based: 1 in the open, darker where
/// the height around rises above the point (the height times `depth` in domain units,
/// looked for out to `radius`). More directions and steps cost more and band less.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct HeightOcclusion {
    pub directions: u32,
    pub steps: u32,
}

/// The range of directions and of steps an occlusion may take.
const OCCLUSION_RANGE: std::ops::RangeInclusive<u32> = 1..=64;

impl Default for HeightOcclusion {
    fn default() -> HeightOcclusion {
        HeightOcclusion {
            directions: 8,
            steps: 12,
        }
    }
}

impl Definition for HeightOcclusion {
    image_node!();
    fn title(&self) -> &'static str {
        "Ambient occlusion"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["ao", "occlusion from height", "hbao", "cavity", "shadow"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("height", FLOAT, f(0.0)).sampled(),
                input("radius", FLOAT, f(0.05)).soft(0.0, 0.2).at_least(0.0),
                input("depth", FLOAT, f(0.05)).soft(0.0, 0.5),
            ],
            vec![output("occlusion", FLOAT)],
        )
    }
    fn check(&self) -> Option<String> {
        [("directions", self.directions), ("steps", self.steps)]
            .into_iter()
            .find(|(_, count)| !OCCLUSION_RANGE.contains(count))
            .map(|(name, count)| {
                format!(
                    "{name} {count} is out of range ({} to {})",
                    OCCLUSION_RANGE.start(),
                    OCCLUSION_RANGE.end()
                )
            })
    }
    fn emit(&self, io: &mut Emit) {
        let call = format!(
            "veneer_height_occlusion({}, s.uv, {}, {}, {}, {})",
            io.input("height"),
            io.input("radius"),
            io.input("depth"),
            count_literal(self.directions),
            count_literal(self.steps)
        );
        io.single(call);
        io.uses("veneer_height_occlusion");
    }
    fn ranges(&self, _: &mut Ranges) -> Vec<Lanes> {
        vec![splat(Interval::UNIT)]
    }
}

impl Evaluate for HeightOcclusion {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let (radius, depth) = (io.float("radius").to_f64(), io.float("depth").to_f64());
        let height = io.image("height");
        let occlusion =
            height.height_occlusion(io.domain(), radius, depth, self.directions, self.steps);
        vec![[R::c(occlusion); 3]]
    }
}

impl Configure for HeightOcclusion {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        vec![
            Setting::Count {
                label: "directions",
                value: &mut self.directions,
                range: OCCLUSION_RANGE,
            },
            Setting::Count {
                label: "steps",
                value: &mut self.steps,
                range: OCCLUSION_RANGE,
            },
        ]
    }
}

impl Catalogue for HeightOcclusion {
    fn menu() -> Vec<(String, Self)> {
        vec![("Ambient occlusion".into(), HeightOcclusion::default())]
    }
    fn examples() -> Vec<Self> {
        vec![
            HeightOcclusion::default(),
            HeightOcclusion {
                directions: 1,
                steps: 1,
            },
        ]
    }
}

/// A buffer moved by `offset`, turned `angle` degrees and scaled by `scale` about the
/// tile's centre, read with the buffer's edge mode.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Transform2D {
    pub ty: ValueType,
    pub filter: Filter,
}

impl Definition for Transform2D {
    image_node!();
    fn title(&self) -> &'static str {
        "Transform 2D"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["offset", "rotate", "scale", "move image", "tile transform"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("image", self.ty, f(0.0)).sampled(),
                input("offset", VEC2, v2(0.0, 0.0)).soft(-1.0, 1.0),
                input("angle", FLOAT, f(0.0)).soft(-180.0, 180.0),
                input("scale", VEC2, v2(1.0, 1.0)).soft(0.1, 4.0),
            ],
            vec![output("result", self.ty)],
        )
    }
    fn check(&self) -> Option<String> {
        None
    }
    fn emit(&self, io: &mut Emit) {
        let function = self.filter.wgsl();
        let at = format!(
            "veneer_transform_2d_uv(s.uv, {}, {}, {})",
            io.input("offset"),
            io.input("angle"),
            io.input("scale")
        );
        io.single(format!(
            "{function}({}, {at}).{}",
            io.input("image"),
            swizzle(self.ty)
        ));
        io.uses(function);
        io.uses("veneer_transform_2d_uv");
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        vec![io.input("image").map(|lane| self.filter.range(lane))]
    }
}

impl Evaluate for Transform2D {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let offset = io
            .input("offset")
            .map(|lane| f64::from(lane.to_f64() as f32));
        let scale = io
            .input("scale")
            .map(|lane| f64::from(lane.to_f64() as f32));
        let angle = io.float("angle").to_f64();
        let at = transform_2d_uv(
            io.domain(),
            [offset[0], offset[1]],
            angle,
            [scale[0], scale[1]],
        );
        let texel = self.filter.read(io.image("image"), at);
        vec![typed(texel, self.ty)]
    }
}

impl Configure for Transform2D {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        vec![
            choice("type", &mut self.ty, &TYPES),
            choice("filter", &mut self.filter, &Filter::ALL),
        ]
    }
}

impl Catalogue for Transform2D {
    fn menu() -> Vec<(String, Self)> {
        vec![(
            "Transform 2D".into(),
            Transform2D {
                ty: ValueType::Color,
                filter: Filter::Bilinear,
            },
        )]
    }
    fn examples() -> Vec<Self> {
        let mut examples: Vec<Transform2D> = TYPES
            .into_iter()
            .map(|ty| Transform2D {
                ty,
                filter: Filter::Bilinear,
            })
            .collect();
        examples.push(Transform2D {
            ty: ValueType::Float,
            filter: Filter::Bicubic,
        });
        examples
    }
}

/// Makes a buffer repeat: within `width` (a fraction of the tile) of each edge it fades
/// to copies of itself moved half a tile, which continue across the edges (a photo or
/// any input that does not tile).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct MakeTileable {
    pub ty: ValueType,
}

impl Definition for MakeTileable {
    image_node!();
    fn title(&self) -> &'static str {
        "Make tileable"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["seamless", "tile", "wrap", "repeat", "offset blend"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("image", self.ty, f(0.0)).sampled(),
                input("width", FLOAT, f(0.15)).soft(0.01, 0.5),
            ],
            vec![output("result", self.ty)],
        )
    }
    fn check(&self) -> Option<String> {
        None
    }
    fn emit(&self, io: &mut Emit) {
        let width = io.input("width").to_string();
        emit_image_call(io, "veneer_make_tileable", self.ty, &[width.as_str()]);
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        vec![io.input("image")]
    }
}

impl Evaluate for MakeTileable {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let width = io.float("width").to_f64();
        let texel = io.image("image").make_tileable(io.domain(), width);
        vec![typed(texel, self.ty)]
    }
}

super::math::typed_settings!(
    MakeTileable,
    TYPES,
    menu[("Make tileable", ValueType::Color)]
);

/// A buffer read moved along a direction by a value: `amount` × `intensity` domain
/// units at `angle` degrees from +u (wire a mask or a noise to `intensity`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct DirectionalWarp {
    pub ty: ValueType,
}

impl Definition for DirectionalWarp {
    image_node!();
    fn title(&self) -> &'static str {
        "Directional warp"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["offset", "shift", "displace along", "smear"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("image", self.ty, f(0.0)).sampled(),
                input("intensity", FLOAT, f(0.0)).soft(0.0, 1.0),
                input("angle", FLOAT, f(0.0)).soft(0.0, 360.0),
                input("amount", FLOAT, f(0.05)).soft(0.0, 0.5),
            ],
            vec![output("result", self.ty)],
        )
    }
    fn check(&self) -> Option<String> {
        None
    }
    fn emit(&self, io: &mut Emit) {
        let at = format!(
            "veneer_directional_warp_uv(s.uv, {}, {}, {})",
            io.input("intensity"),
            io.input("angle"),
            io.input("amount")
        );
        let read = format!("veneer_buffer_bilinear({}, {at})", io.input("image"));
        io.single(format!("{read}.{}", swizzle(self.ty)));
        io.uses("veneer_buffer_bilinear");
        io.uses("veneer_directional_warp_uv");
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        vec![io.input("image")]
    }
}

impl Evaluate for DirectionalWarp {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let intensity = io.float("intensity").to_f64();
        let (angle, amount) = (io.float("angle").to_f64(), io.float("amount").to_f64());
        let at = directional_warp_uv(io.domain(), intensity, angle, amount);
        vec![typed(io.image("image").bilinear(at), self.ty)]
    }
}

super::math::typed_settings!(
    DirectionalWarp,
    TYPES,
    menu[("Directional warp", ValueType::Color)]
);

/// A buffer read moved downhill along the slope of a second buffer, `amount` × slope
/// domain units: a warp by a gradient (the image flows off the slope's ridges).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct SlopeWarp {
    pub ty: ValueType,
}

impl Definition for SlopeWarp {
    image_node!();
    fn title(&self) -> &'static str {
        "Slope warp"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["gradient warp", "warp by slope", "flow", "displace"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("image", self.ty, f(0.0)).sampled(),
                input("slope", FLOAT, f(0.0)).sampled(),
                input("amount", FLOAT, f(0.002)).soft(-0.01, 0.01),
            ],
            vec![output("result", self.ty)],
        )
    }
    fn check(&self) -> Option<String> {
        None
    }
    fn emit(&self, io: &mut Emit) {
        let call = format!(
            "veneer_slope_warp({}, {}, s.uv, {})",
            io.input("image"),
            io.input("slope"),
            io.input("amount")
        );
        io.single(format!("{call}.{}", swizzle(self.ty)));
        io.uses("veneer_slope_warp");
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        vec![io.input("image")]
    }
}

impl Evaluate for SlopeWarp {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let amount = io.float("amount").to_f64();
        let (image, slope) = (io.image("image"), io.image("slope"));
        vec![typed(image.slope_warp(slope, io.domain(), amount), self.ty)]
    }
}

super::math::typed_settings!(SlopeWarp, TYPES, menu[("Slope warp", ValueType::Color)]);
