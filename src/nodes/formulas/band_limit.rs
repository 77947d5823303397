//! Band-limited profiles, formula for formula as in shaders/band_limit.wgsl: periodic and
//! thresholding patterns box-filtered analytically over a footprint, periodic ones fading
//! to their mean past Nyquist. The CPU evaluator draws patterns in full (it has no pixel
//! footprint); the tiles' coverage shares the fade, and the tests check the WGSL
//! functions against these twins and the twins against numerical box filters.

use super::real::Real;
#[cfg(test)]
use super::shapes::smoothstep;

/// `veneer_nyquist_fade`: how much of a periodic pattern's variation a box `width`
/// periods wide keeps on top of the box filter itself (1 up to half a period, 0 from a
/// whole one on).
pub fn nyquist_fade<R: Real>(width: R) -> R {
    let t = ((width - R::c(0.5)) / R::c(0.5)).clamp(R::c(0.0), R::c(1.0));
    R::c(1.0) - t * t * (R::c(3.0) - R::c(2.0) * t)
}

/// `veneer_band_limited_sine`: 0.5 + 0.5 sin(phase) over `width` radians (the box's
/// sin(w/2)/(w/2) by its Taylor series to the 12th power).
#[cfg(test)]
pub fn band_limited_sine<R: Real>(phase: R, width: R) -> R {
    let half = R::c(0.5) * width.abs().min(R::c(std::f64::consts::TAU));
    let h2 = half * half;
    let sinc = [156.0, 110.0, 72.0, 42.0, 20.0, 6.0]
        .iter()
        .fold(R::c(1.0), |inner, &d| R::c(1.0) - h2 / R::c(d) * inner);
    R::c(0.5) + R::c(0.5) * phase.sin() * sinc * nyquist_fade(half / R::c(std::f64::consts::PI))
}

/// `veneer_corner_rounding`: (h − d)² / (2h) while a corner at `d` is inside a box of
/// half-width `h`, else 0.
#[cfg(test)]
fn corner_rounding<R: Real>(h: R, d: R) -> R {
    if d >= h {
        R::c(0.0)
    } else {
        (h - d) * (h - d) / (R::c(2.0) * h)
    }
}

/// `veneer_band_limited_triangle`: the triangle wave of `t` over `width` units.
#[cfg(test)]
pub fn band_limited_triangle<R: Real>(t: R, width: R) -> R {
    let (one, two) = (R::c(1.0), R::c(2.0));
    let u = t.fract();
    let h = R::c(0.5) * width.abs().min(one);
    let troughs = corner_rounding(h, u) + corner_rounding(h, one - u);
    let peak = corner_rounding(h, (u - R::c(0.5)).abs());
    let value = two * u.min(one - u) + two * (troughs - peak);
    R::mix(R::c(0.5), value, nyquist_fade(two * h))
}

/// `veneer_band_limited_floor`: floor(u) over `width` units.
#[cfg(test)]
pub fn band_limited_floor<R: Real>(u: R, width: R) -> R {
    let (zero, one) = (R::c(0.0), R::c(1.0));
    let h = R::c(0.5) * width.abs().min(one);
    let whole = u.floor();
    let f = u - whole;
    let shares = if h <= zero {
        zero
    } else {
        ((f + h - one).max(zero) - (h - f).max(zero)) / (R::c(2.0) * h)
    };
    R::mix(u - R::c(0.5), whole + shares, nyquist_fade(R::c(2.0) * h))
}

/// `veneer_band_limited_rising_smoothstep`: smoothstep rising from `edge0` to `edge1`
/// (or a step where they are equal) over `width` around `x`.
#[cfg(test)]
fn band_limited_rising_smoothstep<R: Real>(edge0: R, edge1: R, x: R, width: R) -> R {
    if width > R::c(0.0) {
        box_filtered_rising_smoothstep(edge0, edge1, x, width)
    } else {
        smoothstep(edge0, edge1, x)
    }
}

/// The rising smoothstep's box filter for `width` > 0.
#[cfg(test)]
fn box_filtered_rising_smoothstep<R: Real>(edge0: R, edge1: R, x: R, width: R) -> R {
    let (zero, one, half) = (R::c(0.0), R::c(1.0), R::c(0.5));
    let h = half * width;
    let (low, high) = (x - h, x + h);
    let below = ((edge0 - low) / width).clamp(zero, one);
    let above = ((high - edge1) / width).clamp(zero, one);
    let on = (one - below - above).max(zero);
    let (from, to) = (low.max(edge0), high.min(edge1));
    let half_span = half * edge1 - half * edge0;
    let (t, r) = if half_span <= zero {
        (zero, zero)
    } else {
        let middle = half * from + half * to;
        (
            ((half * middle - half * edge0) / half_span).clamp(zero, one),
            (half * to - half * from).max(zero) / (R::c(2.0) * half_span),
        )
    };
    let mean_on = t * t * (R::c(3.0) - R::c(2.0) * t) + (one - R::c(2.0) * t) * r * r;
    on * mean_on + above
}

/// `veneer_band_limited_smoothstep`: the safe smoothstep over `width` around `x`.
#[cfg(test)]
pub fn band_limited_smoothstep<R: Real>(edge0: R, edge1: R, x: R, width: R) -> R {
    if edge0 > edge1 {
        R::c(1.0) - band_limited_rising_smoothstep(edge1, edge0, x, width)
    } else {
        band_limited_rising_smoothstep(edge0, edge1, x, width)
    }
}

/// `veneer_band_limited_step`: step(edge, x) over `width` around `x`.
#[cfg(test)]
pub fn band_limited_step<R: Real>(edge: R, x: R, width: R) -> R {
    if width <= R::c(0.0) {
        R::step(edge, x)
    } else {
        ((x - edge) / width.max(R::c(1.0e-30)) + R::c(0.5)).clamp(R::c(0.0), R::c(1.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nodes::formulas::shapes::triangle_wave;

    /// The mean of `f` over [x − width/2, x + width/2] by the midpoint rule.
    fn box_mean(f: impl Fn(f64) -> f64, x: f64, width: f64) -> f64 {
        let n = 20_000;
        (0..n)
            .map(|k| f(x - 0.5 * width + (k as f64 + 0.5) / n as f64 * width))
            .sum::<f64>()
            / n as f64
    }

    fn sine(phase: f64) -> f64 {
        0.5 + 0.5 * phase.sin()
    }

    /// Points spread over several periods, on corners and off them.
    fn points() -> Vec<f64> {
        let mut points: Vec<f64> = (0..400).map(|k| -3.7 + k as f64 * 0.0371).collect();
        points.extend([0.0, 0.5, 1.0, 0.25, 0.75, -1.0, 2.5, 1.0e6 + 0.3]);
        points
    }

    #[test]
    fn a_footprint_of_zero_or_almost_zero_gives_the_pattern() {
        for x in points() {
            for width in [0.0, 1.0e-7] {
                let close = |a: f64, b: f64, what: &str| {
                    assert!(
                        (a - b).abs() <= 1.0e-6,
                        "{what} at {x}, width {width}: {a} vs {b}"
                    )
                };
                close(band_limited_sine(x, width), sine(x), "sine");
                close(
                    band_limited_triangle(x, width),
                    triangle_wave(x, 1.0),
                    "triangle",
                );
                if width == 0.0 || (x - x.round()).abs() > 1.0e-6 {
                    close(band_limited_floor(x, width), x.floor(), "floor");
                }
                for (e0, e1) in [(0.2, 0.9), (0.9, 0.2), (0.4, 0.4), (-3.0, 3.0)] {
                    if width == 0.0 || (x - e0).abs() > 1.0e-6 {
                        close(
                            band_limited_smoothstep(e0, e1, x, width),
                            smoothstep(e0, e1, x),
                            "smoothstep",
                        );
                    }
                }
                if width == 0.0 || (x - 0.3).abs() > 1.0e-6 {
                    close(band_limited_step(0.3, x, width), f64::step(0.3, x), "step");
                }
            }
        }
    }

    #[test]
    fn from_a_whole_period_on_the_periodic_ones_hold_their_mean() {
        for x in points().into_iter().take(400) {
            for periods in [1.0, 1.3, 2.0, 7.5, 1.0e4] {
                assert_eq!(band_limited_sine(x, periods * std::f64::consts::TAU), 0.5);
                assert_eq!(band_limited_triangle(x, periods), 0.5);
                assert!((band_limited_floor(x, periods) - (x - 0.5)).abs() < 1.0e-12);
            }
        }
    }

    #[test]
    fn below_nyquist_they_are_the_box_filtered_pattern() {
        for x in points().into_iter().take(400).step_by(7) {
            for fraction in [0.01, 0.1, 0.25, 0.37, 0.5] {
                // The floor's jumps cost the midpoint rule up to 1/20,000.
                let close = |a: f64, b: f64, what: &str| {
                    let tolerance = if what == "floor" { 1.0e-4 } else { 2.0e-6 };
                    assert!(
                        (a - b).abs() <= tolerance,
                        "{what} at {x}, {fraction}: {a} vs {b}"
                    )
                };
                let radians = fraction * std::f64::consts::TAU;
                close(
                    band_limited_sine(x, radians),
                    box_mean(sine, x, radians),
                    "sine",
                );
                close(
                    band_limited_triangle(x, fraction),
                    box_mean(|t| triangle_wave(t, 1.0), x, fraction),
                    "triangle",
                );
                close(
                    band_limited_floor(x, fraction),
                    box_mean(f64::floor, x, fraction),
                    "floor",
                );
            }
            // Thresholds are not periodic: any width is filtered exactly.
            for width in [0.01, 0.3, 1.0, 4.0] {
                for (e0, e1) in [(0.2, 0.9), (0.9, 0.2), (0.4, 0.4), (-3.0, 3.0)] {
                    assert!(
                        (band_limited_smoothstep(e0, e1, x, width)
                            - box_mean(|v| smoothstep(e0, e1, v), x, width))
                        .abs()
                            <= 1.0e-4,
                        "smoothstep({e0}, {e1}) at {x}, width {width}"
                    );
                }
                let stepped = box_mean(|v| f64::step(0.3, v), x, width);
                assert!((band_limited_step(0.3, x, width) - stepped).abs() <= 1.0e-4);
            }
        }
    }

    #[test]
    fn the_fade_keeps_everything_to_nyquist_and_nothing_from_a_period_on() {
        assert_eq!(nyquist_fade(0.0f64), 1.0);
        assert_eq!(nyquist_fade(0.5f64), 1.0);
        assert_eq!(nyquist_fade(1.0f64), 0.0);
        assert_eq!(nyquist_fade(3.0f64), 0.0);
        assert!((nyquist_fade(0.75f64) - 0.5).abs() < 1.0e-12);
    }
}
