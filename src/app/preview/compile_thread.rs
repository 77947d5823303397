//! Compiling the preview's material: at once for small graphs, on a thread of its own
//! for big ones (a 10,000-node graph takes half a second to check and compile: the UI
//! keeps answering meanwhile, and the preview shows the last material until the new
//! one is in).

use crate::codegen::{CompileError, CompileOptions, Compiled, Detail, ParamMode, compile};
use crate::graph::Graph;
use std::sync::{Arc, mpsc};

/// Graphs of more nodes than this (counting the nodes inside groups) compile on a
/// thread of their own; smaller ones compile in the frame of the edit.
pub const BACKGROUND_NODES: usize = 500;

/// The most parameter slots a uniform block takes: 16 KiB, what every device offers.
/// Past it parameters go to a storage buffer (uniform blocks are kept below it: reads
/// from them are known to be uniform, which some drivers, lavapipe among them, need for
/// the screen-space derivatives of footprint-aware noise to come out clean).
pub const UNIFORM_SLOTS: usize = 1024;

/// A compile's outcome.
pub type Outcome = Result<Compiled, CompileError>;

/// How the preview compiles a graph.
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

/// A compile running on its own thread.
pub struct Compiling {
    outcome: mpsc::Receiver<Outcome>,
}

impl Compiling {
    /// Compiles `graph` as `request` says on a thread of its own, waking `ctx` when
    /// done.
    pub fn start(graph: Graph, request: Request, ctx: egui::Context) -> Compiling {
        let (send, outcome) = mpsc::channel();
        let graph = Arc::new(graph);
        let (job_graph, job_send) = (Arc::clone(&graph), send.clone());
        let spawned = std::thread::Builder::new()
            .name("veneer-compile".into())
            .spawn(move || {
                // (The editor may have moved on to a newer compile: then no one listens.)
                let _ = job_send.send(request.compile(&job_graph));
                ctx.request_repaint();
            });
        if spawned.is_err() {
            // No thread to be had: compiled here, as a small graph is.
            let _ = send.send(request.compile(&graph));
        }
        Compiling { outcome }
    }

    /// The outcome, once the compile is done.
    pub fn outcome(&self) -> Option<Outcome> {
        self.outcome.try_recv().ok()
    }
}
