//! Closed intervals of reals and the arithmetic the lint needs, one per vector lane.

/// A closed interval [lo, hi] (possibly unbounded).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    pub lo: f64,
    pub hi: f64,
}

/// Three lanes: a vec3 or colour, a vec2 in the first two, a float in all three.
pub type Lanes = [Interval; 3];

impl Interval {
    /// The interval [lo, hi].
    pub const fn new(lo: f64, hi: f64) -> Interval {
        Interval { lo, hi }
    }

    /// The single value x.
    pub fn point(x: f64) -> Interval {
        Interval::new(x, x)
    }

    /// [0, 1].
    pub const UNIT: Interval = Interval::new(0.0, 1.0);

    /// Whether x lies inside.
    pub fn contains(self, x: f64) -> bool {
        self.lo <= x && x <= self.hi
    }

    /// The largest magnitude.
    pub fn magnitude(self) -> f64 {
        self.lo.abs().max(self.hi.abs())
    }

    /// The smallest interval holding both.
    pub fn hull(self, other: Interval) -> Interval {
        Interval::new(self.lo.min(other.lo), self.hi.max(other.hi))
    }

    pub fn add(self, other: Interval) -> Interval {
        Interval::new(self.lo + other.lo, self.hi + other.hi)
    }

    pub fn sub(self, other: Interval) -> Interval {
        Interval::new(self.lo - other.hi, self.hi - other.lo)
    }

    pub fn mul(self, other: Interval) -> Interval {
        let products = [
            self.lo * other.lo,
            self.lo * other.hi,
            self.hi * other.lo,
            self.hi * other.hi,
        ];
        let products = products.map(|p| if p.is_nan() { 0.0 } else { p });
        Interval::new(
            products.iter().copied().fold(f64::INFINITY, f64::min),
            products.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        )
    }

    /// self / other, with the safe division's 0 where other may be 0.
    pub fn div(self, other: Interval) -> Interval {
        if other.contains(0.0) {
            return Interval::new(-3.0e38, 3.0e38).hull(Interval::point(0.0));
        }
        self.mul(Interval::new(1.0 / other.hi, 1.0 / other.lo))
    }

    /// Clamped into [lo, hi].
    pub fn clamp(self, lo: f64, hi: f64) -> Interval {
        Interval::new(self.lo.clamp(lo, hi), self.hi.clamp(lo, hi))
    }
}

/// The same interval in all three lanes.
pub fn splat(interval: Interval) -> Lanes {
    [interval; 3]
}

/// The largest Euclidean length a vector in the box `lanes` (first `width` lanes) can have.
pub fn max_length(lanes: &Lanes, width: usize) -> f64 {
    lanes[..width]
        .iter()
        .map(|i| i.magnitude().powi(2))
        .sum::<f64>()
        .sqrt()
}
