//! What the editor writes: a graph saved with Ctrl+S, and the recovery file its
//! autosave keeps under the test's `XDG_STATE_HOME`.

use super::session::{STEP, Session};
use std::path::{Path, PathBuf};
use veneer::graph::Graph;

/// What a recovery file holds that the tests read (the file names the original and
/// the process too).
#[derive(serde::Deserialize)]
struct Recovery {
    graph: Graph,
}

/// When `file` was last written, and which file it is (a save replaces the file, so a
/// save within the clock's resolution still shows), if it exists.
fn written(file: &Path) -> Option<(std::time::SystemTime, u64)> {
    let meta = std::fs::metadata(file).ok()?;
    Some((
        meta.modified().ok()?,
        std::os::unix::fs::MetadataExt::ino(&meta),
    ))
}

impl Session {
    /// Saves with Ctrl+S and returns the graph written to `file` (the document's file),
    /// once the file has been written again and the title has lost its star.
    pub(super) fn save(&mut self, file: &Path) -> Graph {
        let before = written(file);
        self.key("ctrl+s");
        let graph = self.wait_for(&format!("Ctrl+S to write {}", file.display()), STEP, |_| {
            (written(file) != before)
                .then(|| veneer::graph::load(file).ok())
                .flatten()
        });
        let name = file.file_name().unwrap_or_default().to_string_lossy();
        self.expect_title(&format!("{name} — Veneer"));
        graph
    }

    /// The editor's recovery files (`recovery-<pid>-<n>.ron` under the test's
    /// `XDG_STATE_HOME`).
    pub(super) fn recovery_files(&self) -> Vec<PathBuf> {
        let state = self.dir.join("state/veneer");
        let mut files: Vec<PathBuf> = std::fs::read_dir(state)
            .into_iter()
            .flatten()
            .flatten()
            .map(|entry| entry.path())
            .filter(|path| {
                path.file_name()
                    .is_some_and(|name| name.to_string_lossy().starts_with("recovery"))
            })
            .collect();
        files.sort();
        files
    }

    /// The graph in the editor's one recovery file, if there is exactly one and it reads.
    pub(super) fn recovered(&self) -> Option<Graph> {
        let [file] = self.recovery_files().try_into().ok()?;
        let text = std::fs::read_to_string(file).ok()?;
        ron::from_str::<Recovery>(&text)
            .ok()
            .map(|saved| saved.graph)
    }
}
