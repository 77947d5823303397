//! Every node kind's recorded derivatives against central finite differences: at random
//! inputs within each pin's soft range, the derivative of every output lane by every
//! input lane, taken on a tape in f64, must match the central difference in f64 to 1e-4
//! (relative, or absolute below 1) wherever the node is smooth there. Where it is not —
//! a floor, a step, a cell border or a hash within the difference's reach, seen as the
//! central differences at two step sizes disagreeing — the sample is skipped. Every kind
//! with inputs and outputs must be compared somewhere, and the skipped samples stay few.

use super::Draws;
use super::tape::{Recording, Var};
use crate::nodes::NodeKind;
use crate::nodes::cpu::{Eval, Surface};
use crate::nodes::formulas::real::V3;
use crate::nodes::pins::InputPin;

/// Inputs drawn per kind.
const SAMPLES: usize = 12;

/// Whether the node can be evaluated from its input pins alone.
fn evaluable(kind: &NodeKind) -> bool {
    let definition = kind.definition();
    let pins = definition.signature().inputs;
    definition.bitmap().is_none()
        && !matches!(kind, NodeKind::Group(_))
        && !pins.iter().any(|pin| pin.sampled || pin.re_evaluated)
}

/// The node's outputs at `inputs`, in f64.
fn outputs(kind: &NodeKind, pins: &[InputPin], inputs: &[V3<f64>]) -> Vec<V3<f64>> {
    let surface = Surface::<f64>::at([0.3, 0.2, 0.1]);
    kind.eval(&Eval::new(pins, inputs, &surface))
}

#[test]
fn every_kinds_derivatives_match_central_differences_where_it_is_smooth() {
    let mut draws = Draws::new(7);
    let mut failures = Vec::new();
    let (mut compared_kinds, mut all_compared, mut all_skipped) = (0, 0, 0);
    for kind in NodeKind::examples() {
        if !evaluable(&kind) {
            continue;
        }
        let pins = kind.definition().signature().inputs;
        let (mut compared, mut skipped) = (0usize, 0usize);
        for _ in 0..SAMPLES {
            let inputs: Vec<V3<f64>> = (pins.iter())
                .map(|pin| {
                    let (low, high) = (pin.range.soft_min, pin.range.soft_max);
                    let (low, high) = match low.is_finite() && high.is_finite() && low < high {
                        true => (low, high),
                        false => (-1.0, 1.0),
                    };
                    let mut lanes = [0.0; 3];
                    for lane in lanes.iter_mut().take(pin.ty.width()) {
                        *lane = low + (high - low) * draws.uniform();
                    }
                    lanes
                })
                .collect();
            let mut recording = Recording::start();
            let leaves: Vec<V3<Var<f64>>> = (inputs.iter().zip(&pins))
                .map(|(lanes, pin)| {
                    let mut vars = lanes.map(Var::constant);
                    for lane in 0..pin.ty.width() {
                        vars[lane] = recording.leaf(lanes[lane]);
                    }
                    vars
                })
                .collect();
            let surface = Surface::<Var<f64>>::at([0.3, 0.2, 0.1]);
            let recorded = kind.eval(&Eval::new(&pins, &leaves, &surface));
            let signature_outputs = kind.definition().signature().outputs;
            // Leaf k is lane `lane` of pin `pin`.
            let places: Vec<(usize, usize)> = (pins.iter().enumerate())
                .flat_map(|(pin, p)| (0..p.ty.width()).map(move |lane| (pin, lane)))
                .collect();
            for (j, output) in signature_outputs.iter().enumerate() {
                let width = output.ty.width();
                for (out_lane, &value) in recorded[j].iter().enumerate().take(width) {
                    let gradient = recording.gradient(&[(value, 1.0)]);
                    for (k, &(pin, lane)) in places.iter().enumerate() {
                        let x = inputs[pin][lane];
                        let difference = |h: f64| {
                            let at = |delta: f64| {
                                let mut moved = inputs.clone();
                                moved[pin][lane] = x + delta;
                                outputs(&kind, &pins, &moved)[j][out_lane]
                            };
                            (at(h) - at(-h)) / (2.0 * h)
                        };
                        let h = 1e-5 * x.abs().max(1.0);
                        let (coarse, fine) = (difference(h), difference(h / 4.0));
                        let scale = fine.abs().max(1.0);
                        if !coarse.is_finite() || (coarse - fine).abs() > 1e-5 * scale {
                            skipped += 1;
                            continue;
                        }
                        compared += 1;
                        if (gradient[k] - fine).abs() > 1e-4 * scale {
                            failures.push(format!(
                                "{}: d {}.{out_lane} / d {}.{lane} at {:?} is {} on the tape, {} by differences",
                                ron::to_string(&kind).unwrap_or_default(),
                                output.name,
                                pins[pin].name,
                                inputs,
                                gradient[k],
                                fine
                            ));
                        }
                    }
                }
            }
        }
        if pins.is_empty() || kind.definition().signature().outputs.is_empty() {
            continue;
        }
        assert!(compared > 0, "{}: never smooth where sampled", kind.name());
        compared_kinds += 1;
        (all_compared, all_skipped) = (all_compared + compared, all_skipped + skipped);
    }
    failures.dedup_by(|a, b| a.split(':').next() == b.split(':').next());
    assert!(
        failures.is_empty(),
        "{} kinds differ:\n{}",
        failures.len(),
        failures.join("\n")
    );
    assert!(compared_kinds > 40, "{compared_kinds}");
    assert!(
        all_skipped * 10 < all_compared,
        "{all_skipped} of {all_compared} skipped"
    );
}
