//! The real editor window's frame rate, measured from outside: the `veneer` binary on
//! its own Xvfb display (software rasteriser), driven by `xdotool` with real pointer
//! events, writing a line per frame (`veneer edit --frame-log`). What the user sees —
//! painting, the preview thread's drafts and the window system included — where
//! `editor_frames` (kittest) measures parts.
//!
//! In one run, on the wood preset, twice each: **the baseline**, the pointer moving over
//! the graph with no button held (each move repaints the window: painting alone), and
//! **a parameter dragged** (the rings' frequency in its node, a pixel every 10 ms: each
//! frame edits, recompiles nothing, and the preview draws a draft). Skipped (not failed)
//! without Xvfb and xdotool, which `.ci/run` installs.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant, SystemTime};
use veneer::app::FRAME_LOG_HEADER;

/// The window's size (the editor's default) on a larger screen.
const SCREEN: &str = "1600x900x24";
/// Where the rings' frequency field is in the window as wood opens (the inspector is
/// not needed: node bodies edit their constants).
const RINGS_FREQUENCY: (i32, i32) = (292, 331);
/// An empty spot of the canvas, for the pointer to move over.
const EMPTY_CANVAS: (i32, i32) = (600, 760);
/// How long each scenario runs, and how much of its start is left out (the first
/// frames of a drag switch the preview to drafts).
const RUN: Duration = Duration::from_secs(6);
const WARM_UP: Duration = Duration::from_secs(1);
/// Pointer events a second, as a hand dragging a slider produces them.
const EVENTS_PER_SECOND: u32 = 100;

fn main() {
    for tool in ["Xvfb", "xdotool"] {
        if !on_path(tool) {
            println!("editor_window: skipped, `{tool}` is not installed (.ci/run installs it)");
            return;
        }
    }
    let dir = tempfile::tempdir().expect("a scratch folder");
    let display = format!(":{}", 60 + std::process::id() % 200);
    let _xvfb = Owned(
        Command::new("Xvfb")
            .args([display.as_str(), "-screen", "0", SCREEN, "-nolisten", "tcp"])
            .stderr(Stdio::null())
            .spawn()
            .expect("Xvfb starts"),
    );
    wait_for(|| Path::new(&format!("/tmp/.X11-unix/X{}", &display[1..])).exists());
    let log = dir.path().join("frames.csv");
    let wood = Path::new(env!("CARGO_MANIFEST_DIR")).join("graphs/wood.ron");
    std::fs::create_dir_all(dir.path().join("run")).unwrap();
    let editor = Owned(
        Command::new(env!("CARGO_BIN_EXE_veneer"))
            .arg("edit")
            .arg(&wood)
            .arg("--frame-log")
            .arg(&log)
            .env("DISPLAY", &display)
            .env("XDG_STATE_HOME", dir.path())
            .env("XDG_RUNTIME_DIR", dir.path().join("run"))
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("the editor starts"),
    );
    let window = xdotool(&display, "search --sync --name Veneer\n")
        .lines()
        .next()
        .expect("the editor's window appears")
        .to_string();
    // Opening builds the preview's pipelines and every thumbnail: wait for quiet.
    wait_until_idle(&log, Duration::from_secs(2));
    let mut results = Vec::new();
    for round in 0..2 {
        for dragged in [false, true] {
            let (started, ended) = run_scenario(&display, &window, dragged);
            wait_until_idle(&log, Duration::from_millis(1500));
            results.push((round, dragged, measure(&log, started + WARM_UP, ended)));
        }
    }
    drop(editor);
    report(&results);
}

/// Moves the pointer for [`RUN`]: over empty canvas, or pressing on the rings'
/// frequency and dragging it back and forth. Returns when the events began and ended.
fn run_scenario(display: &str, window: &str, dragged: bool) -> (SystemTime, SystemTime) {
    let (x, y) = if dragged {
        RINGS_FREQUENCY
    } else {
        EMPTY_CANVAS
    };
    let mut script = format!("mousemove --window {window} {x} {y}\nsleep 0.3\n");
    if dragged {
        script.push_str("mousedown 1\nsleep 0.1\n");
    }
    let pause = 1.0 / f64::from(EVENTS_PER_SECOND);
    let events = RUN.as_secs_f64() * f64::from(EVENTS_PER_SECOND);
    for event in 0..events as u32 {
        // Forty pixels right, forty back.
        let step = if (event / 40) % 2 == 0 { 1 } else { -1 };
        script.push_str(&format!("mousemove_relative -- {step} 0\nsleep {pause}\n"));
    }
    if dragged {
        script.push_str("mouseup 1\n");
    }
    let started = SystemTime::now() + Duration::from_millis(if dragged { 400 } else { 300 });
    xdotool(display, &script);
    (started, SystemTime::now())
}

/// What the frame log says of the frames that began between `from` and `to`.
#[derive(Debug)]
struct Measured {
    frames: usize,
    per_second: f64,
    main_thread_median_ms: f64,
    edits: u64,
    recompiles: u64,
}

fn measure(log: &Path, from: SystemTime, to: SystemTime) -> Measured {
    let seconds = |at: SystemTime| {
        at.duration_since(SystemTime::UNIX_EPOCH)
            .unwrap()
            .as_secs_f64()
    };
    let (from, to) = (seconds(from), seconds(to));
    let text = std::fs::read_to_string(log).expect("the frame log");
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some(FRAME_LOG_HEADER));
    let frames: Vec<[f64; 4]> = lines
        .map(|line| {
            let fields: Vec<f64> = line
                .split(',')
                .map(|f| f.parse().expect("a number"))
                .collect();
            [fields[0], fields[1], fields[2], fields[3]]
        })
        .filter(|frame| frame[0] >= from && frame[0] <= to)
        .collect();
    assert!(
        frames.len() >= 2,
        "no frames between the scenario's start and end"
    );
    let (first, last) = (frames[0], frames[frames.len() - 1]);
    let mut main: Vec<f64> = frames.iter().map(|frame| frame[1]).collect();
    main.sort_by(f64::total_cmp);
    Measured {
        frames: frames.len(),
        per_second: (frames.len() - 1) as f64 / (last[0] - first[0]),
        main_thread_median_ms: main[main.len() / 2],
        edits: (last[2] - first[2]) as u64,
        recompiles: (last[3] - first[3]) as u64,
    }
}

fn report(results: &[(usize, bool, Measured)]) {
    println!(
        "editor window, wood preset, 1400×860 on Xvfb, {EVENTS_PER_SECOND} pointer events a second:"
    );
    println!("| round | what | frames a second | main thread (median) | edits | recompiles |");
    println!("| --- | --- | --- | --- | --- | --- |");
    for (round, dragged, measured) in results {
        let what = if *dragged {
            "the rings' frequency dragged"
        } else {
            "baseline: the pointer moved over the graph"
        };
        println!(
            "| {} | {what} | {:.1} ({} frames) | {:.2} ms | {} | {} |",
            round + 1,
            measured.per_second,
            measured.frames,
            measured.main_thread_median_ms,
            measured.edits,
            measured.recompiles
        );
        if *dragged {
            assert!(
                measured.edits > 0,
                "the drag edited nothing: is RINGS_FREQUENCY still where the field is?"
            );
            assert_eq!(measured.recompiles, 0, "a drag recompiled");
        }
    }
}

/// Runs `script` through one `xdotool` (commands on its standard input), returning
/// what it printed.
fn xdotool(display: &str, script: &str) -> String {
    let mut child = Command::new("xdotool")
        .arg("-")
        .env("DISPLAY", display)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .expect("xdotool starts");
    child
        .stdin
        .take()
        .expect("its input")
        .write_all(script.as_bytes())
        .expect("the script goes to xdotool");
    let output = child.wait_with_output().expect("xdotool ends");
    String::from_utf8_lossy(&output.stdout).into_owned()
}

/// Waits until the editor has drawn no frame for `quiet` (at most two minutes).
fn wait_until_idle(log: &Path, quiet: Duration) {
    let started = Instant::now();
    let mut last = (0, Instant::now());
    while started.elapsed() < Duration::from_secs(120) {
        let length = std::fs::metadata(log).map(|meta| meta.len()).unwrap_or(0);
        if length != last.0 {
            last = (length, Instant::now());
        } else if last.1.elapsed() >= quiet && length > FRAME_LOG_HEADER.len() as u64 + 1 {
            return;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    panic!("the editor never went quiet");
}

fn wait_for(ready: impl Fn() -> bool) {
    let started = Instant::now();
    while !ready() {
        assert!(
            started.elapsed() < Duration::from_secs(20),
            "Xvfb did not start"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
}

fn on_path(tool: &str) -> bool {
    std::env::var_os("PATH").is_some_and(|path| {
        std::env::split_paths(&path).any(|dir: PathBuf| dir.join(tool).is_file())
    })
}

/// A child process ended (SIGTERM, then waited for) however the bench ends.
struct Owned(Child);

impl Drop for Owned {
    fn drop(&mut self) {
        if let Ok(pid) = libc::pid_t::try_from(self.0.id()) {
            // SAFETY: signals our own child.
            unsafe { libc::kill(pid, libc::SIGTERM) };
        }
        let _ = self.0.wait();
    }
}
