//! Numerical hazards, found by propagating value ranges (intervals) through the graph:
//! degenerate parameters, divisions and normalisations that may hit zero, powers of
//! negative bases, fractal frequencies past f32 precision, and the sine hash used where
//! f32 can no longer tell lattice cells apart. `veneer check` prints these as warnings;
//! the editor marks the nodes.

mod propagate;

pub use crate::nodes::interval::{Interval, Lanes};
pub use crate::nodes::ranges::{F32_LATTICE_LIMIT, SINE_HASH_SAFE_COORDINATE};

use crate::graph::check::CheckedGraph;
use crate::graph::{Graph, NodeId};
use std::fmt;

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
