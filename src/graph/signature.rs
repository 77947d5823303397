//! Pin signatures: the inputs and outputs of every node kind.

use super::kind::{MathOp, NodeKind};
use super::value::{Value, ValueType};

/// What an unconnected input uses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PinDefault {
    /// A constant, overridable per node in the graph file.
    Const(Value),
    /// The surface position (texture-space coordinate), like Blender's implicit vector input.
    Position,
    /// The input must be wired.
    Required,
}

/// One input pin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InputPin {
    pub name: &'static str,
    pub ty: ValueType,
    pub default: PinDefault,
}

/// One output pin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OutputPin {
    pub name: &'static str,
    pub ty: ValueType,
}

/// The pins of a node kind.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Signature {
    pub inputs: Vec<InputPin>,
    pub outputs: Vec<OutputPin>,
}

impl Signature {
    /// The input pin called `name` and its index.
    pub fn input(&self, name: &str) -> Option<(usize, &InputPin)> {
        self.inputs
            .iter()
            .enumerate()
            .find(|(_, pin)| pin.name == name)
    }

    /// The output pin called `name` and its index.
    pub fn output(&self, name: &str) -> Option<(usize, &OutputPin)> {
        self.outputs
            .iter()
            .enumerate()
            .find(|(_, pin)| pin.name == name)
    }
}

fn f(x: f64) -> PinDefault {
    PinDefault::Const(Value::Float(x))
}
fn v3(x: f64, y: f64, z: f64) -> PinDefault {
    PinDefault::Const(Value::Vec3(x, y, z))
}
fn rgb(r: f64, g: f64, b: f64) -> PinDefault {
    PinDefault::Const(Value::Color(r, g, b))
}
fn splat(ty: ValueType, x: f64) -> PinDefault {
    PinDefault::Const(Value::Float(x).convert(ty))
}
fn input(name: &'static str, ty: ValueType, default: PinDefault) -> InputPin {
    InputPin { name, ty, default }
}
fn output(name: &'static str, ty: ValueType) -> OutputPin {
    OutputPin { name, ty }
}

const FLOAT: ValueType = ValueType::Float;
const VEC2: ValueType = ValueType::Vec2;
const VEC3: ValueType = ValueType::Vec3;
const COLOR: ValueType = ValueType::Color;
const REQUIRED: PinDefault = PinDefault::Required;
const POSITION: PinDefault = PinDefault::Position;

/// Names of vector components, in order.
pub const COMPONENTS: [&str; 3] = ["x", "y", "z"];

impl NodeKind {
    /// The pins of this node kind (they depend on settings such as `ty`).
    pub fn signature(&self) -> Signature {
        use NodeKind::*;
        let (inputs, outputs) = match self {
            Position => (vec![], vec![output("position", VEC3)]),
            Normal => (vec![], vec![output("normal", VEC3)]),
            Uv => (vec![], vec![output("uv", VEC2)]),
            Time => (vec![], vec![output("time", FLOAT)]),
            Field { .. } => (vec![], vec![output("distance", FLOAT)]),
            Constant { ty } => (
                vec![input("value", *ty, splat(*ty, 0.0))],
                vec![output("value", *ty)],
            ),
            Transform => (
                vec![
                    input("p", VEC3, POSITION),
                    input("scale", VEC3, v3(1.0, 1.0, 1.0)),
                    input("rotation", VEC3, v3(0.0, 0.0, 0.0)),
                    input("offset", VEC3, v3(0.0, 0.0, 0.0)),
                ],
                vec![output("p", VEC3)],
            ),
            Project => (
                vec![
                    input("p", VEC3, POSITION),
                    input("origin", VEC3, v3(0.0, 0.0, 0.0)),
                    input("direction", VEC3, v3(1.0, 0.0, 0.0)),
                ],
                vec![output("x", FLOAT)],
            ),
            Cylindrical => (
                vec![
                    input("p", VEC3, POSITION),
                    input("origin", VEC3, v3(0.0, 0.0, 0.0)),
                    input("axis", VEC3, v3(0.0, 1.0, 0.0)),
                ],
                vec![
                    output("t", FLOAT),
                    output("r", FLOAT),
                    output("theta", FLOAT),
                ],
            ),
            DomainWarp { .. } => (
                vec![
                    input("p", VEC3, POSITION),
                    input("strength", FLOAT, f(1.0)),
                    input("scale", FLOAT, f(1.0)),
                ],
                vec![output("p", VEC3)],
            ),
            Noise { .. } => (
                vec![input("p", VEC3, POSITION), input("scale", FLOAT, f(1.0))],
                vec![output("value", FLOAT)],
            ),
            Fbm { .. } | Turbulence { .. } | FractalSum { .. } => {
                let amplitude = if matches!(self, Fbm { .. }) { 0.5 } else { 1.0 };
                (
                    vec![
                        input("p", VEC3, POSITION),
                        input("scale", FLOAT, f(1.0)),
                        input("lacunarity", FLOAT, f(2.0)),
                        input("gain", FLOAT, f(0.5)),
                        input("amplitude", FLOAT, f(amplitude)),
                    ],
                    vec![output("value", FLOAT)],
                )
            }
            Worley { .. } => (
                vec![
                    input("p", VEC3, POSITION),
                    input("scale", FLOAT, f(1.0)),
                    input("jitter", FLOAT, f(1.0)),
                    input("lacunarity", FLOAT, f(2.0)),
                    input("gain", FLOAT, f(0.5)),
                ],
                vec![output("value", FLOAT)],
            ),
            SineBand => (
                vec![
                    input("x", FLOAT, REQUIRED),
                    input("frequency", FLOAT, f(1.0)),
                    input("distortion", FLOAT, f(1.0)),
                    input("turbulence", FLOAT, f(0.0)),
                ],
                vec![output("band", FLOAT)],
            ),
            Front => (
                vec![
                    input("distance", FLOAT, REQUIRED),
                    input("threshold", FLOAT, f(0.5)),
                    input("width", FLOAT, f(0.05)),
                    input("noise", FLOAT, f(0.0)),
                ],
                vec![output("covered", FLOAT)],
            ),
            Layers { ty } => (
                vec![
                    input("distance", FLOAT, REQUIRED),
                    input("noise", FLOAT, f(0.0)),
                    input("width", FLOAT, f(0.02)),
                    input("edge1", FLOAT, f(0.25)),
                    input("edge2", FLOAT, f(0.5)),
                    input("edge3", FLOAT, f(0.75)),
                    input("inner", *ty, splat(*ty, 0.0)),
                    input("second", *ty, splat(*ty, 0.33)),
                    input("third", *ty, splat(*ty, 0.67)),
                    input("outer", *ty, splat(*ty, 1.0)),
                ],
                vec![output("result", *ty)],
            ),
            Isolines => (
                vec![
                    input("value", FLOAT, REQUIRED),
                    input("spacing", FLOAT, f(0.1)),
                    input("width", FLOAT, f(0.01)),
                ],
                vec![output("line", FLOAT)],
            ),
            NoiseBump { .. } => (
                vec![
                    input("p", VEC3, POSITION),
                    input("scale", FLOAT, f(1.0)),
                    input("strength", FLOAT, f(0.05)),
                ],
                vec![output("bump", VEC3)],
            ),
            TriangleWave => (
                vec![
                    input("x", FLOAT, REQUIRED),
                    input("frequency", FLOAT, f(1.0)),
                ],
                vec![output("value", FLOAT)],
            ),
            Tiles => (
                vec![
                    input("p", VEC3, POSITION),
                    input("size", VEC2, PinDefault::Const(Value::Vec2(1.0, 1.0))),
                    input("gap", VEC2, PinDefault::Const(Value::Vec2(0.02, 0.02))),
                    input("row_offset", FLOAT, f(0.5)),
                    input("blur", FLOAT, f(0.0)),
                ],
                vec![
                    output("mask", FLOAT),
                    output("cell", VEC2),
                    output("local", VEC2),
                ],
            ),
            Rings => (
                vec![
                    input("p", VEC3, POSITION),
                    input("origin", VEC3, v3(0.0, 0.0, 0.0)),
                    input("axis", VEC3, v3(0.0, 1.0, 0.0)),
                    input("frequency", FLOAT, f(1.0)),
                ],
                vec![output("value", FLOAT)],
            ),
            Math { op, ty } => {
                let identity = match op {
                    MathOp::Multiply | MathOp::Divide | MathOp::Power => 1.0,
                    _ => 0.0,
                };
                (
                    vec![
                        input("a", *ty, splat(*ty, 0.0)),
                        input("b", *ty, splat(*ty, identity)),
                    ],
                    vec![output("result", *ty)],
                )
            }
            Unary { ty, .. } => (vec![input("x", *ty, REQUIRED)], vec![output("result", *ty)]),
            Mix { ty } => (
                vec![
                    input("a", *ty, splat(*ty, 0.0)),
                    input("b", *ty, splat(*ty, 1.0)),
                    input("factor", FLOAT, f(0.5)),
                ],
                vec![output("result", *ty)],
            ),
            Clamp { ty } => (
                vec![
                    input("x", *ty, REQUIRED),
                    input("min", FLOAT, f(0.0)),
                    input("max", FLOAT, f(1.0)),
                ],
                vec![output("result", *ty)],
            ),
            Step { ty } => (
                vec![input("edge", FLOAT, f(0.5)), input("x", *ty, REQUIRED)],
                vec![output("result", *ty)],
            ),
            Smoothstep => (
                vec![
                    input("edge0", FLOAT, f(0.0)),
                    input("edge1", FLOAT, f(1.0)),
                    input("x", FLOAT, REQUIRED),
                ],
                vec![output("result", FLOAT)],
            ),
            Remap => (
                vec![
                    input("x", FLOAT, REQUIRED),
                    input("from_min", FLOAT, f(0.0)),
                    input("from_max", FLOAT, f(1.0)),
                    input("to_min", FLOAT, f(0.0)),
                    input("to_max", FLOAT, f(1.0)),
                ],
                vec![output("result", FLOAT)],
            ),
            Length { ty } => (
                vec![input("v", *ty, REQUIRED)],
                vec![output("length", FLOAT)],
            ),
            Dot { ty } => (
                vec![input("a", *ty, REQUIRED), input("b", *ty, REQUIRED)],
                vec![output("dot", FLOAT)],
            ),
            Normalize { ty } => (vec![input("v", *ty, REQUIRED)], vec![output("unit", *ty)]),
            Split { ty } => (
                vec![input("v", *ty, REQUIRED)],
                COMPONENTS[..ty.width()]
                    .iter()
                    .map(|name| output(name, FLOAT))
                    .collect(),
            ),
            Combine { ty } => (
                COMPONENTS[..ty.width()]
                    .iter()
                    .map(|name| input(name, FLOAT, f(0.0)))
                    .collect(),
                vec![output("v", *ty)],
            ),
            ColorRamp { .. } => (
                vec![input("factor", FLOAT, REQUIRED)],
                vec![output("color", COLOR)],
            ),
            Material => (
                vec![
                    input("albedo", COLOR, rgb(0.8, 0.8, 0.8)),
                    input("alpha", FLOAT, f(1.0)),
                    input("specular", COLOR, rgb(0.04, 0.04, 0.04)),
                    input("shininess", FLOAT, f(32.0)),
                    input("bump", VEC3, v3(0.0, 0.0, 0.0)),
                    input("height", FLOAT, f(0.0)),
                ],
                vec![],
            ),
        };
        Signature { inputs, outputs }
    }
}
