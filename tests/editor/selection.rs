//! One selection, as in Blender: a click selects that node alone (Shift adds or makes
//! it active, Ctrl toggles), the inspector follows the active node, a box replaces the
//! selection unless Shift (Ctrl removes), a click on empty canvas clears; Delete and X
//! delete it; pasted and duplicated nodes become it, and a duplicate follows the mouse
//! until a click (Escape puts it back). Alt+drag pans and never moves a node; a right
//! click on empty canvas opens the add-node search, which takes the typing.

use crate::add_node::{Editor, copy, focused_field, hover, key, newest, typing};
use crate::navigation::{GRAPH_AREA, drag, on_screen, selected};
use crate::support::{flat_wood_editor, inspects, press, scratch, shows};
use egui::{Event, Key, Modifiers, PointerButton, Pos2, Rect, vec2};
use egui_kittest::kittest::Queryable;
use veneer::graph::NodeId;

/// Clicks `button` at `pos` holding `modifiers`.
fn click(harness: &mut Editor, pos: Pos2, button: PointerButton, modifiers: Modifiers) {
    harness.event(Event::ModifiersChanged(modifiers));
    harness.event(Event::PointerMoved(pos));
    harness.run();
    for pressed in [true, false] {
        harness.event(Event::PointerButton {
            pos,
            button,
            pressed,
            modifiers,
        });
    }
    harness.run();
    harness.event(Event::ModifiersChanged(Modifiers::NONE));
    harness.run();
}

/// Clicks the title of the node titled `title`, holding `modifiers`.
fn click_title(harness: &mut Editor, title: &str, modifiers: Modifiers) {
    let at = on_screen(harness, title).center();
    click(harness, at, PointerButton::Primary, modifiers);
}

/// The labels of the selected nodes, in selection order (the active one last).
/// Gives the keyboard to the inspector's label field, which holds `label`.
fn focus_label_field(harness: &mut Editor, label: &str) {
    harness
        .get_all_by_value(label)
        .next()
        .expect("the label field")
        .focus();
    harness.run();
}

fn selection(harness: &Editor) -> Vec<String> {
    harness.state().selected_labels()
}

/// The id of the node labelled `label`, if the graph has one.
fn node(harness: &Editor, label: &str) -> Option<NodeId> {
    let graph = &harness.state().document().graph;
    graph.nodes.iter().find(|n| n.label == label).map(|n| n.id)
}

/// Every node's rectangle on screen, as last drawn.
fn node_rects(harness: &Editor) -> Vec<(NodeId, Rect)> {
    let app = harness.state();
    let ids = app.document().graph.nodes.iter().map(|node| node.id);
    ids.filter_map(|id| Some((id, app.node_on_screen(id)?)))
        .collect()
}

/// A point of the graph panel at least 40 points from every node.
fn empty_spot(harness: &Editor) -> Pos2 {
    let rects = node_rects(harness);
    let points = (0..20).flat_map(|y| (0..20).map(move |x| (x, y)));
    points
        .map(|(x, y)| GRAPH_AREA.min + vec2(60.0 + 40.0 * x as f32, 80.0 + 36.0 * y as f32))
        .find(|point| {
            GRAPH_AREA.shrink(40.0).contains(*point)
                && rects
                    .iter()
                    .all(|(_, rect)| !rect.expand(40.0).contains(*point))
        })
        .expect("the flat wood leaves empty canvas")
}

/// Asserts that node `id`'s rectangle overlaps no other node's.
fn assert_clear(harness: &Editor, id: NodeId) {
    let rects = node_rects(harness);
    let (_, mine) = rects.iter().find(|(node, _)| *node == id).expect("drawn");
    for (other, rect) in &rects {
        assert!(
            *other == id || !rect.intersects(*mine),
            "node {id} at {mine:?} lies on node {other} at {rect:?}"
        );
    }
}

#[test]
fn a_click_after_a_box_selection_selects_that_node_alone_and_delete_removes_it() {
    let mut harness = flat_wood_editor(&scratch("sel-box-click"));
    for round in 0..2 {
        let (trunk, drift) = (
            on_screen(&harness, "trunk"),
            on_screen(&harness, "coarse warp space"),
        );
        let start = trunk.min - vec2(12.0, 12.0);
        let none = Modifiers::NONE;
        drag(
            &mut harness,
            PointerButton::Primary,
            none,
            start,
            drift.center(),
        );
        assert_eq!(selected(&harness), ["coarse warp space", "trunk"]);
        let clicked = ["tint space", "ring sharp"][round];
        click_title(&mut harness, clicked, none);
        assert_eq!(selection(&harness), [clicked], "round {round}");
        assert!(
            inspects(&harness, clicked),
            "the inspector follows the click"
        );
        press(&mut harness, Key::Delete, false);
        assert_eq!(node(&harness, clicked), None, "the clicked node is deleted");
        assert!(node(&harness, "trunk").is_some() && node(&harness, "coarse warp space").is_some());
    }
}

#[test]
fn shift_click_adds_ctrl_click_toggles_a_box_replaces_and_empty_canvas_clears() {
    let mut harness = flat_wood_editor(&scratch("sel-modifiers"));
    let (none, shift, ctrl) = (Modifiers::NONE, Modifiers::SHIFT, Modifiers::COMMAND);
    click_title(&mut harness, "trunk", none);
    click_title(&mut harness, "tint space", shift);
    assert_eq!(selection(&harness), ["trunk", "tint space"]);
    assert!(
        inspects(&harness, "tint space"),
        "the last clicked is active"
    );
    // Shift on a selected node makes it active; on the active one, deselects it.
    click_title(&mut harness, "trunk", shift);
    assert_eq!(selection(&harness), ["tint space", "trunk"]);
    assert!(inspects(&harness, "trunk"));
    click_title(&mut harness, "trunk", shift);
    assert_eq!(selection(&harness), ["tint space"]);
    click_title(&mut harness, "coarse warp space", ctrl);
    assert_eq!(selection(&harness), ["tint space", "coarse warp space"]);
    click_title(&mut harness, "coarse warp space", ctrl);
    assert_eq!(selection(&harness), ["tint space"]);
    // A plain box replaces the selection.
    let (trunk, drift) = (
        on_screen(&harness, "trunk"),
        on_screen(&harness, "coarse warp space"),
    );
    drag(
        &mut harness,
        PointerButton::Primary,
        none,
        trunk.min - vec2(12.0, 12.0),
        drift.center(),
    );
    assert_eq!(selected(&harness), ["coarse warp space", "trunk"]);
    let spot = empty_spot(&harness);
    click(&mut harness, spot, PointerButton::Primary, none);
    assert!(selection(&harness).is_empty(), "{:?}", selection(&harness));
    assert!(shows(&harness, "Select a node to edit it"));
}

#[test]
fn delete_and_x_delete_the_selection_but_not_while_typing() {
    let mut harness = flat_wood_editor(&scratch("sel-x"));
    click_title(&mut harness, "ring sharp", Modifiers::NONE);
    key(&mut harness, Modifiers::NONE, Key::X, Some("x"));
    assert_eq!(
        node(&harness, "ring sharp"),
        None,
        "X deleted the selected node"
    );
    click_title(&mut harness, "tint space", Modifiers::NONE);
    let tint = node(&harness, "tint space").expect("tint space");
    // Typed into the node's label field in the inspector.
    focus_label_field(&mut harness, "tint space");
    key(&mut harness, Modifiers::NONE, Key::X, Some("x"));
    assert!(
        harness.state().document().graph.node(tint).is_some(),
        "X typed into a field"
    );
    press(&mut harness, Key::Escape, false);
    // Typed into the add-node search.
    let spot = empty_spot(&harness);
    hover(&mut harness, spot);
    key(&mut harness, Modifiers::NONE, Key::Space, Some(" "));
    key(&mut harness, Modifiers::NONE, Key::X, Some("x"));
    assert_eq!(
        focused_field(&harness).map(|(_, text)| text),
        Some("x".into())
    );
    assert!(
        harness.state().document().graph.node(tint).is_some(),
        "X typed into the search"
    );
    key(&mut harness, Modifiers::NONE, Key::Escape, None);
    press(&mut harness, Key::Delete, false);
    assert!(
        harness.state().document().graph.node(tint).is_none(),
        "Delete deleted it"
    );
}

#[test]
fn duplicates_become_the_selection_and_follow_the_mouse_until_a_click() {
    let mut harness = flat_wood_editor(&scratch("sel-duplicate"));
    click_title(&mut harness, "trunk", Modifiers::NONE);
    let trunk = node(&harness, "trunk").expect("trunk");
    // Ctrl+D with the mouse on the original: the copy is placed clear of every node.
    let mouse = on_screen(&harness, "trunk").center();
    hover(&mut harness, mouse);
    key(&mut harness, Modifiers::COMMAND, Key::D, None);
    let copy = newest(&harness);
    assert_ne!(copy.id, trunk);
    assert_eq!(
        harness.state().selected_nodes(),
        [copy.id],
        "the copy is selected"
    );
    harness.run_steps(2);
    assert_clear(&harness, copy.id);
    // It follows the mouse, until a click.
    let scale = harness.state().graph_to_screen().scaling;
    let placed = copy.position;
    hover(&mut harness, mouse + vec2(100.0, 40.0));
    let moved = newest(&harness).position;
    let by = vec2(moved.0 - placed.0, moved.1 - placed.1) * scale;
    assert!(
        (by - vec2(100.0, 40.0)).length() < 1.0,
        "the copy moved by {by:?}"
    );
    click(
        &mut harness,
        mouse + vec2(100.0, 40.0),
        PointerButton::Primary,
        Modifiers::NONE,
    );
    assert_eq!(
        harness.state().selected_nodes(),
        [copy.id],
        "the click kept it selected"
    );
    hover(&mut harness, mouse + vec2(300.0, 200.0));
    assert_eq!(newest(&harness).position, moved, "the click put it down");
    assert!(harness.state().document().graph.node(trunk).is_some());
    // Escape puts a duplicate back where it was placed.
    key(&mut harness, Modifiers::COMMAND, Key::D, None);
    let second = newest(&harness);
    hover(&mut harness, mouse + vec2(200.0, 300.0));
    assert_ne!(
        newest(&harness).position,
        second.position,
        "it follows the mouse"
    );
    key(&mut harness, Modifiers::NONE, Key::Escape, None);
    assert_eq!(
        newest(&harness).position,
        second.position,
        "Escape put it back"
    );
    hover(&mut harness, mouse);
    assert_eq!(newest(&harness).position, second.position, "and it stays");
    assert_eq!(harness.state().selected_nodes(), [second.id]);
    // Deleted while they follow the mouse, copies are let go of: the next click selects.
    key(&mut harness, Modifiers::COMMAND, Key::D, None);
    press(&mut harness, Key::Delete, false);
    click_title(&mut harness, "trunk", Modifiers::NONE);
    assert_eq!(selection(&harness), ["trunk"]);
}

#[test]
fn undo_while_a_duplicate_follows_the_mouse_takes_back_the_duplicate_alone() {
    let mut harness = flat_wood_editor(&scratch("sel-duplicate-undo"));
    // A step before: a node deleted.
    click_title(&mut harness, "tint space", Modifiers::NONE);
    press(&mut harness, Key::Delete, false);
    assert!(node(&harness, "tint space").is_none());
    let before = harness.state().document().graph.clone();
    click_title(&mut harness, "trunk", Modifiers::NONE);
    let mouse = on_screen(&harness, "trunk").center();
    hover(&mut harness, mouse);
    key(&mut harness, Modifiers::COMMAND, Key::D, None);
    hover(&mut harness, mouse + vec2(120.0, 60.0));
    assert_eq!(
        harness.state().document().graph.nodes.len(),
        before.nodes.len() + 1
    );
    key(&mut harness, Modifiers::COMMAND, Key::Z, None);
    assert!(
        harness.state().document().graph == before,
        "Ctrl+Z during the move takes back the copy and its moves, nothing before"
    );
    // The copy is let go of: the mouse moves nothing now.
    hover(&mut harness, mouse + vec2(300.0, 200.0));
    assert!(harness.state().document().graph == before);
    key(&mut harness, Modifiers::COMMAND, Key::Z, None);
    assert!(
        node(&harness, "tint space").is_some(),
        "the next Ctrl+Z the deletion"
    );
    key(
        &mut harness,
        Modifiers::COMMAND | Modifiers::SHIFT,
        Key::Z,
        None,
    );
    key(
        &mut harness,
        Modifiers::COMMAND | Modifiers::SHIFT,
        Key::Z,
        None,
    );
    let redone = &harness.state().document().graph;
    assert_eq!(
        redone.nodes.len(),
        before.nodes.len() + 1,
        "redo puts the copy back"
    );
}

#[test]
fn a_name_typed_letter_by_letter_is_one_undo_step() {
    let mut harness = flat_wood_editor(&scratch("sel-typed-name"));
    click_title(&mut harness, "tint space", Modifiers::NONE);
    focus_label_field(&mut harness, "tint space");
    key(&mut harness, Modifiers::NONE, Key::End, None);
    for letter in ["2", "b"] {
        typing(&mut harness, letter);
    }
    press(&mut harness, Key::Enter, false);
    assert!(
        node(&harness, "tint space2b").is_some(),
        "the name was typed"
    );
    // The field has let go of the keyboard: Ctrl+Z is the graph's.
    assert!(focused_field(&harness).is_none());
    key(&mut harness, Modifiers::COMMAND, Key::Z, None);
    assert!(
        node(&harness, "tint space").is_some(),
        "one Ctrl+Z takes back the whole name, not its last letter"
    );
}

#[test]
fn pasted_and_added_nodes_become_the_selection_clear_of_the_others() {
    let mut harness = flat_wood_editor(&scratch("sel-paste"));
    let (none, shift) = (Modifiers::NONE, Modifiers::SHIFT);
    click_title(&mut harness, "trunk", none);
    click_title(&mut harness, "tint space", shift);
    let copied = copy(&mut harness);
    harness.run();
    let before: Vec<NodeId> = harness
        .state()
        .document()
        .graph
        .nodes
        .iter()
        .map(|n| n.id)
        .collect();
    // Pasted with the mouse on the trunk: beside it, not on it.
    let trunk = on_screen(&harness, "trunk").center();
    hover(&mut harness, trunk);
    harness.event(Event::Paste(copied));
    harness.run();
    harness.run_steps(2);
    let graph = &harness.state().document().graph;
    let mut pasted: Vec<NodeId> = graph
        .nodes
        .iter()
        .map(|n| n.id)
        .filter(|id| !before.contains(id))
        .collect();
    assert_eq!(pasted.len(), 2);
    let mut selected = harness.state().selected_nodes();
    selected.sort();
    pasted.sort();
    assert_eq!(selected, pasted, "the pasted nodes are the selection");
    for id in pasted {
        assert_clear(&harness, id);
    }
    // A node added from the search with the mouse on a node lands beside it, selected.
    let ring = on_screen(&harness, "ring sharp").center();
    hover(&mut harness, ring);
    key(&mut harness, Modifiers::NONE, Key::Space, Some(" "));
    typing(&mut harness, "worley");
    key(&mut harness, Modifiers::NONE, Key::Enter, None);
    harness.run_steps(2);
    let added = newest(&harness);
    assert_eq!(harness.state().selected_nodes(), [added.id]);
    assert_clear(&harness, added.id);
}

#[test]
fn an_alt_drag_that_starts_on_a_node_pans_and_leaves_the_node_where_it_is() {
    let mut harness = flat_wood_editor(&scratch("sel-alt-drag"));
    for _round in 0..2 {
        let trunk = node(&harness, "trunk").expect("trunk");
        let position = harness
            .state()
            .document()
            .graph
            .node(trunk)
            .unwrap()
            .position;
        let before = harness.state().graph_to_screen();
        let from = on_screen(&harness, "trunk").center();
        let by = vec2(120.0, -60.0);
        drag(
            &mut harness,
            PointerButton::Primary,
            Modifiers::ALT,
            from,
            from + by,
        );
        let panned = harness.state().graph_to_screen().translation - before.translation;
        assert!(
            (panned - by).length() < 1.0,
            "panned by {panned:?}, not {by:?}"
        );
        let graph = &harness.state().document().graph;
        assert_eq!(
            graph.node(trunk).unwrap().position,
            position,
            "the node moved"
        );
        assert!(
            !harness.state().document().history.can_undo(),
            "a move was recorded"
        );
    }
}

#[test]
fn a_right_click_on_empty_canvas_opens_the_search_there_and_it_takes_the_typing() {
    let mut harness = flat_wood_editor(&scratch("sel-right-click"));
    for round in 0..2 {
        let spot = empty_spot(&harness);
        let thumbnails = harness.state().thumbnails().enabled;
        click(
            &mut harness,
            spot,
            PointerButton::Secondary,
            Modifiers::NONE,
        );
        let (field, text) = focused_field(&harness).expect("the right click opened the search");
        assert_eq!(text, "");
        assert!(
            (field.min - spot).length() < 60.0,
            "round {round}: the search is at {field:?}, not {spot:?}"
        );
        key(&mut harness, Modifiers::NONE, Key::T, Some("t"));
        assert_eq!(
            focused_field(&harness).map(|(_, text)| text),
            Some("t".into())
        );
        assert_eq!(
            harness.state().thumbnails().enabled,
            thumbnails,
            "T toggled thumbnails"
        );
        key(&mut harness, Modifiers::NONE, Key::Escape, None);
        assert!(focused_field(&harness).is_none());
    }
}

/// Presses `key` (with Ctrl when `command`) and draws one frame, as a window does for
/// one key when nothing else asks for frames.
fn one_frame_key(harness: &mut Editor, key: Key, command: bool) {
    let modifiers = if command {
        Modifiers::COMMAND
    } else {
        Modifiers::NONE
    };
    harness.key_press_modifiers(modifiers, key);
    harness.step();
}

#[test]
fn the_status_bar_counts_the_nodes_in_the_frame_of_the_edit() {
    let mut harness = flat_wood_editor(&scratch("sel-count"));
    let count = harness.state().document().graph.nodes.len();
    let counts = |harness: &Editor, count: usize| shows(harness, &format!("{count} nodes ·"));
    assert!(counts(&harness, count));
    click_title(&mut harness, "ring sharp", Modifiers::NONE);
    one_frame_key(&mut harness, Key::Delete, false);
    assert!(counts(&harness, count - 1), "in the frame of the Delete");
    harness.run();
    one_frame_key(&mut harness, Key::Z, true);
    assert!(counts(&harness, count), "in the frame of the undo");
    harness.run();
    click_title(&mut harness, "trunk", Modifiers::NONE);
    one_frame_key(&mut harness, Key::D, true);
    assert!(counts(&harness, count + 1), "in the frame of the duplicate");
}

#[test]
fn ctrl_z_and_ctrl_d_leave_the_graph_alone_while_typing() {
    let mut harness = flat_wood_editor(&scratch("sel-typing-ctrl"));
    // Something to undo: a node deleted.
    click_title(&mut harness, "ring sharp", Modifiers::NONE);
    key(&mut harness, Modifiers::NONE, Key::X, Some("x"));
    assert_eq!(node(&harness, "ring sharp"), None);
    click_title(&mut harness, "tint space", Modifiers::NONE);
    let before = harness.state().document().graph.nodes.len();
    focus_label_field(&mut harness, "tint space");
    key(&mut harness, Modifiers::COMMAND, Key::Z, None);
    key(&mut harness, Modifiers::COMMAND, Key::D, None);
    assert_eq!(
        harness.state().document().graph.nodes.len(),
        before,
        "Ctrl+Z or Ctrl+D reached the graph while a field had the keyboard"
    );
    assert_eq!(node(&harness, "ring sharp"), None, "the graph's undo ran");
    // Out of the field, Ctrl+Z undoes the deletion.
    press(&mut harness, Key::Escape, false);
    harness.run();
    key(&mut harness, Modifiers::COMMAND, Key::Z, None);
    assert!(
        node(&harness, "ring sharp").is_some(),
        "Ctrl+Z undid the deletion"
    );
}
