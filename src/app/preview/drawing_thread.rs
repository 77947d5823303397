//! The threads that draw with GPU devices of their own (the previews, the thumbnails)
//! are waited for when the editor closes. A process that exits while one of them still
//! tears its device down crashes in the driver's exit handlers (seen with Mesa: a
//! segfault in `swrast_dri.so` after SIGTERM, while the preview thread was unmapping
//! its device's memory), so a closing editor waits for them, within a limit.

use std::sync::mpsc::{Receiver, channel};
use std::time::Duration;

/// How long a closing editor waits for a drawing thread: longer than any draw, and than
/// a device starting on a machine whose cores are all busy (over 3 s was seen while the
/// test suite ran), shorter than a very large graph's pipeline build (then the editor
/// exits regardless).
const LIMIT: Duration = Duration::from_secs(10);

/// A drawing thread, to be waited for.
pub struct DrawingThread {
    /// Disconnects when the thread has ended (its end is dropped, unwinding too).
    ended: Receiver<()>,
}

impl DrawingThread {
    /// Starts `body` on a thread named `name`.
    pub fn spawn(name: &str, body: impl FnOnce() + Send + 'static) -> DrawingThread {
        let (end, ended) = channel::<()>();
        std::thread::Builder::new()
            .name(name.into())
            .spawn(move || {
                let _end = end;
                body();
            })
            .expect("a drawing thread starts");
        DrawingThread { ended }
    }

    /// Waits until the thread has ended, at most [`LIMIT`]; returns whether it did.
    pub fn wait(&self) -> bool {
        matches!(
            self.ended.recv_timeout(LIMIT),
            Err(std::sync::mpsc::RecvTimeoutError::Disconnected)
        )
    }
}

/// For the workers' tests: starts a worker with `start` (given its wake-up call), drops
/// it, and checks that its thread had ended by then (the thread owned the wake-up call).
#[cfg(test)]
pub fn assert_dropping_waits_for_the_thread<W>(start: impl FnOnce(Box<dyn Fn() + Send>) -> W) {
    let alive = std::sync::Arc::new(());
    let held = std::sync::Arc::clone(&alive);
    let worker = start(Box::new(move || {
        let _ = &held;
    }));
    drop(worker);
    assert_eq!(
        std::sync::Arc::strong_count(&alive),
        1,
        "the thread outlived its worker"
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Instant;

    #[test]
    fn waits_for_the_thread_to_end() {
        let thread = DrawingThread::spawn("test", || std::thread::sleep(Duration::from_millis(50)));
        let started = Instant::now();
        assert!(thread.wait());
        assert!(started.elapsed() >= Duration::from_millis(30));
    }

    #[test]
    fn a_thread_that_panics_has_ended_too() {
        let thread = DrawingThread::spawn("test", || panic!("a failing draw"));
        assert!(thread.wait());
    }
}
