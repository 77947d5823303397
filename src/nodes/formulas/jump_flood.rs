//! CPU twins of `shaders/jump_flood.wgsl`: the jump-flooding distance transform of a
//! mask image, step by step as the GPU runs it, and the bevel profile.

use super::buffers::Image;
use crate::nodes::passes::EdgeMode;

/// How many jump-flooding steps run: halving from half the largest buffer
/// ([`crate::nodes::passes::MAX_BUFFER_SIZE`], 2¹³) to one texel, then two more of one.
pub const JFA_STEPS: u32 = 15;

/// The seed state of `texel` (as `veneer_jfa_seed`): where the mask crosses 0.5 near an
/// on-side texel, by the mask's steeper one-sided slopes, within one texel. Computed in
/// f32 as the GPU computes it: the seed's place decides which seed is nearest.
pub fn jfa_seed(image: &Image, texel: [i64; 2], inside: bool) -> [f64; 4] {
    let at = |dx: i64, dy: i64| image.texel(texel[0] + dx, texel[1] + dy)[0] as f32;
    let m = at(0, 0);
    if (m > 0.5) == inside {
        return [0.0, 0.0, 0.0, 1.0];
    }
    let steeper = |a: f32, b: f32| match () {
        _ if a * b < 0.0 => 0.0,
        _ if b.abs() > a.abs() => b,
        _ => a,
    };
    let slope = [
        steeper(m - at(-1, 0), at(1, 0) - m),
        steeper(m - at(0, -1), at(0, 1) - m),
    ];
    let squared = slope[0] * slope[0] + slope[1] * slope[1];
    let mut offset = [0.0_f32; 2];
    if squared > 1e-12 {
        offset = slope.map(|s| (0.5 - m) * s / squared);
        let length = (offset[0] * offset[0] + offset[1] * offset[1]).sqrt();
        if length > 1.0 {
            offset = offset.map(|o| o / length);
        }
    }
    [
        texel[0] as f64 + f64::from(offset[0]),
        texel[1] as f64 + f64::from(offset[1]),
        1.0,
        1.0,
    ]
}

/// From `texel` to `seed`, the shorter way across the wrap (as `veneer_jfa_delta`).
fn delta(texel: [i64; 2], seed: [f64; 2], size: [f64; 2], edge: EdgeMode) -> [f64; 2] {
    let mut d = [seed[0] - texel[0] as f64, seed[1] - texel[1] as f64];
    if edge == EdgeMode::Wrap {
        for k in 0..2 {
            d[k] -= size[k] * (d[k] / size[k]).round_ties_even();
        }
    }
    d
}

/// Jump-flooding step `k` at `texel` (as `veneer_jfa_step`).
pub fn jfa_step(image: &Image, texel: [i64; 2], k: u32) -> [f64; 4] {
    let size = [f64::from(image.width), f64::from(image.height)];
    let step = (i64::from(image.width) >> (k + 1)).max(1);
    let squared = |state: [f64; 4]| {
        let d = delta(texel, [state[0], state[1]], size, image.edge);
        d[0] * d[0] + d[1] * d[1]
    };
    let mut best = image.texel(texel[0], texel[1]);
    let mut nearest = if best[2] > 0.5 {
        squared(best)
    } else {
        f64::MAX
    };
    for k9 in 0..9 {
        let offset = [(k9 % 3 - 1) * step, (k9 / 3 - 1) * step];
        let candidate = image.texel(texel[0] + offset[0], texel[1] + offset[1]);
        if candidate[2] > 0.5 {
            let distance = squared(candidate);
            if distance < nearest {
                nearest = distance;
                best = candidate;
            }
        }
    }
    best
}

/// The distance in domain units from `texel` to its seed (as `veneer_jfa_distance`).
pub fn jfa_distance(image: &Image, texel: [i64; 2], far: f64) -> [f64; 4] {
    let state = image.texel(texel[0], texel[1]);
    let size = [f64::from(image.width), f64::from(image.height)];
    let distance = if state[2] > 0.5 {
        let d = delta(texel, [state[0], state[1]], size, image.edge);
        (d[0] / size[0]).hypot(d[1] / size[1])
    } else {
        far
    };
    [distance, distance, distance, 1.0]
}

/// A bevel's height at distance `d` inside a mask (as `veneer_bevel`).
pub fn bevel(d: f64, width: f64, profile: u32) -> f64 {
    let t = (d / width.max(1e-6)).clamp(0.0, 1.0);
    match profile {
        1 => t * t * (3.0 - 2.0 * t),
        2 => (t * (2.0 - t)).sqrt(),
        _ => t,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The distance image of `mask` (`n` texels square) by every stage in turn.
    fn transform(mask: &[bool], n: u32, edge: EdgeMode, inside: bool) -> Image {
        let mut image = Image {
            width: n,
            height: n,
            edge,
            texels: mask
                .iter()
                .map(|&on| [f32::from(u8::from(on)), 0.0, 0.0, 1.0])
                .collect(),
        };
        image = image.map_texels(|image, texel| jfa_seed(image, texel, inside));
        for k in 0..JFA_STEPS {
            image = image.map_texels(|image, texel| jfa_step(image, texel, k));
        }
        image.map_texels(|image, texel| jfa_distance(image, texel, 1e4))
    }

    #[test]
    fn jump_flooding_gives_the_exact_distance_to_a_point_across_the_wrap() {
        let n = 16;
        let mut mask = vec![false; (n * n) as usize];
        mask[(2 * n + 1) as usize] = true;
        let wrapped = transform(&mask, n, EdgeMode::Wrap, false);
        let clamped = transform(&mask, n, EdgeMode::Clamp, false);
        for y in 0..n as i64 {
            for x in 0..n as i64 {
                let brute = |wrap: bool| {
                    let mut d = [(x - 1) as f64, (y - 2) as f64];
                    if wrap {
                        d = d.map(|d| d - 16.0 * (d / 16.0).round_ties_even());
                    }
                    d[0].hypot(d[1]) / 16.0
                };
                let at = (y * n as i64 + x) as usize;
                assert!((f64::from(wrapped.texels[at][0]) - brute(true)).abs() < 1e-6);
                assert!((f64::from(clamped.texels[at][0]) - brute(false)).abs() < 1e-6);
            }
        }
    }

    #[test]
    fn inside_a_square_the_distance_grows_towards_its_middle_and_outside_is_zero() {
        let n = 16;
        let mask: Vec<bool> = (0..n * n)
            .map(|k| (4..12).contains(&(k % n)) && (4..12).contains(&(k / n)))
            .collect();
        let inside = transform(&mask, n, EdgeMode::Clamp, true);
        assert_eq!(inside.texels[0][0], 0.0);
        // The edge lies between texels: half a texel from the first one inside.
        let edge = inside.texels[(4 * n + 6) as usize][0];
        let middle = inside.texels[(7 * n + 7) as usize][0];
        assert!((f64::from(edge) - 0.5 / 16.0).abs() < 1e-6 && middle > edge);
        assert_eq!(bevel(0.0, 0.1, 2), 0.0);
        assert_eq!(bevel(1.0, 0.1, 1), 1.0);
    }
}
