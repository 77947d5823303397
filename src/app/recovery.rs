//! Autosave to a recovery file, offered on the next start if Veneer did not exit cleanly.

use crate::graph::Graph;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// What the recovery file holds.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Recovery {
    /// The file the unsaved graph belongs to, if it had one.
    pub original: Option<PathBuf>,
    pub graph: Graph,
}

/// The default recovery file: `$XDG_STATE_HOME/veneer/recovery.ron`, else
/// `~/.local/state/veneer/recovery.ron`.
pub fn default_path() -> PathBuf {
    let state = std::env::var_os("XDG_STATE_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|home| PathBuf::from(home).join(".local/state")))
        .unwrap_or_else(std::env::temp_dir);
    state.join("veneer/recovery.ron")
}

/// Writes the unsaved graph to the recovery file `path` (atomically).
pub fn autosave(path: &Path, recovery: &Recovery) -> std::io::Result<()> {
    if let Some(folder) = path.parent() {
        std::fs::create_dir_all(folder)?;
    }
    let text = ron::ser::to_string_pretty(recovery, ron::ser::PrettyConfig::new().depth_limit(2))
        .map_err(std::io::Error::other)?;
    crate::fsutil::write_atomic(path, text.as_bytes())
}

/// The content of the recovery file `path`, if there is a readable one.
pub fn pending(path: &Path) -> Option<Recovery> {
    ron::from_str(&read_ron(path)?).ok()
}

/// Removes the recovery file (after a clean exit, or once the user has decided).
pub fn clear(path: &Path) {
    let _ = std::fs::remove_file(path);
}

/// The recent-files list kept beside the recovery file.
pub fn recent_path(recovery_file: &Path) -> PathBuf {
    recovery_file.with_file_name("recent.ron")
}

/// The recent files saved by an earlier session (none if unreadable).
pub fn load_recent(recovery_file: &Path) -> Vec<PathBuf> {
    read_ron(&recent_path(recovery_file))
        .and_then(|text| ron::from_str(&text).ok())
        .unwrap_or_default()
}

/// Saves the recent-files list (atomically).
pub fn save_recent(recovery_file: &Path, recent: &[PathBuf]) -> std::io::Result<()> {
    let path = recent_path(recovery_file);
    if let Some(folder) = path.parent() {
        std::fs::create_dir_all(folder)?;
    }
    let text = ron::ser::to_string_pretty(&recent, ron::ser::PrettyConfig::new())
        .map_err(std::io::Error::other)?;
    crate::fsutil::write_atomic(&path, text.as_bytes())
}

/// The text of a RON file of ours, if it is a readable regular file within the limit
/// for graph files.
fn read_ron(path: &Path) -> Option<String> {
    let bytes = crate::fsutil::read_limited(path, crate::fsutil::ReadLimit::GRAPH).ok()?;
    String::from_utf8(bytes).ok()
}
