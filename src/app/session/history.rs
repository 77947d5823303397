//! Undo and redo over whole-graph snapshots. Edits made during one pointer drag
//! (a slider, a colour picker, moving nodes) are committed as one step.

use crate::graph::Graph;

/// Undo and redo stacks around the last committed graph.
pub struct History {
    committed: Graph,
    undo: Vec<Graph>,
    redo: Vec<Graph>,
}

/// The most steps kept.
const LIMIT: usize = 500;

impl History {
    /// A history whose present is `graph`.
    pub fn new(graph: Graph) -> History {
        History {
            committed: graph,
            undo: Vec::new(),
            redo: Vec::new(),
        }
    }

    /// Records `current` as a new step if it differs from the last committed graph.
    /// Call when no drag is in progress, so a whole drag becomes one step.
    pub fn commit(&mut self, current: &Graph) -> bool {
        if *current == self.committed {
            return false;
        }
        let previous = std::mem::replace(&mut self.committed, current.clone());
        self.undo.push(previous);
        if self.undo.len() > LIMIT {
            self.undo.remove(0);
        }
        self.redo.clear();
        true
    }

    /// The graph before the last step, if any.
    pub fn undo(&mut self) -> Option<Graph> {
        let previous = self.undo.pop()?;
        self.redo
            .push(std::mem::replace(&mut self.committed, previous.clone()));
        Some(previous)
    }

    /// The graph of the last undone step, if any.
    pub fn redo(&mut self) -> Option<Graph> {
        let next = self.redo.pop()?;
        self.undo
            .push(std::mem::replace(&mut self.committed, next.clone()));
        Some(next)
    }

    /// Whether there is something to undo / redo.
    pub fn can_undo(&self) -> bool {
        !self.undo.is_empty()
    }
    pub fn can_redo(&self) -> bool {
        !self.redo.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::graph::{NodeKind, Value};
    use crate::nodes::Constant;

    #[test]
    fn a_drag_of_many_frames_is_one_step() {
        let mut graph = Graph::default();
        let node = graph.add(
            "v",
            NodeKind::Constant(Constant {
                ty: crate::graph::ValueType::Float,
            }),
        );
        let mut history = History::new(graph.clone());
        for frame in 1..=30 {
            graph.set_input(node, "value", Value::Float(frame as f64 / 10.0));
        }
        assert!(history.commit(&graph));
        assert!(!history.commit(&graph));
        let before = history.undo().expect("one step");
        assert!(before.node(node).unwrap().inputs.is_empty());
        assert!(history.undo().is_none());
        assert_eq!(history.redo().expect("redo"), graph);
    }
}
