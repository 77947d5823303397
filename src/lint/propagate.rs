//! Range propagation: the interval of every output, node by node in dependency order,
//! and the hazards each node's input ranges reveal (each kind's rules are in its
//! definition, `nodes/`).

use super::Lint;
use crate::graph::NodeId;
use crate::graph::check::{CheckedGraph, InputSource};
use crate::nodes::interval::{Interval, Lanes};
use crate::nodes::ranges::Ranges;
use std::collections::BTreeMap;

pub fn run(graph: &CheckedGraph, positions: Lanes) -> Vec<Lint> {
    let mut ranges: BTreeMap<NodeId, Vec<Lanes>> = BTreeMap::new();
    let mut lints = Vec::new();
    for checked in &graph.order {
        let inputs: Vec<Lanes> = checked
            .inputs
            .iter()
            .map(|source| match source {
                InputSource::Wire { node, output, .. } => ranges[node][*output],
                InputSource::Const(value) => value.components().map(Interval::point),
                InputSource::Position => positions,
            })
            .collect();
        let mut io = Ranges::new(&checked.signature.inputs, &inputs, positions);
        if let Some(bitmap) = graph.bitmaps.get(&checked.node.id) {
            io = io.with_bitmap(
                bitmap
                    .lanes
                    .map(|[lo, hi]| Interval::new(lo.into(), hi.into())),
            );
        }
        let outputs = checked.node.kind.definition().ranges(&mut io);
        lints.extend(io.finish().into_iter().map(|message| Lint {
            node: checked.node.id,
            node_name: checked.node.to_string(),
            message,
        }));
        ranges.insert(checked.node.id, outputs);
    }
    lints
}
