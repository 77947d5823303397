//! The document being edited: its file, undo history, revision, recovery files and the
//! actions that save and export it.

pub(in crate::app) mod actions;
pub(in crate::app) mod commands;
pub(in crate::app) mod document;
pub(in crate::app) mod export_job;
pub(in crate::app) mod recovery;
pub(in crate::app) mod sync;

use std::path::PathBuf;

/// The document being edited and what keeps it: its revision, the recovery file it is
/// autosaved to, the recent files, the window title.
pub(in crate::app) struct Session {
    pub document: document::Document,
    pub recent: Vec<PathBuf>,
    /// This window's autosave of unsaved work.
    pub autosave: recovery::Autosave,
    /// Beside which windows autosave unsaved work (and the recent files are kept).
    pub recovery_file: PathBuf,
    /// Set once the user has agreed to close (or nothing was unsaved).
    pub allowed_to_close: bool,
    /// The window title last sent.
    pub title: String,
    /// How many times the graph has changed, and what followed which change.
    pub revision: sync::Revision,
    /// Whether the document had unsaved changes when input last arrived.
    pub dirty: bool,
    /// The export running on its own thread, if one is.
    pub export: Option<export_job::ExportJob>,
}

impl Session {
    /// A session on `document`, autosaving beside `recovery_file` to a file of its own.
    pub fn new(document: document::Document, recovery_file: PathBuf) -> Session {
        Session {
            document,
            recent: recovery::load_recent(&recovery_file),
            autosave: recovery::Autosave::new(recovery::window_file(&recovery_file)),
            recovery_file,
            allowed_to_close: false,
            title: String::new(),
            revision: Default::default(),
            dirty: false,
            export: None,
        }
    }

    /// The document was just saved: nothing to recover, and its dirty mark is worked
    /// out again.
    pub fn saved(&mut self) {
        self.autosave.forget();
        self.revision.recheck();
    }
}
