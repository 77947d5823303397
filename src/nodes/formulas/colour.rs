//! Colour adjustments and blend modes, formula for formula as in shaders/colour.wgsl.

// The node kinds that use these arrive through the node registry.

use super::real::{Real, V3, finite, map, zip};
use super::shapes::safe_pow;

/// `veneer_colour_mix`: `a (1 - t) + b t`, t clamped to [0, 1], the result to the finite range.
pub fn colour_mix<R: Real>(a: V3<R>, b: V3<R>, t: R) -> V3<R> {
    let s = t.clamp(R::c(0.0), R::c(1.0));
    zip(a, b, |a, b| finite(a * (R::c(1.0) - s) + b * s))
}

/// `veneer_rgb_to_hsv`: (hue in turns, saturation, value) as Blender's rgb_to_hsv.
pub fn rgb_to_hsv<R: Real>(c: V3<R>) -> V3<R> {
    let (zero, one, half) = (R::c(0.0), R::c(1.0), R::c(0.5));
    let cmax = c[0].max(c[1].max(c[2]));
    let cmin = c[0].min(c[1].min(c[2]));
    let s = if cmax <= zero {
        zero
    } else if cmin > zero {
        (cmax - cmin) / cmax
    } else {
        one
    };
    let span = half * cmax - half * cmin;
    if s == zero || span == zero {
        return [zero, s, cmax];
    }
    let d = map(c, |x| (half * cmax - half * x) / span);
    let sector = if c[0] == cmax {
        d[2] - d[1]
    } else if c[1] == cmax {
        R::c(2.0) + d[0] - d[2]
    } else {
        R::c(4.0) + d[1] - d[0]
    } / R::c(6.0);
    let h = if sector < zero { sector + one } else { sector };
    [h, s, cmax]
}

/// `veneer_hsv_to_rgb`: Blender's hsv_to_rgb with the hue wrapped and the saturation
/// clamped to [0, 1].
pub fn hsv_to_rgb<R: Real>(hsv: V3<R>) -> V3<R> {
    let one = R::c(1.0);
    let turn = hsv[0].fract();
    let h = if turn >= one { R::c(0.0) } else { turn } * R::c(6.0);
    let s = hsv[1].clamp(R::c(0.0), one);
    let v = hsv[2];
    let i = h.floor().min(R::c(5.0));
    let f = h - i;
    let p = v * (one - s);
    let q = v * (one - s * f);
    let t = v * (one - s * (one - f));
    match i.to_f64() as i32 {
        0 => [v, t, p],
        1 => [q, v, p],
        2 => [p, v, t],
        3 => [p, q, v],
        4 => [t, p, v],
        _ => [v, p, q],
    }
}

/// `veneer_hue_saturation_value`: Blender's Hue/Saturation/Value at factor 1, the hue
/// shifted by `hue_shift` turns (0: unchanged).
pub fn hue_saturation_value<R: Real>(c: V3<R>, hue_shift: R, saturation: R, value: R) -> V3<R> {
    let hsv = rgb_to_hsv(c);
    let h = (hsv[0] + hue_shift.fract()).fract();
    let s = (hsv[1] * saturation).clamp(R::c(0.0), R::c(1.0));
    let v = finite(hsv[2] * value);
    hsv_to_rgb([h, s, v])
}

/// `veneer_hue_saturation_value_mix`: the adjusted colour blended over `c` by `factor`.
pub fn hue_saturation_value_mix<R: Real>(
    c: V3<R>,
    hue_shift: R,
    saturation: R,
    value: R,
    factor: R,
) -> V3<R> {
    colour_mix(
        c,
        hue_saturation_value(c, hue_shift, saturation, value),
        factor,
    )
}

/// `veneer_brightness_contrast`: Blender's max((1 + contrast) c + brightness - contrast / 2, 0).
pub fn brightness_contrast<R: Real>(c: V3<R>, brightness: R, contrast: R) -> V3<R> {
    let limit = R::c(1.0e18);
    let k = contrast.clamp(-limit, limit);
    map(c, |x| {
        let x = x.clamp(-limit, limit);
        ((R::c(1.0) + k) * x + (brightness - R::c(0.5) * k))
            .max(R::c(0.0))
            .min(R::c(3.0e38))
    })
}

/// `veneer_gamma`: c^gamma for positive channels, others unchanged.
pub fn gamma<R: Real>(c: V3<R>, gamma: R) -> V3<R> {
    map(c, |x| if x > R::c(0.0) { safe_pow(x, gamma) } else { x })
}

/// `veneer_invert`: c blended towards 1 - c by `factor` (clamped to [0, 1]).
pub fn invert<R: Real>(c: V3<R>, factor: R) -> V3<R> {
    colour_mix(c, map(c, |x| R::c(1.0) - x), factor)
}

/// `veneer_levels`: Photoshop/Substance levels.
pub fn levels<R: Real>(
    c: V3<R>,
    in_black: R,
    in_white: R,
    gamma: R,
    out_black: R,
    out_white: R,
) -> V3<R> {
    let (zero, one, half) = (R::c(0.0), R::c(1.0), R::c(0.5));
    let span = half * in_white - half * in_black;
    let g = gamma.clamp(R::c(1.0e-4), R::c(1.0e4));
    map(c, |x| {
        let t = if span == zero {
            R::step(in_black, x)
        } else {
            ((half * x - half * in_black) / span).clamp(zero, one)
        };
        let curved = if g == one { t } else { safe_pow(t, one / g) };
        finite(out_black * (one - curved) + out_white * curved)
    })
}

/// `veneer_blend_multiply`: a * b blended over a by `factor`.
pub fn blend_multiply<R: Real>(a: V3<R>, b: V3<R>, factor: R) -> V3<R> {
    colour_mix(a, zip(a, b, |a, b| finite(a * b)), factor)
}

/// `veneer_blend_screen`: 1 - (1 - a)(1 - b) blended over a by `factor`.
pub fn blend_screen<R: Real>(a: V3<R>, b: V3<R>, factor: R) -> V3<R> {
    let one = R::c(1.0);
    colour_mix(
        a,
        zip(a, b, |a, b| finite(one - (one - a) * (one - b))),
        factor,
    )
}

/// `veneer_blend_overlay`: 2ab where a < 0.5, else 1 - 2(1 - a)(1 - b), blended over a.
pub fn blend_overlay<R: Real>(a: V3<R>, b: V3<R>, factor: R) -> V3<R> {
    let (one, two) = (R::c(1.0), R::c(2.0));
    let overlay = zip(a, b, |a, b| {
        finite(if a < R::c(0.5) {
            two * (a * b)
        } else {
            one - two * ((one - a) * (one - b))
        })
    });
    colour_mix(a, overlay, factor)
}

/// `veneer_blend_soft_light`: Blender's soft light, Pegtop's (1 - 2b) a² + 2ab, blended over a.
pub fn blend_soft_light<R: Real>(a: V3<R>, b: V3<R>, factor: R) -> V3<R> {
    let limit = R::c(1.0e12);
    let soft = zip(a, b, |a, b| {
        let (x, y) = (a.clamp(-limit, limit), b.clamp(-limit, limit));
        (R::c(1.0) - R::c(2.0) * y) * x * x + R::c(2.0) * x * y
    });
    colour_mix(a, soft, factor)
}

/// `veneer_blend_difference`: |a - b| blended over a by `factor`.
pub fn blend_difference<R: Real>(a: V3<R>, b: V3<R>, factor: R) -> V3<R> {
    colour_mix(a, zip(a, b, |a, b| (a - b).abs().min(R::c(3.0e38))), factor)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: [f64; 3], b: [f64; 3], tolerance: f64) -> bool {
        (0..3).all(|k| (a[k] - b[k]).abs() <= tolerance)
    }

    /// Colours on a 9³ grid over [0, 1]³.
    fn grid() -> impl Iterator<Item = [f64; 3]> {
        (0..729).map(|k| [k % 9, (k / 9) % 9, k / 81].map(|i| f64::from(i) / 8.0))
    }

    const EXTREMES: [f64; 11] = [
        -3.4e38, -1.0e20, -1.0, -1.0e-40, 0.0, 1.0e-40, 0.5, 1.0, 2.0, 1.0e20, 3.4e38,
    ];

    #[test]
    fn hsv_of_known_colours() {
        for (rgb, hsv) in [
            ([1.0, 0.0, 0.0], [0.0, 1.0, 1.0]),
            ([0.0, 1.0, 0.0], [1.0 / 3.0, 1.0, 1.0]),
            ([0.0, 0.0, 1.0], [2.0 / 3.0, 1.0, 1.0]),
            ([1.0, 1.0, 0.0], [1.0 / 6.0, 1.0, 1.0]),
            ([1.0, 0.0, 1.0], [5.0 / 6.0, 1.0, 1.0]),
            ([0.5, 0.25, 0.25], [0.0, 0.5, 0.5]),
            ([0.5, 0.5, 0.5], [0.0, 0.0, 0.5]),
            ([0.0, 0.0, 0.0], [0.0, 0.0, 0.0]),
            ([-0.5, -0.2, -0.9], [0.0, 0.0, -0.2]),
        ] {
            assert!(
                close(rgb_to_hsv(rgb), hsv, 1.0e-12),
                "{rgb:?}: {:?}",
                rgb_to_hsv(rgb)
            );
            if hsv[2] >= 0.0 {
                assert!(close(hsv_to_rgb(hsv), rgb, 1.0e-12), "{hsv:?}");
            }
        }
    }

    #[test]
    fn rgb_to_hsv_and_back_is_the_identity() {
        for c in grid() {
            let hsv = rgb_to_hsv::<f64>(c);
            assert!((0.0..=1.0).contains(&hsv[0]) && (0.0..=1.0).contains(&hsv[1]));
            assert!(close(hsv_to_rgb(hsv), c, 1.0e-12), "{c:?}");
            let narrow = hsv_to_rgb(rgb_to_hsv::<f32>(c.map(|x| x as f32)));
            assert!(close(narrow.map(f64::from), c, 1.0e-6), "{c:?}");
            let same = hue_saturation_value::<f64>(c, 0.0, 1.0, 1.0);
            assert!(close(same, c, 1.0e-12), "{c:?}");
        }
    }

    #[test]
    fn hue_wraps_and_is_continuous() {
        let red = hsv_to_rgb::<f64>([0.0, 1.0, 1.0]);
        for h in [1.0, -1.0, 7.0] {
            assert!(close(hsv_to_rgb([h, 1.0, 1.0]), red, 1.0e-12));
        }
        assert!(close(
            hsv_to_rgb([-0.25, 1.0, 1.0]),
            hsv_to_rgb([0.75, 1.0, 1.0]),
            1.0e-12
        ));
        let mut previous = hsv_to_rgb::<f32>([-2.0, 0.8, 0.9]);
        for k in 1..=4000 {
            let c = hsv_to_rgb::<f32>([-2.0 + k as f32 * 0.001, 0.8, 0.9]);
            assert!((0..3).all(|i| (c[i] - previous[i]).abs() < 0.01), "at {k}");
            previous = c;
        }
        // Just below a whole turn, f32 fract gives 1: still red.
        assert!(close(
            hsv_to_rgb::<f32>([-1.0e-9, 1.0, 1.0]).map(f64::from),
            red,
            1.0e-6
        ));
    }

    #[test]
    fn hue_saturation_value_turns_desaturates_and_scales() {
        let red = [1.0, 0.0, 0.0];
        assert!(close(
            hue_saturation_value(red, 1.0 / 3.0, 1.0, 1.0),
            [0.0, 1.0, 0.0],
            1.0e-12
        ));
        assert!(close(
            hue_saturation_value(red, -1.0 / 3.0, 1.0, 1.0),
            [0.0, 0.0, 1.0],
            1.0e-12
        ));
        let c = [0.8, 0.4, 0.2];
        assert!(close(
            hue_saturation_value(c, 0.3, 0.0, 1.0),
            [0.8; 3],
            1.0e-12
        ));
        assert!(close(
            hue_saturation_value(c, 0.0, 1.0, 0.5),
            [0.4, 0.2, 0.1],
            1.0e-12
        ));
        // Saturation clamps at 1: fully saturated stays fully saturated.
        assert!(close(
            hue_saturation_value(red, 0.0, 3.0, 1.0),
            red,
            1.0e-12
        ));
    }

    #[test]
    fn brightness_contrast_gamma_and_invert_follow_blender() {
        let c = [0.25, 0.5, 1.0];
        assert_eq!(brightness_contrast(c, 0.0, 0.0), c);
        assert_eq!(
            brightness_contrast([-0.5, 0.0, 0.5], 0.0, 0.0),
            [0.0, 0.0, 0.5]
        );
        assert_eq!(brightness_contrast(c, 0.0, 1.0), [0.0, 0.5, 1.5]);
        assert_eq!(brightness_contrast(c, 0.25, 0.0), [0.5, 0.75, 1.25]);
        assert_eq!(gamma(c, 1.0), c);
        assert_eq!(gamma([0.5, 0.0, -2.0], 2.0), [0.25, 0.0, -2.0]);
        assert_eq!(gamma([0.5, 4.0, 1.0], 0.0), [1.0; 3]);
        assert!(close(
            gamma([0.25, 4.0, 1.0], -0.5),
            [2.0, 0.5, 1.0],
            1.0e-12
        ));
        assert_eq!(invert(c, 1.0), [0.75, 0.5, 0.0]);
        assert_eq!(invert(c, 0.0), c);
        assert_eq!(invert(c, 0.5), [0.5; 3]);
        assert_eq!(invert(c, 7.0), invert(c, 1.0));
    }

    #[test]
    fn levels_identity_steps_and_curves() {
        for c in grid() {
            assert_eq!(levels(c, 0.0, 1.0, 1.0, 0.0, 1.0), c);
            assert_eq!(
                levels::<f32>(c.map(|x| x as f32), 0.0, 1.0, 1.0, 0.0, 1.0),
                c.map(|x| x as f32)
            );
        }
        assert_eq!(
            levels([-0.5, 1.5, 0.5], 0.0, 1.0, 1.0, 0.0, 1.0),
            [0.0, 1.0, 0.5]
        );
        assert_eq!(
            levels([0.2, 0.3, 0.4], 0.3, 0.3, 1.0, 0.0, 1.0),
            [0.0, 1.0, 1.0]
        );
        assert!(close(
            levels([0.25, 0.5, 0.75], 0.0, 1.0, 2.0, 0.0, 1.0),
            [0.5, 0.5f64.sqrt(), 0.75f64.sqrt()],
            1.0e-12
        ));
        assert!(close(
            levels([0.2, 0.6, 1.0], 0.2, 1.0, 1.0, 0.1, 0.5),
            [0.1, 0.3, 0.5],
            1.0e-12
        ));
        // Reversed input levels invert.
        assert!(close(
            levels([0.0, 0.25, 1.0], 1.0, 0.0, 1.0, 0.0, 1.0),
            [1.0, 0.75, 0.0],
            1.0e-12
        ));
    }

    #[test]
    fn blends_of_black_white_and_grey() {
        let (black, white, c) = ([0.0; 3], [1.0; 3], [0.2, 0.5, 0.9]);
        assert_eq!(blend_multiply(white, c, 1.0), c);
        assert_eq!(blend_multiply(c, black, 1.0), black);
        assert!(close(blend_screen(black, c, 1.0), c, 1.0e-12));
        assert_eq!(blend_screen(c, white, 1.0), white);
        assert_eq!(blend_difference(c, c, 1.0), black);
        assert_eq!(blend_difference(white, c, 1.0), invert(c, 1.0));
        assert!(close(blend_overlay(c, [0.5; 3], 1.0), c, 1.0e-12));
        assert_eq!(blend_overlay(black, c, 1.0), black);
        assert_eq!(blend_overlay(white, c, 1.0), white);
        assert!(close(blend_soft_light(c, [0.5; 3], 1.0), c, 1.0e-12));
        assert_eq!(blend_soft_light(black, c, 1.0), black);
        assert!(close(
            blend_soft_light(c, black, 1.0),
            c.map(|a| a * a),
            1.0e-12
        ));
        assert!(close(
            blend_soft_light(c, white, 1.0),
            c.map(|a| 2.0 * a - a * a),
            1.0e-12
        ));
        type Blend = fn(V3<f64>, V3<f64>, f64) -> V3<f64>;
        let blends: [Blend; 5] = [
            blend_multiply,
            blend_screen,
            blend_overlay,
            blend_soft_light,
            blend_difference,
        ];
        for blend in blends {
            assert_eq!(blend(c, white, 0.0), c);
            assert_eq!(blend(c, black, -3.0), c);
            assert!(close(
                blend(c, [0.7, 0.1, 0.4], 0.5),
                colour_mix(c, blend(c, [0.7, 0.1, 0.4], 1.0), 0.5),
                1.0e-12
            ));
            for a in grid() {
                for b in [black, white, [0.3, 0.6, 0.9]] {
                    let v = blend(a, b, 0.7);
                    assert!(
                        v.iter().all(|x| (0.0..=1.0 + 1.0e-12).contains(x)),
                        "{a:?} {b:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn every_colour_function_is_finite_for_any_finite_input() {
        let finite3 = |c: [f32; 3]| c.iter().all(|x| x.is_finite());
        for &x in &EXTREMES {
            for &y in &EXTREMES {
                for &z in &EXTREMES {
                    let c = [x, y, z].map(|v| v as f32);
                    let (k, m) = (x as f32, y as f32);
                    let results = [
                        rgb_to_hsv(c),
                        hsv_to_rgb(c),
                        hue_saturation_value(c, k, m, z as f32),
                        hue_saturation_value([z as f32, 0.5, 0.1], k, m, 3.0),
                        brightness_contrast(c, k, m),
                        brightness_contrast([z as f32; 3], k, m),
                        gamma(c, k),
                        invert(c, k),
                        levels(c, k, m, z as f32, k, m),
                        levels([0.5; 3], k, m, 1.0, z as f32, k),
                        blend_multiply(c, [k, m, 1.0], z as f32),
                        blend_screen(c, [k, m, 1.0], z as f32),
                        blend_overlay(c, [k, m, 1.0], z as f32),
                        blend_soft_light(c, [k, m, 1.0], z as f32),
                        blend_difference(c, [k, m, 1.0], z as f32),
                        blend_soft_light(c, [m, k, z as f32], 1.0),
                    ];
                    for (i, r) in results.iter().enumerate() {
                        assert!(finite3(*r), "function {i} at {x} {y} {z}: {r:?}");
                    }
                }
            }
        }
    }
}
