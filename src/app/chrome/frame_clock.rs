//! Measuring the editor's frames. The frame rate the status bar shows (*View → Frame
//! rate*): frames a second and the main thread's mean time per frame over the last
//! second of continuous redrawing (one frame's interval alone jumps between 14 and 26
//! fps on a software rasteriser while a parameter is dragged; a second's worth reads
//! steadily); the main thread's CPU time; and the frame log `--frame-log` writes.

use std::collections::VecDeque;
use std::io::Write;
use std::path::Path;
use std::time::{Duration, Instant, SystemTime};

/// How far back the rate looks.
const WINDOW: Duration = Duration::from_secs(1);
/// Frames further apart than this are not continuous redrawing: the count starts over.
const PAUSE: Duration = Duration::from_millis(500);

/// The starts of recent frames and the main thread's time in each.
#[derive(Default)]
pub struct FrameClock {
    frames: VecDeque<(Instant, Duration)>,
}

/// What the clock read over its window.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameRate {
    /// Frames a second.
    pub per_second: f64,
    /// The main thread's mean time per frame (the rest is painting and waiting).
    pub main_thread: Duration,
}

impl FrameClock {
    /// Notes a frame that began at `started` and whose main-thread work took
    /// `main_thread` (called as that work ends).
    pub fn record(&mut self, started: Instant, main_thread: Duration) {
        if let Some(&(last, _)) = self.frames.back()
            && started.saturating_duration_since(last) > PAUSE
        {
            self.frames.clear();
        }
        self.frames.push_back((started, main_thread));
        while let Some(&(first, _)) = self.frames.front()
            && started.saturating_duration_since(first) > WINDOW
        {
            self.frames.pop_front();
        }
    }

    /// The rate over the window, or `None` until two frames of continuous redrawing
    /// were seen.
    pub fn rate(&self) -> Option<FrameRate> {
        let (&(first, _), &(last, _)) = (self.frames.front()?, self.frames.back()?);
        let span = last.saturating_duration_since(first).as_secs_f64();
        let intervals = self.frames.len() - 1;
        if intervals == 0 || span <= 0.0 {
            return None;
        }
        let work: Duration = self.frames.iter().map(|&(_, work)| work).sum();
        Some(FrameRate {
            per_second: intervals as f64 / span,
            main_thread: work / self.frames.len() as u32,
        })
    }
}

/// The CPU time the calling thread has used (zero where the platform does not say).
pub fn thread_cpu_time() -> Duration {
    #[cfg(unix)]
    {
        let mut now = libc::timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        // SAFETY: `clock_gettime` writes one `timespec`, which `now` is.
        if unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut now) } == 0 {
            return Duration::new(now.tv_sec as u64, now.tv_nsec as u32);
        }
    }
    Duration::ZERO
}

/// `veneer edit --frame-log FILE`: one CSV line per frame, for measuring the real window
/// from outside (`benches/editor_window.rs`): when the frame began (seconds since the
/// Unix epoch), the main thread's time in it, and the graph's revision and compile count
/// after it (a drag that edits bumps the revision; it must not recompile); then where
/// the main thread's time went ([`FrameProfile`]: its CPU time, the panels, and the
/// document's followers).
pub struct FrameLog {
    file: std::io::BufWriter<std::fs::File>,
}

/// The frame log's first line.
pub const FRAME_LOG_HEADER: &str = "unix_seconds,main_thread_ms,revision,compiles,\
cpu_ms,panels_ms,sync_ms,compile_ms,lint_ms,thumbnails_ms,history_ms";

impl FrameLog {
    /// Creates (or empties) `path` and writes the header. `path` is opened by what it is
    /// ([`crate::fsutil::open_stream`]): a FIFO without a reader is refused at once.
    pub fn create(path: &Path) -> Result<FrameLog, String> {
        let failed = |error: std::io::Error| {
            format!("{}: cannot write the frame log: {error}", path.display())
        };
        let file = crate::fsutil::open_stream(path).map_err(failed)?;
        let mut file = std::io::BufWriter::new(file);
        writeln!(file, "{FRAME_LOG_HEADER}").map_err(failed)?;
        file.flush().map_err(failed)?;
        Ok(FrameLog { file })
    }

    /// Writes one frame's line (and sends it on at once: the editor may be killed).
    /// A write that fails is dropped: the log is for measuring, not for the work.
    pub fn record(
        &mut self,
        started: SystemTime,
        profile: &FrameProfile,
        revision: u64,
        compiles: u64,
    ) {
        let seconds = started
            .duration_since(SystemTime::UNIX_EPOCH)
            .unwrap_or_default()
            .as_secs_f64();
        let ms = |time: Duration| time.as_secs_f64() * 1e3;
        let parts = [
            profile.cpu,
            profile.panels(),
            profile.sync,
            profile.compile,
            profile.lint,
            profile.thumbnails,
            profile.history,
        ];
        let parts: String = parts.map(|part| format!(",{:.3}", ms(part))).concat();
        let main = ms(profile.total);
        let _ = writeln!(
            self.file,
            "{seconds:.6},{main:.3},{revision},{compiles}{parts}"
        )
        .and_then(|()| self.file.flush());
    }
}

/// Where the main thread's time went in one frame of the editor.
#[derive(Clone, Copy, Debug, Default)]
pub struct FrameProfile {
    /// The whole of [`eframe::App::ui`]: laying out the panels and everything below.
    pub total: Duration,
    /// The CPU time the main thread spent in it: `total` less the time other threads
    /// (the previews, the driver's rasteriser) had the core.
    pub cpu: Duration,
    /// Taking the graph view's edits into the document.
    pub sync: Duration,
    /// Deciding whether to recompile, and recompiling.
    pub compile: Duration,
    pub lint: Duration,
    /// Bringing the node thumbnails in step (the drawing is on another thread).
    pub thumbnails: Duration,
    /// The dirty mark, title and autosave.
    pub history: Duration,
}

impl FrameProfile {
    /// The time spent laying out and drawing the panels (egui and egui-snarl): the
    /// whole frame less the document's upkeep.
    pub fn panels(&self) -> Duration {
        self.total
            .saturating_sub(self.sync + self.compile + self.lint + self.thumbnails + self.history)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn clock_of(starts_ms: &[u64], work_ms: u64) -> FrameClock {
        let origin = Instant::now();
        let mut clock = FrameClock::default();
        for &start in starts_ms {
            clock.record(
                origin + Duration::from_millis(start),
                Duration::from_millis(work_ms),
            );
        }
        clock
    }

    #[test]
    fn counts_frames_over_the_last_second() {
        // 50 ms apart for two seconds: 20 fps, the first second forgotten.
        let starts: Vec<u64> = (0..=40).map(|frame| frame * 50).collect();
        let clock = clock_of(&starts, 3);
        let rate = clock.rate().expect("continuous frames");
        assert!((rate.per_second - 20.0).abs() < 1e-9, "{rate:?}");
        assert_eq!(rate.main_thread, Duration::from_millis(3));
        assert_eq!(clock.frames.len(), 21);
    }

    #[test]
    fn uneven_frames_read_as_their_mean() {
        // Alternating 30 ms and 70 ms frames: 20 fps, not 14 or 33.
        let mut starts = vec![0];
        for frame in 0..20u64 {
            starts.push(starts.last().unwrap() + if frame % 2 == 0 { 30 } else { 70 });
        }
        let rate = clock_of(&starts, 1).rate().expect("continuous frames");
        assert!((rate.per_second - 20.0).abs() < 1e-9, "{rate:?}");
    }

    #[test]
    fn thread_cpu_time_counts_work_and_not_sleep() {
        let before = thread_cpu_time();
        std::thread::sleep(Duration::from_millis(30));
        let slept = thread_cpu_time() - before;
        // Busy until the thread has run 30 ms (or 5 s have passed: on a loaded machine
        // the thread gets only part of a core).
        let started = Instant::now();
        let mut sum = 0u64;
        while thread_cpu_time() - before - slept < Duration::from_millis(30)
            && started.elapsed() < Duration::from_secs(5)
        {
            for _ in 0..1000 {
                sum = sum.wrapping_add(std::hint::black_box(1));
            }
        }
        let worked = thread_cpu_time() - before - slept;
        assert!(slept < Duration::from_millis(10), "{slept:?} while asleep");
        assert!(
            worked > Duration::from_millis(10),
            "{worked:?} while busy ({sum})"
        );
    }

    #[test]
    fn the_frame_log_writes_a_line_a_frame() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("frames.csv");
        let mut log = FrameLog::create(&path).unwrap();
        let at = SystemTime::UNIX_EPOCH + Duration::from_millis(1_700_000_000_250);
        let profile = FrameProfile {
            total: Duration::from_micros(2_500),
            cpu: Duration::from_micros(2_000),
            compile: Duration::from_micros(500),
            thumbnails: Duration::from_micros(250),
            ..FrameProfile::default()
        };
        log.record(at, &profile, 7, 1);
        let text = std::fs::read_to_string(&path).unwrap();
        assert_eq!(
            text,
            format!(
                "{FRAME_LOG_HEADER}\n1700000000.250000,2.500,7,1,\
                 2.000,1.750,0.000,0.500,0.000,0.250,0.000\n"
            )
        );
        assert!(FrameLog::create(&dir.path().join("missing/frames.csv")).is_err());
    }

    #[test]
    fn a_pause_starts_the_count_over() {
        assert_eq!(clock_of(&[0], 1).rate(), None);
        // Two frames, then a pause: the frame after it stands alone.
        assert_eq!(clock_of(&[0, 40, 1000], 1).rate(), None);
        let rate = clock_of(&[0, 40, 1000, 1100], 1)
            .rate()
            .expect("two frames");
        assert!((rate.per_second - 10.0).abs() < 1e-9, "{rate:?}");
    }
}
