//! The scalar type the evaluator runs in (f32 like the GPU, or f64 as the reference),
//! and the small vector helpers the node formulas need.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// A floating-point scalar: f32 or f64.
pub trait Real:
    Copy
    + PartialOrd
    + std::fmt::Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// `x` rounded to this precision.
    fn c(x: f64) -> Self;
    fn to_f64(self) -> f64;
    fn floor(self) -> Self;
    fn sin(self) -> Self;
    fn cos(self) -> Self;
    fn sqrt(self) -> Self;
    fn abs(self) -> Self;
    fn atan2(self, x: Self) -> Self;
    fn powf(self, e: Self) -> Self;
    /// eˣ, rounded from f64 (so an f32 result is the correctly rounded one; a GPU's is
    /// within a few ulps of it).
    fn exp(self) -> Self;
    /// The largest finite value.
    fn max_finite() -> Self;

    /// `self - floor(self)`, as WGSL's fract.
    fn fract(self) -> Self {
        self - self.floor()
    }
    fn min(self, other: Self) -> Self {
        if other < self { other } else { self }
    }
    fn max(self, other: Self) -> Self {
        if other > self { other } else { self }
    }
    fn clamp(self, low: Self, high: Self) -> Self {
        self.max(low).min(high)
    }
    /// WGSL's mix: `a * (1 - t) + b * t`.
    fn mix(a: Self, b: Self, t: Self) -> Self {
        a * (Self::c(1.0) - t) + b * t
    }
    /// WGSL's step: 1 where `self >= edge`.
    fn step(edge: Self, x: Self) -> Self {
        if x >= edge {
            Self::c(1.0)
        } else {
            Self::c(0.0)
        }
    }
}

macro_rules! impl_real {
    ($t:ty) => {
        impl Real for $t {
            fn c(x: f64) -> Self {
                x as $t
            }
            fn to_f64(self) -> f64 {
                self as f64
            }
            fn floor(self) -> Self {
                <$t>::floor(self)
            }
            fn sin(self) -> Self {
                <$t>::sin(self)
            }
            fn cos(self) -> Self {
                <$t>::cos(self)
            }
            fn sqrt(self) -> Self {
                <$t>::sqrt(self)
            }
            fn abs(self) -> Self {
                <$t>::abs(self)
            }
            fn atan2(self, x: Self) -> Self {
                <$t>::atan2(self, x)
            }
            fn powf(self, e: Self) -> Self {
                <$t>::powf(self, e)
            }
            fn exp(self) -> Self {
                (self as f64).exp() as $t
            }
            fn max_finite() -> Self {
                <$t>::MAX
            }
        }
    };
}
impl_real!(f32);
impl_real!(f64);

/// Three lanes of a value: a vec3 or colour, a vec2 in the first two, a float in all three.
pub type V3<R> = [R; 3];

/// `f` applied lane by lane.
pub fn map<R: Real>(a: V3<R>, f: impl Fn(R) -> R) -> V3<R> {
    [f(a[0]), f(a[1]), f(a[2])]
}

/// `f` applied lane by lane to two values.
pub fn zip<R: Real>(a: V3<R>, b: V3<R>, f: impl Fn(R, R) -> R) -> V3<R> {
    [f(a[0], b[0]), f(a[1], b[1]), f(a[2], b[2])]
}

pub fn add<R: Real>(a: V3<R>, b: V3<R>) -> V3<R> {
    zip(a, b, |x, y| x + y)
}
pub fn sub<R: Real>(a: V3<R>, b: V3<R>) -> V3<R> {
    zip(a, b, |x, y| x - y)
}
pub fn mul<R: Real>(a: V3<R>, b: V3<R>) -> V3<R> {
    zip(a, b, |x, y| x * y)
}
pub fn scale<R: Real>(a: V3<R>, s: R) -> V3<R> {
    map(a, |x| x * s)
}
pub fn splat<R: Real>(x: R) -> V3<R> {
    [x, x, x]
}
/// Dot product over the first `width` lanes.
pub fn dot<R: Real>(a: V3<R>, b: V3<R>, width: usize) -> R {
    (1..width).fold(a[0] * b[0], |sum, k| sum + a[k] * b[k])
}
pub fn cross<R: Real>(a: V3<R>, b: V3<R>) -> V3<R> {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
pub fn length<R: Real>(a: V3<R>, width: usize) -> R {
    dot(a, a, width).sqrt()
}

/// The largest magnitude the finite clamps allow (`veneer_finite_<type>`).
const FINITE: f64 = 3.0e38;

/// Past this, a vector's square is taken after scaling it by [`DOWN`].
const SQUARE_LIMIT: f64 = 1.0e38;

/// 2⁻¹⁰⁰, which scales a vector down exactly (its inverse back up).
pub const DOWN: f64 = 7.888609052210118e-31;

/// `x` clamped to the finite range (`veneer_finite_<type>`): a sum or product of finite
/// values is finite or an infinity, never NaN, and the clamp makes it finite.
pub fn finite<R: Real>(x: R) -> R {
    x.clamp(R::c(-FINITE), R::c(FINITE))
}

/// The length over the first `width` lanes for any finite vector (`veneer_length_<type>`):
/// where the square overflows, of the vector scaled down by 2⁻¹⁰⁰ and back; clamped to
/// the finite range.
pub fn finite_length<R: Real>(a: V3<R>, width: usize) -> R {
    let length = if dot(a, a, width) > R::c(SQUARE_LIMIT) {
        R::c(1.0 / DOWN) * length(scale(a, R::c(DOWN)), width)
    } else {
        length(a, width)
    };
    length.min(R::c(FINITE))
}

/// The dot product over the first `width` lanes for any finite vectors
/// (`veneer_dot_<type>`): each product clamped to ±1e38, so the sum cannot overflow.
pub fn finite_dot<R: Real>(a: V3<R>, b: V3<R>, width: usize) -> R {
    let limit = R::c(1.0e38);
    dot(
        map(mul(a, b), |x| x.clamp(-limit, limit)),
        splat(R::c(1.0)),
        width,
    )
}

/// Unit vector along the first `width` lanes; zero when too short (as `veneer_safe_normalize`).
/// A vector whose square overflows is scaled down by 2⁻¹⁰⁰ first (exact).
pub fn safe_normalize<R: Real>(a: V3<R>, width: usize) -> V3<R> {
    let squared = dot(a, a, width);
    if squared < R::c(1.0e-30) {
        return splat(R::c(0.0));
    }
    let a = if squared > R::c(SQUARE_LIMIT) {
        scale(a, R::c(DOWN))
    } else {
        a
    };
    let inverse = R::c(1.0) / dot(a, a, width).sqrt();
    let mut unit = scale(a, inverse);
    for lane in unit.iter_mut().skip(width) {
        *lane = R::c(0.0);
    }
    unit
}
