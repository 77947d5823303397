//! The graph canvas on screen: its colour, where it is, and the nodes drawn on it, found
//! as islands of other colours and matched with the nodes of the graph file the editor
//! opened (a graph written by the test: its nodes laid out in rows, apart and unwired).

use super::session::{STEP, Session};
use super::shot::{Rect, Shot, full, islands_where};
use std::path::PathBuf;
use veneer::graph::{Graph, NodeId, NodeKind};

/// How far a pixel's channels may be from the canvas colour and still be canvas (the
/// anti-aliased edges of shapes are not).
const TOLERANCE: u8 = 3;

/// The smallest island taken for a node, in pixels each way.
const NODE_PIXELS: i32 = 30;

/// How far apart, across and down, [`grid`] puts nodes, in graph units: at the zoom a
/// small graph opens at, far enough that nothing drawn joins two nodes.
const GRID: (f32, f32) = (400.0, 350.0);

/// A graph of nodes of `kinds`, labelled `n0`, `n1`… and unwired, in rows of `columns`
/// [`GRID`] apart, and a Material right of the first row.
pub(super) fn grid(columns: usize, kinds: &[NodeKind]) -> Graph {
    let mut graph = Graph::default();
    let mut place = |label: &str, kind: NodeKind, column: usize, row: usize| {
        let id = graph.add(label, kind);
        let node = graph.node_mut(id).expect("the node just added");
        node.position = (column as f32 * GRID.0, row as f32 * GRID.1);
    };
    for (k, kind) in kinds.iter().enumerate() {
        place(&format!("n{k}"), kind.clone(), k % columns, k / columns);
    }
    place("material", NodeKind::Material, columns, 0);
    graph
}

/// Four nodes in two rows of two (the first row's without inputs) and a Material, as
/// [`grid`] lays them out: for the flows that click, drag and copy nodes.
pub(super) fn four_nodes() -> Graph {
    let kinds = [
        NodeKind::Position,
        NodeKind::Uv,
        NodeKind::Invert,
        NodeKind::Gamma,
    ];
    grid(2, &kinds)
}

/// The id of `graph`'s node labelled `label`.
pub(super) fn id(graph: &Graph, label: &str) -> NodeId {
    graph
        .nodes
        .iter()
        .find(|node| node.label == label)
        .map(|node| node.id)
        .expect("a node of the test's graph")
}

/// The labels of `graph`'s nodes, in its order.
pub(super) fn labels(graph: &Graph) -> Vec<&str> {
    graph.nodes.iter().map(|node| node.label.as_str()).collect()
}

/// The canvas colour: the commonest in the left half of the window, where the graph is.
pub(super) fn canvas_colour(shot: &Shot) -> [u8; 3] {
    let (w, h) = (shot.width as i32, shot.height as i32);
    let mut counts = std::collections::HashMap::new();
    for y in (h / 10..h * 9 / 10).step_by(3) {
        for x in (0..w / 2).step_by(3) {
            *counts.entry(shot.px(x, y)).or_insert(0usize) += 1;
        }
    }
    counts
        .into_iter()
        .max_by_key(|(_, n)| *n)
        .map_or([0; 3], |(colour, _)| colour)
}

/// Whether pixel `p` is the canvas colour `canvas`.
pub(super) fn is_canvas(p: [u8; 3], canvas: [u8; 3]) -> bool {
    (0..3).all(|c| p[c].abs_diff(canvas[c]) <= TOLERANCE)
}

/// Where the canvas is on screen: the rows and columns mostly of its colour, less the
/// outline drawn around it.
pub(super) fn canvas_area(shot: &Shot) -> Rect {
    let canvas = canvas_colour(shot);
    let (w, h) = (shot.width as i32, shot.height as i32);
    let mostly = |count: usize, of: i32| count * 3 > of as usize;
    let columns: Vec<i32> = (0..w)
        .filter(|&x| {
            mostly(
                (0..h).filter(|&y| is_canvas(shot.px(x, y), canvas)).count(),
                h,
            )
        })
        .collect();
    let rows: Vec<i32> = (0..h)
        .filter(|&y| {
            mostly(
                (0..w).filter(|&x| is_canvas(shot.px(x, y), canvas)).count(),
                w,
            )
        })
        .collect();
    let (Some(&x0), Some(&x1), Some(&y0), Some(&y1)) =
        (columns.first(), columns.last(), rows.first(), rows.last())
    else {
        return Rect::around((w / 2, h / 2), 0);
    };
    Rect {
        x0: x0 + 2,
        y0: y0 + 2,
        x1: x1 - 1,
        y1: y1 - 1,
    }
}

/// The islands of pixels other than the canvas colour in `area`, at least
/// [`NODE_PIXELS`] wide and tall: the nodes, when nothing joins them.
pub(super) fn islands(shot: &Shot, area: Rect) -> Vec<Rect> {
    let canvas = canvas_colour(shot);
    let mut found = islands_where(shot, area, |p| !is_canvas(p, canvas));
    found.retain(|r| r.x1 - r.x0 >= NODE_PIXELS && r.y1 - r.y0 >= NODE_PIXELS);
    found
}

/// A graph's nodes as drawn: each node's rectangle on screen, and the view's transform
/// from graph to screen coordinates worked out from them.
pub(super) struct Drawn {
    pub(super) nodes: Vec<(NodeId, Rect)>,
    /// Screen pixels per graph unit.
    zoom: f64,
    /// Where the graph's origin is on screen (a node's top-left corner is
    /// `origin + zoom × position`).
    origin: (f64, f64),
}

impl Drawn {
    /// Finds every node of `graph` among the islands of `shot`: both put in rows (by
    /// their tops) and each row left to right, they must match one to one, and the
    /// horizontal gaps between nodes must give one zoom. `None` if they do not.
    pub(super) fn find(shot: &Shot, graph: &Graph) -> Option<Drawn> {
        let mut found = islands(shot, canvas_area(shot));
        found.sort_by_key(|rect| rect.y0);
        let mut rows: Vec<Vec<Rect>> = Vec::new();
        for rect in found {
            match rows.last_mut() {
                Some(row) if rect.y0 - row[0].y0 <= 6 => row.push(rect),
                _ => rows.push(vec![rect]),
            }
        }
        let mut nodes: Vec<&veneer::graph::Node> = graph.nodes.iter().collect();
        nodes.sort_by(|a, b| {
            let (a, b) = (a.position, b.position);
            a.1.total_cmp(&b.1).then(a.0.total_cmp(&b.0))
        });
        let mut paired = Vec::new();
        let mut rest = nodes.as_slice();
        for mut row in rows {
            row.sort_by_key(|rect| rect.x0);
            if rest.len() < row.len()
                || rest[..row.len()]
                    .iter()
                    .any(|n| n.position.1 != rest[0].position.1)
            {
                return None;
            }
            let (here, after) = rest.split_at(row.len());
            paired.extend(here.iter().copied().zip(row));
            rest = after;
        }
        if !rest.is_empty() {
            return None;
        }
        // The zoom from the widest horizontal span, checked against every other node.
        let left = paired
            .iter()
            .min_by(|a, b| a.0.position.0.total_cmp(&b.0.position.0))?;
        let right = paired
            .iter()
            .max_by(|a, b| a.0.position.0.total_cmp(&b.0.position.0))?;
        let span = f64::from(right.0.position.0 - left.0.position.0);
        if span <= 0.0 {
            return None;
        }
        let zoom = f64::from(right.1.x0 - left.1.x0) / span;
        let origin = (
            f64::from(left.1.x0) - zoom * f64::from(left.0.position.0),
            f64::from(left.1.y0) - zoom * f64::from(left.0.position.1),
        );
        let drawn = Drawn {
            nodes: paired.iter().map(|(node, rect)| (node.id, *rect)).collect(),
            zoom,
            origin,
        };
        let consistent = paired.iter().all(|(node, rect)| {
            let (x, y) = drawn.to_screen(node.position);
            (x - rect.x0).abs() <= 3 && (y - rect.y0).abs() <= 3
        });
        consistent.then_some(drawn)
    }

    /// Node `id`'s rectangle on screen.
    pub(super) fn rect(&self, id: NodeId) -> Rect {
        self.nodes
            .iter()
            .find(|(node, _)| *node == id)
            .map(|(_, rect)| *rect)
            .expect("a node of the graph")
    }

    /// Where the graph point `position` is on screen.
    pub(super) fn to_screen(&self, (x, y): (f32, f32)) -> (i32, i32) {
        (
            (self.origin.0 + self.zoom * f64::from(x)).round() as i32,
            (self.origin.1 + self.zoom * f64::from(y)).round() as i32,
        )
    }

    /// Node `id`'s size in graph units, as drawn.
    pub(super) fn size(&self, id: NodeId) -> (f32, f32) {
        let rect = self.rect(id);
        (
            (f64::from(rect.x1 - rect.x0) / self.zoom) as f32,
            (f64::from(rect.y1 - rect.y0) / self.zoom) as f32,
        )
    }

    /// A point on node `id`'s title, where a click selects it.
    pub(super) fn title(&self, id: NodeId) -> (i32, i32) {
        let rect = self.rect(id);
        (rect.x0 + 30, rect.y0 + 10)
    }
}

impl Session {
    /// Writes `graph` to the file `name` in the scratch folder, opens the editor on it
    /// and finds its nodes on screen: the file, and the nodes as drawn.
    pub(super) fn open_drawn(&mut self, name: &str, graph: &Graph) -> (PathBuf, Drawn) {
        let file = self.dir.join(name);
        veneer::graph::save(graph, &file).expect("the graph is written");
        self.start_editor(&file, &format!("{name} — Veneer"));
        let drawn = self.drawn(graph);
        (file, drawn)
    }

    /// Waits for the window to settle with every node of `graph` drawn where
    /// [`Drawn::find`] finds it.
    pub(super) fn drawn(&mut self, graph: &Graph) -> Drawn {
        let what = format!(
            "the graph's {} nodes drawn apart, in rows",
            graph.nodes.len()
        );
        let found = self.try_wait_for(&what, STEP, |s| {
            let whole = full(&s.shot());
            Drawn::find(&s.settled(whole), graph)
        });
        match found {
            Some(drawn) => drawn,
            None => {
                let shot = self.shot();
                let islands = islands(&shot, canvas_area(&shot));
                self.fail(&format!(
                    "waited {STEP:?} for {what}; the canvas shows {islands:?}"
                ))
            }
        }
    }
}
