//! CPU mirrors of `shaders/fields.wgsl`: fronts, layers, isolines and noise bumps.

use super::noise;
use super::real::{Real, V3, add, finite, map, scale};
use super::shapes::smoothstep;
use crate::nodes::settings::Basis;

/// `veneer_front`: how much a material spreading from the sources covers, 1 near them
/// and 0 far away. The transition is centred `centre` widths past the threshold and
/// spans `softness` widths on either side of that:
/// `1 − smoothstep(T + (c − s)·w, T + (c + s)·w, distance + noise)`.
///
/// The defaults (c = s = ½) are Veneer's first front (0 beyond `T + w`); seed 003's
/// §5.2.4, C.2 and C.3 `smoothstep(d − w/2, d + w/2, T + w)` is c = 1, s = ½, and its
/// C.4 and C.5 `smoothstep(d − w, d + w, T + n)` is c = 0, s = 1 with the noise
/// negated (the thesis adds it to the threshold, the node to the distance).
///
/// The edges and the sum are clamped to the finite range.
pub fn front<R: Real>(distance: R, threshold: R, width: R, noise: R, centre: R, softness: R) -> R {
    let width = width.max(R::c(0.0));
    let softness = softness.max(R::c(0.0));
    let low = finite(threshold + finite(centre - softness) * width);
    let high = finite(threshold + finite(centre + softness) * width);
    R::c(1.0) - smoothstep(low, high, finite(distance + noise))
}

/// `veneer_isolines`: the value in periods (of at least 1e-30) clamped to the finite range.
pub fn isolines<R: Real>(value: R, spacing: R, width: R) -> R {
    if spacing <= R::c(0.0) || width <= R::c(0.0) {
        return R::c(0.0);
    }
    let period = spacing.max(R::c(1.0e-30));
    let offset = (finite(value / period) + R::c(0.5)).fract() - R::c(0.5);
    R::c(1.0) - smoothstep(R::c(0.0), width, offset.abs() * period)
}

/// `veneer_noise_bump_<basis>`.
pub fn noise_bump<R: Real>(
    basis: Basis,
    p: V3<R>,
    scale_by: R,
    strength: R,
    period: noise::Period,
) -> V3<R> {
    let q = scale(p, scale_by);
    let h = R::c(0.01);
    let axis = |k: usize| {
        let mut step = [R::c(0.0); 3];
        step[k] = h;
        let back = scale(step, R::c(-1.0));
        let rise = noise::repeating(basis, add(q, step), period)
            - noise::repeating(basis, add(q, back), period);
        rise / (R::c(2.0) * h)
    };
    map(scale([axis(0), axis(1), axis(2)], -strength), finite)
}

#[cfg(test)]
mod tests {
    use super::front;
    use crate::nodes::formulas::shapes::smoothstep;

    /// Distances across every transition below.
    fn distances() -> impl Iterator<Item = f64> {
        (0..=400).map(|i| f64::from(i) / 400.0)
    }

    #[test]
    fn the_default_placement_is_the_first_front_exactly() {
        let (threshold, width, noise) = (0.3, 0.07, 0.01);
        for d in distances() {
            let first = 1.0 - smoothstep(threshold, threshold + width, d + noise);
            assert_eq!(front(d, threshold, width, noise, 0.5, 0.5), first);
        }
    }

    #[test]
    fn the_thesis_fronts_are_placements() {
        let (threshold, width, noise) = (0.3, 0.07, 0.02);
        for d in distances() {
            // §5.2.4, C.2, C.3: smoothstep(d - w/2, d + w/2, T + w), 50% at T + w.
            let shore = smoothstep(d - width * 0.5, d + width * 0.5, threshold + width);
            assert!((front(d, threshold, width, 0.0, 1.0, 0.5) - shore).abs() < 1e-12);
            // C.4, C.5: smoothstep(d - w, d + w, T + noise), the noise on the threshold.
            let centred = smoothstep(d - width, d + width, threshold + noise);
            let ours = front(d, threshold + noise, width, 0.0, 0.0, 1.0);
            assert!((ours - centred).abs() < 1e-12);
        }
        assert!((front(0.37_f64, 0.3, 0.07, 0.0, 1.0, 0.5) - 0.5).abs() < 1e-12);
    }
}
