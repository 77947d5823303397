//! Packing charts into the unit square at one scale, the largest that fits, with `gap`
//! between charts and half of it to the square's edges (so that wrapping textures keep
//! the gap too). Each chart is first turned to the smallest rectangle round it (over
//! the directions of its convex hull's edges). Charts are packed by their shapes on a
//! grid of cells ([`raster`]), so that they interlock and small ones fill the holes of
//! large ones, unless their rectangles laid in shelves ([`shelf`]) fit at a larger
//! scale (as when more charts come than the grid holds).

mod bitmap;
mod raster;
mod shelf;

use glam::DVec2;

/// Where each chart goes: `place(chart, point)` maps a point of the chart's plane into
/// the unit square.
pub(super) struct Layout {
    /// UV units per unit of the charts' planes, the same for every chart.
    scale: f64,
    placements: Vec<Placement>,
}

/// How one chart is turned and moved.
#[derive(Clone)]
struct Placement {
    turn: Turn,
    /// Where the lower corner of the turned chart's bounding box lands in the unit
    /// square.
    corner: DVec2,
}

impl Layout {
    /// Where `point` of chart `chart`'s plane lands in the unit square.
    pub fn place(&self, chart: usize, point: DVec2) -> DVec2 {
        let placement = &self.placements[chart];
        placement.corner + self.scale * placement.turn.apply(point)
    }
}

/// A chart turned in its plane, with the bounding box it then has.
#[derive(Clone, Copy, Debug)]
struct Turn {
    /// The unit direction that becomes +u.
    direction: DVec2,
    /// The lower corner of the turned chart's bounding box.
    origin: DVec2,
    /// The size of that box.
    size: DVec2,
}

impl Turn {
    /// The turn by `direction` of a chart whose convex hull is `hull`.
    fn by(direction: DVec2, hull: &[DVec2]) -> Turn {
        let turned = hull.iter().map(|&p| turned(direction, p));
        let (min, max) = turned.fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p), hi.max(p))
        });
        if min.x > max.x {
            // No points: nothing to turn.
            return Turn {
                direction,
                origin: DVec2::ZERO,
                size: DVec2::ZERO,
            };
        }
        Turn {
            direction,
            origin: min,
            size: max - min,
        }
    }

    /// The smallest-area bounding box of the convex `hull` over the directions of its
    /// edges (of two as small, the squarer), turned so that it is at least as wide as
    /// tall.
    fn lying(hull: &[DVec2]) -> Turn {
        let edges = (0..hull.len()).map(|k| hull[(k + 1) % hull.len()] - hull[k]);
        let smallest = (edges.filter_map(|edge| edge.try_normalize()))
            .map(|direction| Turn::by(direction, hull))
            .reduce(|best, turn| if turn.smaller_than(&best) { turn } else { best })
            .unwrap_or_else(|| Turn::by(DVec2::X, hull));
        if smallest.size.y > smallest.size.x {
            smallest.quarter(hull)
        } else {
            smallest
        }
    }

    /// The same chart turned a further quarter turn clockwise.
    fn quarter(&self, hull: &[DVec2]) -> Turn {
        Turn::by(self.direction.perp(), hull)
    }

    /// Whether this box has less area than `other`, or as much (to a billionth) and a
    /// shorter longest side.
    fn smaller_than(&self, other: &Turn) -> bool {
        let (area, other_area) = (self.size.x * self.size.y, other.size.x * other.size.y);
        if (area - other_area).abs() > 1e-9 * area.max(other_area) {
            area < other_area
        } else {
            self.size.max_element() < other.size.max_element()
        }
    }

    /// Where `point` goes in the turned chart's box (from its lower corner).
    fn apply(&self, point: DVec2) -> DVec2 {
        turned(self.direction, point) - self.origin
    }
}

/// `point` in coordinates whose +x is the unit vector `direction` (a rotation).
fn turned(direction: DVec2, point: DVec2) -> DVec2 {
    DVec2::new(direction.dot(point), direction.perp_dot(point))
}

/// Lays out charts, each given by its triangles in its plane (counter-clockwise), with
/// at least `gap` between them: by shape on a grid of `resolution`² cells (cells no
/// larger than the texels the gap counts, so the gap holds), unless their rectangles in
/// shelves reach a scale the grid does not (then with the gap narrowed as far as it
/// takes for the charts to fit at all).
pub(super) fn pack(charts: &[Vec<[DVec2; 3]>], gap: f64, resolution: u32) -> Layout {
    let hulls: Vec<Vec<DVec2>> = (charts.iter())
        .map(|triangles| convex_hull(triangles.as_flattened()))
        .collect();
    let lying: Vec<Turn> = hulls.iter().map(|hull| Turn::lying(hull)).collect();
    let (shelves, shelves_gap) = shelf::pack(&lying, gap);
    if shelves_gap < gap {
        // Not even the gaps fit: the grid, which keeps them whole, cannot hold the charts.
        return shelves;
    }
    raster::pack(charts, &hulls, &lying, gap, resolution, shelves.scale).unwrap_or(shelves)
}

/// The corners of the convex hull of `points`, counter-clockwise (Andrew's monotone
/// chain); a single point for coincident points, nothing for none.
pub(super) fn convex_hull(points: &[DVec2]) -> Vec<DVec2> {
    let mut sorted = points.to_vec();
    sorted.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    sorted.dedup();
    if sorted.len() < 3 {
        return sorted;
    }
    let mut hull: Vec<DVec2> = Vec::with_capacity(sorted.len() + 1);
    for pass in [
        &sorted[..],
        &sorted.iter().rev().copied().collect::<Vec<_>>()[..],
    ] {
        let start = hull.len();
        for &p in pass {
            while hull.len() >= start + 2 {
                let (a, b) = (hull[hull.len() - 2], hull[hull.len() - 1]);
                if (b - a).perp_dot(p - a) > 0.0 {
                    break;
                }
                hull.pop();
            }
            hull.push(p);
        }
        // Each chain's last point starts the other.
        hull.pop();
    }
    hull
}

/// The bounding boxes of the charts given by their outline points, as placed.
#[cfg(test)]
fn placed_boxes(layout: &Layout, outlines: &[Vec<DVec2>]) -> Vec<(DVec2, DVec2)> {
    (outlines.iter().enumerate())
        .map(|(chart, outline)| {
            let placed = outline.iter().map(|&p| layout.place(chart, p));
            placed.fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p), hi.max(p))
            })
        })
        .collect()
}

/// The smallest distance between two boxes along u or v, checking on the way that each
/// box keeps half of it from the square's edges.
#[cfg(test)]
fn smallest_gap(boxes: &[(DVec2, DVec2)]) -> f64 {
    let mut smallest = f64::INFINITY;
    for (k, &(min, max)) in boxes.iter().enumerate() {
        for &(other_min, other_max) in &boxes[k + 1..] {
            let apart = (other_min - max).max(min - other_max).max_element();
            smallest = smallest.min(apart);
        }
    }
    let rounded = (smallest * 1e9).round() / 1e9;
    for &(min, max) in boxes {
        assert!(min.min_element() >= rounded / 2.0 - 1e-12, "{min}");
        assert!(max.max_element() <= 1.0 - rounded / 2.0 + 1e-12, "{max}");
    }
    rounded
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The smallest-area box round `points` (see [`Turn::lying`]): its size.
    fn lying_box_size(points: &[DVec2]) -> DVec2 {
        Turn::lying(&convex_hull(points)).size
    }

    #[test]
    fn the_smallest_box_of_a_tilted_rectangle_is_the_rectangle_itself() {
        // A 4 × 1 rectangle turned by 30°.
        let direction = DVec2::from_angle(30f64.to_radians());
        let corners = [(0.0, 0.0), (4.0, 0.0), (4.0, 1.0), (0.0, 1.0), (2.0, 0.5)]
            .map(|(x, y)| x * direction + y * direction.perp());
        let size = lying_box_size(&corners);
        assert!((size - DVec2::new(4.0, 1.0)).length() < 1e-9, "{size}");
        // Standing up, it is laid down.
        let standing = corners.map(|p| p.perp());
        let size = lying_box_size(&standing);
        assert!((size - DVec2::new(4.0, 1.0)).length() < 1e-9, "{size}");
    }

    #[test]
    fn of_boxes_as_small_the_squarer_is_taken() {
        // A right triangle with legs 3 and 2: its boxes along a leg and along the
        // hypotenuse have the same area.
        let size = lying_box_size(&[DVec2::ZERO, DVec2::new(3.0, 0.0), DVec2::new(0.0, 2.0)]);
        assert!((size - DVec2::new(3.0, 2.0)).length() < 1e-9, "{size}");
    }

    #[test]
    fn the_hull_keeps_only_the_outer_corners() {
        let points = [
            (0.0, 0.0),
            (1.0, 0.0),
            (0.5, 0.5),
            (1.0, 1.0),
            (0.0, 1.0),
            (0.5, 0.0),
        ]
        .map(DVec2::from);
        assert_eq!(
            convex_hull(&points),
            [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(DVec2::from)
        );
    }
}
