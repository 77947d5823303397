//! Shapes: signed distances over the xz plane (negative inside) with a fill whose edge
//! is anti-aliased over the pixel's footprint, their smooth booleans, and the fills,
//! bevels and glows made from any distance.
//!
//! A shape sits at the origin, sized for the unit square a tile sampler gives each
//! instance ([-0.5, 0.5]²), so it can be placed as it is.

use super::cpu::Eval;
use super::emit::{Detail, Emit};
use super::formulas::real::{Real, V3, splat};
use super::formulas::sdf::{self, ShapeOp, V2};
use super::interval::{self, Interval, Lanes};
use super::pins::{FLOAT, InputPin, POINT, REQUIRED, Signature, VEC2, f, input, output, v2};
use super::ranges::Ranges;
use super::settings::{Basis, Setting, choice};
use super::{Catalogue, Category, Configure, Definition, Evaluate};
use serde::{Deserialize, Serialize};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather
            [$($units)* (ShapeFromSdf, shapes)]
            [$($configured)* (Shape, shapes) (ShapeBoolean, shapes)]
            $($rest)*);
    };
}
pub(super) use kinds;

/// The shapes a Shape node draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum ShapeKind {
    Disc,
    Ellipse,
    Box,
    RoundedBox,
    Polygon,
    Star,
    Capsule,
    Ring,
    /// A smooth radial gradient (its fill), with the disc's distance.
    Bell,
}

impl ShapeKind {
    /// Every shape, in menu order.
    pub const ALL: [ShapeKind; 9] = [
        ShapeKind::Disc,
        ShapeKind::Ellipse,
        ShapeKind::Box,
        ShapeKind::RoundedBox,
        ShapeKind::Polygon,
        ShapeKind::Star,
        ShapeKind::Capsule,
        ShapeKind::Ring,
        ShapeKind::Bell,
    ];

    /// The menu's name.
    fn menu_name(self) -> &'static str {
        match self {
            ShapeKind::Disc => "disc",
            ShapeKind::Ellipse => "ellipse",
            ShapeKind::Box => "box",
            ShapeKind::RoundedBox => "rounded box",
            ShapeKind::Polygon => "polygon",
            ShapeKind::Star => "star",
            ShapeKind::Capsule => "capsule (line segment)",
            ShapeKind::Ring => "ring",
            ShapeKind::Bell => "gradient bell",
        }
    }

    /// The pins that size the shape.
    fn pins(self) -> Vec<InputPin> {
        let radius = |r| input("radius", FLOAT, f(r)).soft(0.0, 1.0);
        let half = input("half_size", VEC2, v2(0.4, 0.3)).soft(0.0, 1.0);
        match self {
            ShapeKind::Disc => vec![radius(0.4)],
            ShapeKind::Ellipse => vec![input("radii", VEC2, v2(0.45, 0.3)).soft(0.0, 1.0)],
            ShapeKind::Box => vec![half],
            ShapeKind::RoundedBox => {
                vec![half, input("corner", FLOAT, f(0.1)).soft(0.0, 0.5)]
            }
            ShapeKind::Polygon => vec![
                radius(0.45),
                input("sides", FLOAT, f(6.0))
                    .limits(3.0, 64.0)
                    .soft(3.0, 12.0),
            ],
            ShapeKind::Star => vec![
                radius(0.45),
                input("points", FLOAT, f(5.0))
                    .limits(2.0, 64.0)
                    .soft(2.0, 12.0),
                input("sharpness", FLOAT, f(0.5)).limits(0.0, 1.0),
            ],
            ShapeKind::Capsule => vec![
                input("a", VEC2, v2(-0.3, 0.0)).soft(-0.5, 0.5),
                input("b", VEC2, v2(0.3, 0.0)).soft(-0.5, 0.5),
                radius(0.1),
            ],
            ShapeKind::Ring => vec![
                radius(0.35),
                input("thickness", FLOAT, f(0.1)).soft(0.0, 0.5),
            ],
            ShapeKind::Bell => vec![radius(0.5)],
        }
    }

    /// The WGSL distance of point `p` (an xz expression) with the pins' expressions.
    fn distance(self, io: &mut Emit, p: &str) -> String {
        let pin = |name: &str| io.input(name).to_string();
        let (function, arguments) = match self {
            ShapeKind::Disc | ShapeKind::Bell => ("veneer_sd_disc", vec![pin("radius")]),
            ShapeKind::Ellipse => ("veneer_sd_ellipse", vec![pin("radii")]),
            ShapeKind::Box => ("veneer_sd_box", vec![pin("half_size"), "0.0".into()]),
            ShapeKind::RoundedBox => ("veneer_sd_box", vec![pin("half_size"), pin("corner")]),
            ShapeKind::Polygon => ("veneer_sd_polygon", vec![pin("radius"), pin("sides")]),
            ShapeKind::Star => (
                "veneer_sd_star",
                vec![pin("radius"), pin("points"), pin("sharpness")],
            ),
            ShapeKind::Capsule => ("veneer_sd_segment", vec![pin("a"), pin("b"), pin("radius")]),
            ShapeKind::Ring => ("veneer_sd_ring", vec![pin("radius"), pin("thickness")]),
        };
        io.uses(function);
        format!("{function}({p}, {})", arguments.join(", "))
    }

    /// The distance of point `p` on the CPU.
    fn eval_distance<R: Real>(self, io: &Eval<R>, p: V2<R>) -> R {
        match self {
            ShapeKind::Disc | ShapeKind::Bell => sdf::disc(p, io.float("radius")),
            ShapeKind::Ellipse => sdf::ellipse(p, io.pair("radii")),
            ShapeKind::Box => sdf::rectangle(p, io.pair("half_size"), R::c(0.0)),
            ShapeKind::RoundedBox => sdf::rectangle(p, io.pair("half_size"), io.float("corner")),
            ShapeKind::Polygon => sdf::polygon(p, io.float("radius"), io.float("sides")),
            ShapeKind::Star => sdf::star(
                p,
                io.float("radius"),
                io.float("points"),
                io.float("sharpness"),
            ),
            ShapeKind::Capsule => sdf::segment(p, io.pair("a"), io.pair("b"), io.float("radius")),
            ShapeKind::Ring => sdf::ring(p, io.float("radius"), io.float("thickness")),
        }
    }
}

/// The edge width a fill spreads over: `softness`, or in footprint detail at least the
/// pixel's footprint (the distance's screen-space change, or inside a placed pattern
/// the instance's footprint, as derivatives are not taken in a sampler's loop).
fn edge_width(io: &Emit, distance: &str, softness: &str) -> String {
    match (io.detail, io.instance()) {
        (Detail::Full, _) => softness.to_string(),
        (Detail::Footprint, Some(instance)) => format!("max({softness}, {instance}.footprint)"),
        (Detail::Footprint, None) => format!("max({softness}, fwidth({distance}))"),
    }
}

/// Binds the node to `veneer_shape(distance, width)`: outputs fill and distance.
fn emit_shape(io: &mut Emit, distance: String) {
    let name = io.name();
    let raw = format!("{name}__distance");
    let width = edge_width(io, &raw, io.input("softness"));
    io.statement(format!("let {raw}: f32 = {distance};"));
    io.bind(
        "veneer_shape_result",
        format!("veneer_shape({raw}, {width})"),
    );
    io.uses("veneer_shape");
    io.outputs(vec![format!("{name}.fill"), format!("{name}.distance")]);
}

/// The pin every fill reads: how far its edge spreads (0: as sharp as the pixel allows).
const SOFTNESS: InputPin = input("softness", FLOAT, f(0.0))
    .limits(0.0, 10.0)
    .soft(0.0, 0.1);

/// The fill and distance outputs (the fill first: thumbnails show it).
fn shape_outputs() -> Vec<super::pins::OutputPin> {
    vec![output("fill", FLOAT), output("distance", FLOAT)]
}

/// A shape at the origin: its signed distance and its anti-aliased fill.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Shape {
    pub shape: ShapeKind,
}

impl Definition for Shape {
    computed_in!(Category::Pattern, unchecked);
    fn title(&self) -> &'static str {
        "Shape"
    }
    fn shown_title(&self) -> String {
        let name = self.shape.menu_name();
        let mut letters = name.chars();
        letters
            .next()
            .map(|first| first.to_uppercase().chain(letters).collect())
            .unwrap_or_default()
    }
    fn keywords(&self) -> &'static [&'static str] {
        &[
            "sdf",
            "signed distance",
            "circle",
            "disc",
            "ellipse",
            "box",
            "rectangle",
            "square",
            "polygon",
            "hexagon",
            "star",
            "capsule",
            "line",
            "segment",
            "ring",
            "bell",
            "gradient",
            "stamp",
        ]
    }
    fn signature(&self) -> Signature {
        let mut inputs = vec![POINT];
        inputs.extend(self.shape.pins());
        inputs.push(SOFTNESS);
        Signature::new(inputs, shape_outputs())
    }
    fn emit(&self, io: &mut Emit) {
        let p = format!("{}.xz", io.input("p"));
        let distance = self.shape.distance(io, &p);
        if self.shape == ShapeKind::Bell {
            let name = io.name();
            io.uses("veneer_bell");
            let bell = format!("veneer_bell({p}, {})", io.input("radius"));
            io.bind(
                "veneer_shape_result",
                format!("veneer_shape_result({distance}, {bell})"),
            );
            io.uses("veneer_shape");
            io.outputs(vec![format!("{name}.fill"), format!("{name}.distance")]);
        } else {
            emit_shape(io, distance);
        }
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        // A shape reaches no farther from the origin than its largest size or point.
        let size = (self.shape.pins().iter())
            .map(|pin| interval::max_length(&io.input(pin.name), pin.ty.width()))
            .fold(0.0, f64::max);
        let reach = io.reach("p");
        vec![
            interval::splat(Interval::UNIT),
            interval::splat(Interval::new(-size, reach + size)),
        ]
    }
}

impl Evaluate for Shape {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let position = io.input("p");
        let p = [position[0], position[2]];
        let distance = self.shape.eval_distance(io, p);
        let fill = match self.shape {
            ShapeKind::Bell => sdf::bell(p, io.float("radius")),
            _ => sdf::fill(distance, io.float("softness")),
        };
        vec![splat(fill), splat(distance)]
    }
}

impl Configure for Shape {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        vec![choice("shape", &mut self.shape, &ShapeKind::ALL)]
    }
}

impl Catalogue for Shape {
    fn menu() -> Vec<(String, Self)> {
        ShapeKind::ALL
            .into_iter()
            .map(|shape| (format!("Shape ({})", shape.menu_name()), Shape { shape }))
            .collect()
    }
    fn examples() -> Vec<Self> {
        ShapeKind::ALL
            .into_iter()
            .map(|shape| Shape { shape })
            .collect()
    }
}

/// Two distances combined: union, `a` less `b`, or intersection, smoothed over
/// `smoothness` (0: exact), with the result's fill.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct ShapeBoolean {
    pub op: ShapeOp,
}

impl Definition for ShapeBoolean {
    computed_in!(Category::Pattern, unchecked);
    fn title(&self) -> &'static str {
        "Shape boolean"
    }
    fn shown_title(&self) -> String {
        format!("Shape {:?}", self.op)
            .to_lowercase()
            .replacen('s', "S", 1)
    }
    fn keywords(&self) -> &'static [&'static str] {
        &[
            "sdf",
            "union",
            "subtract",
            "difference",
            "intersect",
            "combine",
            "smooth min",
            "csg",
        ]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("a", FLOAT, REQUIRED),
                input("b", FLOAT, REQUIRED),
                input("smoothness", FLOAT, f(0.0))
                    .at_least(0.0)
                    .soft(0.0, 0.2),
                SOFTNESS,
            ],
            shape_outputs(),
        )
    }
    fn emit(&self, io: &mut Emit) {
        io.uses("veneer_sd_boolean");
        let distance = format!(
            "veneer_sd_boolean({}, {}, {}, {}u)",
            io.input("a"),
            io.input("b"),
            io.input("smoothness"),
            self.op.code()
        );
        emit_shape(io, distance);
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        let (a, b) = (io.float("a"), io.float("b"));
        let k = io.float("smoothness").magnitude();
        let span = a
            .hull(b)
            .hull(a.mul(Interval::point(-1.0)))
            .hull(b.mul(Interval::point(-1.0)));
        vec![
            interval::splat(Interval::UNIT),
            interval::splat(Interval::new(span.lo - k, span.hi + k)),
        ]
    }
}

impl Evaluate for ShapeBoolean {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let distance = self
            .op
            .apply(io.float("a"), io.float("b"), io.float("smoothness"));
        vec![
            splat(sdf::fill(distance, io.float("softness"))),
            splat(distance),
        ]
    }
}

impl Configure for ShapeBoolean {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        vec![choice("operation", &mut self.op, &ShapeOp::ALL)]
    }
}

impl Catalogue for ShapeBoolean {
    fn menu() -> Vec<(String, Self)> {
        ShapeOp::ALL
            .into_iter()
            .map(|op| (format!("Shape boolean ({op:?})"), ShapeBoolean { op }))
            .collect()
    }
    fn examples() -> Vec<Self> {
        ShapeOp::ALL
            .into_iter()
            .map(|op| ShapeBoolean { op })
            .collect()
    }
}

/// A shape made from any distance: its fill (an outline `thickness` wide when above 0),
/// a bevel rising over `bevel` inside, and glows falling over `glow` outside and
/// `inner_glow` inside.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShapeFromSdf;

impl Definition for ShapeFromSdf {
    computed_in!(Category::Pattern, unchecked);
    fn title(&self) -> &'static str {
        "Shape from SDF"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &[
            "sdf",
            "outline",
            "stroke",
            "bevel",
            "glow",
            "inner glow",
            "distance",
        ]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("distance", FLOAT, REQUIRED),
                input("thickness", FLOAT, f(0.0))
                    .at_least(0.0)
                    .soft(0.0, 0.2),
                input("bevel", FLOAT, f(0.1)).at_least(0.0).soft(0.0, 0.5),
                input("glow", FLOAT, f(0.1)).at_least(0.0).soft(0.0, 0.5),
                input("inner_glow", FLOAT, f(0.1))
                    .at_least(0.0)
                    .soft(0.0, 0.5),
                SOFTNESS,
            ],
            vec![
                output("fill", FLOAT),
                output("bevel", FLOAT),
                output("glow", FLOAT),
                output("inner_glow", FLOAT),
            ],
        )
    }
    fn emit(&self, io: &mut Emit) {
        let name = io.name();
        let width = edge_width(io, io.input("distance"), io.input("softness"));
        io.uses("veneer_sdf_profiles");
        io.bind(
            "veneer_sdf_profiles_result",
            format!(
                "veneer_sdf_profiles({}, {}, {}, {}, {}, {width})",
                io.input("distance"),
                io.input("thickness"),
                io.input("bevel"),
                io.input("glow"),
                io.input("inner_glow"),
            ),
        );
        io.outputs(
            ["fill", "bevel", "glow", "inner_glow"]
                .map(|member| format!("{name}.{member}"))
                .to_vec(),
        );
    }
    fn ranges(&self, _: &mut Ranges) -> Vec<Lanes> {
        vec![interval::splat(Interval::UNIT); 4]
    }
}

impl Evaluate for ShapeFromSdf {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        sdf::profiles(
            io.float("distance"),
            io.float("thickness"),
            io.float("bevel"),
            io.float("glow"),
            io.float("inner_glow"),
            io.float("softness"),
        )
        .map(splat)
        .to_vec()
    }
}

plain_catalogue!(ShapeFromSdf);
