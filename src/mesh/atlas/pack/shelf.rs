//! Packing charts by their bounding rectangles in shelves: rows filled left to right,
//! tallest first, each rectangle padded by half the gap on every side, at the largest
//! scale that fits (found by bisection). The gap is halved as often as it takes for
//! the gaps alone to fit.

use super::{Layout, Placement, Turn};
use glam::DVec2;

/// Lays out charts turned by `turns` by their rectangles: the layout and the gap kept.
pub(super) fn pack(turns: &[Turn], gap: f64) -> (Layout, f64) {
    let sizes: Vec<DVec2> = turns.iter().map(|turn| turn.size).collect();
    let mut order: Vec<usize> = (0..sizes.len()).collect();
    order.sort_by(|&a, &b| {
        (sizes[b].y.total_cmp(&sizes[a].y))
            .then(sizes[b].x.total_cmp(&sizes[a].x))
            .then(a.cmp(&b))
    });
    let mut gap = gap;
    while shelves(&sizes, &order, 0.0, gap).is_none() {
        gap *= 0.5;
    }
    // The scale at which the charts would fill the square with no gaps bounds it above.
    let area: f64 = sizes.iter().map(|s| s.x * s.y).sum();
    let longest = sizes.iter().map(|s| s.x).fold(0.0, f64::max);
    let mut high = (1.0 / area.sqrt()).min(1.0 / longest);
    if !high.is_finite() {
        // Nothing but points: any scale places them.
        high = 1.0;
    }
    let mut low = 0.0;
    if shelves(&sizes, &order, high, gap).is_some() {
        low = high;
    }
    for _ in 0..60 {
        if high - low <= high * 1e-12 {
            break;
        }
        let middle = 0.5 * (low + high);
        match shelves(&sizes, &order, middle, gap) {
            Some(_) => low = middle,
            None => high = middle,
        }
    }
    let corners = shelves(&sizes, &order, low, gap).expect("the scale was found to fit");
    let placements = (turns.iter().zip(corners))
        .map(|(&turn, corner)| Placement { turn, corner })
        .collect();
    let layout = Layout {
        scale: low,
        placements,
    };
    (layout, gap)
}

/// The lower corners of boxes of `sizes` × `scale` laid in rows (shelves) in `order`,
/// each box padded by half of `gap` on every side, or `None` when they overflow the
/// unit square.
fn shelves(sizes: &[DVec2], order: &[usize], scale: f64, gap: f64) -> Option<Vec<DVec2>> {
    let mut corners = vec![DVec2::ZERO; sizes.len()];
    let (mut x, mut shelf_y, mut shelf_height) = (0.0, 0.0, 0.0f64);
    for &chart in order {
        let padded = sizes[chart] * scale + gap;
        if padded.x > 1.0 {
            return None;
        }
        if x + padded.x > 1.0 {
            shelf_y += shelf_height;
            (x, shelf_height) = (0.0, 0.0);
        }
        corners[chart] = DVec2::new(x, shelf_y) + 0.5 * gap;
        x += padded.x;
        shelf_height = shelf_height.max(padded.y);
    }
    (shelf_y + shelf_height <= 1.0).then_some(corners)
}

#[cfg(test)]
mod tests {
    use super::super::{convex_hull, placed_boxes, smallest_gap};
    use super::*;

    fn layout(outlines: &[Vec<DVec2>], gap: f64) -> Layout {
        let turns: Vec<Turn> = (outlines.iter())
            .map(|outline| Turn::lying(&convex_hull(outline)))
            .collect();
        pack(&turns, gap).0
    }

    #[test]
    fn boxes_are_packed_apart_inside_the_square_at_a_common_scale() {
        let square = |side: f64, at: f64| {
            [(0.0, 0.0), (side, 0.0), (side, side), (0.0, side)]
                .map(|(x, y)| DVec2::new(x + at, y - at))
                .to_vec()
        };
        let outlines = vec![
            square(1.0, 3.0),
            square(2.0, -1.0),
            square(0.5, 0.0),
            vec![DVec2::ZERO],
        ];
        let gap = 0.05;
        let layout = layout(&outlines, gap);
        let boxes = placed_boxes(&layout, &outlines);
        assert_eq!(smallest_gap(&boxes), gap);
        // Sides 2 and 1 fill the first shelf (3 × 0.3 + two gaps of 0.05), the rest
        // go on a second.
        assert!((layout.scale - 0.3).abs() < 1e-9, "{}", layout.scale);
        let side = boxes[1].1 - boxes[1].0;
        assert!((side - DVec2::splat(2.0 * layout.scale)).length() < 1e-9);
    }

    #[test]
    fn a_gap_too_wide_for_the_square_is_narrowed_until_the_charts_fit() {
        let outlines: Vec<Vec<DVec2>> = (0..100)
            .map(|_| vec![DVec2::ZERO, DVec2::X, DVec2::Y])
            .collect();
        let layout = layout(&outlines, 0.5);
        // 0.5 halved three times: 16 boxes of 1/16 to a shelf, 7 shelves.
        let gap = smallest_gap(&placed_boxes(&layout, &outlines));
        assert!((gap - 0.0625).abs() < 1e-9, "{gap}");
        assert!(layout.scale > 0.0);
    }
}
