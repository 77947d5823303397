//! Work on a big graph done on a thread of its own: compiling the preview's material
//! and the thumbnails' atlas, and the lint. A 10,000-node graph takes half a second to
//! check and compile and a tenth to lint: done in the frame of an edit, that would be
//! the UI's pause; done here, the UI keeps answering and shows the last material (and
//! warnings) until the new ones are in, the thread behind the window in priority. Small
//! graphs are done at once, in the frame.

use crate::codegen::{CompileError, CompileOptions, Compiled, Detail, ParamMode, compile};
use crate::graph::Graph;
use std::sync::{Arc, Mutex, mpsc};

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
        let spawned = std::thread::Builder::new()
            .name("veneer-background".into())
            .spawn(move || {
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
