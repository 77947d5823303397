//! Map Range and the histogram scan, formula for formula as in shaders/map_range.wgsl.

// The node kind that uses these arrives through the node registry.

use super::real::{Real, finite};

/// `veneer_map_range_factor`: (x - from_min) / (from_max - from_min) without overflow; 0
/// for an empty range.
pub fn map_range_factor<R: Real>(x: R, from_min: R, from_max: R) -> R {
    let half = R::c(0.5);
    let span = half * from_max - half * from_min;
    if span == R::c(0.0) {
        R::c(0.0)
    } else {
        finite((half * x - half * from_min) / span)
    }
}

/// `veneer_map_range_to`: to_min + t (to_max - to_min), optionally clamped to the target.
pub fn map_range_to<R: Real>(t: R, to_min: R, to_max: R, clamp_result: bool) -> R {
    let half = R::c(0.5);
    let y = finite(to_min + t * (half * to_max - half * to_min) * R::c(2.0));
    if clamp_result {
        y.clamp(to_min.min(to_max), to_min.max(to_max))
    } else {
        y
    }
}

/// `veneer_map_range_linear`.
pub fn map_range_linear<R: Real>(
    x: R,
    from_min: R,
    from_max: R,
    to_min: R,
    to_max: R,
    clamp_result: bool,
) -> R {
    map_range_to(
        map_range_factor(x, from_min, from_max),
        to_min,
        to_max,
        clamp_result,
    )
}

/// `veneer_map_range_stepped`: Blender's floor(t (steps + 1)) / steps; to_min for steps <= 0.
pub fn map_range_stepped<R: Real>(
    x: R,
    from_min: R,
    from_max: R,
    to_min: R,
    to_max: R,
    steps: R,
    clamp_result: bool,
) -> R {
    let t = map_range_factor(x, from_min, from_max);
    let levels = if steps > R::c(0.0) {
        finite((t * (steps + R::c(1.0))).floor() / steps.max(R::c(1.0e-30)))
    } else {
        R::c(0.0)
    };
    map_range_to(levels, to_min, to_max, clamp_result)
}

/// `veneer_map_range_smooth`: through 3t² - 2t³, t clamped to [0, 1].
pub fn map_range_smooth<R: Real>(x: R, from_min: R, from_max: R, to_min: R, to_max: R) -> R {
    let t = map_range_factor(x, from_min, from_max).clamp(R::c(0.0), R::c(1.0));
    map_range_to(t * t * (R::c(3.0) - R::c(2.0) * t), to_min, to_max, false)
}

/// `veneer_map_range_smoother`: through 6t⁵ - 15t⁴ + 10t³, t clamped to [0, 1].
pub fn map_range_smoother<R: Real>(x: R, from_min: R, from_max: R, to_min: R, to_max: R) -> R {
    let t = map_range_factor(x, from_min, from_max).clamp(R::c(0.0), R::c(1.0));
    let fade = t * t * t * (t * (t * R::c(6.0) - R::c(15.0)) + R::c(10.0));
    map_range_to(fade, to_min, to_max, false)
}

#[cfg(test)]
mod tests {
    use super::*;

    const EXTREMES: [f64; 9] = [
        -3.4e38, -1.0e20, -1.0, -1.0e-40, 0.0, 1.0e-40, 0.5, 1.0e20, 3.4e38,
    ];

    fn xs() -> impl Iterator<Item = f64> {
        (0..=400).map(|k| -1.0 + f64::from(k) * 0.0075)
    }

    #[test]
    fn the_unit_range_onto_itself_is_the_identity() {
        for x in xs() {
            assert_eq!(map_range_linear(x, 0.0, 1.0, 0.0, 1.0, false), x);
            let narrow = map_range_linear(x as f32, 0.0, 1.0, 0.0, 1.0, false);
            assert_eq!(narrow, x as f32);
            assert_eq!(
                map_range_linear(x, 0.0, 1.0, 0.0, 1.0, true),
                x.clamp(0.0, 1.0)
            );
        }
    }

    #[test]
    fn linear_maps_between_any_ranges() {
        assert_eq!(map_range_linear(5.0, 0.0, 10.0, 100.0, 200.0, false), 150.0);
        assert_eq!(
            map_range_linear(15.0, 0.0, 10.0, 100.0, 200.0, false),
            250.0
        );
        assert_eq!(map_range_linear(15.0, 0.0, 10.0, 100.0, 200.0, true), 200.0);
        assert_eq!(map_range_linear(-5.0, 0.0, 10.0, 200.0, 100.0, true), 200.0);
        assert_eq!(map_range_linear(2.5, 10.0, 0.0, 0.0, 1.0, false), 0.75);
        // An empty source range maps everything to to_min.
        for mode in 0..4 {
            for x in [-1.0, 2.0, 2.0 + 1.0e-12, 9.0] {
                let y = match mode {
                    0 => map_range_linear(x, 2.0, 2.0, 3.0, 4.0, false),
                    1 => map_range_stepped(x, 2.0, 2.0, 3.0, 4.0, 4.0, false),
                    2 => map_range_smooth(x, 2.0, 2.0, 3.0, 4.0),
                    _ => map_range_smoother(x, 2.0, 2.0, 3.0, 4.0),
                };
                assert_eq!(y, 3.0);
            }
        }
    }

    #[test]
    fn stepped_follows_blender() {
        let at = |x: f64, steps: f64| map_range_stepped(x, 0.0, 1.0, 0.0, 1.0, steps, false);
        assert_eq!(at(0.1, 4.0), 0.0);
        assert_eq!(at(0.25, 4.0), 0.25);
        assert_eq!(at(0.59, 4.0), 0.5);
        assert_eq!(at(0.99, 4.0), 1.0);
        assert_eq!(at(1.0, 4.0), 1.25);
        assert_eq!(map_range_stepped(1.0, 0.0, 1.0, 0.0, 1.0, 4.0, true), 1.0);
        assert_eq!(at(0.7, 0.0), 0.0);
        assert_eq!(at(0.7, -2.0), 0.0);
        let levels: std::collections::BTreeSet<u64> = xs()
            .filter(|x| (0.0..1.0).contains(x))
            .map(|x| at(x, 3.0).to_bits())
            .collect();
        assert_eq!(levels.len(), 4);
    }

    #[test]
    fn smooth_modes_are_monotone_continuous_and_in_range() {
        type Map = fn(f64, f64, f64, f64, f64) -> f64;
        for map in [map_range_smooth as Map, map_range_smoother as Map] {
            for (from, to) in [((-0.5, 1.5), (2.0, 6.0)), ((1.5, -0.5), (6.0, 2.0))] {
                let mut previous = map(-1.0, from.0, from.1, to.0, to.1);
                for x in xs() {
                    let y = map(x, from.0, from.1, to.0, to.1);
                    assert!((2.0..=6.0).contains(&y), "{x}: {y}");
                    let rising = (from.1 - from.0) * (to.1 - to.0) > 0.0;
                    assert!(if rising { y >= previous } else { y <= previous });
                    assert!((y - previous).abs() < 0.05);
                    previous = y;
                }
                assert_eq!(map(from.0, from.0, from.1, to.0, to.1), to.0);
                assert_eq!(map(from.1, from.0, from.1, to.0, to.1), to.1);
            }
            // Reversed source range: the same curve as Blender's 1 - smoothstep(max, min).
            let x = 0.3;
            let forward = map(x, 0.0, 1.0, 0.0, 1.0);
            let reversed = map(1.0 - x, 1.0, 0.0, 0.0, 1.0);
            assert!((forward - reversed).abs() < 1.0e-12);
        }
        assert_eq!(map_range_smooth(0.5, 0.0, 1.0, 0.0, 1.0), 0.5);
        assert_eq!(map_range_smoother(0.5, 0.0, 1.0, 0.0, 1.0), 0.5);
        assert!((map_range_smooth(0.25, 0.0, 1.0, 0.0, 1.0) - 0.15625).abs() < 1.0e-15);
        assert!((map_range_smoother(0.25, 0.0, 1.0, 0.0, 1.0) - 0.103515625).abs() < 1.0e-15);
    }

    #[test]
    fn every_mode_is_finite_for_any_finite_input() {
        for &x in &EXTREMES {
            for &a in &EXTREMES {
                for &b in &EXTREMES {
                    for &c in &EXTREMES {
                        let [x, a, b, c] = [x, a, b, c].map(|v| v as f32);
                        let results = [
                            map_range_linear(x, a, b, c, -c, false),
                            map_range_linear(x, a, b, c, 1.0, true),
                            map_range_linear(a, x, 0.0, b, c, false),
                            map_range_stepped(x, a, b, c, 0.0, x, false),
                            map_range_stepped(x, a, b, 0.0, c, c, true),
                            map_range_stepped(x, a, 1.0, b, c, 3.0, false),
                            map_range_smooth(x, a, b, c, -c),
                            map_range_smoother(x, a, b, -c, c),
                        ];
                        for (i, y) in results.iter().enumerate() {
                            assert!(y.is_finite(), "case {i} at {x} {a} {b} {c}: {y}");
                        }
                    }
                }
            }
        }
    }
}

/// `veneer_histogram_scan`: a ramp 1 − contrast wide sweeping [0, 1] as `position` goes
/// from 0 (all black) to 1 (all white).
pub fn histogram_scan<R: Real>(value: R, position: R, contrast: R) -> R {
    let width = (R::c(1.0) - contrast.clamp(R::c(0.0), R::c(1.0))).max(R::c(1e-6));
    let low = R::mix(R::c(1.0), -width, position.clamp(R::c(0.0), R::c(1.0)));
    ((value - low) / width).clamp(R::c(0.0), R::c(1.0))
}
