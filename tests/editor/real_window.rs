//! The real `veneer` binary in a real X window: its own Xvfb display, real key and
//! mouse events through `xdotool`, screenshots through ImageMagick's `import`. What a
//! user does in the first minute: open a copy of a preset, add two nodes by Space +
//! typing + Enter at the mouse, wire them by dragging from an output pin to an input
//! pin, save with Ctrl+S and again with Ctrl+Shift+S + a typed path + Enter, close,
//! reopen the saved file, and compare the files with what was done.
//!
//! Every step waits for something a user would see (a window title, the search popup,
//! each typed letter in it, a node, a wire, a file on disk), polling rather than
//! sleeping (the only pauses pace the mouse as a hand does), and fails after [`STEP`]
//! with what it waited for, a screenshot of the screen and one of the window at the end
//! of each earlier step, in `target/e2e-failures/<test>/`. The editor and the X server
//! are this test's own processes, ended by their pids however the test ends.
//!
//! Without Xvfb, xdotool or ImageMagick the test fails (it does not skip), naming the
//! missing tool and `.ci/run`, which installs them.
//!
//! Pins are found on screen rather than computed: a new node is the part of the
//! (empty) canvas that changed when it was added, and its pins are the discs of a pin
//! colour at its left and right edges.

use std::fs::File;
use std::io::Read;
use std::os::fd::{FromRawFd, OwnedFd};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};

/// How long one step may take before the test fails.
const STEP: Duration = Duration::from_secs(20);
/// How long the window may take to appear (the first frame builds the preview's
/// pipelines, on a software rasteriser that other tests are using too).
const START: Duration = Duration::from_secs(60);
/// How often a condition is polled.
const POLL: Duration = Duration::from_millis(60);

/// The tools the test drives the window with: program, Debian package.
const TOOLS: [(&str, &str); 3] = [
    ("Xvfb", "xvfb"),
    ("xdotool", "xdotool"),
    ("import", "imagemagick"),
];

/// Pin colours (`widgets::type_color`): float, vec2, vec3, colour.
const PIN_COLOURS: [[u8; 3]; 4] = [
    [160, 160, 160],
    [90, 200, 120],
    [100, 140, 230],
    [230, 200, 60],
];

/// Around the mouse, the canvas a new node and its search popup need empty: this far
/// left, right, up and down of the mouse, in pixels.
const ROOM: (i32, i32, i32, i32) = (110, 310, 50, 230);

#[test]
fn add_wire_save_and_reopen_in_a_real_window() {
    require_tools();
    let mut session = Session::start("add_wire_save_reopen");
    let dir = session.dir.clone();
    let original =
        veneer::graph::load(&root("graphs/marble.ron")).expect("the marble preset loads");
    let copy = dir.join("marble copy.ron");
    std::fs::copy(root("graphs/marble.ron"), &copy).expect("copy the preset");
    let copy_bytes = std::fs::read(&copy).unwrap();

    session.step("start the editor on a copy of the marble preset");
    session.start_editor(&copy, "marble copy.ron — Veneer");
    let whole = full(&session.shot());
    session.settled(whole);

    // The graph opens framed, filling the canvas: zoom out about its top-left corner.
    session.step("make room: the wheel zooms out about the pointer");
    session.move_mouse((12, 40));
    session.xdotool(&["click", "--repeat", "2", "--delay", "100", "5"]);
    let first = session.settled(whole);

    session.step("find empty canvas for two nodes");
    let (at_noise, at_remap) = match free_spots(&first) {
        Some(spots) => spots,
        None => session.fail("no empty canvas of 420 × 280 pixels for each of two nodes"),
    };

    session.step("add a Noise node: Space at the mouse, type 'noise', Enter");
    let noise = session.add_node(at_noise, "noise");
    session.step("add a Remap node: Space at the mouse, type 'remap', Enter");
    let remap = session.add_node(at_remap, "remap");
    session.expect_title("* marble copy.ron — Veneer");

    session.step("wire Noise's output to Remap's first input by dragging");
    let from = match noise.output {
        Some(pin) => pin,
        None => session.fail("the new Noise node shows no output pin at its right edge"),
    };
    let to = match remap.input {
        Some(pin) => pin,
        None => session.fail("the new Remap node shows no input pin at its left edge"),
    };
    let before = session.shot();
    let hints = hint_pixels(&before, remap.bounds);
    session.drag_wire(from, to, noise.bounds);
    // A wire is drawn symmetric about its middle, and once connected Remap's input no
    // longer asks (in orange) to be connected.
    let middle = Rect::around(((from.0 + to.0) / 2, (from.1 + to.1) / 2), 4);
    session.wait_for(
        "the wire connected and Remap's 'connect' hint gone",
        STEP,
        |s| {
            let now = s.shot();
            let wire = diff(&before, &now, middle, false).0 > 0;
            (wire && (hints == 0 || hint_pixels(&now, remap.bounds) == 0)).then_some(())
        },
    );

    session.step("save with Ctrl+S");
    session.key("ctrl+s");
    session.wait_for("the file saved with 2 more nodes", STEP, |_| {
        veneer::graph::load(&copy)
            .ok()
            .filter(|graph| graph.nodes.len() == original.nodes.len() + 2)
    });
    session.expect_title("marble copy.ron — Veneer");

    session.step("save as with Ctrl+Shift+S, a typed path and Enter");
    let saved_as = dir.join("saved as.ron");
    let before = session.shot();
    session.key("ctrl+shift+s");
    // A modal dialog dims everything behind it.
    session.wait_for("the Save as dialog", STEP, |s| {
        let (changed, _) = diff(&before, &s.shot(), full(&before), false);
        (changed * 3 > before.width * before.height).then_some(())
    });
    session.type_text(&saved_as.display().to_string());
    session.key("Return");
    session.wait_for("the file written by Save as", STEP, |_| {
        veneer::graph::load(&saved_as).ok()
    });
    session.expect_title("saved as.ron — Veneer");

    session.step("close the editor (SIGTERM, as a desktop's logout or `kill` does)");
    session.close_editor();
    let state = dir.join("state/veneer");
    let leftovers: Vec<String> = std::fs::read_dir(&state)
        .map(|entries| {
            entries
                .flatten()
                .map(|entry| entry.file_name().to_string_lossy().into_owned())
                .filter(|name| name.starts_with("recovery"))
                .collect()
        })
        .unwrap_or_default();
    if !leftovers.is_empty() {
        session.fail(&format!(
            "the saved session left work to recover in {}: {leftovers:?}",
            state.display()
        ));
    }

    session.step("reopen the saved file");
    let saved_bytes = std::fs::read(&saved_as).unwrap();
    session.start_editor(&saved_as, "saved as.ron — Veneer");
    session.settled(whole);
    session.close_editor();
    if std::fs::read(&saved_as).unwrap() != saved_bytes {
        session.fail("opening and closing the saved file changed it");
    }

    session.step("compare the saved files with the edits");
    let saved = veneer::graph::load(&copy).expect("the Ctrl+S file loads");
    let again = veneer::graph::load(&saved_as).expect("the Save as file loads");
    if saved != again {
        session.fail("Ctrl+S and Save as wrote different graphs");
    }
    if std::fs::read(&copy).unwrap() == copy_bytes {
        session.fail("Ctrl+S did not change the file");
    }
    let added: Vec<_> = saved
        .nodes
        .iter()
        .filter(|node| original.node(node.id).is_none())
        .collect();
    let kinds: Vec<&str> = added.iter().map(|node| node.kind.title()).collect();
    let (Some(noise_node), Some(remap_node)) = (
        added.iter().find(|node| node.kind.title() == "Noise"),
        added.iter().find(|node| node.kind.title() == "Remap"),
    ) else {
        session.fail(&format!(
            "the saved file's new nodes are {kinds:?}, not a Noise and a Remap"
        ))
    };
    if added.len() != 2 {
        session.fail(&format!(
            "the saved file has {} new nodes: {kinds:?}",
            added.len()
        ));
    }
    for node in &original.nodes {
        let kept = saved.node(node.id).is_some_and(|saved| {
            saved.kind == node.kind && saved.inputs == node.inputs && saved.label == node.label
        });
        if !kept {
            session.fail(&format!(
                "the preset's node {} changed in the saved file",
                node.id
            ));
        }
    }
    let output = noise_node.kind.signature().outputs[0].name;
    let input = remap_node.kind.signature().inputs[0].name;
    let wire = veneer::graph::Wire {
        from: veneer::graph::PinRef::new(noise_node.id, output),
        to: veneer::graph::PinRef::new(remap_node.id, input),
    };
    let new_wires: Vec<_> = saved
        .wires
        .iter()
        .filter(|wire| !original.wires.contains(wire))
        .collect();
    if new_wires != [&wire] || saved.wires.len() != original.wires.len() + 1 {
        session.fail(&format!(
            "the saved file's new wires are {new_wires:?}, not only {wire:?} \
             (and {} of the preset's {} wires kept)",
            saved
                .wires
                .iter()
                .filter(|w| original.wires.contains(w))
                .count(),
            original.wires.len()
        ));
    }
    session.finish();
}

/// A chain of `count` nodes — a position, transforms, a material — every one of them
/// at the origin, as a generator that writes no positions leaves them.
fn stacked_chain(count: usize) -> veneer::graph::Graph {
    use veneer::graph::{Graph, NodeKind, PinRef, Wire};
    let mut graph = Graph::default();
    let mut previous = (graph.add("p", NodeKind::Position), "position");
    for k in 1..count - 1 {
        let next = graph.add(&format!("t{k}"), NodeKind::Transform);
        graph.wires.push(Wire {
            from: PinRef::new(previous.0, previous.1),
            to: PinRef::new(next, "p"),
        });
        previous = (next, "p");
    }
    let material = graph.add("material", NodeKind::Material);
    graph.wires.push(Wire {
        from: PinRef::new(previous.0, previous.1),
        to: PinRef::new(material, "normal"),
    });
    graph
}

#[test]
fn ten_thousand_nodes_at_one_point_open_laid_out_in_a_real_window() {
    require_tools();
    let mut session = Session::start("stacked_nodes");
    let path = session.dir.join("stacked.ron");
    let graph = stacked_chain(10_000);
    veneer::graph::save(&graph, &path).expect("the graph saves");

    session.step("open 10,000 nodes at one point: they are laid out, the document edited");
    session.start_editor(&path, "* stacked.ron — Veneer");
    let whole = full(&session.shot());
    session.settled(whole);

    session.step("save with Ctrl+S: the layout is kept, nothing else changed");
    session.key("ctrl+s");
    let saved = session.wait_for("the file saved with its nodes apart", STEP, |_| {
        veneer::graph::load(&path).ok().filter(|saved| {
            let mut positions: Vec<_> = saved.nodes.iter().map(|n| n.position).collect();
            positions.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
            positions.dedup();
            positions.len() == saved.nodes.len()
        })
    });
    session.expect_title("stacked.ron — Veneer");
    if saved.wires != graph.wires || saved.nodes.len() != graph.nodes.len() {
        session.fail("saving the laid-out graph changed more than its positions");
    }
    session.close_editor();
    session.finish();
}

#[test]
fn a_fifo_for_a_recent_list_and_a_group_containing_itself_change_nothing_in_a_real_window() {
    require_tools();
    let mut session = Session::start("fifo_and_group_loop");
    // A FIFO where the recent-files list goes: opening a file remembers it there, which
    // waited for a reader forever (a black window that ignored SIGTERM).
    let state = session.dir.join("state/veneer");
    std::fs::create_dir_all(&state).expect("the state folder");
    let status = Command::new("mkfifo")
        .arg(state.join("recent.ron"))
        .status()
        .expect("mkfifo");
    assert!(status.success());
    let path = session.dir.join("loop.ron");
    std::fs::write(&path, crate::groups::SELF_CONTAINING).expect("the graph is written");

    session.step("open a graph whose group contains itself: it opens, not edited");
    session.start_editor(&path, "loop.ron — Veneer");
    let whole = full(&session.shot());
    session.settled(whole);
    session.expect_title("loop.ron — Veneer");

    session.step("close the editor with SIGTERM: it ends, the file as it was");
    session.close_editor();
    if std::fs::read_to_string(&path).unwrap() != crate::groups::SELF_CONTAINING {
        session.fail("the graph file changed");
    }
    session.finish();
}

/// Fails, naming the README's test command, when a tool the test needs is missing.
fn require_tools() {
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
fn root(path: &str) -> PathBuf {
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

/// A rectangle of pixels, `x0..x1` × `y0..y1`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Rect {
    x0: i32,
    y0: i32,
    x1: i32,
    y1: i32,
}

impl Rect {
    fn around((x, y): (i32, i32), radius: i32) -> Rect {
        Rect {
            x0: x - radius,
            y0: y - radius,
            x1: x + radius + 1,
            y1: y + radius + 1,
        }
    }

    /// The canvas a node added at `at` (and its popup) may cover.
    fn room(at: (i32, i32)) -> Rect {
        let (left, right, up, down) = ROOM;
        Rect {
            x0: at.0 - left,
            y0: at.1 - up,
            x1: at.0 + right,
            y1: at.1 + down,
        }
    }

    fn contains(&self, (x, y): (i32, i32)) -> bool {
        (self.x0..self.x1).contains(&x) && (self.y0..self.y1).contains(&y)
    }

    fn overlaps(&self, other: &Rect) -> bool {
        self.x0 < other.x1 && other.x0 < self.x1 && self.y0 < other.y1 && other.y0 < self.y1
    }

    fn clip(&self, shot: &Shot) -> Rect {
        Rect {
            x0: self.x0.max(0),
            y0: self.y0.max(0),
            x1: self.x1.min(shot.width as i32),
            y1: self.y1.min(shot.height as i32),
        }
    }

    fn include(rect: Option<Rect>, (x, y): (i32, i32)) -> Rect {
        match rect {
            None => Rect::around((x, y), 0),
            Some(r) => Rect {
                x0: r.x0.min(x),
                y0: r.y0.min(y),
                x1: r.x1.max(x + 1),
                y1: r.y1.max(y + 1),
            },
        }
    }
}

/// The whole of a screenshot.
fn full(shot: &Shot) -> Rect {
    Rect {
        x0: 0,
        y0: 0,
        x1: shot.width as i32,
        y1: shot.height as i32,
    }
}

/// A screenshot, 8-bit RGB.
#[derive(Clone)]
struct Shot {
    width: usize,
    height: usize,
    rgb: Vec<u8>,
}

impl Shot {
    /// Reads a binary PPM (P6, maxval 255), as `import -depth 8 ppm:` writes it.
    fn from_ppm(bytes: &[u8]) -> Option<Shot> {
        let mut fields = Vec::new();
        let mut at = 0;
        while fields.len() < 4 {
            while bytes.get(at)?.is_ascii_whitespace() {
                at += 1;
            }
            let start = at;
            while !bytes.get(at)?.is_ascii_whitespace() {
                at += 1;
            }
            fields.push(std::str::from_utf8(&bytes[start..at]).ok()?.to_string());
        }
        let data = &bytes[at + 1..];
        let (width, height): (usize, usize) = (fields[1].parse().ok()?, fields[2].parse().ok()?);
        (fields[0] == "P6" && fields[3] == "255" && data.len() >= width * height * 3).then(|| {
            Shot {
                width,
                height,
                rgb: data[..width * height * 3].to_vec(),
            }
        })
    }

    fn px(&self, x: i32, y: i32) -> [u8; 3] {
        let i = 3 * (y as usize * self.width + x as usize);
        [self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]]
    }
}

/// Whether a pixel is coloured rather than grey (the text cursor is pale blue, text grey).
fn tinted([r, g, b]: [u8; 3]) -> bool {
    r.max(g).max(b) - r.min(g).min(b) > 8
}

/// Pixels of `rect` that differ between `a` and `b` (with `ignore_tinted`, only between
/// grey pixels: the blinking text cursor does not count), and their bounding box.
fn diff(a: &Shot, b: &Shot, rect: Rect, ignore_tinted: bool) -> (usize, Option<Rect>) {
    if (a.width, a.height) != (b.width, b.height) {
        return (a.width * a.height, Some(full(a)));
    }
    let rect = rect.clip(a);
    let (mut count, mut bounds) = (0, None);
    for y in rect.y0..rect.y1 {
        for x in rect.x0..rect.x1 {
            let (p, q) = (a.px(x, y), b.px(x, y));
            if p != q && !(ignore_tinted && (tinted(p) || tinted(q))) {
                count += 1;
                bounds = Some(Rect::include(bounds, (x, y)));
            }
        }
    }
    (count, bounds)
}

/// Two places for the mouse whose [`Rect::room`]s are empty canvas and apart, side by
/// side if there is room.
fn free_spots(shot: &Shot) -> Option<((i32, i32), (i32, i32))> {
    let (w, h) = (shot.width as i32, shot.height as i32);
    // The canvas colour: the commonest in the left half, where the graph is.
    let mut counts = std::collections::HashMap::new();
    for y in (h / 10..h * 9 / 10).step_by(3) {
        for x in (0..w / 2).step_by(3) {
            *counts.entry(shot.px(x, y)).or_insert(0usize) += 1;
        }
    }
    let canvas = counts.into_iter().max_by_key(|(_, n)| *n)?.0;
    // Summed-area table of pixels that are not canvas.
    let stride = (w + 1) as usize;
    let mut sums = vec![0u32; stride * (h + 1) as usize];
    for y in 0..h {
        let mut row = 0;
        for x in 0..w {
            let p = shot.px(x, y);
            row += u32::from((0..3).any(|c| p[c].abs_diff(canvas[c]) > 3));
            sums[(y + 1) as usize * stride + (x + 1) as usize] =
                sums[y as usize * stride + (x + 1) as usize] + row;
        }
    }
    let empty = |r: Rect| {
        r.x0 >= 0 && r.y0 >= 0 && r.x1 <= w && r.y1 <= h && {
            let at = |x: i32, y: i32| sums[y as usize * stride + x as usize];
            at(r.x1, r.y1) + at(r.x0, r.y0) - at(r.x0, r.y1) - at(r.x1, r.y0) == 0
        }
    };
    let spots: Vec<(i32, i32)> = (0..h)
        .step_by(10)
        .flat_map(|y| (0..w).step_by(10).map(move |x| (x, y)))
        .filter(|&at| empty(Rect::room(at)))
        .collect();
    let apart = |a: (i32, i32), b: (i32, i32)| !Rect::room(a).overlaps(&Rect::room(b));
    let side_by_side = spots.iter().find_map(|&a| {
        spots
            .iter()
            .find(|&&b| b.1 == a.1 && b.0 > a.0 && apart(a, b))
            .map(|&b| (a, b))
    });
    side_by_side.or_else(|| {
        spots
            .iter()
            .find_map(|&a| spots.iter().find(|&&b| apart(a, b)).map(|&b| (a, b)))
    })
}

/// Pixels of the orange "connect" hint of a required input that has no wire, in `rect`.
fn hint_pixels(shot: &Shot, rect: Rect) -> usize {
    let rect = rect.clip(shot);
    let mut count = 0;
    for y in rect.y0..rect.y1 {
        for x in rect.x0..rect.x1 {
            let [r, g, b] = shot.px(x, y);
            count += usize::from(r > 200 && (100..=150).contains(&g) && b < 90);
        }
    }
    count
}

/// Discs of a pin colour inside `rect`: their centres.
fn pins(shot: &Shot, rect: Rect) -> Vec<(i32, i32)> {
    let rect = rect.clip(shot);
    let core = |x: i32, y: i32| {
        let p = shot.px(x, y);
        PIN_COLOURS.contains(&p)
            && (-1..=1).all(|dy| (-1..=1).all(|dx| shot.px(x + dx, y + dy) == p))
    };
    let mut cores: Vec<(i32, i32)> = Vec::new();
    for y in rect.y0 + 1..rect.y1 - 1 {
        for x in rect.x0 + 1..rect.x1 - 1 {
            if core(x, y) {
                cores.push((x, y));
            }
        }
    }
    // Group cores closer than 3 pixels; a disc's centre is its cores' mean.
    let mut groups: Vec<Vec<(i32, i32)>> = Vec::new();
    for point in cores {
        match groups.iter_mut().find(|group| {
            group
                .iter()
                .any(|q| (q.0 - point.0).abs() <= 2 && (q.1 - point.1).abs() <= 2)
        }) {
            Some(group) => group.push(point),
            None => groups.push(vec![point]),
        }
    }
    groups
        .iter()
        .map(|group| {
            let n = group.len() as i32;
            (
                group.iter().map(|p| p.0).sum::<i32>() / n,
                group.iter().map(|p| p.1).sum::<i32>() / n,
            )
        })
        .collect()
}

/// A node added on screen: where it is, and its first input and output pins.
struct Added {
    bounds: Rect,
    input: Option<(i32, i32)>,
    output: Option<(i32, i32)>,
}

/// The test's X server and editor, ended by pid when the session ends, however it ends.
struct Session {
    name: &'static str,
    dir: PathBuf,
    display: String,
    xvfb: Child,
    editor: Option<Child>,
    editor_log: PathBuf,
    editors: usize,
    window: Option<String>,
    mouse: Option<(i32, i32)>,
    step: String,
    steps: usize,
    failed: bool,
}

impl Session {
    /// A scratch folder and an X server of our own on a free display.
    fn start(name: &'static str) -> Session {
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

    fn step(&mut self, step: &str) {
        self.picture();
        self.steps += 1;
        self.step = step.to_string();
    }

    /// Takes a screenshot of the whole screen into `target/e2e-failures/` and panics
    /// with `what`, the step, the screenshot's path and the editor's output.
    fn fail(&mut self, what: &str) -> ! {
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

    fn xdotool(&mut self, args: &[&str]) -> String {
        match self.run("xdotool", args, STEP) {
            Ok(out) => out,
            Err(error) => self.fail(&error),
        }
    }

    /// Polls `check` until it gives something, for up to `timeout`.
    fn wait_for<T>(
        &mut self,
        what: &str,
        timeout: Duration,
        mut check: impl FnMut(&mut Session) -> Option<T>,
    ) -> T {
        let started = Instant::now();
        loop {
            if let Some(found) = check(self) {
                return found;
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
                self.fail(&format!("waited {timeout:?} for {what}"));
            }
            std::thread::sleep(POLL);
        }
    }

    /// Starts `veneer edit file` and waits for its window titled `title`, then focuses it.
    fn start_editor(&mut self, file: &Path, title: &str) {
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
    fn close_editor(&mut self) {
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
    fn shot(&mut self) -> Shot {
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
    fn settled(&mut self, rect: Rect) -> Shot {
        let mut last = self.shot();
        self.wait_for("the window to stop changing", STEP, |s| {
            let next = s.shot();
            let same = diff(&last, &next, rect, true).0 == 0;
            last = next;
            same.then(|| last.clone())
        })
    }

    fn key(&mut self, keys: &str) {
        let window = self.window.clone().expect("a window");
        self.xdotool(&["windowfocus", "--sync", &window]);
        self.xdotool(&["key", keys]);
    }

    fn type_text(&mut self, text: &str) {
        self.xdotool(&["type", "--delay", "20", "--", text]);
    }

    fn move_mouse(&mut self, (x, y): (i32, i32)) {
        let window = self.window.clone().expect("a window");
        let (x_text, y_text) = (x.to_string(), y.to_string());
        let mut args = vec!["mousemove", "--window", &window];
        // --sync waits for the pointer to move: not when it is there already.
        if self.mouse != Some((x, y)) {
            args.push("--sync");
        }
        args.extend([x_text.as_str(), y_text.as_str()]);
        self.xdotool(&args);
        self.mouse = Some((x, y));
    }

    /// Drags a wire with the left button from the output pin at `from` (of the node
    /// shown in `node`) to the input pin at `to`, as a hand does, each stage seen on
    /// screen before the next: the pin lit under the pointer, the press (given a frame
    /// of its own: egui finds what was pressed where the pointer is when it reads the
    /// press), a wire following the pointer out of the pin, the wire at the input pin,
    /// the release.
    fn drag_wire(&mut self, from: (i32, i32), to: (i32, i32), node: Rect) {
        let before = self.shot();
        self.move_mouse(from);
        self.wait_for("the output pin lit under the pointer", STEP, |s| {
            (diff(&before, &s.shot(), Rect::around(from, 8), false).0 >= 10).then_some(())
        });
        let hovered = self.shot();
        self.xdotool(&["mousedown", "1"]);
        std::thread::sleep(Duration::from_millis(500));
        let length = f64::from((to.0 - from.0).pow(2) + (to.1 - from.1).pow(2))
            .sqrt()
            .max(1.0);
        let along = |distance: f64| {
            (
                from.0 + (f64::from(to.0 - from.0) * distance / length).round() as i32,
                from.1 + (f64::from(to.1 - from.1) * distance / length).round() as i32,
            )
        };
        self.move_mouse(along(16.0));
        let stub = Rect::around(along(11.0), 2);
        let mut rest = node;
        // The node without its pin: what must not move while the wire is drawn out.
        rest.x1 = rest.x1.min(from.0 - 14);
        let pulled = self.wait_for("a wire following the pointer out of the pin", STEP, |s| {
            let now = s.shot();
            if diff(&hovered, &now, rest, false).0 > 100 {
                return Some(false);
            }
            (diff(&hovered, &now, stub, false).0 > 0).then_some(true)
        });
        if !pulled {
            self.xdotool(&["mouseup", "1"]);
            self.fail(
                "pressing the pin and moving away panned the view or moved the node instead \
                 of drawing a wire",
            );
        }
        let steps = 10;
        for i in 1..=steps {
            let distance = 16.0 + (length - 16.0) * f64::from(i) / f64::from(steps);
            self.move_mouse(along(distance));
            // About a frame between moves, as a hand gives.
            std::thread::sleep(Duration::from_millis(30));
        }
        self.move_mouse(to);
        // Wires enter input pins from the left.
        let end = Rect::around((to.0 - 11, to.1), 2);
        self.wait_for("the wire reaching the input pin", STEP, |s| {
            (diff(&hovered, &s.shot(), end, false).0 > 0).then_some(())
        });
        self.xdotool(&["mouseup", "1"]);
    }

    /// Adds a node at `at` as a user does: Space with the mouse there, the query typed
    /// (each key seen in the search before the next), Enter. Returns the node's pins.
    fn add_node(&mut self, at: (i32, i32), query: &str) -> Added {
        self.move_mouse(at);
        let room = Rect::room(at);
        let height = self.shot().height as i32;
        let columns = Rect {
            x0: room.x0,
            y0: 30,
            x1: room.x1,
            y1: height - 30,
        };
        let before = self.settled(columns);
        self.key("space");
        // The popup may sit higher than the mouse near the window's bottom edge.
        let popup = self.wait_for("the add-node search to open at the mouse", STEP, |s| {
            let (count, bounds) = diff(&before, &s.shot(), columns, true);
            bounds.filter(|b| count > 2000 && b.x0 <= at.0 + 5 && b.x1 >= at.0 + 100)
        });
        let mut last = self.shot();
        for c in query.chars() {
            self.type_text(&c.to_string());
            let typed = format!("'{c}' of '{query}' to show in the search");
            last = self.wait_for(&typed, STEP, |s| {
                let next = s.shot();
                (diff(&last, &next, popup, true).0 > 0).then_some(next)
            });
        }
        self.key("Return");
        let mut previous: Option<Shot> = None;
        let (bounds, found) = self.wait_for(
            "the new node under the mouse, the search closed",
            STEP,
            |s| {
                let next = s.shot();
                let settled = previous
                    .as_ref()
                    .is_some_and(|p| diff(p, &next, columns, false).0 == 0);
                let (_, bounds) = diff(&before, &next, room, false);
                previous = Some(next.clone());
                let bounds = bounds.filter(|b| settled && b.contains(at))?;
                let found = pins(&next, bounds);
                let middle = (bounds.x0 + bounds.x1) / 2;
                let left = found.iter().any(|p| p.0 < middle);
                let right = found.iter().any(|p| p.0 >= middle);
                (left && right).then_some((bounds, found))
            },
        );
        let middle = (bounds.x0 + bounds.x1) / 2;
        let topmost = |right: bool| {
            found
                .iter()
                .filter(|p| (p.0 >= middle) == right)
                .min_by_key(|p| p.1)
                .copied()
        };
        Added {
            bounds,
            input: topmost(false),
            output: topmost(true),
        }
    }

    /// Fails unless the window's title is `title`.
    fn expect_title(&mut self, title: &str) {
        let window = self.window.clone().expect("a window");
        self.wait_for(&format!("the window title '{title}'"), STEP, |s| {
            let name = s.run("xdotool", &["getwindowname", &window], STEP).ok()?;
            (name.trim() == title).then_some(())
        });
    }

    /// The test passed: the scratch folder goes.
    fn finish(self) {
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
