//! Shapes as signed distances over the xz plane, their booleans and the fills and
//! profiles made from a distance (`shaders/shapes.wgsl`).

use super::real::{Real, finite};

/// Two lanes.
pub type V2<R> = [R; 2];

/// `x` within ±1e9 (`veneer_sd_limit`).
fn limit<R: Real>(x: R) -> R {
    x.clamp(R::c(-1.0e9), R::c(1.0e9))
}

/// Both lanes within ±1e9.
fn limit2<R: Real>(p: V2<R>) -> V2<R> {
    p.map(limit)
}

fn length<R: Real>(p: V2<R>) -> R {
    (p[0] * p[0] + p[1] * p[1]).sqrt()
}

fn dot<R: Real>(a: V2<R>, b: V2<R>) -> R {
    a[0] * b[0] + a[1] * b[1]
}

fn sign<R: Real>(x: R) -> R {
    let zero = R::c(0.0);
    if x > zero {
        R::c(1.0)
    } else if x < zero {
        R::c(-1.0)
    } else {
        zero
    }
}

/// `veneer_sd_disc`.
pub fn disc<R: Real>(p: V2<R>, radius: R) -> R {
    length(limit2(p)) - limit(radius)
}

/// `veneer_sd_ellipse`.
pub fn ellipse<R: Real>(point: V2<R>, radii: V2<R>) -> R {
    let p = limit2(point);
    let r = limit2(radii).map(|r| r.abs().max(R::c(1.0e-4)));
    let k0 = length([p[0] / r[0], p[1] / r[1]]);
    let k1 = length([p[0] / (r[0] * r[0]), p[1] / (r[1] * r[1])]);
    finite(if k1 > R::c(0.0) {
        k0 * (k0 - R::c(1.0)) / k1
    } else {
        -r[0].min(r[1])
    })
}

/// `veneer_sd_box`.
pub fn rectangle<R: Real>(point: V2<R>, half: V2<R>, corner: R) -> R {
    let zero = R::c(0.0);
    let p = limit2(point);
    let h = limit2(half).map(R::abs);
    let r = corner.clamp(zero, h[0].min(h[1]));
    let d = [0, 1].map(|k| p[k].abs() - (h[k] - r));
    finite(length(d.map(|x| x.max(zero))) + d[0].max(d[1]).min(zero) - r)
}

/// `veneer_sd_sector`.
fn sector<R: Real>(p: V2<R>, half_angle: R) -> V2<R> {
    let span = R::c(2.0) * half_angle;
    let angle = p[0].atan2(p[1]) + half_angle;
    let within = angle - span * (angle / span).floor() - half_angle;
    let l = length(p);
    [l * within.cos(), l * within.sin().abs()]
}

/// `veneer_sd_polygon`.
pub fn polygon<R: Real>(point: V2<R>, size: R, sides: R) -> R {
    let (p, radius) = (limit2(point), limit(size));
    let n = (sides + R::c(0.5)).floor().clamp(R::c(3.0), R::c(64.0));
    let half_angle = R::c(std::f64::consts::PI) / n;
    let corner = [half_angle.cos(), half_angle.sin()];
    let turned = sector(p, half_angle);
    let mut q = [
        turned[0] - radius * corner[0],
        turned[1] - radius * corner[1],
    ];
    q[1] = q[1] + (-q[1]).clamp(R::c(0.0), radius * corner[1]);
    finite(length(q) * sign(q[0]))
}

/// `veneer_sd_star`.
pub fn star<R: Real>(point: V2<R>, size: R, points: R, sharpness: R) -> R {
    let (p, radius) = (limit2(point), limit(size));
    let n = (points + R::c(0.5)).floor().clamp(R::c(2.0), R::c(64.0));
    let m = R::mix(n, R::c(2.0), sharpness.clamp(R::c(0.0), R::c(1.0)));
    let half_angle = R::c(std::f64::consts::PI) / n;
    let edge_angle = R::c(std::f64::consts::PI) / m;
    let corner = [half_angle.cos(), half_angle.sin()];
    let edge = [edge_angle.cos(), edge_angle.sin()];
    let turned = sector(p, half_angle);
    let q = [
        turned[0] - radius * corner[0],
        turned[1] - radius * corner[1],
    ];
    let slide = (-dot(q, edge)).clamp(R::c(0.0), radius * corner[1] / edge[1]);
    let q = [q[0] + edge[0] * slide, q[1] + edge[1] * slide];
    finite(length(q) * sign(q[0]))
}

/// `veneer_sd_segment`.
pub fn segment<R: Real>(p: V2<R>, a: V2<R>, b: V2<R>, radius: R) -> R {
    let (p, a, b) = (limit2(p), limit2(a), limit2(b));
    let pa = [p[0] - a[0], p[1] - a[1]];
    let ba = [b[0] - a[0], b[1] - a[1]];
    let along = (dot(pa, ba) / dot(ba, ba).max(R::c(1.0e-20))).clamp(R::c(0.0), R::c(1.0));
    length([pa[0] - ba[0] * along, pa[1] - ba[1] * along]) - limit(radius)
}

/// `veneer_sd_ring`.
pub fn ring<R: Real>(p: V2<R>, radius: R, thickness: R) -> R {
    (length(limit2(p)) - limit(radius)).abs() - R::c(0.5) * limit(thickness).abs()
}

/// `veneer_bell`.
pub fn bell<R: Real>(p: V2<R>, radius: R) -> R {
    let r = length(limit2(p)) / limit(radius).abs().max(R::c(1.0e-20));
    let inner = (R::c(1.0) - r * r).max(R::c(0.0));
    inner * inner
}

/// `veneer_smooth_min`.
pub fn smooth_min<R: Real>(a: R, b: R, k: R) -> R {
    let w = k.max(R::c(1.0e-20));
    let h = (R::c(0.5) + R::c(0.5) * (b - a) / w).clamp(R::c(0.0), R::c(1.0));
    finite(R::mix(b, a, h) - k.max(R::c(0.0)) * h * (R::c(1.0) - h))
}

/// A boolean of two distances (`veneer_sd_boolean`'s operations).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum ShapeOp {
    Union,
    Subtract,
    Intersect,
}

impl ShapeOp {
    /// Every operation, in menu order.
    pub const ALL: [ShapeOp; 3] = [ShapeOp::Union, ShapeOp::Subtract, ShapeOp::Intersect];

    /// The WGSL's number for the operation.
    pub fn code(self) -> u32 {
        self as u32
    }

    /// The operation on distances `a` and `b`, smoothed over `k`.
    pub fn apply<R: Real>(self, a: R, b: R, k: R) -> R {
        match self {
            ShapeOp::Union => smooth_min(a, b, k),
            ShapeOp::Subtract => -smooth_min(-a, b, k),
            ShapeOp::Intersect => -smooth_min(-a, -b, k),
        }
    }
}

/// `veneer_shape_fill`.
pub fn fill<R: Real>(d: R, width: R) -> R {
    let zero = R::c(0.0);
    if width > zero {
        (R::c(0.5) - d / width).clamp(zero, R::c(1.0))
    } else if d <= zero {
        R::c(1.0)
    } else {
        zero
    }
}

/// The profiles of a shape made from a distance (`veneer_sdf_profiles`): fill, bevel,
/// outer glow and inner glow.
pub fn profiles<R: Real>(d: R, thickness: R, bevel: R, outer: R, inner: R, width: R) -> [R; 4] {
    let zero = R::c(0.0);
    let one = R::c(1.0);
    let tiny = R::c(1.0e-20);
    let shape = if thickness > zero {
        d.abs() - R::c(0.5) * thickness
    } else {
        d
    };
    let rise = (-shape / bevel.max(tiny)).clamp(zero, one);
    let out = (one - shape / outer.max(tiny)).clamp(zero, one);
    let into = (one + shape / inner.max(tiny)).clamp(zero, one);
    [
        fill(shape, width),
        rise * rise * (R::c(3.0) - R::c(2.0) * rise),
        if shape > zero { out * out } else { zero },
        if shape <= zero { into * into } else { zero },
    ]
}
