//! The add-node search as an artist uses it: opened at the mouse by Space, Tab, Shift+A or
//! the menu, every time; typed into at once; arrows and Enter; Escape; nodes, pastes and
//! duplicates landing at the mouse; frames; wires dropped on empty canvas.

use crate::support::{editor, press, scratch, shows};
use egui::{Event, Key, Modifiers, Pos2};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use veneer::app::VeneerApp;
use veneer::graph::NodeKind;

pub type Editor = Harness<'static, VeneerApp>;

/// A key as a real keyboard sends it: down, the text it types, up.
pub fn key(harness: &mut Editor, modifiers: Modifiers, key: Key, text: Option<&str>) {
    let event = |pressed| Event::Key {
        key,
        pressed,
        modifiers,
        repeat: false,
        physical_key: None,
    };
    harness.event(Event::ModifiersChanged(modifiers));
    harness.event(event(true));
    if let Some(text) = text {
        harness.event(Event::Text(text.into()));
    }
    harness.event(event(false));
    harness.event(Event::ModifiersChanged(Modifiers::NONE));
    harness.run();
}

/// Typing on the keyboard, into whatever has focus (no click first).
pub fn typing(harness: &mut Editor, text: &str) {
    harness.event(Event::Text(text.into()));
    harness.run();
}

pub fn hover(harness: &mut Editor, pos: Pos2) {
    harness.hover_at(pos);
    harness.run();
}

/// A click of the primary button at `pos` (pressed and let go where the mouse is).
fn click_at(harness: &mut Editor, pos: Pos2) {
    harness.drag_at(pos);
    harness.run();
    harness.event(Event::PointerButton {
        pos,
        button: egui::PointerButton::Primary,
        pressed: false,
        modifiers: Modifiers::NONE,
    });
    harness.run();
}

/// Ctrl+C: the text the editor put on the clipboard (the selected nodes as RON).
pub fn copy(harness: &mut Editor) -> String {
    harness.event(Event::Copy);
    harness.step();
    harness
        .output()
        .platform_output
        .commands
        .iter()
        .find_map(|command| match command {
            egui::OutputCommand::CopyText(text) => Some(text.clone()),
            _ => None,
        })
        .expect("Ctrl+C copied the selected nodes")
}

/// A new, almost empty graph (the material output only).
fn new_graph(harness: &mut Editor) {
    press(harness, Key::N, true);
    assert_eq!(harness.state().document().graph.nodes.len(), 1);
}

/// The text field that has keyboard focus, if any: its screen rectangle and text.
pub fn focused_field(harness: &Editor) -> Option<(egui::Rect, String)> {
    harness
        .query_by(|node| node.role() == egui::accesskit::Role::TextInput && node.is_focused())
        .map(|node| (node.rect(), node.value().unwrap_or_default()))
}

/// The node with the largest id: the one added last.
pub fn newest(harness: &Editor) -> veneer::graph::Node {
    let graph = &harness.state().document().graph;
    graph
        .nodes
        .iter()
        .max_by_key(|node| node.id)
        .cloned()
        .expect("a node")
}

/// Where the only label `text` is on screen, in the graph (whose widgets report graph
/// coordinates).
fn in_graph(harness: &Editor, text: &str) -> egui::Rect {
    harness.state().graph_to_screen() * harness.get_by_label(text).rect()
}

/// Where a node's top-left corner is on screen.
fn on_screen(harness: &Editor, position: (f32, f32)) -> Pos2 {
    harness.state().graph_to_screen() * Pos2::new(position.0, position.1)
}

/// A point of the graph panel where a copy of `node` put down with its top-left corner
/// there would touch no node on screen.
fn clear_of_nodes(harness: &Editor, node: veneer::graph::NodeId) -> Pos2 {
    let app = harness.state();
    let size = app.node_on_screen(node).expect("the node is drawn").size();
    let rects: Vec<egui::Rect> = app
        .document()
        .graph
        .nodes
        .iter()
        .filter_map(|other| app.node_on_screen(other.id))
        .collect();
    let corners = (0..12).flat_map(|y| (0..12).map(move |x| (x, y)));
    corners
        .map(|(x, y)| Pos2::new(100.0 + 60.0 * x as f32, 120.0 + 60.0 * y as f32))
        .find(|corner| {
            let footprint = egui::Rect::from_min_size(*corner, size).expand(80.0);
            rects.iter().all(|rect| !rect.intersects(footprint))
        })
        .expect("the graph panel has room for a copy")
}

/// Asserts that `node` sits under `mouse`: its top-left corner a little up-left of it.
fn assert_under(harness: &Editor, node: &veneer::graph::Node, mouse: Pos2) {
    let corner = on_screen(harness, node.position);
    let offset = mouse - corner;
    assert!(
        (0.0..120.0).contains(&offset.x) && (0.0..60.0).contains(&offset.y),
        "{} is at {corner:?}, not under the mouse at {mouse:?}",
        node.kind.title()
    );
}

/// Opens the search with `opener` at `mouse`, types `query` without clicking, presses
/// Enter, and checks the search was at the mouse with its text box focused.
fn add_by_keyboard(harness: &mut Editor, mouse: Pos2, opener: (Modifiers, Key, &str), query: &str) {
    let before = harness.state().document().graph.nodes.len();
    hover(harness, mouse);
    let (modifiers, opener, text) = opener;
    key(
        harness,
        modifiers,
        opener,
        (!text.is_empty()).then_some(text),
    );
    let (rect, text) = focused_field(harness).expect("the search's text box has focus at once");
    assert_eq!(
        text, "",
        "the key that opened the search is not typed into it"
    );
    assert!(
        (rect.min - mouse).length() < 60.0,
        "the search opened at {rect:?}, not at the mouse {mouse:?}"
    );
    typing(harness, query);
    assert_eq!(
        focused_field(harness).map(|(_, text)| text),
        Some(query.into())
    );
    key(harness, Modifiers::NONE, Key::Enter, None);
    assert_eq!(
        harness.state().document().graph.nodes.len(),
        before + 1,
        "Enter added the highlighted node"
    );
    assert!(
        focused_field(harness).is_none_or(|(_, text)| text != query),
        "the search closed"
    );
}

const SPACE: (Modifiers, Key, &str) = (Modifiers::NONE, Key::Space, " ");
const TAB: (Modifiers, Key, &str) = (Modifiers::NONE, Key::Tab, "");
const SHIFT_A: (Modifiers, Key, &str) = (Modifiers::SHIFT, Key::A, "A");

#[test]
fn space_tab_and_shift_a_open_the_search_at_the_mouse_every_time() {
    let dir = scratch("add-every-time");
    let mut harness = editor(&dir, None);
    new_graph(&mut harness);
    // Spots clear of each other's nodes and of the material (a node added over others
    // lands beside them: see the selection tests).
    let spots = [
        (Pos2::new(150.0, 150.0), SPACE),
        (Pos2::new(300.0, 680.0), SPACE),
        (Pos2::new(120.0, 420.0), TAB),
        (Pos2::new(650.0, 700.0), SHIFT_A),
        (Pos2::new(700.0, 150.0), SPACE),
    ];
    for (mouse, opener) in spots {
        add_by_keyboard(&mut harness, mouse, opener, "worley");
        let node = newest(&harness);
        assert!(node.kind.title().starts_with("Worley"), "{:?}", node.kind);
        assert_under(&harness, &node, mouse);
    }
    assert_eq!(harness.state().document().graph.nodes.len(), 6);
}

#[test]
fn the_arrow_keys_move_the_highlight_and_enter_picks_it() {
    let dir = scratch("add-arrows");
    let mut harness = editor(&dir, None);
    new_graph(&mut harness);
    add_by_keyboard(&mut harness, Pos2::new(150.0, 200.0), SPACE, "noise");
    let first = newest(&harness).kind;
    hover(&mut harness, Pos2::new(150.0, 500.0));
    key(&mut harness, Modifiers::NONE, Key::Space, Some(" "));
    typing(&mut harness, "noise");
    for arrow in [Key::ArrowDown, Key::ArrowDown, Key::ArrowUp] {
        key(&mut harness, Modifiers::NONE, arrow, None);
    }
    key(&mut harness, Modifiers::NONE, Key::Enter, None);
    let second = newest(&harness);
    assert_ne!(
        second.kind, first,
        "Enter picked the second entry, not the first"
    );
    assert!(second.kind.title().contains("oise"), "{:?}", second.kind);
    assert_under(&harness, &second, Pos2::new(150.0, 500.0));
}

#[test]
fn escape_closes_the_search_and_it_opens_again() {
    let dir = scratch("add-escape");
    let mut harness = editor(&dir, None);
    new_graph(&mut harness);
    for round in 0..3 {
        hover(&mut harness, Pos2::new(200.0 + 40.0 * round as f32, 300.0));
        key(&mut harness, Modifiers::NONE, Key::Space, Some(" "));
        typing(&mut harness, "wor");
        assert!(
            shows(&harness, "Worley"),
            "round {round}: the search lists Worley"
        );
        key(&mut harness, Modifiers::NONE, Key::Escape, None);
        assert!(
            focused_field(&harness).is_none(),
            "round {round}: Escape closed it"
        );
        assert!(
            !shows(&harness, "Worley"),
            "round {round}: nothing of it stays"
        );
    }
    assert_eq!(harness.state().document().graph.nodes.len(), 1);
    // Edit → Add node opens it too, over the graph: its text box takes the typing.
    harness.get_by_label("Edit").click();
    harness.run();
    harness.get_by_label("Add node…").click();
    harness.run();
    assert!(
        focused_field(&harness).is_some(),
        "the menu opened the search"
    );
    typing(&mut harness, "tiles");
    key(&mut harness, Modifiers::NONE, Key::Enter, None);
    assert_eq!(harness.state().document().graph.nodes.len(), 2);
    let node = newest(&harness);
    let corner = on_screen(&harness, node.position);
    assert!(
        harness.state().document().graph.nodes.len() == 2
            && (0.0..900.0).contains(&corner.x)
            && (30.0..860.0).contains(&corner.y),
        "the new node is in view: {corner:?}"
    );
}

#[test]
fn a_click_on_the_search_does_not_reach_the_node_under_it() {
    let dir = scratch("add-click-through");
    let mut harness = editor(&dir, None);
    new_graph(&mut harness);
    // Open the search with the mouse on the material node's title.
    let title = in_graph(&harness, "material");
    hover(&mut harness, title.left_center() + egui::vec2(4.0, 0.0));
    key(&mut harness, Modifiers::NONE, Key::Space, Some(" "));
    // Its text box lies over the material node: a click on it stays in the search.
    let (field, _) = focused_field(&harness).expect("the search is open");
    assert!(
        field.center().y > title.max.y,
        "the text box is over the node's body"
    );
    harness.hover_at(field.center());
    harness.drag_at(field.center());
    harness.run();
    harness.event(Event::PointerButton {
        pos: field.center(),
        button: egui::PointerButton::Primary,
        pressed: false,
        modifiers: Modifiers::NONE,
    });
    harness.run();
    assert!(
        shows(&harness, "Select a node to edit it"),
        "the click on the search selected the node under it"
    );
    typing(&mut harness, "tiles");
    harness.get_by_label("Tiles").click();
    harness.run();
    assert_eq!(harness.state().document().graph.nodes.len(), 2);
    assert_eq!(newest(&harness).kind.title(), "Tiles");
    assert!(shows(&harness, "#2"), "the inspector shows the new node");
}

#[test]
fn pasted_and_duplicated_nodes_land_at_the_mouse_in_their_layout() {
    let dir = scratch("add-paste");
    let mut harness = editor(&dir, None);
    new_graph(&mut harness);
    add_by_keyboard(&mut harness, Pos2::new(120.0, 150.0), SPACE, "worley");
    let original = newest(&harness);
    // Ctrl+D: a copy under the mouse (it follows the mouse until a click puts it down).
    let mouse = Pos2::new(200.0, 680.0);
    hover(&mut harness, mouse);
    key(&mut harness, Modifiers::COMMAND, Key::D, None);
    let hint = "click to put them down";
    assert!(
        shows(&harness, hint),
        "the status bar says how the copy is placed"
    );
    click_at(&mut harness, mouse);
    assert!(!shows(&harness, hint), "not once it is put down");
    let duplicate = newest(&harness);
    assert_ne!(duplicate.id, original.id, "Ctrl+D added a node");
    assert_eq!(duplicate.kind, original.kind);
    let corner = on_screen(&harness, duplicate.position);
    assert!(
        (corner - mouse).length() < 2.0,
        "{corner:?} is not at the mouse {mouse:?}"
    );

    // Ctrl+C copies the clicked node as text (not its title); Ctrl+V pastes it at the mouse.
    let title = on_screen(&harness, original.position) + egui::vec2(40.0, 12.0);
    hover(&mut harness, title);
    click_at(&mut harness, title);
    let copied = copy(&mut harness);
    assert!(
        copied.contains("nodes"),
        "Ctrl+C copied {copied:?}, not the node"
    );
    harness.run();
    let mouse = clear_of_nodes(&harness, original.id);
    hover(&mut harness, mouse);
    harness.event(Event::Paste(copied.clone()));
    harness.run();
    let pasted = newest(&harness);
    assert_eq!(harness.state().document().graph.nodes.len(), 4);
    let corner = on_screen(&harness, pasted.position);
    assert!(
        (corner - mouse).length() < 2.0,
        "{corner:?} is not at the mouse {mouse:?}"
    );
    // Pasted again without moving the mouse: beside the first paste, not on it.
    harness.event(Event::Paste(copied));
    harness.run();
    let again = on_screen(&harness, newest(&harness).position);
    assert!(
        (again - corner).length() > 20.0,
        "the second paste covers the first"
    );
}

#[test]
fn frames_come_from_the_search_and_ctrl_j() {
    let dir = scratch("add-frame");
    let mut harness = editor(&dir, None);
    new_graph(&mut harness);
    // Nothing selected: the frame goes where the search was opened.
    let mouse = Pos2::new(150.0, 500.0);
    hover(&mut harness, mouse);
    key(&mut harness, Modifiers::NONE, Key::Space, Some(" "));
    typing(&mut harness, "comment");
    key(&mut harness, Modifiers::NONE, Key::Enter, None);
    let frames = harness.state().document().graph.frames.clone();
    assert_eq!(frames.len(), 1, "the search's Frame entry added a frame");
    let corner = on_screen(&harness, frames[0].min);
    assert!(
        (mouse - corner).length() < 60.0,
        "{corner:?} is not at {mouse:?}"
    );
    assert_eq!(
        harness.state().document().graph.nodes.len(),
        1,
        "no node added"
    );

    // With a node selected, the search also offers a frame around it, and so does Ctrl+J.
    crate::support::select_node(&mut harness, "material");
    hover(&mut harness, Pos2::new(150.0, 200.0));
    key(&mut harness, Modifiers::NONE, Key::Space, Some(" "));
    typing(&mut harness, "frame around");
    key(&mut harness, Modifiers::NONE, Key::Enter, None);
    key(&mut harness, Modifiers::COMMAND, Key::J, None);
    let graph = &harness.state().document().graph;
    assert_eq!(graph.frames.len(), 3);
    let (x, y) = graph.nodes[0].position;
    for frame in &graph.frames[1..] {
        assert!(
            frame.min.0 < x && frame.min.1 < y && frame.max.0 > x && frame.max.1 > y,
            "{frame:?} is not around the material at {:?}",
            (x, y)
        );
    }
    assert_eq!(graph.nodes.len(), 1, "no node added");
}

#[test]
fn the_status_bar_counts_one_node_in_the_singular() {
    let dir = scratch("add-count");
    let mut harness = editor(&dir, None);
    assert!(shows(&harness, "2 nodes"));
    new_graph(&mut harness);
    assert!(shows(&harness, "1 node ·"), "the status bar says '1 node'");
    assert!(!shows(&harness, "1 nodes"));
}

/// Drags a wire from the "value" output pin (right of its label) to `drop` on empty
/// canvas.
fn drop_wire_from_value(harness: &mut Harness<'static, VeneerApp>, drop: Pos2) {
    let label = in_graph(harness, "value");
    let pin = Pos2::new(label.max.x + 4.0, label.center().y);
    hover(harness, pin);
    harness.drag_at(pin);
    harness.run();
    for step in 1..=5 {
        hover(harness, pin + (drop - pin) * step as f32 / 5.0);
    }
    harness.event(Event::PointerButton {
        pos: drop,
        button: egui::PointerButton::Primary,
        pressed: false,
        modifiers: Modifiers::NONE,
    });
    harness.run();
}

#[test]
fn a_wire_dropped_on_empty_canvas_offers_groups_by_their_pins() {
    let dir = scratch("add-dropped-wire-group");
    let mut harness = editor(&dir, None);
    new_graph(&mut harness);
    add_by_keyboard(&mut harness, Pos2::new(150.0, 200.0), SPACE, "noise");
    let noise = newest(&harness);
    drop_wire_from_value(&mut harness, Pos2::new(250.0, 600.0));
    // ring_wood (the library's) takes floats: offered, placed and wired to its first.
    typing(&mut harness, "ring_wood");
    key(&mut harness, Modifiers::NONE, Key::Enter, None);
    let graph = &harness.state().document().graph;
    let group = graph
        .nodes
        .iter()
        .find(|node| matches!(&node.kind, NodeKind::Group(g) if g.name == "ring_wood"))
        .expect("the group node is placed");
    let wire = graph
        .wires
        .iter()
        .find(|wire| wire.to.node == group.id)
        .expect("the group node is wired");
    assert_eq!(
        (wire.from.node, wire.to.pin.as_str()),
        (noise.id, "ring_frequency")
    );
}

#[test]
fn a_wire_dropped_on_empty_canvas_offers_the_nodes_it_fits_and_connects_the_pick() {
    let dir = scratch("add-dropped-wire");
    let mut harness = editor(&dir, None);
    new_graph(&mut harness);
    add_by_keyboard(&mut harness, Pos2::new(150.0, 200.0), SPACE, "noise");
    let noise = newest(&harness);
    // Clear of the material (a node added over others lands beside them).
    let drop = Pos2::new(150.0, 560.0);
    drop_wire_from_value(&mut harness, drop);
    let (field, _) = focused_field(&harness).expect("the dropped wire opened the search");
    assert!(
        (field.min - drop).length() < 60.0,
        "the search is at the drop: {field:?}"
    );
    assert!(shows(&harness, "Add and connect"));
    // A float output fits a Remap's input, but a Position node takes no input at all.
    typing(&mut harness, "position");
    assert!(
        !shows(&harness, "Position"),
        "incompatible kinds are not offered"
    );
    for _ in 0.."position".len() {
        key(&mut harness, Modifiers::NONE, Key::Backspace, None);
    }
    typing(&mut harness, "remap");
    key(&mut harness, Modifiers::NONE, Key::Enter, None);
    let remap = newest(&harness);
    assert_eq!(remap.kind.title(), "Remap");
    assert_under(&harness, &remap, drop);
    let graph = &harness.state().document().graph;
    let wire = graph
        .wires
        .iter()
        .find(|wire| wire.to.node == remap.id)
        .expect("the new node is wired");
    assert_eq!(wire.from.node, noise.id);
}
