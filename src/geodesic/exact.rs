//! The exact polyhedral distance, by window propagation in the style of Chen & Han as
//! improved by Xin & Wang (ICH, 2009). A window is an interval of an edge lit by one
//! (pseudo-)source unfolded into the plane of the next triangle; windows are taken
//! in order of their nearest point and pushed across triangles. Saddle and boundary
//! vertices, where shortest paths may bend, become pseudo-sources of their own.
//! Two prunings keep the count of windows down without losing exactness: "one angle,
//! one split" (of the windows lighting a triangle's far vertex through the same edge,
//! only the nearest may send children to both sides of it) and ICH's test against the
//! distances already known at the window edge's two vertices.

use super::triangulation::{NO_TWIN, Triangulation, half_edge, split};
use glam::DVec2;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Relative slack in comparisons of path lengths.
const SLACK: f64 = 1.0e-12;

/// Windows propagated per triangle before the method gives up on windows: good meshes
/// need 36 (torus:48) to 81 (genus2:40) per triangle, growing with the square root of
/// the size; a sliver folded onto itself took millions (found by fuzzing).
const WINDOWS_PER_FACE: usize = 2000;

/// The least window budget of a mesh, so that small meshes are never cut short.
const MIN_WINDOWS: usize = 200_000;

/// An interval `[b0, b1]` of half-edge `edge`, lit from `source`: coordinates in the
/// half-edge's frame (its tail at the origin, its head on the positive x axis, its
/// triangle above), the source below the axis, `sigma` further back along the path.
#[derive(Clone, Copy)]
struct Window {
    edge: u32,
    b0: f64,
    b1: f64,
    source: DVec2,
    sigma: f64,
}

impl Window {
    /// The distance along this window's paths to the point `(x, 0)`.
    fn distance_at(&self, x: f64) -> f64 {
        self.sigma + self.source.distance(DVec2::new(x, 0.0))
    }

    /// The smallest distance to any point of the interval.
    fn nearest(&self) -> f64 {
        let x = self.source.x.clamp(self.b0, self.b1);
        self.distance_at(x)
    }
}

/// Work waiting in the queue: a window (by its place in the window store) or a vertex
/// to settle, packed in a `u32` (the top bit says which).
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
struct Event(u32);

const VERTEX_EVENT: u32 = 1 << 31;

/// The queue: events by the distance they start from, nearest first (ties by event, so
/// the order is the same on every run). Distances are never negative, so their bits
/// order as the numbers do: heap entries are 12 bytes of integers, compared inline,
/// with the windows themselves in a store beside the heap (a heap of whole windows,
/// compared as floats, took two thirds of the time).
#[derive(Default)]
struct Queue {
    heap: BinaryHeap<Reverse<(u64, Event)>>,
    /// Windows waiting, by slot; freed slots are reused.
    windows: Vec<Window>,
    free: Vec<u32>,
}

impl Queue {
    fn push(&mut self, key: f64, event: Event) {
        self.heap.push(Reverse((key.max(0.0).to_bits(), event)));
    }

    fn push_vertex(&mut self, key: f64, v: u32) {
        self.push(key, Event(v | VERTEX_EVENT));
    }

    fn push_window(&mut self, key: f64, window: Window) {
        let slot = match self.free.pop() {
            Some(slot) => {
                self.windows[slot as usize] = window;
                slot
            }
            None => {
                self.windows.push(window);
                (self.windows.len() - 1) as u32
            }
        };
        self.push(key, Event(slot));
    }

    /// The nearest event: its distance, and the vertex to settle or the window (taken
    /// out of the store).
    fn pop(&mut self) -> Option<(f64, Result<u32, Window>)> {
        let Reverse((key, Event(event))) = self.heap.pop()?;
        let key = f64::from_bits(key);
        if event & VERTEX_EVENT != 0 {
            return Some((key, Ok(event & !VERTEX_EVENT)));
        }
        self.free.push(event);
        Some((key, Err(self.windows[event as usize])))
    }
}

/// The best path found so far to the far vertex of a half-edge's triangle through that
/// half-edge: its length and where it crosses the edge.
#[derive(Clone, Copy)]
struct Split {
    distance: f64,
    x: f64,
}

/// Exact distances from `sources` over `surface`; `progress(reached, vertices)` is
/// called as paths reach vertices. Vertices no source reaches are `inf`.
pub fn exact_distances(
    surface: &Triangulation,
    sources: &[u32],
    progress: impl FnMut(usize, usize),
) -> Vec<f64> {
    Propagation::new(surface).run(sources, progress)
}

struct Propagation<'a> {
    surface: &'a Triangulation,
    /// For each vertex, the half-edges leaving it (one per triangle corner).
    around: Vec<Vec<u32>>,
    /// Whether shortest paths may bend at the vertex (sources included: paths start
    /// there): such a vertex lights the triangles around it when settled.
    bends: Vec<bool>,
    /// Vertices some path has reached so far (for progress).
    reached: usize,
    distance: Vec<f64>,
    splits: Vec<Option<Split>>,
    queue: Queue,
    /// Windows that may still be propagated; at zero, paths continue along edges only.
    budget: usize,
}

impl<'a> Propagation<'a> {
    fn new(surface: &'a Triangulation) -> Self {
        let n = surface.vertex_count;
        let mut around = vec![Vec::new(); n];
        let mut bends = surface.boundary_vertices();
        let angle_sums = surface.angle_sums();
        for (f, face) in surface.faces.iter().enumerate() {
            let flat = surface.area(f)
                <= 1.0e-14
                    * surface.lengths[f]
                        .iter()
                        .fold(0.0, |m: f64, l| m.max(l * l));
            for k in 0..3 {
                around[face[k] as usize].push(half_edge(f, k));
                bends[face[k] as usize] |= flat;
            }
        }
        for (bend, sum) in bends.iter_mut().zip(angle_sums) {
            *bend |= sum > std::f64::consts::TAU * (1.0 + 1.0e-9);
        }
        Propagation {
            surface,
            around,
            bends,
            distance: vec![f64::INFINITY; n],
            reached: 0,
            splits: vec![None; surface.faces.len() * 3],
            queue: Queue::default(),
            budget: (WINDOWS_PER_FACE * surface.faces.len()).max(MIN_WINDOWS),
        }
    }

    fn run(mut self, sources: &[u32], mut progress: impl FnMut(usize, usize)) -> Vec<f64> {
        let n = self.surface.vertex_count;
        for &s in sources.iter().filter(|&&s| (s as usize) < n) {
            // A source lights its surroundings as a vertex where paths bend does.
            self.bends[s as usize] = true;
            self.lower(s, 0.0);
        }
        let mut reported = 0;
        while let Some((key, event)) = self.queue.pop() {
            if self.reached >= reported + 4096 {
                reported = self.reached;
                progress(reported.min(n), n);
            }
            match event {
                Ok(v) => {
                    if key <= self.distance[v as usize] {
                        self.emit_from_vertex(v);
                    }
                }
                Err(window) => {
                    if self.budget > 0 && self.useful(&window) {
                        self.budget -= 1;
                        if self.budget == 0 {
                            // Out of windows (a degenerate mesh): finish along edges from
                            // every vertex reached so far, so each reachable vertex gets
                            // an upper bound instead of staying infinite.
                            for (v, &d) in self.distance.iter().enumerate() {
                                if d.is_finite() {
                                    self.queue.push_vertex(d, v as u32);
                                }
                            }
                        }
                        self.propagate(&window);
                    }
                }
            }
        }
        progress(n, n);
        self.distance
    }

    /// Records a path of length `d` to `v` if it is shorter than the known one; a vertex
    /// that lights its surroundings (a source, a vertex where paths bend, every vertex
    /// once the windows run out) is queued to do so from there. Other vertices are never
    /// queued: windows alone carry paths past them (queuing them all put three vertex
    /// events in the queue per window, for nothing).
    fn lower(&mut self, v: u32, d: f64) {
        let known = self.distance[v as usize];
        if d < known {
            self.reached += usize::from(known == f64::INFINITY);
            self.distance[v as usize] = d;
            if self.bends[v as usize] || self.budget == 0 {
                self.queue.push_vertex(d, v);
            }
        }
    }

    fn push(&mut self, window: Window) {
        let wide = window.b1 - window.b0 > 1.0e-10 * self.surface.length(window.edge);
        if wide && self.useful(&window) {
            self.queue.push_window(window.nearest(), window);
        }
    }

    /// ICH's test: a window is useless when a known path to one end of its edge, followed
    /// along the edge, reaches the far end of the window sooner than the window does (then
    /// it does so for every point of the window).
    fn useful(&self, w: &Window) -> bool {
        let length = self.surface.length(w.edge);
        let tail = self.distance[self.surface.tail(w.edge) as usize];
        let head = self.distance[self.surface.head(w.edge) as usize];
        let beaten = |by: f64, window: f64| window > by * (1.0 + SLACK) + SLACK * length;
        !(beaten(tail + w.b1, w.distance_at(w.b1))
            || beaten(head + length - w.b0, w.distance_at(w.b0)))
    }

    /// A vertex where paths bend lights the far edge of every triangle around it, and
    /// its neighbours along the edges.
    fn emit_from_vertex(&mut self, v: u32) {
        let d = self.distance[v as usize];
        let windows = self.budget > 0;
        for i in 0..self.around[v as usize].len() {
            let h = self.around[v as usize][i];
            let (f, k) = split(h);
            let l = self.surface.lengths[f];
            let (next, previous) = (
                self.surface.faces[f][(k + 1) % 3],
                self.surface.faces[f][(k + 2) % 3],
            );
            self.lower(next, d + l[k]);
            self.lower(previous, d + l[(k + 2) % 3]);
            let far = half_edge(f, k + 1);
            let across = self.surface.twins[far as usize];
            if across == NO_TWIN || !windows {
                continue;
            }
            // In the frame of `across` (tail = previous, head = next), v lies below.
            let length = l[(k + 1) % 3];
            let (to_tail, to_head) = (l[(k + 2) % 3], l[k]);
            let x = (length * length + to_tail * to_tail - to_head * to_head) / (2.0 * length);
            let y = -(to_tail * to_tail - x * x).max(0.0).sqrt();
            self.push(Window {
                edge: across,
                b0: 0.0,
                b1: length,
                source: DVec2::new(x, y),
                sigma: d,
            });
        }
    }

    /// Pushes a window across its triangle onto the two far edges.
    fn propagate(&mut self, w: &Window) {
        let (f, k) = split(w.edge);
        let length = self.surface.lengths[f][k];
        let (l_bc, l_ca) = (
            self.surface.lengths[f][(k + 1) % 3],
            self.surface.lengths[f][(k + 2) % 3],
        );
        let cx = (length * length + l_ca * l_ca - l_bc * l_bc) / (2.0 * length);
        let cy = (l_ca * l_ca - cx * cx).max(0.0).sqrt();
        let (a, b, c) = (DVec2::ZERO, DVec2::new(length, 0.0), DVec2::new(cx, cy));
        let s = w.source;
        if cy <= 1.0e-12 * length || s.y >= -1.0e-12 * length {
            return; // a flat triangle or a grazing source: its vertices bend paths instead
        }
        let cross = s.x + (c.x - s.x) * (-s.y) / (c.y - s.y);
        // Paths through the window to the triangle's corners: exact where a corner is in
        // sight, valid upper bounds (bending at the window's end) everywhere.
        let corners = self.surface.faces[f];
        let seen = DVec2::new(cross.clamp(w.b0, w.b1), 0.0);
        let far_vertex = corners[(k + 2) % 3];
        self.lower(far_vertex, w.distance_at(seen.x) + seen.distance(c));
        self.lower(corners[k], w.distance_at(w.b0) + w.b0);
        self.lower(corners[(k + 1) % 3], w.distance_at(w.b1) + length - w.b1);
        let (mut left, mut right) = (cross > w.b0, cross < w.b1);
        if left && right {
            let through_c = w.sigma + s.distance(c);
            match self.splits[w.edge as usize] {
                Some(best) if through_c > best.distance * (1.0 + SLACK) => {
                    // A shorter path to c crosses the edge on one side: the children on
                    // that side would cross it and lose.
                    left = best.x > cross;
                    right = !left;
                }
                _ => {
                    self.splits[w.edge as usize] = Some(Split {
                        distance: through_c,
                        x: cross,
                    });
                }
            }
        }
        let ray = |x: f64, p: DVec2, q: DVec2| ray_hit(s, DVec2::new(x, 0.0), p, q);
        if right {
            // Onto edge b→c (half-edge k + 1): from where the ray through max(b0, cross)
            // lands (c itself on a split) to where the ray through b1 lands.
            let start = if left { 1.0 } else { ray(w.b0, b, c) };
            let end = ray(w.b1, b, c);
            self.child(w, half_edge(f, k + 1), b, c, end, start);
        }
        if left {
            let start = ray(w.b0, c, a);
            let end = if right { 0.0 } else { ray(w.b1, c, a) };
            self.child(w, half_edge(f, k + 2), c, a, end, start);
        }
    }

    /// The child window on half-edge `edge` (from `p` to `q` in the parent's frame), over
    /// the parameters `[t0, t1]` of `p + t(q − p)`, moved into the frame of the triangle
    /// across.
    fn child(&mut self, w: &Window, edge: u32, p: DVec2, q: DVec2, t0: f64, t1: f64) {
        let (t0, t1) = (t0.clamp(0.0, 1.0), t1.clamp(0.0, 1.0));
        let (t0, t1) = (t0.min(t1), t0.max(t1));
        let across = self.surface.twins[edge as usize];
        if across == NO_TWIN {
            return;
        }
        // The triangle across runs the edge from q to p, with this triangle below.
        let length = p.distance(q);
        let along = (p - q) / length;
        let relative = w.source - q;
        self.push(Window {
            edge: across,
            b0: (1.0 - t1) * length,
            b1: (1.0 - t0) * length,
            source: DVec2::new(relative.dot(along), relative.dot(along.perp())),
            sigma: w.sigma,
        });
    }
}

/// Where the ray from `from` through `through` meets the line `p + t(q − p)`, as `t`.
fn ray_hit(from: DVec2, through: DVec2, p: DVec2, q: DVec2) -> f64 {
    let direction = through - from;
    let edge = q - p;
    let denominator = direction.perp_dot(edge);
    if denominator.abs() < f64::MIN_POSITIVE {
        return 0.5;
    }
    (p - from).perp_dot(direction) / denominator
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Mesh;

    #[test]
    fn a_flat_grid_gives_straight_line_distances() {
        let mut mesh = Mesh::default();
        mesh.push_grid(12, 9, |u, v| ([u * 4.0, 0.0, v * 3.0], [0.0, 1.0, 0.0]));
        let surface = Triangulation::from_mesh(&mesh);
        let d = exact_distances(&surface, &[0], |_, _| {});
        for (v, p) in mesh.positions.iter().enumerate() {
            let expected = (p[0] * p[0] + p[2] * p[2]).sqrt() as f64;
            assert!(
                (d[v] - expected).abs() < 1e-5,
                "vertex {v}: {} vs {expected}",
                d[v]
            );
        }
    }

    #[test]
    fn ray_hits_are_parameters_along_the_edge() {
        let t = ray_hit(
            DVec2::new(0.0, -1.0),
            DVec2::new(0.0, 0.0),
            DVec2::new(-1.0, 1.0),
            DVec2::new(1.0, 1.0),
        );
        assert!((t - 0.5).abs() < 1e-12);
    }
}
