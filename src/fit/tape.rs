//! Reverse-mode derivatives through the CPU evaluator. [`Var`] is a [`Real`] whose every
//! operation is recorded on a tape of the calling thread, with the partial derivatives
//! of its result by its operands; a backward pass over the tape gives the derivative of
//! one or several outputs by every leaf at once, at a cost of a few times the evaluation
//! whatever the number of leaves (forward-mode dual numbers would cost once per leaf).
//! Every node formula is generic over [`Real`], so the whole evaluator differentiates.
//!
//! Values are held and computed in the precision `F`: f32 for fitting, as the GPU
//! computes them (the sine hashes of the noises give other numbers in f64, so an f64 fit
//! would fit another pattern than the one rendered), f64 where the derivatives are
//! checked against finite differences; the partial derivatives are taken in f64 from
//! those values.
//!
//! Where a formula is not differentiable (a floor, a comparison, a hash of the value's
//! bits), the recorded derivative is the one of the branch taken: zero through a floor
//! or a step, which is the derivative almost everywhere.

use crate::nodes::formulas::real::Real;
use std::cell::RefCell;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// No entry of the tape: a constant.
const CONSTANT: u32 = u32::MAX;

/// One recorded operation: up to two operands and the partial derivative by each.
#[derive(Clone, Copy)]
struct Entry {
    operands: [(u32, f64); 2],
}

thread_local! {
    static TAPE: RefCell<Vec<Entry>> = const { RefCell::new(Vec::new()) };
}

/// A value of precision `F` recorded on the calling thread's tape (or a constant).
#[derive(Clone, Copy, Debug)]
pub struct Var<F: Real = f32> {
    value: F,
    index: u32,
}

impl<F: Real> Var<F> {
    /// A constant (rounded to `F`): no derivative flows into it.
    pub fn constant(value: f64) -> Var<F> {
        Var {
            value: F::c(value),
            index: CONSTANT,
        }
    }

    /// The value.
    pub fn value(self) -> f64 {
        self.value.to_f64()
    }

    /// A result of `value` whose partial derivatives by `operands` are given.
    fn record(value: F, operands: [(Var<F>, f64); 2]) -> Var<F> {
        let live = |(var, partial): (Var<F>, f64)| match var.index {
            CONSTANT => (CONSTANT, 0.0),
            index => (index, partial),
        };
        let operands = operands.map(live);
        if operands.iter().all(|(index, _)| *index == CONSTANT) {
            return Var {
                value,
                index: CONSTANT,
            };
        }
        Var {
            value,
            index: push(Entry { operands }),
        }
    }

    /// A result of one operand.
    fn unary(value: F, operand: Var<F>, partial: f64) -> Var<F> {
        Var::record(value, [(operand, partial), (Var::constant(0.0), 0.0)])
    }
}

/// Appends `entry` to this thread's tape, returning its index.
fn push(entry: Entry) -> u32 {
    TAPE.with(|tape| {
        let mut tape = tape.borrow_mut();
        let index = u32::try_from(tape.len()).expect("a tape of fewer than 2³² entries");
        tape.push(entry);
        index
    })
}

/// A recording: the leaves made for it, and the tape cleared when it starts.
pub struct Recording {
    leaves: Vec<u32>,
}

impl Recording {
    /// Starts a recording on the calling thread (clearing what an earlier one left).
    pub fn start() -> Recording {
        TAPE.with(|tape| tape.borrow_mut().clear());
        Recording { leaves: Vec::new() }
    }

    /// A new leaf holding `value` (rounded to `F`): a variable the derivatives are taken
    /// by.
    pub fn leaf<F: Real>(&mut self, value: f64) -> Var<F> {
        let var = Var {
            value: F::c(value),
            index: push(Entry {
                operands: [(CONSTANT, 0.0); 2],
            }),
        };
        self.leaves.push(var.index);
        var
    }

    /// The derivative of `Σ weight × output` by every leaf, in the order they were made.
    pub fn gradient<F: Real>(&self, outputs: &[(Var<F>, f64)]) -> Vec<f64> {
        TAPE.with(|tape| {
            let tape = tape.borrow();
            let mut adjoint = vec![0.0; tape.len()];
            for &(output, weight) in outputs {
                if output.index != CONSTANT {
                    adjoint[output.index as usize] += weight;
                }
            }
            for index in (0..tape.len()).rev() {
                let carried = adjoint[index];
                if carried == 0.0 {
                    continue;
                }
                for (operand, partial) in tape[index].operands {
                    if operand != CONSTANT {
                        adjoint[operand as usize] += carried * partial;
                    }
                }
            }
            (self.leaves.iter())
                .map(|&leaf| adjoint[leaf as usize])
                .collect()
        })
    }
}

impl<F: Real> PartialEq for Var<F> {
    fn eq(&self, other: &Var<F>) -> bool {
        self.value == other.value
    }
}

impl<F: Real> PartialOrd for Var<F> {
    fn partial_cmp(&self, other: &Var<F>) -> Option<std::cmp::Ordering> {
        self.value.partial_cmp(&other.value)
    }
}

impl<F: Real> Add for Var<F> {
    type Output = Var<F>;
    fn add(self, other: Var<F>) -> Var<F> {
        Var::record(self.value + other.value, [(self, 1.0), (other, 1.0)])
    }
}

impl<F: Real> Sub for Var<F> {
    type Output = Var<F>;
    fn sub(self, other: Var<F>) -> Var<F> {
        Var::record(self.value - other.value, [(self, 1.0), (other, -1.0)])
    }
}

impl<F: Real> Mul for Var<F> {
    type Output = Var<F>;
    fn mul(self, other: Var<F>) -> Var<F> {
        Var::record(
            self.value * other.value,
            [(self, other.value()), (other, self.value())],
        )
    }
}

impl<F: Real> Div for Var<F> {
    type Output = Var<F>;
    fn div(self, other: Var<F>) -> Var<F> {
        let quotient = self.value / other.value;
        let by = 1.0 / other.value();
        Var::record(quotient, [(self, by), (other, -quotient.to_f64() * by)])
    }
}

impl<F: Real> Neg for Var<F> {
    type Output = Var<F>;
    fn neg(self) -> Var<F> {
        Var::unary(-self.value, self, -1.0)
    }
}

impl<F: Real> Real for Var<F> {
    fn c(x: f64) -> Var<F> {
        Var::constant(x)
    }
    fn to_f64(self) -> f64 {
        self.value()
    }
    fn floor(self) -> Var<F> {
        Var::constant(self.value.floor().to_f64())
    }
    fn sin(self) -> Var<F> {
        Var::unary(self.value.sin(), self, self.value().cos())
    }
    fn cos(self) -> Var<F> {
        Var::unary(self.value.cos(), self, -self.value().sin())
    }
    fn sqrt(self) -> Var<F> {
        let root = self.value.sqrt();
        // The derivative at 0 is infinite; the branch's one-sided limit is taken as 0 so
        // a length of zero passes nothing back rather than NaN.
        let partial = if root.to_f64() > 0.0 {
            0.5 / root.to_f64()
        } else {
            0.0
        };
        Var::unary(root, self, partial)
    }
    fn abs(self) -> Var<F> {
        let sign = if self.value() < 0.0 { -1.0 } else { 1.0 };
        Var::unary(self.value.abs(), self, sign)
    }
    fn atan2(self, x: Var<F>) -> Var<F> {
        let (y, xv) = (self.value(), x.value());
        let squared = y * y + xv * xv;
        let (by_y, by_x) = match squared > 0.0 {
            true => (xv / squared, -y / squared),
            false => (0.0, 0.0),
        };
        Var::record(self.value.atan2(x.value), [(self, by_y), (x, by_x)])
    }
    fn powf(self, e: Var<F>) -> Var<F> {
        let (base, exponent) = (self.value(), e.value());
        let power = self.value.powf(e.value);
        let by_base = match base != 0.0 {
            true => exponent * power.to_f64() / base,
            false if exponent == 1.0 => 1.0,
            false => 0.0,
        };
        let by_exponent = match base > 0.0 {
            true => power.to_f64() * base.ln(),
            false => 0.0,
        };
        let finite = |x: f64| if x.is_finite() { x } else { 0.0 };
        Var::record(power, [(self, finite(by_base)), (e, finite(by_exponent))])
    }
    fn exp(self) -> Var<F> {
        let power = self.value.exp();
        Var::unary(power, self, power.to_f64())
    }
    fn max_finite() -> Var<F> {
        Var {
            value: F::max_finite(),
            index: CONSTANT,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_gradient_of_a_small_expression_is_the_calculus_one() {
        let mut recording = Recording::start();
        let x: Var = recording.leaf(0.7);
        let y: Var = recording.leaf(-1.3);
        // f = sin(x) * y + x / y + sqrt(x * x + y * y)
        let f = x.sin() * y + x / y + (x * x + y * y).sqrt();
        let (xv, yv) = (f64::from(0.7f32), f64::from(-1.3f32));
        let r = (xv * xv + yv * yv).sqrt();
        let expected = [
            xv.cos() * yv + 1.0 / yv + xv / r,
            xv.sin() - xv / (yv * yv) + yv / r,
        ];
        let gradient = recording.gradient(&[(f, 1.0)]);
        for (got, want) in gradient.iter().zip(expected) {
            assert!((got - want).abs() < 1e-6, "{gradient:?} vs {expected:?}");
        }
    }

    #[test]
    fn constants_and_floors_pass_nothing_back() {
        let mut recording = Recording::start();
        let x: Var = recording.leaf(2.5);
        let f = x.floor() * Var::c(3.0) + Var::c(1.0);
        assert_eq!(recording.gradient(&[(f, 1.0)]), vec![0.0]);
    }
}
