//! CPU mirrors of `shaders/fields.wgsl`: fronts, layers, isolines and noise bumps.

use super::noise;
use super::real::{Real, V3, add, scale};
use super::shapes::smoothstep;
use crate::nodes::settings::Basis;

/// `veneer_front`: 1 up to the threshold, 0 beyond `threshold + width`.
pub fn front<R: Real>(distance: R, threshold: R, width: R, noise: R) -> R {
    R::c(1.0)
        - smoothstep(
            threshold,
            threshold + width.max(R::c(0.0)),
            distance + noise,
        )
}

/// `veneer_isolines`.
pub fn isolines<R: Real>(value: R, spacing: R, width: R) -> R {
    if spacing <= R::c(0.0) || width <= R::c(0.0) {
        return R::c(0.0);
    }
    let offset = ((value / spacing + R::c(0.5)).fract() - R::c(0.5)).abs() * spacing;
    R::c(1.0) - smoothstep(R::c(0.0), width, offset)
}

/// `veneer_noise_bump_<basis>`.
pub fn noise_bump<R: Real>(basis: Basis, p: V3<R>, scale_by: R, strength: R) -> V3<R> {
    let q = scale(p, scale_by);
    let h = R::c(0.01);
    let axis = |k: usize| {
        let mut step = [R::c(0.0); 3];
        step[k] = h;
        let back = scale(step, R::c(-1.0));
        (noise::basis(basis, add(q, step)) - noise::basis(basis, add(q, back))) / (R::c(2.0) * h)
    };
    scale([axis(0), axis(1), axis(2)], -strength)
}
