//! Building the editor in a test harness, and reading what it shows.

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use std::path::{Path, PathBuf};
use veneer::app::VeneerApp;

/// A scratch folder unique to one test.
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("veneer-editor-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir
}

/// The editor on a chain of `nodes` nodes ([`crate::big_graphs::chain`]) laid out in
/// bands `width` canvas units wide, saved in `dir`.
pub fn chain_editor(dir: &Path, nodes: usize, width: f32) -> Harness<'static, VeneerApp> {
    let mut graph = crate::big_graphs::chain(nodes);
    veneer::graph::layout::arrange_in_rows(&mut graph, width, 1000.0);
    let path = dir.join("chain.ron");
    veneer::graph::save(&graph, &path).expect("the graph saves");
    editor(dir, Some(path))
}

/// The editor in a 1400×900 window, rendering through wgpu, on `graph` (or the wood
/// preset), autosaving into `dir`.
/// Preset `name` saved as `<name>.ron` in `dir`, for an editor to open: its path.
pub fn saved_preset(dir: &Path, name: &str) -> PathBuf {
    let path = dir.join(format!("{name}.ron"));
    let graph = veneer::graph::preset(name).expect("a shipped preset");
    veneer::graph::save(&graph, &path).expect("the graph is written");
    path
}

pub fn editor(dir: &Path, graph: Option<PathBuf>) -> Harness<'static, VeneerApp> {
    let recovery = dir.join("recovery.ron");
    // A graph just opened is framed again over its first frames, as its nodes' sizes
    // settle: `run` may take a few more steps than egui's default four.
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1400.0, 900.0))
        .with_max_steps(16)
        .wgpu()
        .build_eframe(move |cc| VeneerApp::with_recovery_file(cc, graph, recovery));
    // Steps, not `run`: a graph with distance fields keeps repainting while they solve.
    harness.run_steps(4);
    harness
}

/// The wood preset with a hazard inside its group: the rings' smoothstep with equal
/// edges (a hard step). The group no longer follows the library, which would bring its
/// own definition back on opening.
pub fn wood_with_a_hazard_inside() -> veneer::graph::Graph {
    let mut graph = veneer::graph::preset("wood").expect("the wood preset");
    let definition = graph.groups.get_mut("ring_wood").expect("the wood group");
    definition.linked = false;
    let sharp = definition
        .nodes
        .iter_mut()
        .find(|n| n.label == "ring sharp");
    let sharp = sharp.expect("the rings' smoothstep");
    sharp
        .inputs
        .insert("edge0".into(), veneer::graph::Value::Float(0.85));
    graph
}

/// The editor on the wood preset with its `ring_wood` group dissolved (saved in `dir`):
/// the seed's nodes all at the top level, for tests that select them by name.
pub fn flat_wood_editor(dir: &Path) -> Harness<'static, VeneerApp> {
    let mut graph = veneer::graph::preset("wood").expect("the wood preset");
    let group = graph
        .nodes
        .iter()
        .find(|node| matches!(node.kind, veneer::graph::NodeKind::Group(_)))
        .expect("the wood preset is built on a group")
        .id;
    veneer::graph::group::ungroup(&mut graph, group).expect("the group dissolves");
    // The material to the right of everything the group held.
    let right = graph
        .nodes
        .iter()
        .map(|node| node.position.0)
        .fold(0.0, f32::max);
    let material = graph.nodes.iter_mut().find(|node| node.label == "material");
    material.expect("the material node").position = (right + 400.0, 0.0);
    let path = dir.join("flat wood.ron");
    veneer::graph::save(&graph, &path).expect("the flat wood is written");
    editor(dir, Some(path))
}

/// The rendered window, once the previews (drawn on their own thread) show what was
/// last asked of them.
pub fn screen(harness: &mut Harness<'static, VeneerApp>) -> image::RgbaImage {
    settle_previews(harness);
    window_image(harness)
}

/// The window as the real one shows it. kittest clears to transparent where eframe
/// clears to the app's clear colour (the graph canvas's, which the editor does not
/// paint again), so kittest's render is laid over that colour.
pub fn window_image(harness: &mut Harness<'static, VeneerApp>) -> image::RgbaImage {
    let mut image = harness.render().expect("the window renders");
    let visuals = harness.ctx.global_style().visuals.clone();
    let clear = eframe::App::clear_color(harness.state(), &visuals);
    for pixel in image.pixels_mut() {
        // Premultiplied alpha, blended in gamma space as egui does.
        let cover = 1.0 - f32::from(pixel[3]) / 255.0;
        for (channel, below) in pixel.0.iter_mut().zip(clear) {
            *channel = (f32::from(*channel) + below * 255.0 * cover)
                .round()
                .min(255.0) as u8;
        }
    }
    image
}

/// Steps the editor until its previews show, at full quality, what was last asked of
/// them (at most a minute: the software rasteriser compiles slowly).
pub fn settle_previews(harness: &mut Harness<'static, VeneerApp>) {
    settle_previews_within(harness, 60);
}

/// [`settle_previews`], waiting at most `seconds`.
pub fn settle_previews_within(harness: &mut Harness<'static, VeneerApp>, seconds: u64) {
    let started = std::time::Instant::now();
    // One step posts what the last frame changed; settled means drawn and taken in.
    harness.step();
    while !harness.state().preview_settled() {
        assert!(
            started.elapsed() < std::time::Duration::from_secs(seconds),
            "the preview did not catch up within {seconds} s"
        );
        std::thread::sleep(std::time::Duration::from_millis(5));
        harness.step();
    }
    harness.step();
}

/// Pixels of the preview panel (the right side, above the controls).
pub fn preview_pixels(image: &image::RgbaImage) -> Vec<u8> {
    let mut pixels = Vec::new();
    for y in 60..440 {
        for x in 960..1380 {
            pixels.extend_from_slice(&image.get_pixel(x, y).0);
        }
    }
    pixels
}

/// Presses a key, optionally with Ctrl, and lets the app react.
pub fn press(harness: &mut Harness<'static, VeneerApp>, key: egui::Key, command: bool) {
    let modifiers = if command {
        egui::Modifiers::COMMAND
    } else {
        egui::Modifiers::NONE
    };
    harness.key_press_modifiers(modifiers, key);
    harness.run();
}

/// Turns the mouse wheel a notch towards the user (the graph zooms in about the
/// pointer), and lets two frames pass.
pub fn wheel_notch(harness: &mut Harness<'static, VeneerApp>) {
    harness.event(egui::Event::MouseWheel {
        unit: egui::MouseWheelUnit::Line,
        delta: egui::vec2(0.0, 1.0),
        phase: egui::TouchPhase::Move,
        modifiers: egui::Modifiers::NONE,
    });
    harness.run_steps(2);
}

/// Clicks the node whose title is `title` in the graph panel, and checks that the
/// inspector now shows that node (its label field holds the title).
pub fn select_node(harness: &mut Harness<'static, VeneerApp>, title: &str) {
    click_node(harness, title);
    assert!(
        inspects(harness, title),
        "clicking '{title}' did not select it"
    );
}

/// Whether the inspector shows the node labelled `label` (its label field holds it).
pub fn inspects(harness: &Harness<'static, VeneerApp>, label: &str) -> bool {
    harness
        .query_by(|node| {
            node.role() == egui::accesskit::Role::TextInput
                && node.value().as_deref() == Some(label)
        })
        .is_some()
}

/// Clicks the node whose title is `title` in the graph panel.
pub fn click_node(harness: &mut Harness<'static, VeneerApp>, title: &str) {
    // The title (a group output may be named after the node too), where it is on screen.
    click_at(
        harness,
        crate::navigation::on_screen(harness, title).center(),
    );
}

/// A left click at `position`, and a frame to take it in.
pub fn click_at(harness: &mut Harness<'static, VeneerApp>, position: egui::Pos2) {
    harness.event(egui::Event::PointerMoved(position));
    for pressed in [true, false] {
        let button = egui::PointerButton::Primary;
        harness.event(egui::Event::PointerButton {
            pos: position,
            button,
            pressed,
            modifiers: Default::default(),
        });
    }
    harness.run();
}

/// Whether some label on screen contains `text`.
pub fn shows(harness: &Harness<'static, VeneerApp>, text: &str) -> bool {
    harness
        .query_all_by(|node| {
            node.value().is_some_and(|v| v.contains(text))
                || node.label().is_some_and(|l| l.contains(text))
        })
        .next()
        .is_some()
}

/// Types `text` into the only text field on screen (focusing it first).
pub fn type_into_field(harness: &mut Harness<'static, VeneerApp>, text: &str) {
    harness
        .get_by_role(egui::accesskit::Role::TextInput)
        .focus();
    harness.run();
    harness
        .get_by_role(egui::accesskit::Role::TextInput)
        .type_text(text);
    harness.run();
}

/// Adds a node through the Space search: types `query`, clicks the entry `entry`.
pub fn add_node(harness: &mut Harness<'static, VeneerApp>, query: &str, entry: &str) {
    press(harness, egui::Key::Space, false);
    type_into_field(harness, query);
    harness.get_by_label(entry).click();
    harness.run();
}

/// With the material selected, wires `source` (as the inspector names it, "node · pin")
/// into its alpha, the first input left at a constant.
pub fn wire_into_alpha(harness: &mut Harness<'static, VeneerApp>, source: &str) {
    select_node(harness, "material");
    harness
        .get_all_by_value("constant")
        .next()
        .expect("alpha's connect choice")
        .click_accesskit();
    harness.run();
    harness.get_by_label(source).click_accesskit();
    harness.run();
}

/// Types `text` over the value of the drag value currently showing `shown` (the first one
/// in the window: the inspector's, as the side panel comes before the graph) and presses
/// Enter. A focused drag value is a text
/// field with its text selected; it commits when it loses focus.
pub fn retype_drag_value(harness: &mut Harness<'static, VeneerApp>, shown: &str, text: &str) {
    harness
        .get_all_by_value(shown)
        .next()
        .expect("a drag value shows the value")
        .focus();
    harness.run();
    // Typed into the field being edited (it shows the bare number, without the
    // drag value's prefix or suffix).
    harness
        .query_all_by(|node| node.is_focused())
        .next()
        .expect("the drag value is being edited")
        .type_text(text);
    harness.run();
    press(harness, egui::Key::Enter, false);
}

/// The variable that names the folder a child editor works in (see [`child_editor`]).
pub const CHILD_FOLDER: &str = "VENEER_CHILD_EDITOR_FOLDER";

/// The folder a child editor test works in, when this process is one (else `None`).
pub fn child_folder() -> Option<PathBuf> {
    std::env::var_os(CHILD_FOLDER).map(PathBuf::from)
}

/// Runs the ignored test `test` of this binary as a child editor working in `dir`, and
/// waits until it has written `marker` in `dir` (it must keep running until killed).
pub fn child_editor(test: &str, dir: &Path, marker: &str) -> std::process::Child {
    let mut child = std::process::Command::new(std::env::current_exe().expect("test binary"))
        .args(["--exact", test, "--ignored", "--nocapture"])
        .env(CHILD_FOLDER, dir)
        .stdout(std::process::Stdio::null())
        .spawn()
        .expect("the child editor starts");
    let marker = dir.join(marker);
    let started = std::time::Instant::now();
    while !marker.exists() {
        if let Some(status) = child.try_wait().expect("child status") {
            panic!("the child editor {test} ended before it was killed: {status}");
        }
        assert!(
            started.elapsed() < std::time::Duration::from_secs(300),
            "the child editor {test} did not write {}",
            marker.display()
        );
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    child
}

/// Keeps a child editor's window running until the parent kills it.
pub fn run_until_killed(harness: &mut Harness<'static, VeneerApp>) -> ! {
    loop {
        harness.step();
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
}

/// Clouds that repeat over the unit tile: gradient fBm with a period of 4 cells at scale
/// 4, as the albedo and the height.
pub fn periodic_clouds() -> veneer::graph::Graph {
    use veneer::graph::{Basis, NodeKind, Value};
    let mut graph = veneer::graph::Graph::default();
    let position = graph.add("position", NodeKind::Position);
    let clouds = graph.add(
        "clouds",
        NodeKind::Fbm(veneer::nodes::Fbm {
            basis: Basis::Gradient,
            octaves: 4,
            normalize: true,
            rotate: false,
            period: 4,
        }),
    );
    graph.set_input(clouds, "scale", Value::Float(4.0));
    let material = graph.add("material", NodeKind::Material);
    graph.connect(position, "position", clouds, "p");
    graph.connect(clouds, "value", material, "albedo");
    graph.connect(clouds, "value", material, "height");
    graph
}
