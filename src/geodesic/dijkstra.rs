//! The cheap baseline: shortest paths along mesh edges (Dijkstra). Always an upper bound
//! of the true geodesic distance; too long by up to ~8% on regular grids where paths
//! must zigzag (the accuracy reports compare it with the exact method).

use crate::mesh::Mesh;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

#[derive(PartialEq)]
struct Visit {
    distance: f64,
    vertex: u32,
}

impl Eq for Visit {}

impl Ord for Visit {
    fn cmp(&self, other: &Visit) -> Ordering {
        other
            .distance
            .total_cmp(&self.distance)
            .then_with(|| other.vertex.cmp(&self.vertex))
    }
}

impl PartialOrd for Visit {
    fn partial_cmp(&self, other: &Visit) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// Edge-path distances from `sources` to every vertex of `mesh`, calling
/// `progress(vertices settled, vertices)` every few thousand vertices.
pub fn edge_distances(
    mesh: &Mesh,
    sources: &[u32],
    mut progress: impl FnMut(usize, usize),
) -> Vec<f64> {
    let count = mesh.positions.len();
    let mut neighbours: Vec<Vec<(u32, f64)>> = vec![Vec::new(); count];
    let position = |i: u32| glam::DVec3::from(mesh.positions[i as usize].map(f64::from));
    for triangle in mesh.indices.chunks_exact(3) {
        for k in 0..3 {
            let (a, b) = (triangle[k], triangle[(k + 1) % 3]);
            if a != b {
                let length = position(a).distance(position(b));
                neighbours[a as usize].push((b, length));
                neighbours[b as usize].push((a, length));
            }
        }
    }
    let mut distance = vec![f64::INFINITY; count];
    let mut heap = BinaryHeap::new();
    for &source in sources.iter().filter(|&&s| (s as usize) < count) {
        distance[source as usize] = 0.0;
        heap.push(Visit {
            distance: 0.0,
            vertex: source,
        });
    }
    let mut settled = 0;
    while let Some(Visit {
        distance: d,
        vertex,
    }) = heap.pop()
    {
        if d > distance[vertex as usize] {
            continue;
        }
        settled += 1;
        if settled % 4096 == 0 {
            progress(settled, count);
        }
        for &(next, length) in &neighbours[vertex as usize] {
            let candidate = d + length;
            if candidate < distance[next as usize] {
                distance[next as usize] = candidate;
                heap.push(Visit {
                    distance: candidate,
                    vertex: next,
                });
            }
        }
    }
    progress(count, count);
    distance
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(n: u32) -> Mesh {
        let mut mesh = Mesh::default();
        mesh.push_grid(n, n, |u, v| ([u, 0.0, v], [0.0, 1.0, 0.0]));
        mesh
    }

    #[test]
    fn distances_along_an_axis_are_exact_and_diagonals_are_upper_bounds() {
        let mesh = grid(10);
        let d = edge_distances(&mesh, &[0], |_, _| {});
        assert!((d[10] - 1.0).abs() < 1e-6, "along the x edge row");
        let corner = d[120];
        assert!(
            corner >= 2f64.sqrt() - 1e-6 && corner <= 2.0 + 1e-6,
            "the far corner: {corner}"
        );
    }

    #[test]
    fn several_sources_give_the_minimum_and_unreached_vertices_are_infinite() {
        let mut mesh = grid(4);
        let apart = mesh.push_vertex([9.0, 9.0, 9.0], [0.0, 1.0, 0.0], [0.0, 0.0]);
        let one = edge_distances(&mesh, &[0], |_, _| {});
        let two = edge_distances(&mesh, &[0, 24], |_, _| {});
        assert!(two.iter().zip(&one).all(|(a, b)| a <= b));
        assert_eq!(two[24], 0.0);
        assert!(one[apart as usize].is_infinite() && !one[apart as usize].is_nan());
        let normalized = crate::geodesic::normalized(&one);
        assert!((crate::geodesic::max_finite(&normalized) - 1.0).abs() < 1e-12);
        assert!(normalized[apart as usize].is_infinite());
    }
}
