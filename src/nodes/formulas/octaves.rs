//! Fractal sums with a rotation per octave, formula for formula as in
//! shaders/fractal_rotated.wgsl.

// The node kinds that use these arrive through the node registry.

use super::real::{Real, V3, dot, finite, scale};
use super::shapes::fractal;
use crate::nodes::settings::{Basis, FractalMode};

/// The rows of the octave rotation: 137.50776405° (the golden angle) about (1, 2, 3)/√14.
const ROTATION: [[f64; 3]; 3] = [
    [-0.613271101, -0.293401571, 0.733358081],
    [0.789792679, -0.240977770, 0.564054287],
    [0.011228581, 0.925119037, 0.379511115],
];

/// `veneer_octave_rotate`: `p` turned by the fixed octave rotation, clamped to the finite range.
pub fn octave_rotate<R: Real>(p: V3<R>) -> V3<R> {
    ROTATION.map(|row| finite(dot(row.map(R::c), p, 3)))
}

/// `veneer_<mode>_rotated_<basis>`: the fractal sum of [`fractal`] with octave i sampled
/// at R^i p (times its frequency). Each octave's term is [`fractal`]'s single-octave sum,
/// so the two cannot drift apart.
pub fn fractal_rotated<R: Real>(
    mode: FractalMode,
    basis: Basis,
    p: V3<R>,
    octaves: u32,
    [lacunarity, gain, amplitude]: [R; 3],
    normalize: bool,
    cutoff: R,
) -> R {
    let (mut sum, mut amp, mut freq, mut total) = (R::c(0.0), amplitude, R::c(1.0), R::c(0.0));
    let mut q = p.map(finite);
    for i in 0..octaves {
        let shown_from = cutoff - R::c(f64::from(i));
        let one = [lacunarity, gain, amp];
        sum = finite(sum + fractal(mode, basis, scale(q, freq), 1, one, false, shown_from, None));
        total = (total + amp.abs()).min(R::c(3.0e38));
        freq = finite(freq * lacunarity);
        amp = finite(amp * gain);
        q = octave_rotate(q);
    }
    if normalize && total > R::c(0.0) {
        sum / total
    } else {
        sum
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nodes::formulas::real::{length, sub};

    fn matrix_product(a: [[f64; 3]; 3], b: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
        std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
    }

    #[test]
    fn the_octave_rotation_is_a_rotation_by_the_golden_angle_that_never_repeats() {
        let transposed: [[f64; 3]; 3] =
            std::array::from_fn(|i| std::array::from_fn(|j| ROTATION[j][i]));
        let identity = matrix_product(ROTATION, transposed);
        for (i, row) in identity.iter().enumerate() {
            for (j, x) in row.iter().enumerate() {
                let expected = if i == j { 1.0 } else { 0.0 };
                assert!((x - expected).abs() < 1.0e-9);
            }
        }
        let r = ROTATION;
        let det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1])
            - r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0])
            + r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
        assert!((det - 1.0).abs() < 1.0e-9);
        // The axis (1, 2, 3) stays put.
        let axis = octave_rotate::<f64>([1.0, 2.0, 3.0]);
        assert!(length(sub(axis, [1.0, 2.0, 3.0]), 3) < 1.0e-8);
        // Angle from the trace: 1 + 2 cos(angle).
        let trace = r[0][0] + r[1][1] + r[2][2];
        let golden = 360.0 * (1.0 - 2.0 / (1.0 + 5f64.sqrt()));
        assert!(((trace - 1.0) / 2.0 - golden.to_radians().cos()).abs() < 1.0e-8);
        // No power comes back to the identity; the nearest returns are at Fibonacci
        // numbers of octaves (13: 12.4 degrees off, 21: 7.7, 34: 4.7).
        let mut power = ROTATION;
        for k in 2..=64 {
            power = matrix_product(power, ROTATION);
            let trace: f64 = power[0][0] + power[1][1] + power[2][2];
            let angle = ((trace - 1.0) / 2.0).clamp(-1.0, 1.0).acos().to_degrees();
            let bound = if k < 21 {
                12.0
            } else if k < 34 {
                7.5
            } else {
                2.5
            };
            assert!(angle > bound, "R^{k} turns by only {angle} degrees");
        }
    }

    #[test]
    fn the_octave_rotation_keeps_lengths_and_stays_finite() {
        for p in [
            [0.3, -1.2, 7.0],
            [1.0e7, -1.0e7, 3.0],
            [3.0e38, 3.0e38, 3.0e38],
        ] {
            let narrow = octave_rotate::<f32>(p.map(|x| x as f32));
            assert!(narrow.iter().all(|x| x.is_finite()), "{p:?}");
            if p[0] < 1.0e30 {
                let q = octave_rotate::<f64>(p);
                assert!((length(q, 3) / length(p, 3) - 1.0).abs() < 1.0e-9);
            }
        }
    }

    #[test]
    fn one_octave_is_the_unrotated_fractal() {
        for mode in [
            FractalMode::Fbm,
            FractalMode::Turbulence,
            FractalMode::FractalSum,
        ] {
            for p in [[0.3, -1.2, 7.0], [11.5, 0.25, -3.75]] {
                let params = [2.0, 0.5, 0.8];
                let rotated =
                    fractal_rotated::<f64>(mode, Basis::Gradient, p, 1, params, true, 1.0e9);
                let plain = fractal::<f64>(mode, Basis::Gradient, p, 1, params, true, 1.0e9, None);
                assert_eq!(rotated, plain);
            }
        }
    }

    #[test]
    fn rotated_fractals_stay_in_range_are_continuous_and_finite() {
        for basis in Basis::ALL {
            for mode in [
                FractalMode::Fbm,
                FractalMode::Turbulence,
                FractalMode::FractalSum,
            ] {
                let range = match mode {
                    FractalMode::Fbm | FractalMode::Turbulence => 0.0..=1.0,
                    FractalMode::FractalSum => -1.0..=1.0,
                };
                let at = |p: [f64; 3]| {
                    fractal_rotated::<f64>(mode, basis, p, 6, [2.0, 0.5, 1.0], true, 1.0e9)
                };
                let mut previous = at([-3.0, 0.3, 0.7]);
                for k in 0..2000 {
                    let t = k as f64 * 0.002;
                    let v = at([t - 3.0, 0.3 + 0.5 * t, 0.7 - t]);
                    assert!(range.contains(&v), "{mode:?} {basis:?}: {v}");
                    assert!(
                        (v - previous).abs() < 0.1,
                        "{mode:?} {basis:?} jumps at {t}"
                    );
                    previous = v;
                }
                for x in [1.0e5, -1.0e7, 1.0e20] {
                    let p = [x, -x, 0.5 * x].map(|v| v as f32);
                    let v = fractal_rotated::<f32>(mode, basis, p, 6, [2.0, 0.5, 1.0], true, 1.0e9);
                    assert!(v.is_finite(), "{mode:?} {basis:?} at {x}");
                }
            }
        }
    }

    #[test]
    fn cut_off_octaves_count_as_their_mean() {
        let p = [0.3, -1.2, 7.0];
        let params = [2.0, 0.5, 1.0];
        let full =
            fractal_rotated::<f64>(FractalMode::Fbm, Basis::Simplex, p, 3, params, false, 1.0e9);
        let cut =
            fractal_rotated::<f64>(FractalMode::Fbm, Basis::Simplex, p, 5, params, false, 3.0);
        assert!((cut - (full + 0.5 * (0.125 + 0.0625))).abs() < 1.0e-12);
    }
}
