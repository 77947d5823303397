//! Undo made of commands against undo made of snapshots, on a 10,000-node chain: a
//! node in the middle removed (a structural edit, its wires with it), then undone.
//! - commands: `graph::edit::History` applies the edit and records its inverse (the node
//!   and its two wires), and undo applies that inverse;
//! - snapshots: the same edit, then what the editor's snapshot history did (whole-graph
//!   comparison with the last committed graph and a clone of it on commit, a clone of the
//!   previous graph on undo).
//!
//! `cargo bench --bench edits`

use criterion::{Criterion, criterion_group, criterion_main};
use veneer::graph::edit::{GraphEdit, History, Level, apply};
use veneer::graph::{Graph, NodeId};

#[path = "../tests/engine/big_graphs.rs"]
#[allow(dead_code)]
mod big_graphs;

/// The edit measured: the middle node of the chain removed.
fn remove_middle() -> GraphEdit {
    GraphEdit::RemoveNodes {
        level: Level::Top,
        nodes: vec![NodeId(5_000)],
    }
}

fn undo(c: &mut Criterion) {
    let mut graph = big_graphs::chain(10_000);
    graph.canonicalize();
    let mut group = c.benchmark_group("graph edits: a 10,000-node chain");
    group.bench_function("a node removed and undone, undo made of commands", |b| {
        let mut history = History::new();
        b.iter(|| {
            history.apply(&mut graph, remove_middle()).expect("removes");
            history.undo(&mut graph).expect("a step").expect("undoes")
        })
    });
    group.bench_function("a node removed and undone, undo made of snapshots", |b| {
        let mut committed = graph.clone();
        let mut steps: Vec<Graph> = Vec::new();
        b.iter(|| {
            apply(&mut graph, remove_middle()).expect("removes");
            if graph != committed {
                steps.push(std::mem::replace(&mut committed, graph.clone()));
            }
            let previous = steps.pop().expect("a step");
            committed = previous.clone();
            graph = previous;
        })
    });
    group.finish();
}

criterion_group!(benches, undo);
criterion_main!(benches);
