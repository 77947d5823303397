//! CPU reference evaluator: the same graph, the same formulas as the generated WGSL,
//! evaluated at one point in f32 (like the GPU) or f64 (the reference).

mod colour;
mod fields;
mod gabor;
#[cfg(test)]
mod library_items;
mod noise;
mod octaves;
mod ranges;
mod real;
mod shapes;
mod worley_edge;

pub use real::Real;

use crate::codegen::worley_feature_index;
use crate::graph::check::{CheckedGraph, CheckedNode, InputSource};
use crate::graph::{CheckError, Graph, MathOp, NodeKind, RampInterpolation, UnaryOp, ValueType};
use real::{V3, map, safe_normalize, splat, zip};
use std::collections::BTreeMap;

/// The inputs of a material at one point (the CPU side of `VeneerSurface`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface<R> {
    pub position: [R; 3],
    pub normal: [R; 3],
    pub uv: [R; 2],
    pub fields: [R; 4],
    pub time: R,
}

impl<R: Real> Surface<R> {
    /// A point with normal +y, uv 0, fields 0 and time 0 (the flat render's surface).
    pub fn at(position: [f64; 3]) -> Surface<R> {
        let zero = R::c(0.0);
        Surface {
            position: position.map(R::c),
            normal: [zero, R::c(1.0), zero],
            uv: [zero; 2],
            fields: [zero; 4],
            time: zero,
        }
    }
}

/// What a material returns (the CPU side of `VeneerMaterial`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material<R> {
    pub albedo: [R; 3],
    pub alpha: R,
    pub specular: [R; 3],
    pub shininess: R,
    pub bump: [R; 3],
    pub height: R,
}

/// A graph prepared for evaluation at many points.
pub struct Evaluator {
    graph: CheckedGraph,
    /// Position in `graph.order` of every node id.
    index: BTreeMap<crate::graph::NodeId, usize>,
}

impl Evaluator {
    /// Checks `graph` and prepares it.
    pub fn new(graph: &Graph) -> Result<Evaluator, Vec<CheckError>> {
        Ok(Evaluator::from_checked(crate::graph::check(graph)?))
    }

    /// Prepares an already checked graph.
    pub fn from_checked(graph: CheckedGraph) -> Evaluator {
        let index = graph
            .order
            .iter()
            .enumerate()
            .map(|(i, c)| (c.node.id, i))
            .collect();
        Evaluator { graph, index }
    }

    /// The material at one point, in precision `R`.
    pub fn eval<R: Real>(&self, surface: &Surface<R>) -> Material<R> {
        let mut values: Vec<Vec<V3<R>>> = Vec::with_capacity(self.graph.order.len());
        for checked in &self.graph.order {
            let inputs: Vec<V3<R>> = checked
                .inputs
                .iter()
                .map(|source| match source {
                    InputSource::Wire { node, output, .. } => values[self.index[node]][*output],
                    InputSource::Const(value) => value.components().map(R::c),
                    InputSource::Position => surface.position,
                })
                .collect();
            if checked.node.kind == NodeKind::Material {
                return Material {
                    albedo: inputs[0],
                    alpha: inputs[1][0],
                    specular: inputs[2],
                    shininess: inputs[3][0],
                    bump: inputs[4],
                    height: inputs[5][0],
                };
            }
            values.push(eval_node(checked, &inputs, surface));
        }
        unreachable!("a checked graph ends with its material node")
    }
}

fn vec2<R: Real>(x: V3<R>) -> V3<R> {
    [x[0], x[1], R::c(0.0)]
}

/// The outputs of a node whose inputs are all known constants, evaluated in f32 as the
/// GPU would (codegen folds such nodes into literals).
pub(crate) fn constant_outputs(checked: &CheckedNode, inputs: &[[f32; 3]]) -> Vec<[f32; 3]> {
    eval_node(checked, inputs, &Surface::<f32>::at([0.0; 3]))
}

/// The outputs of one node (each as three lanes) given its inputs.
fn eval_node<R: Real>(checked: &CheckedNode, i: &[V3<R>], s: &Surface<R>) -> Vec<V3<R>> {
    use NodeKind::*;
    let f = |k: usize| i[k][0];
    let one = |x: R| vec![splat(x)];
    match &checked.node.kind {
        Position => vec![s.position],
        Normal => vec![s.normal],
        Uv => vec![[s.uv[0], s.uv[1], R::c(0.0)]],
        Time => one(s.time),
        Field { slot } => one(s.fields[*slot as usize]),
        Constant { .. } => vec![i[0]],
        Transform => vec![shapes::transform(i[0], i[1], i[2], i[3])],
        Project => one(shapes::project(i[0], i[1], i[2])),
        Cylindrical => shapes::cylindrical(i[0], i[1], i[2]).map(splat).to_vec(),
        DomainWarp { basis } => vec![shapes::warp(*basis, i[0], f(1), f(2))],
        Noise { basis } => one(noise::basis(*basis, real::scale(i[0], f(1)))),
        Fbm { .. } | Turbulence { .. } | FractalSum { .. } => {
            let (mode, basis, octaves, normalize) =
                checked.node.kind.fractal().expect("a fractal kind");
            one(shapes::fractal(
                mode,
                basis,
                real::scale(i[0], f(1)),
                octaves,
                [f(2), f(3), f(4)],
                normalize,
                // Every octave: the CPU has no pixel footprint.
                R::c(1.0e9),
            ))
        }
        Worley {
            feature,
            metric,
            octaves,
        } => {
            let (feature, p) = (worley_feature_index(*feature), real::scale(i[0], f(1)));
            let (mut sum, mut amp, mut freq) = (R::c(0.0), R::c(1.0), R::c(1.0));
            if *octaves == 1 {
                sum = shapes::worley_feature(noise::worley(p, f(2), *metric), feature);
            } else {
                for _ in 0..*octaves {
                    sum = sum
                        + amp
                            * shapes::worley_feature(
                                noise::worley(real::scale(p, freq), f(2), *metric),
                                feature,
                            );
                    freq = freq * f(3);
                    amp = amp * f(4);
                }
            }
            one(sum)
        }
        SineBand => one(shapes::sine_band(f(0), f(1), f(2), f(3))),
        TriangleWave => one(shapes::triangle_wave(f(0), f(1))),
        Tiles => {
            let (mask, cell, local) = shapes::tiles(i[0], i[1], i[2], f(3), f(4));
            vec![
                splat(mask),
                vec2([cell[0], cell[1], R::c(0.0)]),
                vec2([local[0], local[1], R::c(0.0)]),
            ]
        }
        Rings => one(shapes::rings(i[0], i[1], i[2], f(3))),
        Front => one(fields::front(f(0), f(1), f(2), f(3))),
        Layers { .. } => vec![fields::layers(i)],
        Isolines => one(fields::isolines(f(0), f(1), f(2))),
        NoiseBump { basis } => vec![fields::noise_bump(*basis, i[0], f(1), f(2))],
        Math { op, .. } => vec![zip(i[0], i[1], |a, b| match op {
            MathOp::Add => a + b,
            MathOp::Subtract => a - b,
            MathOp::Multiply => a * b,
            MathOp::Divide => shapes::safe_div(a, b),
            MathOp::Power => shapes::safe_pow(a, b),
            MathOp::Minimum => a.min(b),
            MathOp::Maximum => a.max(b),
        })],
        Unary { op, .. } => vec![map(i[0], |x| match op {
            UnaryOp::Abs => x.abs(),
            UnaryOp::Fract => x.fract(),
            UnaryOp::Floor => x.floor(),
            UnaryOp::Sin => x.sin(),
            UnaryOp::Cos => x.cos(),
            UnaryOp::Negate => -x,
            UnaryOp::OneMinus => R::c(1.0) - x,
        })],
        Mix { .. } => vec![shapes::mix3(i[0], i[1], f(2))],
        Clamp { .. } => vec![map(i[0], |x| x.max(f(1)).min(f(2)))],
        Step { .. } => vec![map(i[1], |x| R::step(f(0), x))],
        Smoothstep => one(shapes::smoothstep(f(0), f(1), f(2))),
        Remap => one(shapes::remap(f(0), f(1), f(2), f(3), f(4))),
        Length { ty } => one(real::length(i[0], ty.width())),
        Dot { ty } => one(real::dot(i[0], i[1], ty.width())),
        Normalize { ty } => vec![safe_normalize(i[0], ty.width())],
        Split { ty } => (0..ty.width()).map(|k| splat(i[0][k])).collect(),
        Combine { ty } => {
            let z = if *ty == ValueType::Vec2 {
                R::c(0.0)
            } else {
                f(2)
            };
            vec![[f(0), f(1), z]]
        }
        ColorRamp {
            stops,
            interpolation,
        } => {
            let t = f(0);
            let mut color = shapes::color(stops[0].color);
            for pair in stops.windows(2) {
                let next = shapes::color(pair[1].color);
                color = match interpolation {
                    RampInterpolation::Linear => shapes::mix3(
                        color,
                        next,
                        shapes::linearstep(R::c(pair[0].position), R::c(pair[1].position), t),
                    ),
                    RampInterpolation::Constant if t >= R::c(pair[1].position) => next,
                    RampInterpolation::Constant => color,
                };
            }
            vec![color]
        }
        Material => unreachable!("the material node is handled by the evaluator"),
    }
}
