//! The corners around each vertex in turning order, with their angles, for lighting
//! only the shadow of a saddle vertex.
//!
//! A shortest path through a vertex makes an angle of at least π on both of its sides
//! (else cutting the corner on the narrower side, across the flat fan of triangles there,
//! would shorten it). So a path of length `d` that reaches a saddle vertex from the
//! direction φ can only go on, shortest, in the directions at least π away from φ both
//! ways round: the vertex's *shadow*, a wedge as wide as the vertex's angle excess over
//! 2π. Any path of length `d` will do for φ, so the wedge is right whichever path set the
//! distance; where paths tie, the points outside one path's shadow are reached sooner
//! without the vertex.

use super::super::triangulation::{NO_TWIN, Triangulation, half_edge, split};
use std::f64::consts::PI;

/// A stretch of directions inside one corner: angles from the corner's half-edge.
pub struct Lit {
    pub corner: u32,
    pub from: f64,
    pub to: f64,
}

/// Widening of a shadow on each side, in radians, for rounding in the arrival angle.
const SHADOW_MARGIN: f64 = 1.0e-9;

pub struct Fans {
    /// For each vertex, the half-edges leaving it, one per corner, in turning order
    /// where the fan closes.
    pub corners: Vec<Vec<u32>>,
    /// Whether the vertex's corners close into one fan (not on a boundary, not
    /// non-manifold): only then is its shadow known.
    closed: Vec<bool>,
    /// For each half-edge, where its corner starts in the turning order of its vertex
    /// (the sum of the angles of the corners before it).
    start: Vec<f64>,
    /// For each half-edge, the angle of its corner.
    angle: Vec<f64>,
    /// For each vertex, the sum of its corner angles.
    total: Vec<f64>,
}

impl Fans {
    pub fn new(surface: &Triangulation) -> Fans {
        let n = surface.vertex_count;
        let mut corners = vec![Vec::new(); n];
        let mut angle = vec![0.0; surface.faces.len() * 3];
        for (f, face) in surface.faces.iter().enumerate() {
            for k in 0..3 {
                corners[face[k] as usize].push(half_edge(f, k));
                angle[half_edge(f, k) as usize] = surface.corner_angle(f, k);
            }
        }
        let mut closed = vec![false; n];
        let mut start = vec![0.0; surface.faces.len() * 3];
        let mut total = vec![0.0; n];
        for v in 0..n {
            if let Some(order) = turning_order(surface, &corners[v]) {
                let mut sum = 0.0;
                for &h in &order {
                    start[h as usize] = sum;
                    sum += angle[h as usize];
                }
                corners[v] = order;
                closed[v] = true;
                total[v] = sum;
            }
        }
        Fans {
            corners,
            closed,
            start,
            angle,
            total,
        }
    }

    /// The angle of the corner of half-edge `h`.
    pub fn angle(&self, h: u32) -> f64 {
        self.angle[h as usize]
    }

    /// A direction at the vertex of corner `h`, given by its angle from the corner's
    /// half-edge towards its other edge (past either edge for a direction in the corners
    /// beside it), as an angle round the vertex's whole fan.
    pub fn direction(&self, h: u32, angle: f64, vertex: u32) -> f64 {
        (self.start[h as usize] + angle)
            .rem_euclid(self.total[vertex as usize].max(f64::MIN_POSITIVE))
    }

    /// The stretches of directions, corner by corner, in which a path reaching saddle
    /// vertex `v` from direction `back` (see [`Fans::direction`]) can go on shortest;
    /// `None` where the vertex's fan does not close (then every direction may be needed).
    pub fn shadow(&self, v: u32, back: f64) -> Option<Vec<Lit>> {
        if !self.closed[v as usize] {
            return None;
        }
        let total = self.total[v as usize];
        let (from, to) = (back + PI - SHADOW_MARGIN, back + total - PI + SHADOW_MARGIN);
        let lit = self.corners[v as usize].iter().flat_map(|&h| {
            let (start, angle) = (self.start[h as usize], self.angle[h as usize]);
            // The wedge may run past a full turn: look at it once more, a turn earlier.
            [0.0, total].into_iter().filter_map(move |turn| {
                let (lo, hi) = (
                    (from - turn - start).max(0.0),
                    (to - turn - start).min(angle),
                );
                (lo < hi).then_some(Lit {
                    corner: h,
                    from: lo,
                    to: hi,
                })
            })
        });
        Some(lit.collect())
    }
}

/// The corners of one vertex (half-edges leaving it) ordered by walking from each corner
/// over the edge its triangle reaches the vertex by; `None` if the walk meets a boundary
/// or does not come round through every corner once.
fn turning_order(surface: &Triangulation, corners: &[u32]) -> Option<Vec<u32>> {
    let first = *corners.first()?;
    let mut order = Vec::with_capacity(corners.len());
    let mut h = first;
    loop {
        order.push(h);
        let (f, k) = split(h);
        // The corner across the edge by which this triangle comes back to the vertex.
        let next = surface.twins[half_edge(f, k + 2) as usize];
        if next == NO_TWIN || order.len() > corners.len() {
            return None;
        }
        h = next;
        if h == first {
            break;
        }
    }
    (order.len() == corners.len()).then_some(order)
}
