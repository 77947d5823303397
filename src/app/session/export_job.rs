//! An export running on a thread of its own, so that the window keeps answering: what it
//! writes, how far it has come, and a way to take it back.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, mpsc};

/// How far an export has come and whether it is still wanted, shared with its thread.
#[derive(Default)]
pub struct Progress {
    done: AtomicU64,
    total: AtomicU64,
    cancelled: AtomicBool,
}

impl Progress {
    /// Records `done` of `total` steps; answers whether the export is still wanted.
    pub fn report(&self, done: u64, total: u64) -> bool {
        self.total.store(total, Ordering::Relaxed);
        self.done.store(done, Ordering::Relaxed);
        !self.cancelled.load(Ordering::Relaxed)
    }
}

/// What an export's thread hands back: the status bar's message, or why it failed.
pub type Outcome = Result<String, String>;

/// An export under way.
pub struct ExportJob {
    /// What is written (the file's name), for the status bar.
    pub what: String,
    progress: Arc<Progress>,
    outcome: mpsc::Receiver<Outcome>,
}

impl ExportJob {
    /// Runs `work` on a thread of its own; it reports through the [`Progress`] it is
    /// given, and the window is woken whenever it does and when it ends.
    pub fn start(
        ctx: &egui::Context,
        what: String,
        work: impl FnOnce(&dyn Fn(u64, u64) -> bool) -> Outcome + Send + 'static,
    ) -> ExportJob {
        let progress = Arc::new(Progress::default());
        let (sender, outcome) = mpsc::channel();
        let shared = Arc::clone(&progress);
        let wake = ctx.clone();
        std::thread::Builder::new()
            .name(format!("export {what}"))
            .spawn(move || {
                let report = |done: u64, total: u64| {
                    wake.request_repaint();
                    shared.report(done, total)
                };
                let result = work(&report);
                let _ = sender.send(result);
                wake.request_repaint();
            })
            .expect("an export thread starts");
        ExportJob {
            what,
            progress,
            outcome,
        }
    }

    /// The outcome, once the export has ended (a thread that panicked says so).
    pub fn poll(&self) -> Option<Outcome> {
        match self.outcome.try_recv() {
            Ok(outcome) => Some(outcome),
            Err(mpsc::TryRecvError::Empty) => None,
            Err(mpsc::TryRecvError::Disconnected) => Some(Err(format!(
                "{}: the export stopped unexpectedly",
                self.what
            ))),
        }
    }

    /// The part done, from 0 to 1 (`None` before the first report).
    pub fn fraction(&self) -> Option<f32> {
        let total = self.progress.total.load(Ordering::Relaxed);
        let done = self.progress.done.load(Ordering::Relaxed);
        (total > 0).then(|| (done as f64 / total as f64).min(1.0) as f32)
    }

    /// Asks the export to stop; it ends with nothing written at its next report.
    pub fn cancel(&self) {
        self.progress.cancelled.store(true, Ordering::Relaxed);
    }

    /// Whether [`ExportJob::cancel`] was asked.
    pub fn cancelled(&self) -> bool {
        self.progress.cancelled.load(Ordering::Relaxed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_job_reports_progress_and_stops_when_cancelled() {
        let ctx = egui::Context::default();
        let (step, steps) = mpsc::channel::<()>();
        let job = ExportJob::start(&ctx, "test.glb".into(), move |report| {
            for done in 0..=100 {
                if !report(done, 100) {
                    return Err("cancelled".into());
                }
                // One step each time the test says so.
                if steps.recv().is_err() {
                    break;
                }
            }
            Ok("exported".into())
        });
        step.send(()).unwrap();
        step.send(()).unwrap();
        let started = std::time::Instant::now();
        while job.fraction() < Some(0.02) && started.elapsed().as_secs() < 10 {
            std::thread::yield_now();
        }
        assert_eq!(job.fraction(), Some(0.02));
        assert!(job.poll().is_none(), "still running");
        job.cancel();
        step.send(()).unwrap();
        let outcome = loop {
            if let Some(outcome) = job.poll() {
                break outcome;
            }
            std::thread::yield_now();
        };
        assert_eq!(outcome, Err("cancelled".to_string()));
    }
}
