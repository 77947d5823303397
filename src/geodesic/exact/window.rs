//! Windows: stretches of an edge lit along straight paths from one (pseudo-)source.

use glam::DVec2;

/// An interval `[b0, b1]` of half-edge `edge`, lit from `source`: coordinates in the
/// half-edge's frame (its tail at the origin, its head on the positive x axis, its
/// triangle above), the source below the axis, `sigma` further back along the path;
/// with the distances at its two ends, which every test of it needs.
#[derive(Clone, Copy)]
pub struct Window {
    pub edge: u32,
    pub b0: f64,
    pub b1: f64,
    pub source: DVec2,
    pub sigma: f64,
    pub at_b0: f64,
    pub at_b1: f64,
}

impl Window {
    pub fn new(edge: u32, (b0, b1): (f64, f64), source: DVec2, sigma: f64) -> Window {
        let along = |x: f64| sigma + source.distance(DVec2::new(x, 0.0));
        Window {
            edge,
            b0,
            b1,
            source,
            sigma,
            at_b0: along(b0),
            at_b1: along(b1),
        }
    }

    /// The smallest distance to any point of the interval.
    pub fn nearest(&self) -> f64 {
        if self.source.x <= self.b0 {
            self.at_b0
        } else if self.source.x >= self.b1 {
            self.at_b1
        } else {
            self.sigma - self.source.y
        }
    }
}

/// A window's edge as the code making the window knows it: length, tail and head.
#[derive(Clone, Copy)]
pub struct Ends {
    pub length: f64,
    pub tail: u32,
    pub head: u32,
}

/// Where the ray from `from` through `through` meets the line `p + t(q − p)`, as `t`.
pub fn ray_hit(from: DVec2, through: DVec2, p: DVec2, q: DVec2) -> f64 {
    let direction = through - from;
    let edge = q - p;
    let denominator = direction.perp_dot(edge);
    if denominator.abs() < f64::MIN_POSITIVE {
        return 0.5;
    }
    (p - from).perp_dot(direction) / denominator
}
