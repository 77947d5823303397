//! Work on a big graph done on a thread of its own: compiling the preview's material
//! and the thumbnails' atlas, and the lint. A 10,000-node graph takes half a second to
//! check and compile and a tenth to lint: done in the frame of an edit, that would be
//! the UI's pause; done here, the UI keeps answering and shows the last material (and
//! warnings) until the new ones are in, the thread behind the window in priority. Small
//! graphs are done at once, in the frame.

use crate::codegen::{CompileError, CompileOptions, Compiled, Detail, ParamMode, compile};
use crate::graph::Graph;
use std::sync::{Arc, Condvar, Mutex, mpsc};
use std::time::Duration;

/// Graphs of more nodes than this (counting the nodes inside groups) are compiled,
/// linted and autosaved on a thread of their own; smaller ones in the frame of the edit.
pub const BACKGROUND_NODES: usize = 500;

/// Whether `graph` has more than [`BACKGROUND_NODES`] nodes, inside its groups too.
pub fn is_big(graph: &Graph) -> bool {
    let inner: usize = graph.groups.values().map(|group| group.nodes.len()).sum();
    graph.nodes.len() + inner > BACKGROUND_NODES
}

/// The most parameter slots a uniform block takes: 16 KiB, what every device offers.
/// Past it parameters go to a storage buffer (uniform blocks are kept below it: reads
/// from them are known to be uniform, which some drivers, lavapipe among them, need for
/// the screen-space derivatives of footprint-aware noise to come out clean).
pub const UNIFORM_SLOTS: usize = 1024;

/// The edited graph as one frame's followers see it: borrowed, and copied once, when
/// first asked, for the threads that work on a big graph (the compile and the lint of
/// one edit share a copy: copying 10,000 nodes takes a millisecond of the frame).
pub struct Snapshot<'g> {
    pub graph: &'g Graph,
    copy: std::cell::OnceCell<Arc<Graph>>,
}

impl<'g> Snapshot<'g> {
    pub fn new(graph: &'g Graph) -> Snapshot<'g> {
        Snapshot {
            graph,
            copy: std::cell::OnceCell::new(),
        }
    }

    /// The graph's copy for threads.
    pub fn shared(&self) -> Arc<Graph> {
        Arc::clone(self.copy.get_or_init(|| Arc::new(self.graph.clone())))
    }

    /// The copy, if one was made.
    pub fn into_copy(self) -> Option<Arc<Graph>> {
        self.copy.into_inner()
    }
}

/// The window's frames ended so far. Work started in a frame waits for that frame to
/// end before it takes a core: on two cores, a compile thread started by an undo took a
/// quarter of the rest of that frame's time.
static FRAMES_ENDED: (Mutex<u64>, Condvar) = (Mutex::new(0), Condvar::new());

/// The longest work waits for the frame that started it (a script or a test may start
/// work outside any frame).
const FRAME_WAIT: Duration = Duration::from_millis(50);

/// The window's frame has ended: work that waits for it starts.
pub fn frame_ended() {
    let (ended, changed) = &FRAMES_ENDED;
    if let Ok(mut ended) = ended.lock() {
        *ended += 1;
        changed.notify_all();
    }
}

/// Runs `work` on a thread named `name` that begins once the frame that started it has
/// ended (or after [`FRAME_WAIT`]).
pub fn spawn_after_frame<T: Send + 'static>(
    name: &str,
    work: impl FnOnce() -> T + Send + 'static,
) -> std::io::Result<std::thread::JoinHandle<T>> {
    let (ended, changed) = &FRAMES_ENDED;
    let seen = ended.lock().map(|ended| *ended).unwrap_or_default();
    std::thread::Builder::new()
        .name(name.into())
        .spawn(move || {
            if let Ok(ended) = ended.lock() {
                let _ = changed.wait_timeout_while(ended, FRAME_WAIT, |ended| *ended == seen);
            }
            work()
        })
}

/// A compile's outcome.
pub type Outcome = Result<Compiled, CompileError>;

/// How the editor compiles a graph for the preview.
#[derive(Clone, Copy, Debug)]
pub struct Request {
    /// Every octave of fractals, not just what the pixel footprint shows.
    pub full_detail: bool,
    /// Parameters past [`UNIFORM_SLOTS`] go to a storage buffer.
    pub storage: bool,
}

impl Request {
    /// Compiles `graph` with parameters as uniforms (in a storage buffer when they
    /// pass what a uniform block holds and the request allows it).
    pub fn compile(self, graph: &Graph) -> Outcome {
        let detail = if self.full_detail {
            Detail::Full
        } else {
            Detail::Footprint
        };
        let mut options = CompileOptions {
            params: ParamMode::Uniform,
            detail,
        };
        let result = compile(graph, &options);
        let slots = result.as_ref().map_or(0, |c| c.module.params.len());
        if !self.storage || slots <= UNIFORM_SLOTS {
            return result;
        }
        options.params = ParamMode::Storage;
        compile(graph, &options)
    }
}

/// Work running on a thread of its own, its outcome taken when done.
pub struct Background<T> {
    outcome: mpsc::Receiver<T>,
}

impl<T: Send + 'static> Background<T> {
    /// Runs `work` on a thread of its own, waking `ctx` when done (or here and now,
    /// should no thread be had).
    pub fn start(work: impl FnOnce() -> T + Send + 'static, ctx: egui::Context) -> Background<T> {
        let (send, outcome) = mpsc::channel();
        let work = Arc::new(Mutex::new(Some(work)));
        let (job, job_send) = (Arc::clone(&work), send.clone());
        let spawned = spawn_after_frame("veneer-background", move || {
            crate::app::priority::behind_the_window();
            let work = job.lock().ok().and_then(|mut work| work.take());
            if let Some(work) = work {
                // (The editor may have moved on to newer work: then no one listens.)
                let _ = job_send.send(work());
                ctx.request_repaint();
            }
        });
        if spawned.is_err() {
            let work = work.lock().ok().and_then(|mut work| work.take());
            if let Some(work) = work {
                let _ = send.send(work());
            }
        }
        Background { outcome }
    }

    /// The outcome, once the work is done.
    pub fn outcome(&self) -> Option<T> {
        self.outcome.try_recv().ok()
    }
}

/// Work of one kind on a thread of its own, only the latest asked for: work asked for
/// while some runs waits for it to end, in place of any work waiting before it, and
/// the outcome of work overtaken that way is dropped. Ctrl+Z held down on a
/// 10,000-node graph asks for a compile every frame; each had run to its end, all at
/// once, on two cores.
pub struct Latest<T> {
    running: Option<Background<T>>,
    waiting: Option<(Job<T>, egui::Context)>,
}

/// Work waiting to run.
type Job<T> = Box<dyn FnOnce() -> T + Send>;

impl<T> Default for Latest<T> {
    fn default() -> Latest<T> {
        Latest {
            running: None,
            waiting: None,
        }
    }
}

impl<T: Send + 'static> Latest<T> {
    /// Runs `work` on a thread of its own, waking `ctx` when done: now if nothing
    /// runs, else once what runs has ended.
    pub fn start(&mut self, work: impl FnOnce() -> T + Send + 'static, ctx: egui::Context) {
        if self.running.is_some() {
            self.waiting = Some((Box::new(work), ctx));
        } else {
            self.running = Some(Background::start(work, ctx));
        }
    }

    /// The outcome of the latest work asked for, once done (work overtaken ends
    /// unheard, and the latest starts then).
    pub fn outcome(&mut self) -> Option<T> {
        let outcome = self.running.as_ref()?.outcome()?;
        self.running = None;
        match self.waiting.take() {
            Some((work, ctx)) => {
                self.running = Some(Background::start(work, ctx));
                None
            }
            None => Some(outcome),
        }
    }

    /// Whether work runs or waits.
    pub fn busy(&self) -> bool {
        self.running.is_some()
    }

    /// Forgets the work asked for (what runs ends unheard).
    pub fn forget(&mut self) {
        *self = Latest::default();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn work_started_in_a_frame_runs_once_the_frame_ends_or_without_one() {
        let ended = || FRAMES_ENDED.0.lock().map(|ended| *ended).unwrap();
        let (send, seen) = mpsc::channel();
        let before = ended();
        let work = spawn_after_frame("test", move || send.send(ended()).unwrap()).unwrap();
        frame_ended();
        work.join().unwrap();
        // It saw the frame end (other tests' windows may have ended frames too).
        assert!(seen.recv().unwrap() > before);
        // With no frame ending at all, it still runs (after the longest wait).
        assert_eq!(spawn_after_frame("test", || 7).unwrap().join().unwrap(), 7);
    }

    #[test]
    fn only_the_latest_work_asked_for_runs_after_what_runs() {
        let ctx = egui::Context::default();
        let (gate_send, gate) = mpsc::channel::<()>();
        let mut latest = Latest::default();
        latest.start(move || gate.recv().map_or(0, |()| 1), ctx.clone());
        latest.start(|| 2, ctx.clone());
        latest.start(|| 3, ctx.clone());
        assert!(latest.busy() && latest.outcome().is_none());
        gate_send.send(()).unwrap();
        let mut outcomes = Vec::new();
        let started = std::time::Instant::now();
        while latest.busy() && started.elapsed() < Duration::from_secs(10) {
            outcomes.extend(latest.outcome());
            frame_ended();
            std::thread::sleep(Duration::from_millis(1));
        }
        // The first ran to its end unheard, the second never ran.
        assert_eq!(outcomes, [3]);
    }
}
