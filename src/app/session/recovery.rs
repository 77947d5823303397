//! Autosave of unsaved work, offered on the next start if Veneer did not exit cleanly.
//!
//! Each editor window autosaves to a file of its own, `recovery-<pid>-<n>.ron` beside the
//! default recovery path, so two windows never overwrite each other's work. The file
//! exists only while the window's document has unsaved changes: it is removed when the
//! user saves, discards the changes, or undoes back to what was saved. At start the
//! editor offers the files whose process is gone (a crash, `kill -9`, a power cut); a
//! window that is still running keeps its own.

use crate::app::session::document::Document;
use crate::graph::Graph;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};

/// Seconds between autosaves while the document keeps changing.
pub const AUTOSAVE_SECONDS: f64 = 5.0;

/// Seconds between looks at whether the document is dirty (a look serialises the graph).
const CHECK_SECONDS: f64 = 0.5;

/// What a recovery file holds (written with the graph borrowed: `Recovery<&Graph>`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Recovery<G = Graph> {
    /// The file the unsaved graph belongs to, if it had one.
    pub original: Option<PathBuf>,
    pub graph: G,
    /// The process that wrote it (absent in files of older versions).
    #[serde(default)]
    pub pid: Option<u32>,
    /// When that process started, in clock ticks since boot, to tell it from a later
    /// process given the same id.
    #[serde(default)]
    pub started: Option<u64>,
    /// The recovery file this was read from.
    #[serde(skip)]
    pub file: PathBuf,
    /// When it was last written.
    #[serde(skip)]
    pub saved: Option<std::time::SystemTime>,
}

/// The default recovery path: `$XDG_STATE_HOME/veneer/recovery.ron`, else
/// `~/.local/state/veneer/recovery.ron`. Windows autosave beside it (see [`window_file`]).
pub fn default_path() -> PathBuf {
    let state = std::env::var_os("XDG_STATE_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|home| PathBuf::from(home).join(".local/state")))
        .unwrap_or_else(std::env::temp_dir);
    state.join("veneer/recovery.ron")
}

/// A recovery file for one more window of this process, beside `base`:
/// `<stem>-<pid>-<n>.ron`.
pub fn window_file(base: &Path) -> PathBuf {
    static WINDOWS: AtomicU32 = AtomicU32::new(0);
    let n = WINDOWS.fetch_add(1, Ordering::Relaxed);
    base.with_file_name(format!("{}-{}-{n}.ron", stem(base), std::process::id()))
}

fn stem(base: &Path) -> String {
    base.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "recovery".into())
}

/// The process id in a window file's name `<stem>-<pid>-<n>.ron`.
fn window_pid(base: &Path, name: &str) -> Option<u32> {
    let rest = name
        .strip_prefix(&stem(base))?
        .strip_prefix('-')?
        .strip_suffix(".ron")?;
    let (pid, n) = rest.split_once('-')?;
    n.parse::<u32>().ok()?;
    pid.parse().ok()
}

/// The unsaved work of windows that are gone: the window files beside `base` whose
/// process no longer runs, and `base` itself (written by older versions). Newest first.
pub fn orphans(base: &Path) -> Vec<Recovery> {
    let Some(folder) = base.parent() else {
        return Vec::new();
    };
    let Ok(entries) = std::fs::read_dir(folder) else {
        return Vec::new();
    };
    let legacy = base.file_name();
    let mut found: Vec<Recovery> = entries
        .flatten()
        .filter_map(|entry| {
            let name = entry.file_name();
            let pid = window_pid(base, &name.to_string_lossy());
            if pid.is_none() && Some(name.as_os_str()) != legacy {
                return None;
            }
            let recovery = read(&entry.path())?;
            let alive = pid.is_some_and(|pid| running(pid, recovery.started));
            (!alive).then_some(recovery)
        })
        .collect();
    found.sort_by_key(|recovery| std::cmp::Reverse(recovery.saved));
    found
}

/// The content of the recovery file `path`, if there is a readable one.
pub fn read(path: &Path) -> Option<Recovery> {
    let mut recovery: Recovery = ron::from_str(&read_ron(path)?).ok()?;
    // Group nodes' pins are not stored: they come from the groups.
    crate::graph::group::resolve(&mut recovery.graph);
    // The folder is not stored either: the graph's file paths are relative to its
    // original file's.
    if let Some(original) = &recovery.original {
        recovery.graph.folder = crate::graph::Folder::of_file(original);
    }
    recovery.file = path.to_path_buf();
    recovery.saved = std::fs::metadata(path).and_then(|m| m.modified()).ok();
    Some(recovery)
}

/// Whether process `pid` runs, and is the one that started at `started` (when known).
fn running(pid: u32, started: Option<u64>) -> bool {
    if pid == std::process::id() {
        return true;
    }
    #[cfg(unix)]
    {
        let Ok(pid_t) = libc::pid_t::try_from(pid) else {
            return false;
        };
        // SAFETY: signal 0 only checks that the process exists; nothing is sent.
        let exists = unsafe { libc::kill(pid_t, 0) } == 0
            || std::io::Error::last_os_error().raw_os_error() == Some(libc::EPERM);
        exists && !ended(pid) && (started.is_none() || start_time(pid) == started)
    }
    #[cfg(not(unix))]
    {
        let _ = started;
        true
    }
}

/// Whether process `pid` has ended but is not reaped yet (a zombie; Linux).
fn ended(pid: u32) -> bool {
    let Ok(stat) = std::fs::read_to_string(format!("/proc/{pid}/stat")) else {
        return false;
    };
    let state = stat
        .rsplit_once(')')
        .and_then(|(_, rest)| rest.split_whitespace().next());
    matches!(state, Some("Z" | "X"))
}

/// When process `pid` started, in clock ticks since boot (Linux), if known.
fn start_time(pid: u32) -> Option<u64> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // Fields after the command (which may hold spaces) start at the third, the state;
    // the start time is the 22nd.
    let (_, rest) = stat.rsplit_once(')')?;
    rest.split_whitespace().nth(19)?.parse().ok()
}

/// Writes `recovery` to the recovery file `path` (atomically, and only as a regular file
/// of its own: a link or special file there is refused), unless what it would write
/// hashes to `written` (the file holds it already); returns the hash of what the file
/// holds.
fn autosave(
    path: &Path,
    recovery: &Recovery<&Graph>,
    written: Option<u64>,
) -> std::io::Result<u64> {
    use std::hash::{Hash, Hasher};
    let text = ron::ser::to_string_pretty(recovery, ron::ser::PrettyConfig::new().depth_limit(2))
        .map_err(std::io::Error::other)?;
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    text.hash(&mut hasher);
    let hash = hasher.finish();
    if written != Some(hash) {
        write_own_file(path, &text)?;
    }
    Ok(hash)
}

/// Writes one of the editor's own files (a recovery file, the recent list, the kept
/// choices), making its folder when missing; it is never written through a link nor
/// into a FIFO or device that stands at its path ([`crate::fsutil::Naming::Implied`]).
fn write_own_file(path: &Path, text: &str) -> std::io::Result<()> {
    if let Some(folder) = path.parent() {
        std::fs::create_dir_all(folder)?;
    }
    crate::fsutil::write_implied(path, text.as_bytes())
}

/// Removes a recovery file (once its work is saved, discarded or recovered elsewhere).
pub fn clear(path: &Path) {
    let _ = std::fs::remove_file(path);
}

/// One window's autosave: writes the document's unsaved work to the window's recovery
/// file while it is dirty, and removes the file once it is clean.
pub struct Autosave {
    /// This window's recovery file.
    pub file: PathBuf,
    /// The editor's clock at the last tick.
    now: f64,
    last_check: f64,
    last_write: f64,
    /// A hash of what the file holds, if this window wrote it.
    written: Option<u64>,
    /// A big graph's write under way on its thread (writing a 10,000-node graph out
    /// takes a frame's 20 ms and more; see `background::is_big`).
    writing: Option<std::thread::JoinHandle<std::io::Result<u64>>>,
    /// The document's revision the file (or its absence, for a clean document) is up
    /// to date with.
    settled: Option<u64>,
}

impl Autosave {
    pub fn new(file: PathBuf) -> Autosave {
        Autosave {
            file,
            now: 0.0,
            last_check: f64::NEG_INFINITY,
            last_write: f64::NEG_INFINITY,
            written: None,
            writing: None,
            settled: None,
        }
    }

    /// Call every frame with the editor's clock and the document's revision: writes the
    /// work soon after the document becomes dirty and at most every [`AUTOSAVE_SECONDS`]
    /// while it changes; removes the file once the document is clean again (undone back
    /// to what was saved). Returns in how many seconds it wants to be called again, when
    /// an edit is not on disk yet: the editor wakes for it even when nothing else asks
    /// for a frame (an edit, then a still mouse).
    ///
    /// A big graph is written on a thread of its own, from `copy` when the frame made
    /// one (for the compile and lint threads) and from a copy made here otherwise.
    pub fn tick(
        &mut self,
        now: f64,
        document: &Document,
        revision: u64,
        copy: Option<std::sync::Arc<Graph>>,
    ) -> std::io::Result<Option<f64>> {
        self.now = now;
        if self
            .writing
            .as_ref()
            .is_some_and(|writing| !writing.is_finished())
        {
            return Ok(Some(CHECK_SECONDS));
        }
        self.finish_writing()?;
        if self.settled == Some(revision) {
            return Ok(None);
        }
        let since_check = now - self.last_check;
        if since_check < CHECK_SECONDS {
            return Ok(Some(CHECK_SECONDS - since_check));
        }
        self.last_check = now;
        if !document.is_dirty() {
            self.forget();
            self.settled = Some(revision);
            return Ok(None);
        }
        let wait = AUTOSAVE_SECONDS - (now - self.last_write);
        if self.written.is_some() && wait > 0.0 {
            return Ok(Some(wait));
        }
        self.last_write = self.now;
        if crate::app::preview::background::is_big(&document.graph) {
            let graph = copy.unwrap_or_else(|| std::sync::Arc::new(document.graph.clone()));
            let (file, written, original) =
                (self.file.clone(), self.written, document.path.clone());
            let write = move || autosave(&file, &Recovery::written_now(original, &*graph), written);
            let spawned =
                crate::app::preview::background::spawn_after_frame("veneer-autosave", write);
            self.writing = Some(spawned?);
        } else {
            let recovery = Recovery::written_now(document.path.clone(), &document.graph);
            self.written = Some(autosave(&self.file, &recovery, self.written)?);
        }
        self.settled = Some(revision);
        Ok(None)
    }

    /// Takes in the write running on its thread, waiting for it to end.
    fn finish_writing(&mut self) -> std::io::Result<()> {
        let Some(writing) = self.writing.take() else {
            return Ok(());
        };
        let written = writing
            .join()
            .map_err(|_| std::io::Error::other("the autosave thread failed"))?;
        self.written = Some(written?);
        Ok(())
    }

    /// Writes the document's work now if it is dirty (removes the file if not), once a
    /// write under way on its thread has ended.
    pub fn write_now(&mut self, document: &Document) -> std::io::Result<()> {
        let finished = self.finish_writing();
        if !document.is_dirty() {
            self.forget();
            return finished;
        }
        self.last_write = self.now;
        let recovery = Recovery::written_now(document.path.clone(), &document.graph);
        self.written = Some(autosave(&self.file, &recovery, self.written)?);
        Ok(())
    }

    /// Removes the window's recovery file: the work was saved or deliberately dropped
    /// (a write under way on its thread ends first, so nothing lands after).
    pub fn forget(&mut self) {
        let _ = self.finish_writing();
        if self.written.take().is_some() || self.file.exists() {
            clear(&self.file);
        }
    }
}

impl<G> Recovery<G> {
    /// What this process writes for `graph`, unsaved work on `original` if it has a file.
    fn written_now(original: Option<PathBuf>, graph: G) -> Recovery<G> {
        let pid = std::process::id();
        Recovery {
            original,
            graph,
            pid: Some(pid),
            started: start_time(pid),
            file: PathBuf::new(),
            saved: None,
        }
    }
}

static TERMINATE: AtomicBool = AtomicBool::new(false);
/// The signal that asked, to end by it when the editor is too busy to close itself.
static TERMINATING_SIGNAL: std::sync::atomic::AtomicI32 = std::sync::atomic::AtomicI32::new(0);
/// Whether the window has begun to close after the request.
static TERMINATION_HEARD: AtomicBool = AtomicBool::new(false);

/// How long the editor may take to begin closing after SIGTERM, SIGINT or SIGHUP
/// before the signal ends the process as it would any program: a frame stuck in a long
/// computation (a huge graph's first layout) must not keep the process alive. The
/// recovery file then holds the work as of the last autosave.
pub const TERMINATION_GRACE: std::time::Duration = std::time::Duration::from_secs(3);

/// How long the editor may take to finish closing once it has begun (its work is in
/// the recovery file by then) before the process exits regardless, with status 0:
/// background work — the preview thread compiling a 10,000-node material on a software
/// rasteriser — must not hold the process after its window has gone.
pub const CLOSING_LIMIT: std::time::Duration = std::time::Duration::from_secs(10);

/// Whether the process was asked to end (SIGTERM, SIGINT, SIGHUP) since
/// [`watch_termination`].
pub fn termination_requested() -> bool {
    TERMINATE.load(Ordering::Relaxed)
}

/// Notes that the window is closing because of the request, so that the process is
/// left to finish closing by itself.
pub fn termination_heard() {
    TERMINATION_HEARD.store(true, Ordering::SeqCst);
}

/// Ends the process by the signal that asked, with its default action.
#[cfg(unix)]
fn end_by_signal() {
    let signal = TERMINATING_SIGNAL.load(Ordering::SeqCst);
    // SAFETY: restoring the default action and raising a signal have no preconditions.
    unsafe {
        libc::signal(signal, libc::SIG_DFL);
        libc::raise(signal);
    }
}

#[cfg(unix)]
extern "C" fn on_termination(signal: libc::c_int) {
    TERMINATING_SIGNAL.store(signal, Ordering::SeqCst);
    if TERMINATE.swap(true, Ordering::SeqCst) {
        // Asked twice: the editor did not get to end by itself. End now (signal and
        // raise are async-signal-safe).
        end_by_signal();
    }
}

/// Makes SIGTERM, SIGINT and SIGHUP end the editor as closing its window does, but
/// without asking: unsaved work stays in the recovery file (written now), a clean
/// document leaves none. A second signal ends the process at once. `ctx` is woken
/// to notice.
pub fn watch_termination(ctx: &egui::Context) {
    #[cfg(unix)]
    {
        for signal in [libc::SIGTERM, libc::SIGINT, libc::SIGHUP] {
            // SAFETY: the handler only touches an atomic (and, the second time, restores
            // the default action and re-raises), which is async-signal-safe.
            unsafe {
                let mut action: libc::sigaction = std::mem::zeroed();
                action.sa_sigaction = on_termination as extern "C" fn(libc::c_int) as usize;
                libc::sigemptyset(&mut action.sa_mask);
                action.sa_flags = libc::SA_RESTART;
                libc::sigaction(signal, &action, std::ptr::null_mut());
            }
        }
        let ctx = ctx.clone();
        let _ = std::thread::Builder::new()
            .name("veneer signals".into())
            .spawn(move || {
                let mut asked = None;
                loop {
                    std::thread::sleep(std::time::Duration::from_millis(50));
                    if termination_requested() {
                        ctx.request_repaint();
                        let since = *asked.get_or_insert_with(std::time::Instant::now);
                        let heard = TERMINATION_HEARD.load(Ordering::SeqCst);
                        if !heard && since.elapsed() > TERMINATION_GRACE {
                            end_by_signal();
                        }
                        if heard && since.elapsed() > TERMINATION_GRACE + CLOSING_LIMIT {
                            // SAFETY: ends the process at once, running no exit handlers
                            // that could wait on the threads still at work.
                            unsafe { libc::_exit(0) };
                        }
                    }
                }
            });
    }
    #[cfg(not(unix))]
    let _ = ctx;
}

/// The recent-files list kept beside the recovery file.
pub fn recent_path(recovery_file: &Path) -> PathBuf {
    recovery_file.with_file_name("recent.ron")
}

/// The recent files saved by an earlier session (none if unreadable).
pub fn load_recent(recovery_file: &Path) -> Vec<PathBuf> {
    load_kept(&recent_path(recovery_file))
}

/// Saves the recent-files list (as [`autosave`] writes).
pub fn save_recent(recovery_file: &Path, recent: &[PathBuf]) -> std::io::Result<()> {
    save_kept(&recent_path(recovery_file), &recent)
}

/// The editor's choices kept beside the recovery file (*Fit to image…*'s settings).
pub fn choices_path(recovery_file: &Path) -> PathBuf {
    recovery_file.with_file_name("choices.ron")
}

/// Something an earlier session kept at `path` (the default if it is missing or
/// unreadable: a choice is not worth refusing to start over).
pub fn load_kept<T: serde::de::DeserializeOwned + Default>(path: &Path) -> T {
    read_ron(path)
        .and_then(|text| ron::from_str(&text).ok())
        .unwrap_or_default()
}

/// Keeps `value` at `path` for later sessions (as [`autosave`] writes).
pub fn save_kept<T: Serialize + ?Sized>(path: &Path, value: &T) -> std::io::Result<()> {
    let text = ron::ser::to_string_pretty(value, ron::ser::PrettyConfig::new())
        .map_err(std::io::Error::other)?;
    write_own_file(path, &text)
}

/// The text of a RON file of ours, if it is a readable regular file within the limit
/// for graph files.
fn read_ron(path: &Path) -> Option<String> {
    let bytes = crate::fsutil::read_limited(path, crate::fsutil::ReadLimit::GRAPH).ok()?;
    String::from_utf8(bytes).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_recovered_graph_reads_its_files_from_its_original_folder() {
        let dir =
            std::env::temp_dir().join(format!("veneer-recovery-folder-{}", std::process::id()));
        let file = dir.join("recovery.ron");
        let graph = Graph::default();
        let original = Some(PathBuf::from("/projects/walls/brick.ron"));
        autosave(&file, &Recovery::written_now(original, &graph), None).expect("writes");
        let recovered = read(&file).expect("reads");
        assert_eq!(recovered.graph.folder.path(), Path::new("/projects/walls"));
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn window_files_name_their_process() {
        let base = Path::new("/state/veneer/recovery.ron");
        let file = window_file(base);
        let name = file.file_name().unwrap().to_string_lossy().into_owned();
        assert_eq!(window_pid(base, &name), Some(std::process::id()));
        assert_ne!(window_file(base), file, "each window has its own file");
        assert_eq!(window_pid(base, "recovery.ron"), None);
        assert_eq!(window_pid(base, "recent.ron"), None);
        assert_eq!(window_pid(base, "choices.ron"), None);
        assert_eq!(window_pid(base, "recovery-12-x.ron"), None);
    }

    #[test]
    fn this_process_runs_and_its_start_time_is_known_on_linux() {
        let pid = std::process::id();
        assert!(running(pid, start_time(pid)));
        if cfg!(target_os = "linux") {
            assert!(start_time(pid).is_some());
            // The start time tells this process from another that had the same id.
            let parent = std::os::unix::process::parent_id();
            let started = start_time(parent).unwrap();
            assert!(running(parent, Some(started)));
            assert!(!running(parent, Some(started + 1)));
        }
    }

    #[test]
    fn a_process_that_ended_but_is_not_reaped_is_gone() {
        let mut child = std::process::Command::new("true").spawn().unwrap();
        let pid = child.id();
        // Not waited for yet: a zombie once it has ended.
        std::thread::sleep(std::time::Duration::from_millis(300));
        if cfg!(target_os = "linux") {
            assert!(!running(pid, None), "a zombie counts as gone");
        }
        child.wait().unwrap();
        assert!(!running(pid, None));
    }

    #[test]
    fn a_fifo_where_the_recent_list_goes_is_refused_at_once() {
        let dir = tempfile::tempdir().unwrap();
        let base = dir.path().join("recovery.ron");
        crate::fsutil::tests::mkfifo(&recent_path(&base));
        let saved = crate::fsutil::tests::returns(move || {
            save_recent(&base, &[PathBuf::from("a.ron")]).map_err(|e| e.to_string())
        });
        let error = saved.unwrap_err();
        assert!(error.contains("FIFO"), "{error}");
    }

    #[test]
    fn orphans_are_the_files_of_processes_that_are_gone() {
        let dir = tempfile::tempdir().unwrap();
        let base = dir.path().join("recovery.ron");
        let graph = crate::graph::preset("marble").unwrap();
        let recovery = |pid| Recovery {
            original: None,
            graph: &graph,
            pid: Some(pid),
            started: start_time(pid),
            file: PathBuf::new(),
            saved: None,
        };
        let mine = window_file(&base);
        autosave(&mine, &recovery(std::process::id()), None).unwrap();
        // A process that has ended: a child that has been reaped.
        let mut child = std::process::Command::new("true").spawn().unwrap();
        let gone = child.id();
        child.wait().unwrap();
        let orphan = base.with_file_name(format!("recovery-{gone}-0.ron"));
        autosave(&orphan, &recovery(gone), None).unwrap();
        let found = orphans(&base);
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!(found[0].file, orphan);
        assert_eq!(found[0].graph, graph);
    }

    #[test]
    fn an_edit_after_a_write_asks_for_a_wake_and_is_written_then() {
        let dir = std::env::temp_dir().join(format!("veneer-autosave-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let mut document = Document::new(crate::graph::preset("wood").unwrap(), None);
        let mut autosave = Autosave::new(dir.join("recovery-1-0.ron"));
        document.graph.name = "first edit".into();
        assert_eq!(
            autosave.tick(10.0, &document, 1, None).unwrap(),
            None,
            "written at once"
        );
        let on_disk = |file: &Path| read(file).map(|r| r.graph.name);
        assert_eq!(on_disk(&autosave.file).as_deref(), Some("first edit"));
        // A second edit within the autosave interval: not written yet, but the editor is
        // told when to come back, even if nothing else wakes it.
        document.graph.name = "second edit".into();
        let wait = autosave.tick(11.0, &document, 2, None).unwrap();
        assert_eq!(wait, Some(AUTOSAVE_SECONDS - 1.0));
        assert_eq!(on_disk(&autosave.file).as_deref(), Some("first edit"));
        assert_eq!(
            autosave
                .tick(10.0 + AUTOSAVE_SECONDS, &document, 2, None)
                .unwrap(),
            None
        );
        assert_eq!(on_disk(&autosave.file).as_deref(), Some("second edit"));
        // Nothing new: no wake asked for.
        assert_eq!(autosave.tick(30.0, &document, 2, None).unwrap(), None);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
