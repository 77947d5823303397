//! Every change to the document is a graph edit ([`GraphEdit`]), carried out here:
//! recorded for undo, counted in the revision (with what it changed, for the preview),
//! and shown by the graph view. Edits come from two sides: the graph view's own
//! (taken in from its journal, which it shows already) and the rest of the editor's
//! (the inspector's group and parameter panels, the preview's settings, menus, undo),
//! which the view then follows.

use crate::app::VeneerApp;
use crate::app::canvas::snarl_patch;
use crate::app::canvas::view_edits::edits_from_journal;
use crate::graph::Graph;
use crate::graph::edit::{Change, EditError, GraphEdit, History, Level, Step};

impl VeneerApp {
    /// Carries out `edit` on the document (after the graph view's edits so far) and
    /// shows it. A refused edit changes nothing and says why in the status bar; returns
    /// whether it was carried out.
    pub(in crate::app) fn edit(&mut self, edit: GraphEdit) -> bool {
        let done = self.apply_edit(edit);
        if let Err(error) = &done {
            self.chrome.message = Some(error.clone());
        }
        done.is_ok()
    }

    /// Carries out `edit` on the document as the editor's panels do (for scripts, tests
    /// and benchmarks): an undo step (or part of the gesture under way), shown by the
    /// graph view. A refused edit changes nothing and says why.
    pub fn apply_edit(&mut self, edit: GraphEdit) -> Result<(), String> {
        self.take_in_view_edits();
        self.commit(edit.clone())?;
        self.follow(&edit);
        Ok(())
    }

    /// Carries out `edit` on the document only: the graph view shows it already (a
    /// group pin its "+" declared) or is built again after it.
    pub(in crate::app) fn commit(&mut self, edit: GraphEdit) -> Result<Vec<Change>, String> {
        let document = &mut self.session.document;
        let changes = document.apply(edit).map_err(|error| error.to_string())?;
        self.session.revision.changed(&changes, &document.graph);
        Ok(changes)
    }

    /// Takes the graph view's changes since the last call into the document, as edits
    /// of the level shown. Should the document refuse them (the view let through what
    /// the graph does not allow), the view is built again from the document.
    pub(in crate::app) fn take_in_view_edits(&mut self) {
        let journal = self.canvas.snarl.take_journal();
        if journal.is_empty() {
            return;
        }
        self.session.revision.reads += 1;
        let level = self.canvas.scope.level();
        let graph = &self.session.document.graph;
        let nodes = match &level {
            Level::Top => Some(graph.nodes.as_slice()),
            Level::Group(name) => graph.groups.get(name).map(|group| group.nodes.as_slice()),
        };
        let Some(nodes) = nodes else {
            return self.rebuild_snarl();
        };
        let stored = |id| {
            let at = nodes.partition_point(|node: &crate::graph::Node| node.id < id);
            nodes.get(at).filter(|node| node.id == id)
        };
        let edits = edits_from_journal(
            &journal,
            &self.canvas.snarl,
            &mut self.canvas.shown,
            &level,
            stored,
        );
        if edits.is_empty() {
            return;
        }
        let linked = level
            .group()
            .and_then(|name| graph.groups.get(name))
            .is_some_and(|group| group.linked);
        if let Err(error) = self.commit(GraphEdit::Batch(edits)) {
            self.chrome.message = Some(format!("{error}; the graph view shows the graph again"));
            self.rebuild_snarl();
            return;
        }
        let unlinked = level
            .group()
            .and_then(|name| self.session.document.graph.groups.get(name))
            .is_some_and(|group| !group.linked);
        if let (true, true, Some(name)) = (linked, unlinked, level.group()) {
            self.chrome.message = Some(format!(
                "group '{name}' is local to this graph now (edited): library updates no \
                 longer apply; Save to library shares the edits"
            ));
        }
    }

    /// A change made to the document from outside (a script or test): one undoable
    /// step, and the view built again.
    pub(in crate::app) fn take_in_outside_change(&mut self) {
        let Some(before) = self.session.revision.outside.take() else {
            return;
        };
        let document = &mut self.session.document;
        if document.graph == before {
            return;
        }
        let mut after = std::mem::replace(&mut document.graph, before);
        after.canonicalize();
        crate::graph::group::resolve(&mut after);
        if self
            .commit(GraphEdit::ReplaceGraph(Box::new(after)))
            .is_ok()
        {
            self.rebuild_snarl();
        }
    }

    /// Undoes the last step (inside a group too; a group undone away is left).
    pub fn undo(&mut self) {
        self.travel(History::undo);
    }

    /// Redoes the last undone step.
    pub fn redo(&mut self) {
        self.travel(History::redo);
    }

    /// Undoes or redoes (`step`) after taking in the view's edits, and shows it.
    fn travel(&mut self, step: fn(&mut History, &mut Graph) -> Option<Result<Step, EditError>>) {
        self.take_in_view_edits();
        let document = &mut self.session.document;
        let step = step(&mut document.history, &mut document.graph);
        self.travelled(step);
    }

    /// Shows a step undone or redone.
    fn travelled(&mut self, step: Option<Result<Step, EditError>>) {
        // Undo ends the gesture under way (Ctrl+Z while copies follow the mouse).
        self.session.revision.gesture = false;
        self.canvas.grab.forget();
        match step {
            Some(Ok(step)) => {
                self.session
                    .revision
                    .changed(&step.changes, &self.session.document.graph);
                self.follow(&step.edit);
            }
            Some(Err(error)) => self.chrome.message = Some(format!("cannot undo: {error}")),
            None => {}
        }
    }

    /// Brings the graph view in step with `edit`, just carried out on the document:
    /// node by node where it can, else built again.
    fn follow(&mut self, edit: &GraphEdit) {
        let graph = &self.session.document.graph;
        let level = self.canvas.scope.level();
        let shown = level
            .group()
            .is_none_or(|name| graph.groups.contains_key(name));
        let canvas = &mut self.canvas;
        if !shown || !snarl_patch::follow(&mut canvas.snarl, &mut canvas.shown, &level, edit, graph)
        {
            self.rebuild_snarl();
        }
    }
}
