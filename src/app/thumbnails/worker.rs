//! The thread that draws node thumbnails: it owns a wgpu device of its own, builds the
//! atlas pipeline when the code changes and draws the tiles asked for, so neither the
//! pipeline build nor the draw and readback ever wait on the UI thread.

use crate::app::preview::drawing_thread::DrawingThread;
use crate::codegen::passes::Passes;
use crate::render::{AtlasLayout, FlatRect, GpuContext, ThumbnailRenderer};
use std::sync::Arc;
use std::sync::mpsc::{Receiver, Sender, TryRecvError, channel};

/// Tiles to draw with one module.
pub struct Job {
    /// Changes whenever `wgsl` does (the pipeline is rebuilt then).
    pub generation: u64,
    /// The atlas graph's module, parameters as uniforms.
    pub wgsl: Arc<str>,
    /// Its parameter slots.
    pub slots: usize,
    /// Its passes, when it reads buffers (they change with `wgsl`).
    pub passes: Option<Arc<Passes>>,
    pub layout: AtlasLayout,
    /// The square of the plane every tile samples (and the passes render over).
    pub rect: FlatRect,
    pub time: f32,
    /// The atlas graph's parameter values: what the passes read (the selectors, read
    /// by the final stage alone, change only per tile).
    pub shared: Vec<[f32; 4]>,
    /// Tile index and that tile's parameter values.
    pub tiles: Vec<(usize, Vec<[f32; 4]>)>,
}

/// A job done: the tiles drawn and the whole atlas after drawing them.
pub struct Done {
    pub layout: AtlasLayout,
    pub tiles: Vec<usize>,
    /// RGBA8 rows of the atlas, or why the draw failed.
    pub pixels: Result<Vec<u8>, String>,
}

/// The UI thread's end of the channels; dropping it ends the thread (and waits for it,
/// see [`DrawingThread`]).
pub struct Worker {
    jobs: Sender<Job>,
    done: Receiver<Done>,
    thread: DrawingThread,
}

impl Worker {
    /// Starts the thread; `wake` is called after each job (the UI repaints then).
    pub fn start(wake: impl Fn() + Send + 'static) -> Worker {
        let (jobs, job_receiver) = channel::<Job>();
        let (done_sender, done) = channel();
        let thread = DrawingThread::spawn("veneer thumbnails", move || {
            crate::app::priority::behind_the_window();
            let gpu = GpuContext::new().map_err(|error| error.to_string());
            let mut renderer: Option<(u64, ThumbnailRenderer)> = None;
            for job in job_receiver {
                let pixels = gpu
                    .as_ref()
                    .map_err(Clone::clone)
                    .and_then(|gpu| draw(gpu, &mut renderer, &job));
                let tiles = job.tiles.iter().map(|(index, _)| *index).collect();
                let reply = Done {
                    layout: job.layout,
                    tiles,
                    pixels,
                };
                if done_sender.send(reply).is_err() {
                    break;
                }
                wake();
            }
        });
        Worker { jobs, done, thread }
    }

    /// Hands a job to the thread.
    pub fn send(&self, job: Job) {
        let _ = self.jobs.send(job);
    }

    /// A finished job, if one is waiting; `Err` when the thread has gone.
    pub fn try_done(&self) -> Result<Option<Done>, ()> {
        match self.done.try_recv() {
            Ok(done) => Ok(Some(done)),
            Err(TryRecvError::Empty) => Ok(None),
            Err(TryRecvError::Disconnected) => Err(()),
        }
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        // Hang up both channels: the thread stops at its next job or reply, whatever
        // jobs are still queued.
        let (jobs, _) = channel();
        drop(std::mem::replace(&mut self.jobs, jobs));
        let (_, done) = channel();
        drop(std::mem::replace(&mut self.done, done));
        self.thread.wait();
    }
}

fn draw(
    gpu: &GpuContext,
    renderer: &mut Option<(u64, ThumbnailRenderer)>,
    job: &Job,
) -> Result<Vec<u8>, String> {
    if renderer.as_ref().map(|(generation, _)| *generation) != Some(job.generation) {
        let built = ThumbnailRenderer::new(gpu, &job.wgsl, job.slots, job.passes.as_deref());
        *renderer = Some((job.generation, built.map_err(|error| error.to_string())?));
    }
    let (_, renderer) = renderer.as_mut().expect("built above");
    renderer
        .render(
            gpu,
            job.layout,
            (job.rect, job.time),
            &job.shared,
            &job.tiles,
        )
        .map_err(|error| error.to_string())
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_dropped_worker_has_waited_for_its_thread_and_device() {
        crate::app::preview::drawing_thread::assert_dropping_waits_for_the_thread(
            super::Worker::start,
        );
    }
}
