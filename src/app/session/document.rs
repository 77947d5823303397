//! The graph being edited: where it lives on disk, whether it has unsaved changes, and
//! its undo history, made of the edits ([`GraphEdit`]) that change it.

use crate::graph::Graph;
use crate::graph::edit::{Change, EditError, GraphEdit, History};
use std::path::{Path, PathBuf};

/// A graph open in the editor.
pub struct Document {
    pub graph: Graph,
    /// The file it was opened from or saved to (`None`: a preset or a new graph).
    pub path: Option<PathBuf>,
    /// The graph as last loaded or saved, to tell whether it is dirty (`None`: never
    /// saved as it is, like recovered work).
    saved: Option<Graph>,
    /// Undo and redo: the edits that take each step back.
    pub history: History,
}

impl Document {
    /// A document for `graph`, clean, as loaded from `path`. The graph is kept in
    /// canonical order (as the graph view reads it back: a library group taken in on
    /// loading may come in another order), so that opening it changes nothing.
    pub fn new(mut graph: Graph, path: Option<PathBuf>) -> Document {
        graph.canonicalize();
        Document {
            saved: Some(graph.clone()),
            history: History::new(),
            graph,
            path,
        }
    }

    /// A document that starts dirty: recovered work, never saved as such, or a file
    /// whose nodes were laid out on opening.
    pub fn recovered(mut graph: Graph, path: Option<PathBuf>) -> Document {
        graph.canonicalize();
        Document {
            saved: None,
            history: History::new(),
            graph,
            path,
        }
    }

    /// Carries out `edit` on the graph and records its undo (a step of its own, or part
    /// of the gesture under way); a refused edit changes nothing. Returns what changed.
    pub fn apply(&mut self, edit: GraphEdit) -> Result<Vec<Change>, EditError> {
        self.history.apply(&mut self.graph, edit)
    }

    /// Whether the graph differs from what was last loaded or saved.
    pub fn is_dirty(&self) -> bool {
        self.saved.as_ref() != Some(&self.graph)
    }

    /// Writes the graph to its file (atomically).
    pub fn save(&mut self) -> Result<PathBuf, String> {
        let path = self
            .path
            .clone()
            .ok_or("the graph has no file yet: use Save as")?;
        self.save_as(&path)?;
        Ok(path)
    }

    /// Writes the graph to `path` (atomically) and makes that its file.
    pub fn save_as(&mut self, path: &Path) -> Result<(), String> {
        let folder = crate::graph::Folder::of_file(path);
        let mut moved = self.graph.clone();
        moved.move_to(folder);
        crate::graph::save(&moved, path)
            .map_err(|error| format!("{}: cannot save: {error}", path.display()))?;
        self.graph = moved;
        self.saved = Some(self.graph.clone());
        self.path = Some(path.to_path_buf());
        Ok(())
    }

    /// The window title: file name (or graph name), with a star when `dirty`.
    pub fn title(&self, dirty: bool) -> String {
        let name = match &self.path {
            Some(path) => path
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default(),
            None if self.graph.name.is_empty() => "untitled".to_string(),
            None => self.graph.name.clone(),
        };
        format!("{}{name} — Veneer", if dirty { "* " } else { "" })
    }
}
