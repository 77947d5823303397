//! The test's own X server and editor, driven by `xdotool` and watched through
//! ImageMagick's `import`: input, waits, screenshots and failures.

use super::shot::{Rect, Shot, diff, full};
use std::fs::File;
use std::io::Read;
use std::os::fd::{FromRawFd, OwnedFd};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};

/// How long one step may take before the test fails.
pub(super) const STEP: Duration = Duration::from_secs(20);
/// How long the window may take to appear (the first frame builds the preview's
/// pipelines, on a software rasteriser that other tests are using too).
pub(super) const START: Duration = Duration::from_secs(60);
/// How often a condition is polled.
pub(super) const POLL: Duration = Duration::from_millis(60);

/// The tools the tests drive the window with: program, Debian package.
const TOOLS: [(&str, &str); 3] = [
    ("Xvfb", "xvfb"),
    ("xdotool", "xdotool"),
    ("import", "imagemagick"),
];

/// Fails, naming the README's test command, when a tool the test needs is missing.
pub(super) fn require_tools() {
    let missing: Vec<String> = TOOLS
        .iter()
        .filter(|(program, _)| !on_path(program))
        .map(|(program, package)| format!("{program} (package {package})"))
        .collect();
    assert!(
        missing.is_empty(),
        "the real-window editor test needs {} and cannot find it on PATH. The README's \
         test command, `.ci/run`, installs it (apt-get install xvfb xdotool imagemagick) and \
         then runs `cargo test --release`.",
        missing.join(", ")
    );
}

fn on_path(program: &str) -> bool {
    std::env::var_os("PATH").is_some_and(|path| {
        std::env::split_paths(&path).any(|dir| {
            std::fs::metadata(dir.join(program)).is_ok_and(|meta| {
                meta.is_file()
                    && std::os::unix::fs::PermissionsExt::mode(&meta.permissions()) & 0o111 != 0
            })
        })
    })
}

/// A file of the repository.
pub(super) fn root(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

/// Where screenshots of failures go: `target/e2e-failures/`.
fn failures_dir() -> PathBuf {
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR"));
    tmp.parent().unwrap_or(tmp).join("e2e-failures")
}

/// `text` as a file name.
fn slug(text: &str) -> String {
    text.chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '-' })
        .take(60)
        .collect()
}

/// The test's X server and editor, ended by pid when the session ends, however it ends.
pub(super) struct Session {
    name: &'static str,
    pub(super) dir: PathBuf,
    display: String,
    xvfb: Child,
    editor: Option<Child>,
    editor_log: PathBuf,
    editors: usize,
    pub(super) window: Option<String>,
    pub(super) mouse: Option<(i32, i32)>,
    step: String,
    steps: usize,
    failed: bool,
}

impl Session {
    /// A scratch folder and an X server of our own on a free display.
    pub(super) fn start(name: &'static str) -> Session {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
            .join(format!("real-window-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        for sub in ["state", "runtime", "config"] {
            std::fs::create_dir_all(dir.join(sub)).expect("scratch folder");
        }
        let private = <std::fs::Permissions as std::os::unix::fs::PermissionsExt>::from_mode(0o700);
        std::fs::set_permissions(dir.join("runtime"), private).expect("a private runtime folder");

        // Xvfb picks a free display and writes its number to a pipe once it listens.
        let mut fds = [0; 2];
        // SAFETY: pipe2 fills two fresh descriptors, owned below.
        assert_eq!(
            unsafe { libc::pipe2(fds.as_mut_ptr(), libc::O_CLOEXEC) },
            0,
            "pipe"
        );
        // SAFETY: both descriptors are fresh and owned by nothing else.
        let (read, write) = unsafe { (OwnedFd::from_raw_fd(fds[0]), OwnedFd::from_raw_fd(fds[1])) };
        let write_fd = fds[1];
        let log = File::create(dir.join("xvfb.log")).expect("Xvfb log");
        let mut command = Command::new("Xvfb");
        command
            .args(["-displayfd", &write_fd.to_string()])
            .args([
                "-screen",
                "0",
                "1600x1000x24",
                "-nolisten",
                "tcp",
                "-noreset",
            ])
            .stdin(Stdio::null())
            .stdout(log.try_clone().unwrap())
            .stderr(log);
        // SAFETY: only fcntl, which is async-signal-safe, between fork and exec.
        unsafe {
            std::os::unix::process::CommandExt::pre_exec(&mut command, move || {
                if libc::fcntl(write_fd, libc::F_SETFD, 0) == 0 {
                    Ok(())
                } else {
                    Err(std::io::Error::last_os_error())
                }
            });
        }
        let xvfb = command.spawn().expect("start Xvfb");
        drop(write);
        let (sender, receiver) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let mut text = String::new();
            let _ = File::from(read).read_to_string(&mut text);
            let _ = sender.send(text);
        });
        let mut session = Session {
            name,
            dir: dir.clone(),
            display: String::new(),
            xvfb,
            editor: None,
            editor_log: dir.join("editor-0.log"),
            editors: 0,
            window: None,
            mouse: None,
            step: "start Xvfb".into(),
            steps: 0,
            failed: false,
        };
        // Xvfb keeps the pipe open: read up to the line it writes.
        let number = receiver.recv_timeout(STEP).ok();
        match number.as_deref().map(str::trim).filter(|n| !n.is_empty()) {
            Some(number) => session.display = format!(":{number}"),
            None => {
                let log = std::fs::read_to_string(dir.join("xvfb.log")).unwrap_or_default();
                session.fail(&format!(
                    "Xvfb did not report a display within {STEP:?}: {log}"
                ))
            }
        }
        session
    }

    pub(super) fn step(&mut self, step: &str) {
        self.picture();
        self.steps += 1;
        self.step = step.to_string();
    }

    /// Takes a screenshot of the whole screen into `target/e2e-failures/` and panics
    /// with `what`, the step, the screenshot's path and the editor's output.
    pub(super) fn fail(&mut self, what: &str) -> ! {
        self.failed = true;
        let shot = self.failure_screenshot();
        let log = std::fs::read_to_string(&self.editor_log).unwrap_or_default();
        let tail: String = log
            .lines()
            .rev()
            .take(30)
            .collect::<Vec<_>>()
            .into_iter()
            .rev()
            .collect::<Vec<_>>()
            .join("\n");
        panic!(
            "real window, step '{}': {what}\nscreenshot: {shot}\nscratch folder: {}\nthe editor's last output:\n{tail}",
            self.step,
            self.dir.display()
        );
    }

    /// Saves a picture of the whole screen and of the end of every step so far into
    /// `target/e2e-failures/<test>/`; the folder, or why there are no pictures.
    fn failure_screenshot(&self) -> String {
        let folder = failures_dir().join(self.name);
        let _ = std::fs::remove_dir_all(&folder);
        let _ = std::fs::create_dir_all(&folder);
        for entry in std::fs::read_dir(&self.dir).into_iter().flatten().flatten() {
            let path = entry.path();
            if path.extension().is_some_and(|e| e == "png") {
                let _ = std::fs::copy(&path, folder.join(entry.file_name()));
            }
        }
        let path = folder.join(format!("{:02}-failed-{}.png", self.steps, slug(&self.step)));
        match self.run(
            "import",
            &["-window", "root", &path.display().to_string()],
            STEP,
        ) {
            Ok(_) => format!(
                "{} (the screen as the step failed, and each step's end before)",
                path.display()
            ),
            Err(error) => format!(
                "{} (the steps' ends; none of the failure: {error})",
                folder.display()
            ),
        }
    }

    /// A picture of the window as a step ends, kept for a failure later.
    fn picture(&mut self) {
        if let Some(window) = self.window.clone() {
            let path = self
                .dir
                .join(format!("{:02}-{}.png", self.steps, slug(&self.step)));
            let _ = self.run(
                "import",
                &["-window", &window, &path.display().to_string()],
                STEP,
            );
        }
    }

    /// Runs a tool on our display, up to `timeout`; its standard output.
    fn run(&self, program: &str, args: &[&str], timeout: Duration) -> Result<String, String> {
        let mut child = Command::new(program)
            .args(args)
            .env("DISPLAY", &self.display)
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|error| format!("cannot run {program}: {error}"))?;
        let mut stdout = child.stdout.take().unwrap();
        let mut stderr = child.stderr.take().unwrap();
        let out = std::thread::spawn(move || {
            let mut bytes = Vec::new();
            let _ = stdout.read_to_end(&mut bytes);
            bytes
        });
        let err = std::thread::spawn(move || {
            let mut bytes = Vec::new();
            let _ = stderr.read_to_end(&mut bytes);
            bytes
        });
        let started = Instant::now();
        let status = loop {
            if let Some(status) = child.try_wait().map_err(|e| e.to_string())? {
                break status;
            }
            if started.elapsed() > timeout {
                let _ = child.kill();
                let _ = child.wait();
                return Err(format!(
                    "{program} {args:?} did not finish within {timeout:?}"
                ));
            }
            std::thread::sleep(Duration::from_millis(5));
        };
        let out = String::from_utf8_lossy(&out.join().unwrap_or_default()).into_owned();
        let err = String::from_utf8_lossy(&err.join().unwrap_or_default()).into_owned();
        if status.success() {
            Ok(out)
        } else {
            Err(format!(
                "{program} {args:?} failed ({status}): {}",
                err.trim()
            ))
        }
    }

    pub(super) fn xdotool(&mut self, args: &[&str]) -> String {
        match self.run("xdotool", args, STEP) {
            Ok(out) => out,
            Err(error) => self.fail(&error),
        }
    }

    /// Polls `check` until it gives something, for up to `timeout`.
    pub(super) fn wait_for<T>(
        &mut self,
        what: &str,
        timeout: Duration,
        check: impl FnMut(&mut Session) -> Option<T>,
    ) -> T {
        match self.try_wait_for(what, timeout, check) {
            Some(found) => found,
            None => self.fail(&format!("waited {timeout:?} for {what}")),
        }
    }

    /// Polls `check` until it gives something, for up to `timeout`; `None` if it never
    /// did (the caller says what that means). Fails if the editor exits meanwhile.
    pub(super) fn try_wait_for<T>(
        &mut self,
        what: &str,
        timeout: Duration,
        mut check: impl FnMut(&mut Session) -> Option<T>,
    ) -> Option<T> {
        let started = Instant::now();
        loop {
            if let Some(found) = check(self) {
                return Some(found);
            }
            if let Some(status) = self
                .editor
                .as_mut()
                .and_then(|editor| editor.try_wait().ok().flatten())
            {
                self.editor = None;
                self.fail(&format!(
                    "the editor exited ({status}) while waiting for {what}"
                ));
            }
            if started.elapsed() > timeout {
                return None;
            }
            std::thread::sleep(POLL);
        }
    }

    /// Starts `veneer edit file` and waits for its window titled `title`, then focuses it.
    pub(super) fn start_editor(&mut self, file: &Path, title: &str) {
        self.editor_log = self.dir.join(format!("editor-{}.log", self.editors));
        self.editors += 1;
        let log = File::create(&self.editor_log).expect("editor log");
        let editor = Command::new(env!("CARGO_BIN_EXE_veneer"))
            .arg("edit")
            .arg(file)
            .env("DISPLAY", &self.display)
            .env_remove("WAYLAND_DISPLAY")
            .env("XDG_STATE_HOME", self.dir.join("state"))
            .env("XDG_RUNTIME_DIR", self.dir.join("runtime"))
            .env("XDG_CONFIG_HOME", self.dir.join("config"))
            .stdin(Stdio::null())
            .stdout(log.try_clone().unwrap())
            .stderr(log)
            .spawn()
            .expect("start the editor");
        self.editor = Some(editor);
        self.window = None;
        let window = self.wait_for(&format!("a window titled '{title}'"), START, |s| {
            let found = s
                .run("xdotool", &["search", "--name", "Veneer"], STEP)
                .ok()?;
            found.lines().find_map(|id| {
                let name = s.run("xdotool", &["getwindowname", id], STEP).ok()?;
                (name.trim() == title).then(|| id.to_string())
            })
        });
        self.xdotool(&["windowfocus", "--sync", &window]);
        self.window = Some(window);
        self.mouse = None;
    }

    /// Ends the editor as `kill` does and waits for it to exit cleanly.
    pub(super) fn close_editor(&mut self) {
        let Some(pid) = self.editor.as_ref().map(Child::id) else {
            self.fail("no editor to close");
        };
        self.picture();
        // SAFETY: signals our own child, which has not been reaped yet.
        unsafe { libc::kill(pid as libc::pid_t, libc::SIGTERM) };
        let status: ExitStatus = self.wait_for("the editor to exit after SIGTERM", STEP, |s| {
            s.editor
                .as_mut()
                .and_then(|editor| editor.try_wait().ok().flatten())
        });
        self.editor = None;
        self.window = None;
        if !status.success() {
            self.fail(&format!("the editor exited with {status} after SIGTERM"));
        }
    }

    /// A screenshot of the editor's window (the screen before it has one).
    pub(super) fn shot(&mut self) -> Shot {
        let target = self.window.clone().unwrap_or_else(|| "root".into());
        let path = self.dir.join("shot.ppm");
        let file = format!("ppm:{}", path.display());
        if let Err(error) = self.run("import", &["-window", &target, "-depth", "8", &file], STEP) {
            self.fail(&error);
        }
        match std::fs::read(&path)
            .ok()
            .as_deref()
            .and_then(Shot::from_ppm)
        {
            Some(shot) => shot,
            None => self.fail("import wrote no readable screenshot"),
        }
    }

    /// Waits until `rect` of the window looks the same twice in a row (the blinking
    /// text cursor aside), and returns that screenshot.
    pub(super) fn settled(&mut self, rect: Rect) -> Shot {
        let mut last = self.shot();
        self.wait_for("the window to stop changing", STEP, |s| {
            let next = s.shot();
            let same = diff(&last, &next, rect, true).0 == 0;
            last = next;
            same.then(|| last.clone())
        })
    }

    /// Waits for a modal dialog, `what`, to open over the window as it was in `before`
    /// (a modal dialog dims everything behind it) and to settle; returns the window then.
    pub(super) fn expect_dialog(&mut self, before: &Shot, what: &str) -> Shot {
        let whole = full(before);
        self.wait_for(what, STEP, |s| {
            let (changed, _) = diff(before, &s.shot(), whole, false);
            (changed * 3 > before.width * before.height).then_some(())
        });
        self.settled(whole)
    }

    /// The editor window's title now.
    pub(super) fn title(&mut self) -> String {
        let window = self.window.clone().expect("a window");
        self.xdotool(&["getwindowname", &window]).trim().to_string()
    }

    /// Fails unless the window's title is `title` (within a step's time), naming the
    /// title it has.
    pub(super) fn expect_title(&mut self, title: &str) {
        let what = format!("the window title '{title}'");
        if self
            .try_wait_for(&what, STEP, |s| (s.title() == title).then_some(()))
            .is_none()
        {
            let now = self.title();
            self.fail(&format!("waited {STEP:?} for {what}; it is '{now}'"));
        }
    }

    /// Fails with `otherwise` unless the title gains its star within a step's time:
    /// what was done edited the document.
    pub(super) fn expect_edited(&mut self, otherwise: &str) {
        let star = |s: &mut Session| s.title().starts_with("* ").then_some(());
        if self.try_wait_for("the title's star", STEP, star).is_none() {
            self.fail(otherwise);
        }
    }

    /// The test passed: the scratch folder goes.
    pub(super) fn finish(self) {
        let dir = self.dir.clone();
        let failures = failures_dir().join(self.name);
        drop(self);
        let _ = std::fs::remove_dir_all(dir);
        let _ = std::fs::remove_dir_all(failures);
    }
}

impl Drop for Session {
    fn drop(&mut self) {
        if std::thread::panicking() && !self.failed && !self.display.is_empty() {
            // A panic outside `fail`: still keep a picture of the screen.
            let shot = self.failure_screenshot();
            eprintln!("real window, step '{}': screenshot {shot}", self.step);
        }
        if let Some(mut editor) = self.editor.take() {
            let _ = editor.kill();
            let _ = editor.wait();
        }
        // SAFETY: signals our own child, not reaped yet.
        unsafe { libc::kill(self.xvfb.id() as libc::pid_t, libc::SIGTERM) };
        let started = Instant::now();
        while self.xvfb.try_wait().ok().flatten().is_none() {
            if started.elapsed() > Duration::from_secs(5) {
                let _ = self.xvfb.kill();
                let _ = self.xvfb.wait();
                break;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
    }
}
