//! Placing new nodes clear of those already there: a node added at the mouse, pasted or
//! duplicated nodes (moved together, their layout kept) go to the position nearest the
//! one asked for where their footprints, with a margin, intersect no node's.

use super::footprint::{Bounds, bounds};
use crate::graph::{Node, Wire};
use std::collections::HashMap;

/// Space kept between placed nodes and the nodes already there, in canvas units.
pub const CLEARANCE: f32 = 20.0;
/// Nodes placed together beyond this many keep clear as one block (their bounding
/// rectangle), which keeps the search short when a whole graph is duplicated.
const MOST_PLACED_APART: usize = 32;
/// The side of the grid cells taken space is indexed by, in canvas units.
const CELL: f32 = 512.0;

/// The space taken on a level: its nodes' footprints, indexed by a grid so that what
/// lies near a point is found without looking at every node.
pub struct Taken {
    bounds: Vec<Bounds>,
    cells: HashMap<(i64, i64), Vec<usize>>,
}

impl Taken {
    /// The space `nodes`, joined by `wires`, take where they are.
    pub fn of(nodes: &[Node], wires: &[Wire]) -> Taken {
        Taken::new(bounds(nodes, wires))
    }

    /// The space the rectangles `taken` cover (any not finite are left out).
    pub fn new(taken: Vec<Bounds>) -> Taken {
        let finite = |b: &Bounds| {
            [b.min.0, b.min.1, b.max.0, b.max.1]
                .iter()
                .all(|v| v.is_finite())
        };
        let bounds: Vec<Bounds> = taken.into_iter().filter(finite).collect();
        let mut cells: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
        for (index, area) in bounds.iter().enumerate() {
            for cell in cells_over(area) {
                cells.entry(cell).or_default().push(index);
            }
        }
        Taken { bounds, cells }
    }

    /// The taken rectangles that may intersect `area`, each once, in index order.
    fn near(&self, area: &Bounds) -> Vec<&Bounds> {
        let (columns, rows) = cell_span(area);
        if columns.saturating_mul(rows) > self.bounds.len() as u64 {
            return self.bounds.iter().filter(|b| b.intersects(area)).collect();
        }
        let mut found: Vec<usize> = cells_over(area)
            .filter_map(|cell| self.cells.get(&cell))
            .flatten()
            .copied()
            .collect();
        found.sort_unstable();
        found.dedup();
        found
            .into_iter()
            .map(|index| &self.bounds[index])
            .filter(|b| b.intersects(area))
            .collect()
    }

    /// The shortest move of the rectangles `placed` (placed together) after which none
    /// of them is within [`CLEARANCE`] of a taken one: `(0, 0)` when they are clear
    /// already. Of moves equally short, the one least far sideways, then rightwards,
    /// then downwards. (Rectangles not finite are not moved.)
    pub fn clear_move(&self, placed: &[Bounds]) -> (f32, f32) {
        let Some(block) = placed.iter().copied().reduce(|a, b| a.union(&b)) else {
            return (0.0, 0.0);
        };
        let placed = if placed.len() > MOST_PLACED_APART {
            std::slice::from_ref(&block)
        } else {
            placed
        };
        let size = (block.max.0 - block.min.0).max(block.max.1 - block.min.1);
        let mut reach = size.max(CELL) + 2.0 * CLEARANCE;
        // Each round looks twice as far: the taken space is bounded, so a round finds
        // room unless the rectangles are not finite.
        while reach.is_finite() {
            let blocked = self.blocked_moves(placed, reach);
            if let Some(found) = nearest_free(&blocked, reach) {
                return found;
            }
            reach *= 2.0;
        }
        (0.0, 0.0)
    }

    /// The moves (within `reach` in x and y) that would bring one of `placed` within
    /// [`CLEARANCE`] of a taken rectangle, as rectangles of moves.
    fn blocked_moves(&self, placed: &[Bounds], reach: f32) -> Vec<Bounds> {
        let mut blocked = Vec::new();
        for area in placed {
            let swept = area.expand(reach + CLEARANCE);
            for taken in self.near(&swept) {
                let kept = taken.expand(CLEARANCE);
                blocked.push(Bounds {
                    min: (kept.min.0 - area.max.0, kept.min.1 - area.max.1),
                    max: (kept.max.0 - area.min.0, kept.max.1 - area.min.1),
                });
            }
        }
        blocked
    }
}

/// The grid cells `area` covers.
fn cells_over(area: &Bounds) -> impl Iterator<Item = (i64, i64)> {
    let cell = |v: f32| (v / CELL).floor() as i64;
    let (x0, x1) = (cell(area.min.0), cell(area.max.0));
    let (y0, y1) = (cell(area.min.1), cell(area.max.1));
    (x0..=x1).flat_map(move |x| (y0..=y1).map(move |y| (x, y)))
}

/// How many grid columns and rows `area` spans.
fn cell_span(area: &Bounds) -> (u64, u64) {
    let span = |a: f32, b: f32| ((b / CELL).floor() - (a / CELL).floor()) as u64 + 1;
    (span(area.min.0, area.max.0), span(area.min.1, area.max.1))
}

/// The move nearest `(0, 0)`, within `reach` of it, that lies inside none of the
/// rectangles `blocked` (on an edge is outside), if there is one. The nearest free point
/// lies on the vertical line through the origin or on a vertical edge, and on that
/// line as near `y = 0` as the blocked intervals crossing it leave room for: each such
/// line is tried, nearest first, until none can do better.
fn nearest_free(blocked: &[Bounds], reach: f32) -> Option<(f32, f32)> {
    let mut xs: Vec<f32> = blocked
        .iter()
        .flat_map(|b| [b.min.0, b.max.0])
        .chain([0.0])
        .filter(|x| x.abs() <= reach)
        .collect();
    xs.sort_by(|a, b| a.abs().total_cmp(&b.abs()).then(b.total_cmp(a)));
    xs.dedup();
    let mut best: Option<(f32, (f32, f32))> = None;
    for x in xs {
        if best.is_some_and(|(distance, _)| x.abs() > distance) {
            break;
        }
        let mut crossing: Vec<(f32, f32)> = blocked
            .iter()
            .filter(|b| b.min.0 < x && x < b.max.0)
            .map(|b| (b.min.1, b.max.1))
            .collect();
        crossing.sort_by(|a, b| a.0.total_cmp(&b.0));
        let y = nearest_open_y(&crossing);
        let distance = x.hypot(y);
        if distance <= reach && best.is_none_or(|(shortest, _)| distance < shortest) {
            best = Some((distance, (x, y)));
        }
    }
    best.map(|(_, found)| found)
}

/// The `y` nearest 0 inside none of the open intervals `crossing` (sorted by start):
/// 0 itself, or an end of the run of overlapping intervals over 0 (the one below, the
/// greater, when both are as near).
fn nearest_open_y(crossing: &[(f32, f32)]) -> f32 {
    let mut run: Option<(f32, f32)> = None;
    for &(start, end) in crossing {
        match run {
            Some((low, high)) if start < high => run = Some((low, high.max(end))),
            Some((low, high)) if low < 0.0 && 0.0 < high => break,
            _ => run = Some((start, end)),
        }
    }
    match run {
        Some((low, high)) if low < 0.0 && 0.0 < high => {
            if high <= -low {
                high
            } else {
                low
            }
        }
        _ => 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::graph::layout::Footprint;

    /// The position for `node`, added unwired, nearest `wanted` where it is clear of the
    /// nodes `nodes` (joined by `wires`) already on its level.
    fn place_node(nodes: &[Node], wires: &[Wire], node: &Node, wanted: (f32, f32)) -> (f32, f32) {
        let wanted = (wanted.0.round(), wanted.1.round());
        let area = Footprint::of(node, |_| false).at(wanted);
        let (dx, dy) = Taken::of(nodes, wires).clear_move(&[area]);
        (wanted.0 + dx, wanted.1 + dy)
    }

    /// Moves `placed` (nodes joined by `placed_wires`, pasted or duplicated onto the level
    /// of `nodes` joined by `wires`) together, their layout kept, so that their top-left
    /// position is as near `corner` as it can be with none of them within [`CLEARANCE`] of
    /// a node already there.
    fn place_nodes(
        nodes: &[Node],
        wires: &[Wire],
        placed: &mut [Node],
        placed_wires: &[Wire],
        corner: (f32, f32),
    ) {
        let Some(top_left) = placed
            .iter()
            .map(|node| node.position)
            .reduce(|a, b| (a.0.min(b.0), a.1.min(b.1)))
        else {
            return;
        };
        let to_corner = (
            corner.0.round() - top_left.0.round(),
            corner.1.round() - top_left.1.round(),
        );
        for node in placed.iter_mut() {
            node.position = (
                (node.position.0 + to_corner.0).round(),
                (node.position.1 + to_corner.1).round(),
            );
        }
        let (dx, dy) = Taken::of(nodes, wires).clear_move(&bounds(placed, placed_wires));
        for node in placed.iter_mut() {
            node.position = (node.position.0 + dx, node.position.1 + dy);
        }
    }

    use crate::graph::layout::footprint::overlapping;
    use crate::graph::{Graph, NodeKind};
    use proptest::prelude::*;

    fn area(x: f32, y: f32, width: f32, height: f32) -> Bounds {
        Bounds {
            min: (x, y),
            max: (x + width, y + height),
        }
    }

    fn moved(area: &Bounds, (dx, dy): (f32, f32)) -> Bounds {
        Bounds {
            min: (area.min.0 + dx, area.min.1 + dy),
            max: (area.max.0 + dx, area.max.1 + dy),
        }
    }

    /// Whether `placed`, moved by `by`, keeps [`CLEARANCE`] from every one of `taken`.
    fn clear(taken: &[Bounds], placed: &[Bounds], by: (f32, f32)) -> bool {
        placed.iter().all(|p| {
            let p = moved(p, by);
            taken.iter().all(|t| !t.expand(CLEARANCE).intersects(&p))
        })
    }

    #[test]
    fn a_node_wanted_on_free_canvas_goes_where_it_is_wanted() {
        let graph = crate::graph::preset("wood_classic").unwrap();
        let node = Node::new(graph.next_id(), NodeKind::Position);
        let wanted = (-2000.4, 3000.6);
        let at = place_node(&graph.nodes, &graph.wires, &node, wanted);
        assert_eq!(at, (-2000.0, 3001.0));
    }

    #[test]
    fn a_node_wanted_on_another_goes_to_the_nearest_clear_place() {
        let taken = [area(0.0, 0.0, 200.0, 100.0)];
        let placed = [area(150.0, 60.0, 100.0, 50.0)];
        let by = Taken::new(taken.to_vec()).clear_move(&placed);
        // Right of it is 70 away, below it 60: down it goes, just clear.
        assert_eq!(by, (0.0, 60.0));
        assert!(clear(&taken, &placed, by));
        assert!(!clear(&taken, &placed, (0.0, 59.0)));
    }

    #[test]
    fn a_node_in_a_gap_too_narrow_for_it_goes_past_the_gap() {
        // Two nodes 100 apart: a node 80 wide needs 80 + 2 × 20 between them.
        let taken = [area(0.0, 0.0, 100.0, 400.0), area(200.0, 0.0, 100.0, 400.0)];
        let placed = [area(110.0, 100.0, 80.0, 40.0)];
        let by = Taken::new(taken.to_vec()).clear_move(&placed);
        assert!(clear(&taken, &placed, by), "{by:?}");
        assert_eq!(by, (0.0, -160.0), "above both, the nearest way out");
    }

    #[test]
    fn pasted_nodes_keep_their_layout_and_land_clear_of_the_originals() {
        let graph = crate::graph::preset("rusted_metal").unwrap();
        let mut copies: Vec<Node> = graph.nodes[2..5].to_vec();
        let copied = |id| copies.iter().any(|n: &Node| n.id == id);
        let among: Vec<Wire> = (graph.wires.iter())
            .filter(|w| copied(w.from.node) && copied(w.to.node))
            .cloned()
            .collect();
        let before: Vec<(f32, f32)> = copies.iter().map(|n| n.position).collect();
        let corner = graph.nodes[2].position;
        place_nodes(&graph.nodes, &graph.wires, &mut copies, &among, corner);
        let shift = (
            copies[0].position.0 - before[0].0,
            copies[0].position.1 - before[0].1,
        );
        for (copy, original) in copies.iter().zip(&before) {
            let kept = (original.0 + shift.0, original.1 + shift.1);
            assert_eq!(copy.position, kept, "the layout is kept");
        }
        let taken = bounds(&graph.nodes, &graph.wires);
        assert!(clear(&taken, &bounds(&copies, &among), (0.0, 0.0)));
    }

    #[test]
    fn a_node_lands_clear_in_a_level_of_ten_thousand() {
        let mut graph = Graph::default();
        for k in 0..10_000 {
            graph.add(&format!("n{k}"), NodeKind::Position);
        }
        crate::graph::layout::arrange_in_rows(&mut graph, 20_000.0, 8_000.0);
        let middle = graph.nodes[5_050].position;
        let node = Node::new(graph.next_id(), NodeKind::Transform);
        let at = place_node(&graph.nodes, &graph.wires, &node, middle);
        let mut level = graph.nodes.clone();
        let mut placed = node.clone();
        placed.position = at;
        level.push(placed);
        assert_eq!(overlapping(&level, &graph.wires), None);
        let distance = (at.0 - middle.0).hypot(at.1 - middle.1);
        assert!(distance < 2_000.0, "{distance} away from {middle:?}");
    }

    #[test]
    fn a_whole_level_duplicated_onto_itself_lands_clear_as_a_block() {
        let graph = crate::graph::preset("marble_tiles").unwrap();
        let mut copies = graph.nodes.clone();
        let corner = copies
            .iter()
            .map(|n| n.position)
            .fold((f32::MAX, f32::MAX), |a, b| (a.0.min(b.0), a.1.min(b.1)));
        place_nodes(
            &graph.nodes,
            &graph.wires,
            &mut copies,
            &graph.wires,
            corner,
        );
        let taken = bounds(&graph.nodes, &graph.wires);
        let landed = bounds(&copies, &graph.wires);
        assert!(clear(&taken, &landed, (0.0, 0.0)));
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

        #[test]
        fn the_move_found_is_clear_and_no_shorter_move_is(
            taken in prop::collection::vec((-300i32..300, -300i32..300, 1i32..120, 1i32..120), 0..10),
            placed in prop::collection::vec((-60i32..60, -60i32..60, 1i32..80, 1i32..80), 1..4),
        ) {
            let rect = |(x, y, w, h): (i32, i32, i32, i32)| area(x as f32, y as f32, w as f32, h as f32);
            let taken: Vec<Bounds> = taken.into_iter().map(rect).collect();
            let placed: Vec<Bounds> = placed.into_iter().map(rect).collect();
            let by = Taken::new(taken.clone()).clear_move(&placed);
            prop_assert!(clear(&taken, &placed, by), "{:?} is not clear", by);
            let distance = by.0.hypot(by.1);
            let reach = distance.ceil() as i32;
            for dx in -reach..=reach {
                for dy in -reach..=reach {
                    let shorter = ((dx * dx + dy * dy) as f32).sqrt() < distance - 1e-3;
                    prop_assert!(
                        !(shorter && clear(&taken, &placed, (dx as f32, dy as f32))),
                        "({}, {}) is clear and shorter than {:?}", dx, dy, by
                    );
                }
            }
        }
    }
}
