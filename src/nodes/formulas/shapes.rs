//! Coordinates, patterns and safe arithmetic, as in shaders/coords.wgsl, patterns.wgsl
//! and math.wgsl.

use super::real::{
    DOWN, Real, V3, add, cross, dot, finite, length, map, mul, safe_normalize, scale, sub, zip,
};
use super::{band_limit, noise};
use crate::nodes::settings::{Basis, FractalMode};

/// `veneer_scaled`: `p * scale` clamped to ±1e38, so that a rotation of it stays finite.
fn scaled<R: Real>(p: V3<R>, scale_by: V3<R>) -> V3<R> {
    let limit = R::c(1.0e38);
    map(mul(p, scale_by), |x| x.clamp(-limit, limit))
}

/// `rotate(p * scale) + offset`, rotation in degrees about x, then y, then z; the scaled
/// point clamped to ±1e38 and the result to the finite range (`veneer_transform`, and
/// without rotation `veneer_scale_offset`, which gives the same).
pub fn transform<R: Real>(p: V3<R>, scale_by: V3<R>, rotation: V3<R>, offset: V3<R>) -> V3<R> {
    let a = map(rotation, |d| d * R::c(std::f64::consts::PI / 180.0));
    let (c, s) = (map(a, R::cos), map(a, R::sin));
    let q = scaled(p, scale_by);
    let q = [q[0], c[0] * q[1] - s[0] * q[2], s[0] * q[1] + c[0] * q[2]];
    let q = [c[1] * q[0] + s[1] * q[2], q[1], -s[1] * q[0] + c[1] * q[2]];
    let q = [c[2] * q[0] - s[2] * q[1], s[2] * q[0] + c[2] * q[1], q[2]];
    map(add(q, offset), finite)
}

/// `veneer_half_offset`: half of `p - origin` (exact, so it cannot overflow), scaled down
/// by a further 2⁻¹⁰⁰ where it is too long to square, and the factor undoing the scaling.
fn half_offset<R: Real>(p: V3<R>, origin: V3<R>) -> (V3<R>, R) {
    let half = zip(p, origin, |p, o| R::c(0.5) * p - R::c(0.5) * o);
    if dot(half, half, 3) > R::c(1.0e36) {
        (scale(half, R::c(DOWN)), R::c(2.0 / DOWN))
    } else {
        (half, R::c(2.0))
    }
}

/// Coordinate along a direction, clamped to the finite range.
pub fn project<R: Real>(p: V3<R>, origin: V3<R>, direction: V3<R>) -> R {
    let (half, back) = half_offset(p, origin);
    finite(back * dot(half, safe_normalize(direction, 3), 3))
}

/// (t, r, theta) about an axis, with seed 000's choice of reference up vector; t and r
/// clamped to the finite range.
pub fn cylindrical<R: Real>(p: V3<R>, origin: V3<R>, axis: V3<R>) -> V3<R> {
    let (zero, one) = (R::c(0.0), R::c(1.0));
    let d = safe_normalize(axis, 3);
    let up = if d[1].abs() > R::c(0.95) {
        [one, zero, zero]
    } else {
        [zero, one, zero]
    };
    let u = safe_normalize(cross(up, d), 3);
    let v = cross(d, u);
    let (relative, back) = half_offset(p, origin);
    let t = dot(relative, d, 3);
    let radial = sub(relative, scale(d, t));
    // On (or within rounding noise of) the axis the angle is undefined: 0, as in the WGSL.
    let across = [dot(radial, u, 3), dot(radial, v, 3)];
    let on_axis =
        across[0] * across[0] + across[1] * across[1] <= R::c(1.0e-10) * dot(relative, relative, 3);
    [
        finite(back * t),
        finite(back * length(radial, 3)),
        if on_axis {
            R::c(0.0)
        } else {
            across[1].atan2(across[0])
        },
    ]
}

/// Domain warp by signed noise per axis (repeating every `period` cells when it has
/// one), clamped to the finite range.
pub fn warp<R: Real>(
    basis: Basis,
    p: V3<R>,
    strength: R,
    scale_by: R,
    period: noise::Period,
) -> V3<R> {
    let q = scale(p, scale_by);
    let offset = |o: [f64; 3]| add(q, o.map(R::c));
    let w = [
        noise::signed_repeating(basis, q, period),
        noise::signed_repeating(basis, offset([31.4, 47.2, 12.9]), period),
        noise::signed_repeating(basis, offset([-23.7, 8.3, 51.1]), period),
    ];
    map(add(p, scale(w, strength)), finite)
}

/// Fractal sum of octaves (`veneer_<mode>_<basis>`, and `veneer_<mode>_<basis>_periodic`
/// with a `period`); the frequency, the amplitude and the sums clamped to the finite range.
/// The arguments are the WGSL function's, one for one.
#[allow(clippy::too_many_arguments)]
pub fn fractal<R: Real>(
    mode: FractalMode,
    basis: Basis,
    p: V3<R>,
    octaves: u32,
    [lacunarity, gain, amplitude]: [R; 3],
    normalize: bool,
    cutoff: R,
    period: noise::Period,
) -> R {
    let octave = |q: V3<R>, period| match mode {
        FractalMode::Fbm => noise::repeating(basis, q, period),
        FractalMode::Turbulence => noise::signed_repeating(basis, q, period).abs(),
        FractalMode::FractalSum => noise::signed_repeating(basis, q, period),
    };
    // A periodic sum's octave i spans a whole number of cells over the period.
    let sample = |freq: R| match period {
        None => octave(scale(p, freq), None),
        Some(n) => {
            let cells = noise::octave_period(n, freq, noise::period_step(basis));
            let ratio = R::c(f64::from(cells)) / R::c(f64::from(n));
            octave(scale(p, ratio), Some(cells))
        }
    };
    let mean = R::c(match mode {
        FractalMode::Fbm => 0.5,
        FractalMode::Turbulence => 0.25,
        FractalMode::FractalSum => 0.0,
    });
    let (mut sum, mut amp, mut freq, mut total) = (R::c(0.0), amplitude, R::c(1.0), R::c(0.0));
    for i in 0..octaves {
        let shown = (cutoff - R::c(f64::from(i))).clamp(R::c(0.0), R::c(1.0));
        let value = if shown > R::c(0.0) {
            shown * sample(freq) + (R::c(1.0) - shown) * mean
        } else {
            mean
        };
        sum = finite(sum + amp * value);
        total = (total + amp.abs()).min(R::c(3.0e38));
        freq = finite(freq * lacunarity);
        amp = finite(amp * gain);
    }
    if normalize && total > R::c(0.0) {
        sum / total
    } else {
        sum
    }
}

/// Worley feature 0..3 of (F1, F2, F3).
pub fn worley_feature<R: Real>(f: V3<R>, feature: i32) -> R {
    match feature {
        1 => f[1],
        2 => f[2],
        3 => f[1] - f[0],
        _ => f[0],
    }
}

/// 0.5 + 0.5 sin(frequency x + distortion turbulence), the products and the phase clamped
/// to the finite range.
pub fn sine_band<R: Real>(x: R, frequency: R, distortion: R, turbulence: R) -> R {
    let phase = finite(frequency * x) + finite(distortion * turbulence);
    R::c(0.5) + R::c(0.5) * finite(phase).sin()
}

/// 0 → 1 → 0 once per period, the product clamped to the finite range.
pub fn triangle_wave<R: Real>(x: R, frequency: R) -> R {
    let r = finite(x * frequency).fract() * R::c(2.0);
    if r > R::c(1.0) { R::c(2.0) - r } else { r }
}

fn tile_integral<R: Real>(x: R, gap: R) -> R {
    x.floor() * (R::c(1.0) - gap) + (x.fract() - gap).max(R::c(0.0))
}

/// Share of [x − width/2, x + width/2] covered by tile, faded to the mean past Nyquist
/// (`veneer_tile_coverage`).
fn tile_coverage<R: Real>(x: R, gap: R, width: R) -> R {
    if width <= R::c(0.0) {
        R::step(gap, x.fract())
    } else {
        let half = width * R::c(0.5);
        let soft = (tile_integral(x + half, gap) - tile_integral(x - half, gap))
            / width.max(R::c(1.0e-30));
        R::mix(R::c(1.0) - gap, soft, band_limit::nyquist_fade(width))
    }
}

/// Tiles over the xz plane: (mask, cell, local) as in `veneer_tiles` (the position and the
/// filter width in tiles clamped to ±1e30, the gap to [0, 1]).
pub fn tiles<R: Real>(
    p: V3<R>,
    size: V3<R>,
    gap: V3<R>,
    row_offset: R,
    blur: R,
) -> (R, [R; 2], [R; 2]) {
    let safe = |s: R| {
        if s.abs() < R::c(1.0e-20) {
            R::c(1.0)
        } else {
            s
        }
    };
    let size = [safe(size[0]), safe(size[1])];
    let limit = R::c(1.0e30);
    let mut t = [p[0] / size[0], p[2] / size[1]].map(|x| x.clamp(-limit, limit));
    if (t[0] * R::c(0.5)).fract() > R::c(0.5) {
        t[1] = t[1] + row_offset;
    }
    let coverage: [R; 2] = std::array::from_fn(|k| {
        let width = (blur / size[k].abs()).clamp(-limit, limit);
        tile_coverage(t[k], gap[k].clamp(R::c(0.0), R::c(1.0)), width)
    });
    let ceil = |x: R| -((-x).floor());
    (coverage[0] * coverage[1], t.map(ceil), t.map(R::fract))
}

/// Concentric rings about an axis, the products clamped to the finite range.
pub fn rings<R: Real>(p: V3<R>, origin: V3<R>, axis: V3<R>, frequency: R) -> R {
    let r = cylindrical(p, origin, axis)[1];
    R::c(0.5) + R::c(0.5) * finite(finite(R::c(std::f64::consts::TAU) * frequency) * r).sin()
}

/// a / b; 0 where b is 0; clamped to the finite range.
pub fn safe_div<R: Real>(a: R, b: R) -> R {
    let q = if b == R::c(0.0) { R::c(0.0) } else { a / b };
    q.clamp(-R::c(3.0e38), R::c(3.0e38))
}

/// pow for a > 0, else 0; clamped to the finite range.
pub fn safe_pow<R: Real>(a: R, b: R) -> R {
    if a <= R::c(0.0) {
        R::c(0.0)
    } else {
        a.max(R::c(1.0e-30)).powf(b).min(R::c(3.0e38))
    }
}

/// Clamped linear ramp, a step when the edges are equal; the operands halved first (an
/// exact scaling), so that no difference overflows.
pub fn linearstep<R: Real>(edge0: R, edge1: R, x: R) -> R {
    let half = R::c(0.5);
    let span = half * edge1 - half * edge0;
    if span == R::c(0.0) {
        R::step(edge0, x)
    } else {
        ((half * x - half * edge0) / span).clamp(R::c(0.0), R::c(1.0))
    }
}

/// Safe Hermite smoothstep.
pub fn smoothstep<R: Real>(edge0: R, edge1: R, x: R) -> R {
    let t = linearstep(edge0, edge1, x);
    t * t * (R::c(3.0) - R::c(2.0) * t)
}

/// Linear remap (`veneer_remap`): the linear Map Range without clamping.
pub fn remap<R: Real>(x: R, from_min: R, from_max: R, to_min: R, to_max: R) -> R {
    super::ranges::map_range_linear(x, from_min, from_max, to_min, to_max, false)
}

/// A colour as three lanes.
pub fn color<R: Real>(c: (f64, f64, f64)) -> V3<R> {
    [R::c(c.0), R::c(c.1), R::c(c.2)]
}

/// Lane-wise mix of two values by a scalar (`veneer_mix_<type>`): `a (1 - t) + b t`, each
/// product and the sum clamped to the finite range.
pub fn mix3<R: Real>(a: V3<R>, b: V3<R>, t: R) -> V3<R> {
    zip(a, b, |a, b| {
        finite(finite(a * (R::c(1.0) - t)) + finite(b * t))
    })
}
