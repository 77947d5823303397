//! Undo and redo made of edits: each step is the edit that undoes it. Edits made
//! during one gesture (a drag of a slider, a colour picker, of nodes) are one step, and
//! a run of edits setting the same thing in it keeps only the first one's inverse.

use super::{Change, EditError, GraphEdit, apply};
use crate::graph::Graph;
use std::collections::VecDeque;

/// The most steps kept (the oldest go first).
pub const LIMIT: usize = 500;

/// A step undone or redone: the edit carried out, and what it changed.
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    pub edit: GraphEdit,
    pub changes: Vec<Change>,
}

/// The undo and redo stacks of a graph's edits.
#[derive(Clone, Debug, Default)]
pub struct History {
    /// The edits that undo each step, the last step last.
    undo: VecDeque<GraphEdit>,
    /// The edits that redo each undone step, the last undone last.
    redo: VecDeque<GraphEdit>,
    /// While a gesture is under way: the inverses of its edits so far, in the order
    /// they were made.
    gesture: Option<Vec<GraphEdit>>,
}

impl History {
    /// An empty history.
    pub fn new() -> History {
        History::default()
    }

    /// Carries out `edit` on `graph` and records its inverse: a step of its own, or
    /// part of the gesture under way. An edit that changed nothing records nothing; a
    /// refused one changes nothing. Returns what changed.
    pub fn apply(&mut self, graph: &mut Graph, edit: GraphEdit) -> Result<Vec<Change>, EditError> {
        // A setting's edit is small: kept to tell a drag that comes back to where it
        // started.
        let setting = edit.same_target(&edit).then(|| edit.clone());
        let applied = apply(graph, edit)?;
        if applied.changes.is_empty() {
            return Ok(applied.changes);
        }
        self.redo.clear();
        match &mut self.gesture {
            Some(inverses) => merge(inverses, applied.inverse, setting),
            None => self.push(applied.inverse),
        }
        Ok(applied.changes)
    }

    /// Starts a gesture: the edits until [`History::end_gesture`] are one step.
    pub fn begin_gesture(&mut self) {
        self.end_gesture();
        self.gesture = Some(Vec::new());
    }

    /// Ends the gesture under way, if any, recording its edits as one step.
    pub fn end_gesture(&mut self) {
        let Some(mut inverses) = self.gesture.take() else {
            return;
        };
        match inverses.len() {
            0 => {}
            1 => self.push(inverses.remove(0)),
            _ => {
                inverses.reverse();
                self.push(GraphEdit::Batch(inverses));
            }
        }
    }

    /// Undoes the last step (ending the gesture under way); `None` when there is none.
    /// Should its edit be refused (the graph was changed behind the history's back),
    /// the step stays and the graph is as it was.
    pub fn undo(&mut self, graph: &mut Graph) -> Option<Result<Step, EditError>> {
        self.end_gesture();
        travel(graph, &mut self.undo, &mut self.redo)
    }

    /// Redoes the last undone step (as [`History::undo`] undoes).
    pub fn redo(&mut self, graph: &mut Graph) -> Option<Result<Step, EditError>> {
        self.end_gesture();
        travel(graph, &mut self.redo, &mut self.undo)
    }

    /// Whether there is a step to undo.
    pub fn can_undo(&self) -> bool {
        !self.undo.is_empty() || self.gesture.as_ref().is_some_and(|g| !g.is_empty())
    }

    /// Whether there is a step to redo.
    pub fn can_redo(&self) -> bool {
        !self.redo.is_empty()
    }

    /// Records `inverse` as the newest step, dropping the oldest past [`LIMIT`].
    fn push(&mut self, inverse: GraphEdit) {
        self.undo.push_back(inverse);
        if self.undo.len() > LIMIT {
            self.undo.pop_front();
        }
    }
}

/// Applies the last step of `from` and puts the step that takes it back on `to`; a
/// step the graph refuses stays where it was.
fn travel(
    graph: &mut Graph,
    from: &mut VecDeque<GraphEdit>,
    to: &mut VecDeque<GraphEdit>,
) -> Option<Result<Step, EditError>> {
    let step = from.pop_back()?;
    Some(match apply(graph, step.clone()) {
        Ok(applied) => {
            to.push_back(applied.inverse);
            Ok(Step {
                edit: step,
                changes: applied.changes,
            })
        }
        Err(error) => {
            from.push_back(step);
            Err(error)
        }
    })
}

/// Adds `inverse` to the inverses of a gesture. When it undoes an edit of the same
/// thing as the last one, the last one's inverse undoes both and is kept alone; when
/// `setting` (the edit made) sets that thing back to what the last one's inverse
/// would, the two cancel out.
fn merge(inverses: &mut Vec<GraphEdit>, inverse: GraphEdit, setting: Option<GraphEdit>) {
    match inverses.last() {
        Some(last) if last.same_target(&inverse) => {
            if setting.is_some_and(|edit| restores(&edit, last)) {
                inverses.pop();
            }
        }
        _ => inverses.push(inverse),
    }
}

/// Whether `edit` sets what `inverse` sets, as it would be stored (positions rounded).
fn restores(edit: &GraphEdit, inverse: &GraphEdit) -> bool {
    match (edit, inverse) {
        (GraphEdit::MoveNodes { level, moves }, GraphEdit::MoveNodes { level: l, moves: m }) => {
            let round = |(x, y): (f32, f32)| (x.round(), y.round());
            level == l
                && moves.len() == m.len()
                && moves
                    .iter()
                    .zip(m)
                    .all(|(a, b)| a.0 == b.0 && round(a.1) == round(b.1))
        }
        _ => edit == inverse,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::graph::edit::Level;
    use crate::graph::edit::tests::chain;
    use crate::graph::{NodeId, Value};

    fn set(node: u32, x: f64) -> GraphEdit {
        GraphEdit::SetInput {
            level: Level::Top,
            node: NodeId(node),
            pin: "b".into(),
            value: Some(Value::Float(x)),
        }
    }

    fn moved(x: f32) -> GraphEdit {
        GraphEdit::MoveNodes {
            level: Level::Top,
            moves: vec![(NodeId(2), (x, 0.0)), (NodeId(3), (x + 200.0, 0.0))],
        }
    }

    #[test]
    fn a_drag_of_many_frames_is_one_step_of_one_edit() {
        let mut graph = chain(3);
        let before = graph.clone();
        let mut history = History::new();
        history.begin_gesture();
        for frame in 1..=30 {
            history
                .apply(&mut graph, set(2, frame as f64 / 10.0))
                .unwrap();
            history
                .apply(&mut graph, moved(frame as f32 * 3.3))
                .unwrap();
        }
        // (Two things set in turn: each frame's inverses are kept.)
        history.end_gesture();
        let after = graph.clone();
        assert!(history.undo(&mut graph).unwrap().is_ok());
        assert!(graph == before);
        assert!(history.undo(&mut graph).is_none(), "one step");
        assert!(history.redo(&mut graph).unwrap().is_ok());
        assert!(graph == after);

        // One thing set frame after frame: the first frame's inverse alone.
        let mut history = History::new();
        history.begin_gesture();
        for frame in 1..=30 {
            history.apply(&mut graph, set(3, frame as f64)).unwrap();
        }
        history.end_gesture();
        assert_eq!(history.undo.len(), 1);
        assert_eq!(
            history.undo[0],
            GraphEdit::SetInput {
                level: Level::Top,
                node: NodeId(3),
                pin: "b".into(),
                value: None,
            },
            "the first value's inverse alone"
        );
    }

    #[test]
    fn a_drag_back_to_where_it_started_records_nothing() {
        let mut graph = chain(3);
        let mut history = History::new();
        history.begin_gesture();
        for x in [410.0, 430.2, 400.4] {
            history.apply(&mut graph, moved(x)).unwrap();
        }
        history.end_gesture();
        assert!(!history.can_undo());
        // Setting what is there records nothing either.
        history.apply(&mut graph, moved(400.0)).unwrap();
        assert!(!history.can_undo());
    }

    #[test]
    fn edits_outside_a_gesture_are_steps_of_their_own_up_to_the_limit() {
        let mut graph = chain(3);
        let mut history = History::new();
        for k in 0..LIMIT + 20 {
            history.apply(&mut graph, set(2, k as f64 + 1.0)).unwrap();
        }
        let mut undone = 0;
        while let Some(result) = history.undo(&mut graph) {
            result.unwrap();
            undone += 1;
        }
        assert_eq!(undone, LIMIT);
        assert_eq!(
            graph.node(NodeId(2)).unwrap().inputs["b"],
            Value::Float(20.0),
            "the oldest steps were dropped"
        );
        history.redo(&mut graph).unwrap().unwrap();
        history.apply(&mut graph, set(3, 1.0)).unwrap();
        assert!(!history.can_redo(), "a new edit drops what was undone");
    }

    #[test]
    fn an_undo_the_graph_refuses_keeps_its_step() {
        let mut graph = chain(3);
        let mut history = History::new();
        history.apply(&mut graph, set(3, 1.0)).unwrap();
        // The node goes behind the history's back.
        crate::graph::edit::apply(
            &mut graph,
            GraphEdit::RemoveNodes {
                level: Level::Top,
                nodes: vec![NodeId(3)],
            },
        )
        .unwrap();
        let before = graph.clone();
        assert!(history.undo(&mut graph).unwrap().is_err());
        assert!(graph == before);
        assert!(history.can_undo());
    }
}
