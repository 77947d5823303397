//! A bounding volume hierarchy over a mesh's triangles, for the rays mesh fields cast
//! (ambient occlusion, thickness): binned surface-area-heuristic splits, nodes in one
//! flat array, triangles copied into leaf order so a leaf's triangles sit together in
//! memory. Triangles with a non-finite corner are left out; triangles with no area never
//! hit.

use glam::{Vec3A, Vec4};
use smallvec::SmallVec;

/// The most triangles a leaf holds.
const LEAF_SIZE: usize = 4;
/// The number of bins a node's split is chosen among, along its longest axis.
const BINS: usize = 12;

/// How far outside its edges (in barycentric units) a ray still hits a triangle, so that
/// rounding cannot let a ray slip between two triangles that share an edge or through
/// the vertex where many meet.
const EDGE_SLACK: f32 = 1.0e-5;

/// A node as the build grows it: a box, and either two children (`count == 0`; the first
/// at `first`, the second right after it) or `count` triangles from `first` on.
#[derive(Clone, Copy, Debug)]
struct Node {
    min: Vec3A,
    max: Vec3A,
    first: u32,
    count: u32,
}

/// A [`Node`] packed into 32 bytes for the walk, `first` and `count` in the otherwise
/// unused fourth lanes of the corners.
#[derive(Clone, Copy, Debug)]
struct Packed {
    min: Vec4,
    max: Vec4,
}

impl Packed {
    fn new(node: &Node) -> Packed {
        Packed {
            min: node.min.extend(f32::from_bits(node.first)),
            max: node.max.extend(f32::from_bits(node.count)),
        }
    }

    fn first(&self) -> u32 {
        self.min.w.to_bits()
    }

    fn count(&self) -> u32 {
        self.max.w.to_bits()
    }
}

/// A triangle as the ray test wants it: a corner and the two edges from it.
#[derive(Clone, Copy, Debug)]
struct Triangle {
    corner: Vec3A,
    edge1: Vec3A,
    edge2: Vec3A,
}

/// A hierarchy over the triangles of an indexed mesh.
#[derive(Clone, Debug)]
pub struct Bvh {
    nodes: Vec<Packed>,
    triangles: Vec<Triangle>,
    /// The mesh triangle of each leaf-ordered triangle.
    source: Vec<u32>,
}

/// The nearest hit of a ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Distance along the (unit) ray.
    pub distance: f32,
    /// The mesh triangle hit (index into the triangle list).
    pub triangle: u32,
    /// Barycentric coordinates of the hit towards the triangle's second and third corners.
    pub barycentric: [f32; 2],
}

/// A ray prepared for box tests.
struct Ray {
    origin: Vec3A,
    direction: Vec3A,
    inverse: Vec3A,
}

impl Ray {
    fn new(origin: Vec3A, direction: Vec3A) -> Ray {
        Ray {
            origin,
            direction,
            inverse: direction.recip(),
        }
    }

    /// The distance at which the ray enters `node`'s box, if it does before `limit`.
    fn enters(&self, node: &Packed, limit: f32) -> Option<f32> {
        let t0 = (Vec3A::from_vec4(node.min) - self.origin) * self.inverse;
        let t1 = (Vec3A::from_vec4(node.max) - self.origin) * self.inverse;
        let near = t0.min(t1).max_element().max(0.0);
        let far = t0.max(t1).min_element().min(limit);
        // NaN (a zero direction component on a box face) compares false: no entry.
        (near <= far).then_some(near)
    }

    /// Möller–Trumbore, both faces: distance and barycentrics of a hit in (0, limit).
    fn hits(&self, triangle: &Triangle, limit: f32) -> Option<(f32, [f32; 2])> {
        let p = self.direction.cross(triangle.edge2);
        let determinant = triangle.edge1.dot(p);
        if determinant.abs() < f32::MIN_POSITIVE * 1.0e6 {
            return None;
        }
        let inverse = 1.0 / determinant;
        let s = self.origin - triangle.corner;
        let u = s.dot(p) * inverse;
        if !(-EDGE_SLACK..=1.0 + EDGE_SLACK).contains(&u) {
            return None;
        }
        let q = s.cross(triangle.edge1);
        let v = self.direction.dot(q) * inverse;
        if v < -EDGE_SLACK || u + v > 1.0 + EDGE_SLACK {
            return None;
        }
        let t = triangle.edge2.dot(q) * inverse;
        (t > 0.0 && t < limit).then_some((t, [u, v]))
    }
}

/// A box and the triangle centroids' box of a set of triangles, grown one at a time.
#[derive(Clone, Copy)]
struct Bounds {
    min: Vec3A,
    max: Vec3A,
}

impl Bounds {
    const EMPTY: Bounds = Bounds {
        min: Vec3A::splat(f32::INFINITY),
        max: Vec3A::splat(f32::NEG_INFINITY),
    };

    fn grow(&mut self, point: Vec3A) {
        self.min = self.min.min(point);
        self.max = self.max.max(point);
    }

    fn join(self, other: Bounds) -> Bounds {
        Bounds {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// Half the surface area (what the heuristic compares); 0 when empty.
    fn half_area(&self) -> f32 {
        let extent = (self.max - self.min).max(Vec3A::ZERO);
        extent.x * extent.y + extent.y * extent.z + extent.z * extent.x
    }
}

/// What the build keeps of each triangle.
#[derive(Clone, Copy)]
struct Item {
    bounds: Bounds,
    centroid: Vec3A,
    index: u32,
}

impl Bvh {
    /// A hierarchy over `indices` (three per triangle) into `positions`.
    pub fn new(positions: &[[f32; 3]], indices: &[u32]) -> Bvh {
        let corner = |i: u32| Vec3A::from(positions[i as usize]);
        let mut items: Vec<Item> = indices
            .chunks_exact(3)
            .enumerate()
            .filter_map(|(index, t)| {
                let [a, b, c] = [corner(t[0]), corner(t[1]), corner(t[2])];
                if !(a.is_finite() && b.is_finite() && c.is_finite()) {
                    return None;
                }
                let mut bounds = Bounds::EMPTY;
                [a, b, c].into_iter().for_each(|p| bounds.grow(p));
                Some(Item {
                    bounds,
                    centroid: (a + b + c) / 3.0,
                    index: index as u32,
                })
            })
            .collect();
        let mut nodes = Vec::with_capacity(2 * items.len() / LEAF_SIZE + 1);
        nodes.push(Node {
            min: Vec3A::ZERO,
            max: Vec3A::ZERO,
            first: 0,
            count: 0,
        });
        let mut pending = vec![(0usize, 0usize, items.len())];
        while let Some((node, start, end)) = pending.pop() {
            let bounds = items[start..end]
                .iter()
                .fold(Bounds::EMPTY, |b, item| b.join(item.bounds));
            nodes[node].min = bounds.min;
            nodes[node].max = bounds.max;
            match split(&mut items[start..end]) {
                Some(middle) => {
                    let left = nodes.len();
                    for _ in 0..2 {
                        nodes.push(nodes[node]);
                    }
                    nodes[node].first = left as u32;
                    nodes[node].count = 0;
                    pending.push((left, start, start + middle));
                    pending.push((left + 1, start + middle, end));
                }
                None => {
                    nodes[node].first = start as u32;
                    nodes[node].count = (end - start) as u32;
                }
            }
        }
        // An empty mesh: a root no ray enters.
        if items.is_empty() {
            nodes[0].min = Vec3A::splat(f32::INFINITY);
            nodes[0].max = Vec3A::splat(f32::NEG_INFINITY);
            nodes[0].count = 0;
            nodes[0].first = u32::MAX;
        }
        let triangles = items
            .iter()
            .map(|item| {
                let t = &indices[3 * item.index as usize..][..3];
                let [a, b, c] = [corner(t[0]), corner(t[1]), corner(t[2])];
                Triangle {
                    corner: a,
                    edge1: b - a,
                    edge2: c - a,
                }
            })
            .collect();
        Bvh {
            nodes: nodes.iter().map(Packed::new).collect(),
            triangles,
            source: items.iter().map(|item| item.index).collect(),
        }
    }

    /// Whether a ray from `origin` along the unit `direction` hits a triangle closer than
    /// `limit`. The walk goes on past a hit with the limit cut to it rather than stopping
    /// there: `benches/ray_casting.rs` measured stopping at the first hit 20% slower, as the
    /// early exit compiled to a slower walk for the rays that miss, most of them.
    pub fn occluded(&self, origin: [f32; 3], direction: [f32; 3], limit: f32) -> bool {
        let ray = Ray::new(origin.into(), direction.into());
        self.walk(&ray, limit, |_, triangle, limit| {
            ray.hits(triangle, limit).map(|(t, _)| t)
        })
    }

    /// The nearest triangle a ray from `origin` along the unit `direction` hits closer
    /// than `limit`.
    pub fn nearest(&self, origin: [f32; 3], direction: [f32; 3], limit: f32) -> Option<Hit> {
        let ray = Ray::new(origin.into(), direction.into());
        let mut nearest: Option<(f32, usize, [f32; 2])> = None;
        self.walk(&ray, limit, |index, triangle, limit| {
            let (t, barycentric) = ray.hits(triangle, limit)?;
            nearest = Some((t, index, barycentric));
            Some(t)
        });
        nearest.map(|(distance, index, barycentric)| Hit {
            distance,
            triangle: self.source[index],
            barycentric,
        })
    }

    /// Visits the triangles of the leaves the ray enters before `limit`, nearer boxes
    /// first; `visit` gets each one's leaf-ordered index and returns the hit's distance,
    /// the new limit, when the triangle was hit. Returns whether anything was hit.
    /// Inlined into each query: left to the compiler, `benches/ray_casting.rs` measured
    /// the walks 5–10% slower.
    #[inline(always)]
    fn walk(
        &self,
        ray: &Ray,
        mut limit: f32,
        mut visit: impl FnMut(usize, &Triangle, f32) -> Option<f32>,
    ) -> bool {
        if self.nodes[0].first() == u32::MAX {
            return false;
        }
        let Some(entry) = ray.enters(&self.nodes[0], limit) else {
            return false;
        };
        // Nodes still to walk with the distance at which the ray enters them, so a node
        // is skipped unopened once a nearer hit has cut the limit below its entry. Kept
        // on the stack for trees up to 64 deep (the heap only past that).
        let mut stack: SmallVec<[(u32, f32); 64]> = SmallVec::new();
        stack.push((0, entry));
        let mut found = false;
        while let Some((next, entry)) = stack.pop() {
            if entry > limit {
                continue;
            }
            let node = &self.nodes[next as usize];
            if node.count() > 0 {
                let first = node.first() as usize;
                for index in first..first + node.count() as usize {
                    if let Some(hit) = visit(index, &self.triangles[index], limit) {
                        limit = hit;
                        found = true;
                    }
                }
                continue;
            }
            let (left, right) = (node.first(), node.first() + 1);
            let near_left = ray.enters(&self.nodes[left as usize], limit);
            let near_right = ray.enters(&self.nodes[right as usize], limit);
            // Push the farther child first so the nearer one is walked first.
            match (near_left, near_right) {
                (Some(l), Some(r)) if l <= r => stack.extend([(right, r), (left, l)]),
                (Some(l), Some(r)) => stack.extend([(left, l), (right, r)]),
                (Some(l), None) => stack.push((left, l)),
                (None, Some(r)) => stack.push((right, r)),
                (None, None) => {}
            }
        }
        found
    }

    /// The number of triangles the hierarchy holds (those with finite corners).
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }
}

/// Splits `items` in two by the cheapest of the binned planes along the centroids'
/// longest axis, returning the size of the first part; `None` when a leaf is cheaper or
/// every centroid is the same point. Sets larger than a leaf whose centroids coincide
/// are halved in order, so no leaf grows past a bounded size on degenerate meshes.
fn split(items: &mut [Item]) -> Option<usize> {
    if items.len() <= LEAF_SIZE {
        return None;
    }
    let mut centroids = Bounds::EMPTY;
    items.iter().for_each(|item| centroids.grow(item.centroid));
    let extent = centroids.max - centroids.min;
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    if !(extent[axis] > 0.0) {
        return (items.len() > 4 * LEAF_SIZE).then_some(items.len() / 2);
    }
    let bin_of = |item: &Item| {
        let relative = (item.centroid[axis] - centroids.min[axis]) / extent[axis];
        ((relative * BINS as f32) as usize).min(BINS - 1)
    };
    let mut bins = [(Bounds::EMPTY, 0usize); BINS];
    for item in items.iter() {
        let bin = &mut bins[bin_of(item)];
        bin.0 = bin.0.join(item.bounds);
        bin.1 += 1;
    }
    // Cost of each plane between bins k and k + 1: area × count on both sides.
    let mut below = [0.0f32; BINS - 1];
    let (mut bounds, mut count) = (Bounds::EMPTY, 0);
    for k in 0..BINS - 1 {
        bounds = bounds.join(bins[k].0);
        count += bins[k].1;
        below[k] = bounds.half_area() * count as f32;
    }
    let (mut bounds, mut count) = (Bounds::EMPTY, 0);
    let mut best = (f32::INFINITY, 0);
    for k in (0..BINS - 1).rev() {
        bounds = bounds.join(bins[k + 1].0);
        count += bins[k + 1].1;
        let cost = below[k] + bounds.half_area() * count as f32;
        if cost < best.0 {
            best = (cost, k);
        }
    }
    let whole = items
        .iter()
        .fold(Bounds::EMPTY, |b, item| b.join(item.bounds));
    let leaf_cost = whole.half_area() * items.len() as f32;
    if best.0 >= leaf_cost && items.len() <= 4 * LEAF_SIZE {
        return None;
    }
    let mut middle = 0;
    for k in 0..items.len() {
        if bin_of(&items[k]) <= best.1 {
            items.swap(k, middle);
            middle += 1;
        }
    }
    match middle {
        0 => None,
        m if m == items.len() => None,
        m => Some(m),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Mesh;

    /// The nearest hit by testing every triangle, for comparison.
    fn brute_force(mesh: &Mesh, origin: Vec3A, direction: Vec3A, limit: f32) -> Option<f32> {
        let ray = Ray::new(origin, direction);
        mesh.indices
            .chunks_exact(3)
            .filter_map(|t| {
                let [a, b, c] = [0, 1, 2].map(|k| Vec3A::from(mesh.positions[t[k] as usize]));
                let triangle = Triangle {
                    corner: a,
                    edge1: b - a,
                    edge2: c - a,
                };
                ray.hits(&triangle, limit).map(|(t, _)| t)
            })
            .min_by(f32::total_cmp)
    }

    #[test]
    fn nearest_hits_and_occlusion_agree_with_testing_every_triangle() {
        let mesh = crate::mesh::primitive("torus:40").unwrap();
        let bvh = Bvh::new(&mesh.positions, &mesh.indices);
        assert_eq!(bvh.triangle_count(), mesh.triangle_count());
        let mut state = 7u32;
        let mut next = || {
            state = state.wrapping_mul(747796405).wrapping_add(2891336453);
            (state >> 8) as f32 / (1 << 24) as f32 * 2.0 - 1.0
        };
        for _ in 0..2000 {
            let origin = Vec3A::new(next(), next(), next()) * 1.5;
            let direction = Vec3A::new(next(), next(), next()).normalize_or(Vec3A::X);
            let limit = 0.2 + 2.0 * next().abs();
            let expected = brute_force(&mesh, origin, direction, limit);
            let hit = bvh.nearest(origin.into(), direction.into(), limit);
            assert_eq!(hit.map(|h| h.distance), expected);
            assert_eq!(
                bvh.occluded(origin.into(), direction.into(), limit),
                expected.is_some()
            );
            if let Some(hit) = hit {
                let t = &mesh.indices[3 * hit.triangle as usize..][..3];
                let [a, b, c] = [0, 1, 2].map(|k| Vec3A::from(mesh.positions[t[k] as usize]));
                let [u, v] = hit.barycentric;
                let on_triangle = a + (b - a) * u + (c - a) * v;
                assert!((on_triangle - (origin + direction * hit.distance)).length() < 1e-4);
            }
        }
    }

    #[test]
    fn degenerate_and_empty_meshes_build_and_are_never_hit() {
        let empty = Bvh::new(&[], &[]);
        assert!(!empty.occluded([0.0; 3], [0.0, 0.0, 1.0], 10.0));
        let flat = [[0.0f32; 3]; 64];
        let indices: Vec<u32> = (0..63).flat_map(|i| [i, i + 1, i]).collect();
        let bvh = Bvh::new(&flat, &indices);
        assert!(!bvh.occluded([0.0, 0.0, -1.0], [0.0, 0.0, 1.0], 10.0));
        let broken = [[f32::NAN, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        assert_eq!(Bvh::new(&broken, &[0, 1, 2]).triangle_count(), 0);
    }
}
