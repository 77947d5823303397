//! Finding which triangles of a plane layout a new one might overlap: a uniform grid of
//! square cells, each listing the triangles whose bounding boxes reach into it, and the
//! exact test of two triangles' interiors.

use glam::DVec2;
use rustc_hash::FxHashMap;

/// Triangles of a plane layout, by the grid cells their bounding boxes cover.
pub(super) struct TriangleGrid {
    cell: f64,
    cells: FxHashMap<(i64, i64), Vec<u32>>,
}

impl TriangleGrid {
    /// An empty grid of `cell`-wide cells.
    pub fn new(cell: f64) -> TriangleGrid {
        TriangleGrid {
            cell,
            cells: FxHashMap::default(),
        }
    }

    /// Files triangle `id` with these corners under every cell its bounding box covers.
    pub fn insert(&mut self, id: u32, corners: &[DVec2; 3]) {
        let (min, max) = bounds(corners);
        for key in self.keys(min, max) {
            self.cells.entry(key).or_default().push(id);
        }
    }

    /// The triangles filed under the cells that the bounding box of `corners` covers
    /// (one may come more than once).
    pub fn near(&self, corners: &[DVec2; 3]) -> impl Iterator<Item = u32> + '_ {
        let (min, max) = bounds(corners);
        self.near_box(min, max)
    }

    /// The triangles filed under the cells that the box from `min` to `max` covers (one
    /// may come more than once).
    pub fn near_box(&self, min: DVec2, max: DVec2) -> impl Iterator<Item = u32> + '_ {
        (self.keys(min, max))
            .filter_map(|key| self.cells.get(&key))
            .flatten()
            .copied()
    }

    /// The cells the box from `min` to `max` covers.
    fn keys(&self, min: DVec2, max: DVec2) -> impl Iterator<Item = (i64, i64)> + use<> {
        let [i0, j0, i1, j1] = [min.x, min.y, max.x, max.y].map(|x| (x / self.cell).floor() as i64);
        (i0..=i1).flat_map(move |i| (j0..=j1).map(move |j| (i, j)))
    }
}

/// The bounding box of a triangle: its lower and upper corners.
pub(super) fn bounds(corners: &[DVec2; 3]) -> (DVec2, DVec2) {
    (
        corners[0].min(corners[1]).min(corners[2]),
        corners[0].max(corners[1]).max(corners[2]),
    )
}

/// Whether the interiors of two counter-clockwise triangles overlap: no edge of either
/// has the whole other triangle on its outer side, up to `touch` (a distance within
/// which a corner counts as on the edge's line). Triangles sharing an edge or a corner
/// only touch.
pub(super) fn interiors_overlap(a: &[DVec2; 3], b: &[DVec2; 3], touch: f64) -> bool {
    let ((a_min, a_max), (b_min, b_max)) = (bounds(a), bounds(b));
    let boxes_meet = a_min.cmplt(b_max).all() && b_min.cmplt(a_max).all();
    boxes_meet && !(separates(a, b, touch) || separates(b, a, touch))
}

/// Whether the line of an edge of `a` has all of `b` on its outer side (or within
/// `touch` of the line).
fn separates(a: &[DVec2; 3], b: &[DVec2; 3], touch: f64) -> bool {
    (0..3).any(|k| {
        let (from, edge) = (a[k], a[(k + 1) % 3] - a[k]);
        // Distance × edge length, compared squared: no square root.
        let limit_squared = touch * touch * edge.length_squared();
        b.iter().all(|&p| {
            let outward = edge.perp_dot(p - from);
            outward <= 0.0 || outward * outward <= limit_squared
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn triangle(points: [[f64; 2]; 3]) -> [DVec2; 3] {
        points.map(DVec2::from)
    }

    #[test]
    fn triangles_overlap_only_when_their_interiors_meet() {
        let base = triangle([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
        let cases = [
            // Sharing the long edge, on its other side: they touch.
            ([[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]], false),
            // Sharing a corner only.
            ([[1.0, 0.0], [2.0, 0.0], [2.0, 1.0]], false),
            // A corner poking across the long edge.
            ([[0.4, 0.4], [1.0, 1.0], [0.0, 1.2]], true),
            // Apart, though the bounding boxes meet.
            ([[0.6, 0.6], [1.0, 0.6], [1.0, 1.0]], false),
            // One inside the other.
            ([[0.1, 0.1], [0.3, 0.1], [0.1, 0.3]], true),
            // The same triangle.
            ([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], true),
            // Crossing edges, no corner inside the other (a star of David).
            ([[-0.2, 0.3], [0.7, -0.2], [0.7, 0.8]], true),
        ];
        for (other, overlaps) in cases {
            let other = triangle(other);
            assert_eq!(
                interiors_overlap(&base, &other, 1e-12),
                overlaps,
                "{other:?}"
            );
            assert_eq!(
                interiors_overlap(&other, &base, 1e-12),
                overlaps,
                "{other:?}"
            );
        }
    }

    #[test]
    fn the_grid_finds_triangles_whose_boxes_share_a_cell() {
        let mut grid = TriangleGrid::new(1.0);
        grid.insert(7, &triangle([[0.2, 0.2], [2.5, 0.2], [0.2, 0.5]]));
        grid.insert(8, &triangle([[-3.0, -3.0], [-2.5, -3.0], [-3.0, -2.5]]));
        let near = |points| grid.near(&triangle(points)).collect::<Vec<_>>();
        assert_eq!(near([[2.1, 0.9], [2.2, 0.9], [2.1, 0.95]]), [7]);
        assert!(near([[5.0, 5.0], [6.0, 5.0], [5.0, 6.0]]).is_empty());
        assert_eq!(near([[-2.9, -2.9], [-2.8, -2.9], [-2.9, -2.8]]), [8]);
    }
}
