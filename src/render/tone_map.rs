//! Tone mappers for metallic-roughness previews (`shaders/tone_map.wgsl`): scene-linear
//! light to display-linear values in [0, 1]. The CPU twins here are what the tests hold
//! against the mappers' published values.

use glam::{Mat3, Vec3};

/// How a metallic-roughness preview maps scene light to the display.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum ToneMap {
    /// Clamped to [0, 1].
    None = 0,
    /// Khronos PBR Neutral: colours below 0.76 shown as they are, highlights rolled off
    /// keeping their hue (the default: base colours read true).
    #[default]
    PbrNeutral = 1,
    /// ACES, Stephen Hill's fit of the RRT and sRGB ODT.
    Aces = 2,
    /// AgX, minimal form (sixth-order contrast fit), base look.
    Agx = 3,
}

impl ToneMap {
    /// The display-linear value of scene-linear `colour` (clamped to [0, 1e9] first: light
    /// past 1e9 is white in every mapper, and no mapper overflows below it).
    pub fn apply(self, colour: Vec3) -> Vec3 {
        let c = colour.clamp(Vec3::ZERO, Vec3::splat(1.0e9));
        match self {
            ToneMap::None => c.min(Vec3::ONE),
            ToneMap::PbrNeutral => pbr_neutral(c),
            ToneMap::Aces => aces_fitted(c),
            ToneMap::Agx => agx(c),
        }
    }
}

fn pbr_neutral(colour: Vec3) -> Vec3 {
    const START_COMPRESSION: f32 = 0.8 - 0.04;
    const DESATURATION: f32 = 0.15;
    let x = colour.min_element();
    let offset = if x < 0.08 { x - 6.25 * x * x } else { 0.04 };
    let c = colour - Vec3::splat(offset);
    let peak = c.max_element();
    if peak < START_COMPRESSION {
        return c;
    }
    let d = 1.0 - START_COMPRESSION;
    let new_peak = 1.0 - d * d / (peak + d - START_COMPRESSION);
    let c = c * (new_peak / peak);
    let g = 1.0 - 1.0 / (DESATURATION * (peak - new_peak) + 1.0);
    c.lerp(Vec3::splat(new_peak), g)
}

// The published constants, verbatim.
#[allow(clippy::excessive_precision)]
fn aces_fitted(colour: Vec3) -> Vec3 {
    let input = Mat3::from_cols_array(&[
        0.59719, 0.35458, 0.04823, 0.07600, 0.90834, 0.01566, 0.02840, 0.13383, 0.83777,
    ])
    .transpose();
    let output = Mat3::from_cols_array(&[
        1.60475, -0.53108, -0.07367, -0.10208, 1.10813, -0.00605, -0.00327, -0.07276, 1.07602,
    ])
    .transpose();
    let v = input * colour;
    let fitted = (v * (v + 0.0245786) - 0.000090537) / (v * (0.983729 * v + 0.4329510) + 0.238081);
    (output * fitted).clamp(Vec3::ZERO, Vec3::ONE)
}

#[allow(clippy::excessive_precision)]
fn agx(colour: Vec3) -> Vec3 {
    let inset = Mat3::from_cols_array(&[
        0.842479062253094,
        0.0423282422610123,
        0.0423756549057051,
        0.0784335999999992,
        0.878468636469772,
        0.0784336,
        0.0792237451477643,
        0.0791661274605434,
        0.879142973793104,
    ]);
    let outset = Mat3::from_cols_array(&[
        1.19687900512017,
        -0.0528968517574562,
        -0.0529716355144438,
        -0.0980208811401368,
        1.15190312990417,
        -0.0980434501171241,
        -0.0990297440797205,
        -0.0989611768448433,
        1.15107367264116,
    ]);
    const MIN_EV: f32 = -12.47393;
    const MAX_EV: f32 = 4.026069;
    let v = inset * colour.max(Vec3::splat(1e-10));
    let v = v.to_array().map(|x| x.log2().clamp(MIN_EV, MAX_EV));
    let v = (Vec3::from(v) - MIN_EV) / (MAX_EV - MIN_EV);
    let curve = |x: f32| {
        let (x2, x4) = (x * x, x * x * x * x);
        15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2 + 0.1191 * x
            - 0.00232
    };
    let v = outset * Vec3::new(curve(v.x), curve(v.y), curve(v.z));
    v.clamp(Vec3::ZERO, Vec3::ONE).powf(2.2)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grey(tone_map: ToneMap, x: f32) -> f32 {
        tone_map.apply(Vec3::splat(x)).x
    }

    /// PBR Neutral by its specification (Khronos, "PBR Neutral", 2024): below the toe (0.08) it
    /// is 6.25x², then x − 0.04 up to 0.76, and white 1.0 rolls off to
    /// 1 − 0.24² / (0.96 + 0.24 − 0.76) = 0.869 09.
    #[test]
    fn pbr_neutral_keeps_base_colours_and_rolls_off_highlights() {
        assert!((grey(ToneMap::PbrNeutral, 0.04) - 6.25 * 0.0016).abs() < 1e-7);
        assert!((grey(ToneMap::PbrNeutral, 0.5) - 0.46).abs() < 1e-6);
        assert!((grey(ToneMap::PbrNeutral, 1.0) - 0.869_09).abs() < 1e-5);
        assert!(grey(ToneMap::PbrNeutral, 1e4) < 1.0);
        // A saturated highlight keeps its hue's order and desaturates towards white.
        let red = ToneMap::PbrNeutral.apply(Vec3::new(4.0, 1.0, 0.5));
        assert!(red.x > red.y && red.y > red.z && red.x < 1.0, "{red}");
    }

    /// ACES fitted: grey x goes through the fit's rational curve (the matrices keep grey
    /// grey: their rows sum to 1): 1.0 → 1.024 488 / 1.654 761 = 0.619 12; 0.18 → 0.1056.
    #[test]
    fn aces_fitted_follows_hill_s_curve() {
        assert!((grey(ToneMap::Aces, 1.0) - 0.619_12).abs() < 2e-4);
        let rrt = |v: f32| {
            (v * (v + 0.0245786) - 0.000090537) / (v * (0.983729 * v + 0.432951) + 0.238081)
        };
        assert!((grey(ToneMap::Aces, 0.18) - rrt(0.18)).abs() < 2e-4);
        assert!((grey(ToneMap::Aces, 0.18) - 0.1056).abs() < 1e-3);
        assert!(grey(ToneMap::Aces, 100.0) > 0.99);
    }

    /// AgX: 18% grey sits at the log encoding's 0.606 (10 stops above −12.47 of 16.5),
    /// where the contrast curve gives 0.497 display, 0.215 display-linear.
    #[test]
    fn agx_puts_middle_grey_at_half_display_value() {
        let mid = grey(ToneMap::Agx, 0.18);
        assert!((mid.powf(1.0 / 2.2) - 0.497).abs() < 5e-3, "{mid}");
        assert!(grey(ToneMap::Agx, 0.0) < 1e-3 && grey(ToneMap::Agx, 1e3) > 0.95);
    }

    /// Every mapper is monotonic on grey and stays in [0, 1], from black to 2¹⁰.
    #[test]
    fn every_mapper_is_monotonic_and_bounded() {
        for tone_map in [
            ToneMap::None,
            ToneMap::PbrNeutral,
            ToneMap::Aces,
            ToneMap::Agx,
        ] {
            let mut last = -1.0f32;
            for k in 0..=2000 {
                let x = 2f32.powf(-10.0 + 20.0 * k as f32 / 2000.0) - 2f32.powi(-10);
                let y = grey(tone_map, x);
                assert!(
                    (0.0..=1.0).contains(&y) && y >= last - 1e-6,
                    "{tone_map:?} at {x}: {y} after {last}"
                );
                last = y;
            }
        }
    }

    /// Light of any magnitude, up to an infinity, maps to a finite display value: the
    /// brightest the mapper shows (the shaders' lighting clamps its terms, so a huge
    /// emission shows white, not NaN's black).
    #[test]
    fn every_mapper_shows_any_light_as_a_finite_value() {
        for tone_map in [
            ToneMap::None,
            ToneMap::PbrNeutral,
            ToneMap::Aces,
            ToneMap::Agx,
        ] {
            let brightest = grey(tone_map, 1.0e9);
            for x in [1.0e20, 3.0e38, f32::INFINITY] {
                let y = grey(tone_map, x);
                assert!(y.is_finite() && y == brightest, "{tone_map:?} at {x}: {y}");
            }
        }
    }
}
