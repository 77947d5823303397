//! Range propagation: the interval of every output, node by node in dependency order,
//! and the hazards each node's input ranges reveal.

use super::interval::{Interval, Lanes, max_length, splat};
use super::{F32_LATTICE_LIMIT, Lint, SINE_HASH_SAFE_COORDINATE};
use crate::graph::check::{CheckedGraph, CheckedNode, InputSource};
use crate::graph::{Basis, MathOp, NodeId, NodeKind, UnaryOp};
use std::collections::BTreeMap;

struct Propagation {
    ranges: BTreeMap<NodeId, Vec<Lanes>>,
    lints: Vec<Lint>,
}

impl Propagation {
    fn warn(&mut self, node: &CheckedNode, message: String) {
        self.lints.push(Lint {
            node: node.node.id,
            node_name: node.node.to_string(),
            message,
        });
    }
}

pub fn run(graph: &CheckedGraph, positions: Lanes) -> Vec<Lint> {
    let mut state = Propagation {
        ranges: BTreeMap::new(),
        lints: Vec::new(),
    };
    for checked in &graph.order {
        let inputs: Vec<Lanes> = checked
            .inputs
            .iter()
            .map(|source| match source {
                InputSource::Wire { node, output, .. } => state.ranges[node][*output],
                InputSource::Const(value) => value.components().map(Interval::point),
                InputSource::Position => positions,
            })
            .collect();
        let outputs = node_ranges(checked, &inputs, &positions, &mut state);
        state.ranges.insert(checked.node.id, outputs);
    }
    state.lints
}

fn one(interval: Interval) -> Vec<Lanes> {
    vec![splat(interval)]
}

fn lanewise(a: &Lanes, b: &Lanes, f: impl Fn(Interval, Interval) -> Interval) -> Lanes {
    [f(a[0], b[0]), f(a[1], b[1]), f(a[2], b[2])]
}

/// The constant of an input that is not wired (its interval is one point).
fn constant(lanes: &Lanes) -> Option<f64> {
    (lanes[0].lo == lanes[0].hi).then_some(lanes[0].lo)
}

/// Lints of lattice noise sampled up to `magnitude` with `basis`.
fn lattice_hazards(
    state: &mut Propagation,
    node: &CheckedNode,
    basis: Option<Basis>,
    magnitude: f64,
) {
    if magnitude > F32_LATTICE_LIMIT {
        state.warn(node, format!(
            "samples noise at coordinates up to {magnitude:.3e}, past f32's integer precision ({F32_LATTICE_LIMIT:.3e}): the pattern degrades into blocks"
        ));
    } else if basis == Some(Basis::ValueSine) && magnitude > SINE_HASH_SAFE_COORDINATE {
        state.warn(node, format!(
            "uses the sine hash at coordinates up to {magnitude:.3e}; past {SINE_HASH_SAFE_COORDINATE:.0e} f32 can no longer tell neighbouring cells apart (use the PCG hash)"
        ));
    }
}

fn node_ranges(
    checked: &CheckedNode,
    i: &[Lanes],
    positions: &Lanes,
    state: &mut Propagation,
) -> Vec<Lanes> {
    use NodeKind::*;
    let f = |k: usize| i[k][0];
    match &checked.node.kind {
        Position => vec![*positions],
        Normal => one(Interval::new(-1.0, 1.0)),
        Uv => one(Interval::UNIT),
        Time => one(Interval::new(0.0, f64::INFINITY)),
        Field { .. } => one(Interval::UNIT),
        Constant { .. } => vec![i[0]],
        Transform => {
            let scaled = lanewise(&i[0], &i[1], Interval::mul);
            let rotated = if i[2].iter().all(|lane| lane.lo == 0.0 && lane.hi == 0.0) {
                scaled
            } else {
                let radius = max_length(&scaled, 3);
                splat(Interval::new(-radius, radius))
            };
            vec![lanewise(&rotated, &i[3], Interval::add)]
        }
        Project | Cylindrical | Rings => {
            let relative = lanewise(&i[0], &i[1], Interval::sub);
            let radius = max_length(&relative, 3);
            if max_length(&i[2], 3) == 0.0 {
                state.warn(
                    checked,
                    "the direction or axis is the zero vector: every point maps to 0".into(),
                );
            }
            match checked.node.kind {
                Project => one(Interval::new(-radius, radius)),
                Cylindrical => vec![
                    splat(Interval::new(-radius, radius)),
                    splat(Interval::new(0.0, radius)),
                    splat(Interval::new(-std::f64::consts::PI, std::f64::consts::PI)),
                ],
                _ => one(Interval::UNIT),
            }
        }
        DomainWarp { basis } => {
            let magnitude = max_length(&i[0], 3) * f(2).magnitude();
            lattice_hazards(state, checked, Some(*basis), magnitude);
            let reach = f(1).magnitude();
            vec![i[0].map(|lane| lane.add(Interval::new(-reach, reach)))]
        }
        Noise { basis } => {
            lattice_hazards(
                state,
                checked,
                Some(*basis),
                max_length(&i[0], 3) * f(1).magnitude(),
            );
            one(Interval::UNIT)
        }
        Fbm { .. } | Turbulence { .. } | FractalSum { .. } => {
            let (mode, basis, octaves, normalize) =
                checked.node.kind.fractal().expect("a fractal kind");
            let (lacunarity, gain, amplitude) = (f(2), f(3), f(4));
            if gain.lo >= 1.0 {
                state.warn(
                    checked,
                    format!(
                        "gain {} ≥ 1: octaves grow instead of fading, the sum does not converge",
                        gain.lo
                    ),
                );
            }
            if lacunarity.hi <= 1.0 {
                state.warn(
                    checked,
                    format!("lacunarity {} ≤ 1: octaves do not get finer", lacunarity.hi),
                );
            }
            let top = lacunarity.magnitude().max(1.0).powi(octaves as i32 - 1);
            let magnitude = max_length(&i[0], 3) * f(1).magnitude() * top;
            if !top.is_finite() || top > f64::from(f32::MAX) {
                state.warn(
                    checked,
                    format!(
                        "{octaves} octaves at lacunarity {}: the top frequency overflows f32",
                        lacunarity.hi
                    ),
                );
            } else {
                lattice_hazards(state, checked, Some(basis), magnitude);
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
                (crate::graph::FractalMode::Fbm, true)
                | (crate::graph::FractalMode::Turbulence, true) => {
                    Interval::new(-1.0, 1.0).hull(Interval::UNIT)
                }
                (crate::graph::FractalMode::Fbm, false)
                | (crate::graph::FractalMode::Turbulence, false) => Interval::new(-sum, sum),
                (crate::graph::FractalMode::FractalSum, true) => Interval::new(-1.0, 1.0),
                (crate::graph::FractalMode::FractalSum, false) => Interval::new(-sum, sum),
            };
            one(range)
        }
        Worley { octaves, .. } => {
            lattice_hazards(
                state,
                checked,
                None,
                max_length(&i[0], 3)
                    * f(1).magnitude()
                    * f(3).magnitude().max(1.0).powi(*octaves as i32 - 1),
            );
            let sum: f64 = (0..*octaves).map(|k| f(4).magnitude().powi(k as i32)).sum();
            one(Interval::new(0.0, 3.0 * sum))
        }
        SineBand | TriangleWave => one(Interval::UNIT),
        Tiles => {
            let cells = [i[0][0], i[0][2], Interval::point(0.0)];
            vec![
                splat(Interval::UNIT),
                cells.map(|lane| Interval::new(lane.lo.floor() - 2.0, lane.hi.ceil() + 2.0)),
                splat(Interval::UNIT),
            ]
        }
        Math { op, .. } => {
            let result = match op {
                MathOp::Add => lanewise(&i[0], &i[1], Interval::add),
                MathOp::Subtract => lanewise(&i[0], &i[1], Interval::sub),
                MathOp::Multiply => lanewise(&i[0], &i[1], Interval::mul),
                MathOp::Minimum => lanewise(&i[0], &i[1], |a, b| {
                    Interval::new(a.lo.min(b.lo), a.hi.min(b.hi))
                }),
                MathOp::Maximum => lanewise(&i[0], &i[1], |a, b| {
                    Interval::new(a.lo.max(b.lo), a.hi.max(b.hi))
                }),
                MathOp::Divide => {
                    if i[1].iter().any(|lane| lane.contains(0.0)) {
                        state.warn(
                            checked,
                            "the divisor may be 0 there: the result is 0".into(),
                        );
                    }
                    lanewise(&i[0], &i[1], Interval::div)
                }
                MathOp::Power => {
                    if i[0].iter().any(|lane| lane.lo < 0.0) {
                        state.warn(checked, "the base may be negative, where a power is undefined: the result is 0 there".into());
                    }
                    lanewise(&i[0], &i[1], |base, exponent| {
                        let base = base.clamp(0.0, f64::MAX);
                        let corners = [
                            base.lo.powf(exponent.lo),
                            base.lo.powf(exponent.hi),
                            base.hi.powf(exponent.lo),
                            base.hi.powf(exponent.hi),
                        ];
                        let corners = corners.map(|c| if c.is_nan() { 0.0 } else { c.min(3.0e38) });
                        Interval::new(
                            0.0f64.min(corners.iter().copied().fold(f64::INFINITY, f64::min)),
                            corners.iter().copied().fold(0.0, f64::max),
                        )
                    })
                }
            };
            vec![result]
        }
        Unary { op, .. } => vec![i[0].map(|x| match op {
            UnaryOp::Abs => Interval::new(
                if x.contains(0.0) {
                    0.0
                } else {
                    x.lo.abs().min(x.hi.abs())
                },
                x.magnitude(),
            ),
            UnaryOp::Fract => Interval::UNIT,
            UnaryOp::Floor => Interval::new(x.lo.floor(), x.hi.floor()),
            UnaryOp::Sin | UnaryOp::Cos => Interval::new(-1.0, 1.0),
            UnaryOp::Negate => Interval::new(-x.hi, -x.lo),
            UnaryOp::OneMinus => Interval::new(1.0 - x.hi, 1.0 - x.lo),
        })],
        Front | Layers { .. } => {
            if f(2).lo <= 0.0 {
                state.warn(
                    checked,
                    "the width can be 0: a hard front that aliases (stair-steps) on screen".into(),
                );
            }
            match checked.node.kind {
                Front => one(Interval::UNIT),
                _ => vec![lanewise(
                    &lanewise(&i[6], &i[7], Interval::hull),
                    &lanewise(&i[8], &i[9], Interval::hull),
                    Interval::hull,
                )],
            }
        }
        Isolines => {
            if f(1).lo <= 0.0 || f(2).lo <= 0.0 {
                state.warn(
                    checked,
                    "the spacing or the width can be 0: no lines there".into(),
                );
            }
            one(Interval::UNIT)
        }
        NoiseBump { basis } => {
            lattice_hazards(
                state,
                checked,
                Some(*basis),
                max_length(&i[0], 3) * f(1).magnitude(),
            );
            let reach = 4.0 * f(2).magnitude();
            vec![splat(Interval::new(-reach, reach))]
        }
        Mix { .. } => {
            let factor = f(2);
            vec![lanewise(&i[0], &i[1], |a, b| a.add(b.sub(a).mul(factor)))]
        }
        Clamp { .. } => vec![i[0].map(|x| {
            Interval::new(
                x.lo.max(f(1).lo).min(f(2).hi),
                x.hi.min(f(2).hi).max(f(1).lo),
            )
        })],
        Step { .. } => vec![splat(Interval::UNIT)],
        Smoothstep => {
            match (constant(&i[0]), constant(&i[1])) {
                (Some(a), Some(b)) if a == b => state.warn(
                    checked,
                    format!("edge0 = edge1 = {a}: a hard step, not a smooth one"),
                ),
                (Some(a), Some(b)) if a > b => state.warn(
                    checked,
                    format!("edge0 {a} > edge1 {b}: the ramp falls instead of rising"),
                ),
                _ => {}
            }
            one(Interval::UNIT)
        }
        Remap => {
            if let (Some(a), Some(b)) = (constant(&i[1]), constant(&i[2])) {
                if a == b {
                    state.warn(
                        checked,
                        format!("from_min = from_max = {a}: the result is to_min everywhere"),
                    );
                }
            }
            let t = f(0).sub(f(1)).div(f(2).sub(f(1)));
            one(f(3).add(t.mul(f(4).sub(f(3)))))
        }
        Length { ty } => one(Interval::new(0.0, max_length(&i[0], ty.width()))),
        Dot { ty } => {
            let bound = max_length(&i[0], ty.width()) * max_length(&i[1], ty.width());
            one(Interval::new(-bound, bound))
        }
        Normalize { ty } => {
            if i[0][..ty.width()].iter().all(|lane| lane.contains(0.0)) {
                state.warn(
                    checked,
                    "the vector may be zero, where it has no direction: the result is 0 there"
                        .into(),
                );
            }
            vec![splat(Interval::new(-1.0, 1.0))]
        }
        Split { ty } => (0..ty.width()).map(|k| splat(i[0][k])).collect(),
        Combine { ty } => vec![[
            f(0),
            f(1),
            if ty.width() == 3 {
                f(2)
            } else {
                Interval::point(0.0)
            },
        ]],
        ColorRamp { stops, .. } => {
            let hull = |k: usize| {
                stops
                    .iter()
                    .map(|s| [s.color.0, s.color.1, s.color.2][k])
                    .fold(Interval::new(f64::INFINITY, f64::NEG_INFINITY), |h, c| {
                        h.hull(Interval::point(c))
                    })
            };
            vec![[hull(0), hull(1), hull(2)]]
        }
        Material => vec![],
    }
}
