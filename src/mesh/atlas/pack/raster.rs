//! Packing charts by their shapes on a grid of cells: at a trial scale each chart is
//! rasterised (every cell it touches) in each of its four quarter turns and placed where
//! it first fits, scanning rows upwards and cells rightwards, in the turn that reaches
//! least high; a placed chart reserves its cells grown by the gap, so the next keeps
//! clear of it. Larger charts go first, so smaller ones fill what is left round and
//! inside them. The scale is the largest that fits, found by bisection from one known
//! to fit (the shelves') up to the one at which the charts would cover the square.

use super::bitmap::Bitmap;
use super::{Layout, Placement, Turn};
use glam::DVec2;

/// Bisection steps between a scale that fits and the scale at which the charts would
/// cover the square exactly.
const BISECTIONS: usize = 6;

/// Lays out charts (triangles in their planes, convex hulls, smallest boxes) on a grid
/// of `resolution`² cells with `gap` (rounded up to whole cells) between them, at a
/// scale of at least `at_least`, or `None` when they do not fit there.
pub(super) fn pack(
    charts: &[Vec<[DVec2; 3]>],
    hulls: &[Vec<DVec2>],
    lying: &[Turn],
    gap: f64,
    resolution: u32,
    at_least: f64,
) -> Option<Layout> {
    let turns: Vec<[Turn; 4]> = (lying.iter().zip(hulls))
        .map(|(&turn, hull)| {
            let half = turn.quarter(hull).quarter(hull);
            [turn, turn.quarter(hull), half, half.quarter(hull)]
        })
        .collect();
    let areas: Vec<f64> = (charts.iter())
        .map(|triangles| {
            (triangles.iter())
                .map(|c| 0.5 * (c[1] - c[0]).perp_dot(c[2] - c[0]))
                .sum()
        })
        .collect();
    let mut order: Vec<usize> = (0..charts.len()).collect();
    order.sort_by(|&a, &b| areas[b].total_cmp(&areas[a]).then(a.cmp(&b)));
    let resolution = resolution as usize;
    let gap = (gap * resolution as f64).ceil() as usize;
    let attempt = |scale: f64| -> Option<Vec<Placement>> {
        let mut atlas = Atlas::new(resolution, gap);
        let mut placements: Vec<Option<Placement>> = vec![None; charts.len()];
        let cells = scale * resolution as f64;
        for &chart in &order {
            let (turn, x, y) = atlas.place(&charts[chart], &turns[chart], cells)?;
            let corner = DVec2::new(x as f64, y as f64) / resolution as f64;
            placements[chart] = Some(Placement { turn, corner });
        }
        placements.into_iter().collect()
    };
    let total: f64 = areas.iter().sum();
    let covering = if total > 0.0 {
        total.recip().sqrt()
    } else {
        1.0
    };
    let (mut low, mut high) = (at_least, covering.max(at_least));
    let mut placements = attempt(low)?;
    for _ in 0..BISECTIONS {
        let middle = 0.5 * (low + high);
        if let Some(fitting) = attempt(middle) {
            (low, placements) = (middle, fitting);
        } else {
            high = middle;
        }
    }
    Some(Layout {
        scale: low,
        placements,
    })
}

/// The grid charts are placed on: the unit square's `resolution`² cells, with `gap`
/// cells more on every side so that the cells a chart reserves round itself always lie
/// on the grid. Cells outside the square, and those within half the gap (rounded up) of
/// its edges, start taken.
struct Atlas {
    taken: Bitmap,
    gap: usize,
    /// Free cells in each row, and the first and last free one (columns, `usize::MAX`
    /// and 0 when none).
    free: Vec<usize>,
    first_free: Vec<usize>,
    last_free: Vec<usize>,
}

impl Atlas {
    fn new(resolution: usize, gap: usize) -> Atlas {
        let side = resolution + 2 * gap;
        let mut taken = Bitmap::new(side, side);
        let usable = gap + gap.div_ceil(2)..(gap + resolution).saturating_sub(gap.div_ceil(2));
        for j in 0..side {
            for i in 0..side {
                if !usable.contains(&i) || !usable.contains(&j) {
                    taken.set(i, j);
                }
            }
        }
        let mut atlas = Atlas {
            taken,
            gap,
            free: vec![0; side],
            first_free: vec![0; side],
            last_free: vec![0; side],
        };
        (0..side).for_each(|j| atlas.count_free(j));
        atlas
    }

    /// Recounts the free cells of row `j`.
    fn count_free(&mut self, j: usize) {
        let row = self.taken.row(j);
        let width = self.taken.width;
        let free_in = |word: usize| {
            let bits = !row[word];
            let valid = (width - 64 * word).min(64);
            if valid == 64 {
                bits
            } else {
                bits & ((1u64 << valid) - 1)
            }
        };
        self.free[j] = (0..row.len())
            .map(|w| free_in(w).count_ones() as usize)
            .sum();
        self.first_free[j] = (0..row.len())
            .find(|&w| free_in(w) != 0)
            .map_or(usize::MAX, |w| {
                64 * w + free_in(w).trailing_zeros() as usize
            });
        self.last_free[j] = (0..row.len())
            .rev()
            .find(|&w| free_in(w) != 0)
            .map_or(0, |w| 64 * w + 63 - free_in(w).leading_zeros() as usize);
    }

    /// Places chart `triangles` at `cells` cells to its unit where it fits best (the
    /// turn reaching least high, then lowest, then leftmost), reserving its cells and
    /// the gap round them: its turn and its lower corner in the square's cells, or
    /// `None` when it fits nowhere.
    fn place(
        &mut self,
        triangles: &[[DVec2; 3]],
        turns: &[Turn; 4],
        cells: f64,
    ) -> Option<(Turn, usize, usize)> {
        let mut best: Option<(usize, Turn, usize, usize, Bitmap)> = None;
        for turn in turns {
            let mask = rasterise(triangles, turn, cells, self.taken.width)?;
            // Only spots lower than the best so far are worth a look.
            let top_limit = best.as_ref().map_or(usize::MAX, |b| b.0);
            if let Some((x, y)) = self.first_fit(&mask, top_limit) {
                best = Some((y + mask.height, *turn, x, y, mask));
            }
        }
        let (_, turn, x, y, mask) = best?;
        // The reserved cells start `gap` cells before the chart's, which lie `gap`
        // cells into the grid from the square's.
        let (x, y) = (x - self.gap, y - self.gap);
        let reserved = mask.dilated(self.gap);
        self.taken.or_at(&reserved, x, y);
        (y..y + reserved.height).for_each(|j| self.count_free(j));
        Some((turn, x, y))
    }

    /// The lowest, then leftmost, spot (on the grid) where `mask` meets no taken cell,
    /// below `top_limit` (its top row under it), if any. Rows are passed over without
    /// looking at spots when some row of the mask has more cells than the grid's row it
    /// would lie on has free, and spots where a row's first or last cell would miss its
    /// row's free stretch are skipped.
    fn first_fit(&self, mask: &Bitmap, top_limit: usize) -> Option<(usize, usize)> {
        let side = self.taken.width;
        let spans = mask.spans();
        let last_y = side.checked_sub(mask.height)?;
        let last_x = side.checked_sub(mask.width)?;
        for y in 0..=last_y {
            if y + mask.height >= top_limit {
                break;
            }
            let mut range = Some((0, last_x));
            for (j, span) in spans.iter().enumerate() {
                let (Some((low, high)), Some((count, first, last))) = (range, span) else {
                    continue;
                };
                let row = y + j;
                range = (self.free[row] >= *count && self.first_free[row] != usize::MAX)
                    .then(|| {
                        let high = high.min(self.last_free[row].checked_sub(*last)?);
                        Some((low.max(self.first_free[row].saturating_sub(*first)), high))
                    })
                    .flatten()
                    .filter(|(low, high)| low <= high);
            }
            let Some((low, high)) = range else {
                continue;
            };
            if let Some(x) = (low..=high).find(|&x| self.taken.fits(mask, x, y)) {
                return Some((x, y));
            }
        }
        None
    }
}

/// The cells (`cells` to a unit of the turned chart, the box's lower corner at 0) that
/// the triangles of a chart turned by `turn` touch; `None` when they span `limit` cells
/// or more.
fn rasterise(triangles: &[[DVec2; 3]], turn: &Turn, cells: f64, limit: usize) -> Option<Bitmap> {
    let extent = turn.size * cells;
    if extent.max_element() >= limit as f64 {
        return None;
    }
    let (width, height) = (extent.x as usize + 1, extent.y as usize + 1);
    let mut bitmap = Bitmap::new(width, height);
    for triangle in triangles {
        let corners = triangle.map(|p| turn.apply(p) * cells);
        let (min, max) = super::super::grid::bounds(&corners);
        let [i0, j0] = [min.x, min.y].map(|v| v.floor().max(0.0) as usize);
        let i1 = (max.x.floor().max(0.0) as usize).min(width - 1);
        let j1 = (max.y.floor().max(0.0) as usize).min(height - 1);
        for j in j0..=j1 {
            for i in i0..=i1 {
                if touches(&corners, i as f64, j as f64) {
                    bitmap.set(i, j);
                }
            }
        }
    }
    Some(bitmap)
}

/// Whether the counter-clockwise triangle `corners` touches the cell from (i, j) to
/// (i + 1, j + 1), grown by a millionth of a cell against rounding: no edge has the
/// whole cell outside it (a triangle with no area touches every cell of its box).
fn touches(corners: &[DVec2; 3], i: f64, j: f64) -> bool {
    const GROWTH: f64 = 1e-6;
    let cell = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)].map(|(di, dj)| {
        DVec2::new(
            i + di * (1.0 + 2.0 * GROWTH) - GROWTH,
            j + dj * (1.0 + 2.0 * GROWTH) - GROWTH,
        )
    });
    (0..3).all(|k| {
        let (from, edge) = (corners[k], corners[(k + 1) % 3] - corners[k]);
        cell.iter().any(|&p| edge.perp_dot(p - from) >= 0.0)
    })
}

#[cfg(test)]
mod tests {
    use super::super::{convex_hull, placed_boxes};
    use super::*;

    #[test]
    fn every_point_of_a_triangle_lies_in_a_cell_it_touches() {
        let triangle = [
            DVec2::new(0.3, 0.2),
            DVec2::new(9.7, 3.1),
            DVec2::new(2.2, 6.9),
        ];
        let hull = convex_hull(&triangle);
        let turn = Turn::lying(&hull);
        let bitmap = rasterise(&[triangle], &turn, 8.0, 1000).expect("fits");
        let cells = (0..bitmap.height)
            .flat_map(|j| (0..bitmap.width).map(move |i| (i, j)))
            .filter(|&(i, j)| bitmap.row(j)[i / 64] >> (i % 64) & 1 == 1)
            .count();
        for a in 0..=20 {
            for b in 0..=20 - a {
                let (u, v) = (a as f64 / 20.0, b as f64 / 20.0);
                let point =
                    triangle[0] + u * (triangle[1] - triangle[0]) + v * (triangle[2] - triangle[0]);
                let cell = (turn.apply(point) * 8.0).floor().as_uvec2();
                let (i, j) = (cell.x as usize, cell.y as usize);
                assert!(
                    bitmap.row(j)[i / 64] >> (i % 64) & 1 == 1,
                    "{point} in cell {i}, {j}"
                );
            }
        }
        // Touched cells, not the whole box: the triangle covers about half of it.
        assert!(cells < bitmap.width * bitmap.height * 3 / 4, "{cells}");
    }

    #[test]
    fn a_small_chart_goes_into_the_hole_of_a_ring() {
        // A square ring (outer side 4, hole of side 2) and a small square of side 1.
        let quad = |a: DVec2, b: DVec2, c: DVec2, d: DVec2| vec![[a, b, c], [a, c, d]];
        let p = |x: f64, y: f64| DVec2::new(x, y);
        let ring: Vec<[DVec2; 3]> = [
            quad(p(0.0, 0.0), p(4.0, 0.0), p(4.0, 1.0), p(0.0, 1.0)),
            quad(p(0.0, 3.0), p(4.0, 3.0), p(4.0, 4.0), p(0.0, 4.0)),
            quad(p(0.0, 1.0), p(1.0, 1.0), p(1.0, 3.0), p(0.0, 3.0)),
            quad(p(3.0, 1.0), p(4.0, 1.0), p(4.0, 3.0), p(3.0, 3.0)),
        ]
        .concat();
        let small = quad(p(10.0, 10.0), p(11.0, 10.0), p(11.0, 11.0), p(10.0, 11.0));
        let charts = vec![ring, small];
        let hulls: Vec<Vec<DVec2>> = charts
            .iter()
            .map(|c| convex_hull(c.as_flattened()))
            .collect();
        let lying: Vec<Turn> = hulls.iter().map(|h| Turn::lying(h)).collect();
        // From the scale the shelves reach, which puts the square beside the ring.
        let (shelves, _) = super::super::shelf::pack(&lying, 1.0 / 64.0);
        let layout = pack(&charts, &hulls, &lying, 1.0 / 64.0, 64, shelves.scale).expect("fits");
        assert!(
            layout.scale > shelves.scale * 1.2,
            "{} {}",
            layout.scale,
            shelves.scale
        );
        let outlines: Vec<Vec<DVec2>> = charts.iter().map(|c| c.as_flattened().to_vec()).collect();
        let boxes = placed_boxes(&layout, &outlines);
        // The ring fills most of the square's side, and the small square lies in its
        // hole, a gap from its inner edges.
        let (ring_box, small_box) = (boxes[0], boxes[1]);
        assert!(layout.scale * 4.0 > 0.85, "{}", layout.scale);
        let inner = (ring_box.0 + layout.scale, ring_box.1 - layout.scale);
        let apart = (small_box.0 - inner.0)
            .min(inner.1 - small_box.1)
            .min_element();
        assert!(apart >= 1.0 / 64.0 - 1e-12, "{boxes:?}");
    }
}
