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

/// The far corner of a triangle with side `lengths` in the frame of its edge `k`: that
/// edge from the origin along the positive x axis, the triangle above.
pub fn apex(lengths: [f64; 3], k: usize) -> DVec2 {
    let (length, l_bc, l_ca) = (lengths[k], lengths[(k + 1) % 3], lengths[(k + 2) % 3]);
    let x = (length * length + l_ca * l_ca - l_bc * l_bc) / (2.0 * length);
    DVec2::new(x, (l_ca * l_ca - x * x).max(0.0).sqrt())
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
