//! Numerical hazards, found by propagating value ranges (intervals) through the graph:
//! degenerate parameters, divisions and normalisations that may hit zero, powers of
//! negative bases, fractal frequencies past f32 precision, and the sine hash used where
//! f32 can no longer tell lattice cells apart. `veneer check` prints these as warnings;
//! the editor marks the nodes.

mod interval;
mod propagate;

pub use interval::{Interval, Lanes};

use crate::graph::check::CheckedGraph;
use crate::graph::{Graph, NodeId};
use std::fmt;

/// Past this coordinate magnitude the sine hash's neighbouring lattice cells start to
/// repeat in f32 (measured on the CPU: 0.25% of neighbours repeat at 10⁶ as everywhere
/// closer, 1% at 2·10⁶, half at 4·10⁶; see `eval::noise`'s `sine_hash_precision`).
pub const SINE_HASH_SAFE_COORDINATE: f64 = 1.0e6;

/// Past this magnitude f32 coordinates are spaced more than 1 apart, so lattice noise
/// turns into a stair of repeated cells.
pub const F32_LATTICE_LIMIT: f64 = 1.6777216e7;

/// One numerical hazard, on the node it concerns.
#[derive(Clone, Debug, PartialEq)]
pub struct Lint {
    pub node: NodeId,
    /// The node as named in messages: `node 'label' (#id)`.
    pub node_name: String,
    pub message: String,
}

impl fmt::Display for Lint {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.node_name, self.message)
    }
}

/// The range of surface positions a graph is evaluated over: its preview placement
/// (centre ± size: the preview mesh fits the unit sphere, the flat view the square).
pub fn preview_positions(graph: &Graph) -> Lanes {
    let (c, size) = (graph.preview.center, graph.preview.size.abs());
    [
        Interval::new(c.0 - size, c.0 + size),
        Interval::new(c.1 - size, c.1 + size),
        Interval::new(c.2 - size, c.2 + size),
    ]
}

/// The hazards of a checked graph whose positions lie in `positions`.
pub fn lint(graph: &CheckedGraph, positions: Lanes) -> Vec<Lint> {
    propagate::run(graph, positions)
}
