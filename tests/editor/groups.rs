//! Node groups in the editor: Ctrl+G groups the selection (one undo step, the Material
//! left out), Alt+G dissolves the group back into the same graph, Tab enters a group
//! and leaves it (so does the breadcrumb), the Parameters panel and its presets set a
//! group node's inputs, and the add-node search offers the library's groups.

use crate::navigation::{drag, on_screen};
use crate::support::{
    click_node, editor, press, retype_drag_value, scratch, select_node, shows, type_into_field,
};
use egui::{Key, Modifiers, PointerButton, vec2};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use std::path::{Path, PathBuf};
use veneer::app::VeneerApp;
use veneer::graph::{NodeKind, Value, to_ron};

/// A noise scaled by a multiply into the material: the nodes to group.
const SMALL: &str = r#"(
    version: 1,
    name: "Small",
    nodes: [
        (id: 1, label: "noise", kind: Noise(basis: Gradient), inputs: {}, position: (0.0, 0.0)),
        (id: 2, label: "shade", kind: Math(op: Multiply, ty: Float), inputs: {"b": Float(0.3)}, position: (300.0, 0.0)),
        (id: 3, label: "material", kind: Material, inputs: {}, position: (600.0, 0.0)),
    ],
    wires: [
        (from: (node: 1, pin: "value"), to: (node: 2, pin: "a")),
        (from: (node: 2, pin: "result"), to: (node: 3, pin: "albedo")),
    ],
)
"#;

/// The editor on [`SMALL`], written into `dir`.
fn small_editor(dir: &Path) -> Harness<'static, VeneerApp> {
    let path = dir.join("small.ron");
    std::fs::write(&path, SMALL).expect("the graph is written");
    editor(dir, Some(path))
}

/// The graph's file text.
fn text(harness: &Harness<'static, VeneerApp>) -> String {
    to_ron(&harness.state().document().graph)
}

/// Selects "noise" and "shade" with a rectangle dragged over them from empty canvas.
fn select_noise_and_shade(harness: &mut Harness<'static, VeneerApp>) {
    let (noise, shade) = (on_screen(harness, "noise"), on_screen(harness, "shade"));
    // Clear of the noise node's edge and the reach of its pins.
    let start = noise.min - vec2(40.0, 40.0);
    drag(
        harness,
        PointerButton::Primary,
        Modifiers::NONE,
        start,
        shade.center(),
    );
    let mut selected = harness.state().selected_labels();
    selected.sort();
    assert_eq!(selected, ["noise", "shade"]);
}

/// Presses `key` with `modifiers` and lets the editor react.
fn key(harness: &mut Harness<'static, VeneerApp>, modifiers: Modifiers, key: Key) {
    harness.key_press_modifiers(modifiers, key);
    harness.run();
}

#[test]
fn ctrl_g_groups_the_selection_and_ctrl_z_restores_the_graph() {
    let dir = scratch("group-undo");
    let mut harness = small_editor(&dir);
    let before = text(&harness);

    // The Material alone: nothing to group, and the status bar says why.
    select_node(&mut harness, "material");
    press(&mut harness, Key::G, true);
    assert!(harness.state().document().graph.groups.is_empty());
    assert!(shows(&harness, "nothing to group"));

    select_noise_and_shade(&mut harness);
    press(&mut harness, Key::G, true);
    let graph = &harness.state().document().graph;
    let group = graph.groups.get("group").expect("a group named 'group'");
    assert_eq!(group.nodes.len(), 2, "the noise and the multiply went in");
    assert_eq!(
        graph.nodes.len(),
        2,
        "the group node and the material are left"
    );
    assert_eq!(
        harness.state().selected_labels(),
        ["group"],
        "the new group node is selected"
    );
    assert!(
        harness.state().live().errors.is_empty(),
        "the grouped graph compiles"
    );

    press(&mut harness, Key::Z, true);
    assert_eq!(text(&harness), before, "one Ctrl+Z takes the grouping back");
}

#[test]
fn ctrl_g_then_alt_g_gives_back_the_same_graph() {
    let dir = scratch("group-ungroup");
    let mut harness = small_editor(&dir);
    let before = text(&harness);
    select_noise_and_shade(&mut harness);
    press(&mut harness, Key::G, true);
    assert_ne!(text(&harness), before);
    key(&mut harness, Modifiers::ALT, Key::G);
    assert_eq!(
        text(&harness),
        before,
        "ungrouping puts the same nodes and wires back"
    );
}

#[test]
fn tab_enters_the_group_and_leaves_it() {
    let dir = scratch("group-tab");
    let mut harness = small_editor(&dir);
    select_noise_and_shade(&mut harness);
    press(&mut harness, Key::G, true);

    press(&mut harness, Key::Tab, false);
    harness.run_steps(4);
    assert_eq!(harness.state().group_path(), ["group"]);
    for shown in ["Group input", "Group output", "noise", "shade"] {
        assert!(shows(&harness, shown), "inside the group: {shown}");
    }
    assert!(
        harness.query_by_label("material").is_none(),
        "the top level is not shown"
    );
    assert!(
        harness.query_by_label("Add node").is_none(),
        "Tab on a group node does not open the search"
    );

    // An edit inside changes the definition (and is one undo step).
    select_node(&mut harness, "shade");
    retype_drag_value(&mut harness, "0.300", "0.5");
    let definition = &harness.state().document().graph.groups["group"];
    let scale = definition
        .nodes
        .iter()
        .find(|n| n.label == "shade")
        .unwrap();
    assert_eq!(scale.inputs.get("b"), Some(&Value::Float(0.5)));
    press(&mut harness, Key::Z, true);
    let definition = &harness.state().document().graph.groups["group"];
    let scale = definition
        .nodes
        .iter()
        .find(|n| n.label == "shade")
        .unwrap();
    assert_eq!(
        scale.inputs.get("b"),
        Some(&Value::Float(0.3)),
        "undone inside the group"
    );
    assert_eq!(
        harness.state().group_path(),
        ["group"],
        "undo stays in the group"
    );

    // The breadcrumb's "Graph" goes back up, selecting the group node.
    harness.get_by_label("Graph").click();
    harness.run_steps(4);
    assert!(
        harness.state().group_path().is_empty(),
        "the breadcrumb goes back up"
    );
    assert_eq!(harness.state().selected_labels(), ["group"]);

    press(&mut harness, Key::Tab, false);
    assert_eq!(harness.state().group_path(), ["group"]);
    // Nothing is selected on entering: Tab goes back up.
    press(&mut harness, Key::Tab, false);
    assert!(
        harness.state().group_path().is_empty(),
        "Tab leaves the group"
    );
    assert!(harness.query_by_label("material").is_some());
}

#[test]
fn the_parameters_panel_and_its_presets_set_the_group_node_inputs() {
    let dir = scratch("group-parameters");
    let wood = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("graphs/wood.ron");
    let mut harness = editor(&dir, Some(wood));
    assert!(shows(&harness, "Parameters"));
    let wood_node = |harness: &Harness<'static, VeneerApp>| {
        let graph = &harness.state().document().graph;
        graph
            .nodes
            .iter()
            .find(|n| n.label == "wood")
            .unwrap()
            .clone()
    };
    // The panel comes before the graph: its field is the first showing 0.50.
    retype_drag_value(&mut harness, "0.50", "0.7");
    assert_eq!(
        wood_node(&harness).inputs.get("ring_frequency"),
        Some(&Value::Float(0.7)),
        "the panel sets the group node's input, as --set ring_frequency=0.7 does"
    );
    harness.get_by_label("preset").click();
    harness.run();
    harness.get_by_label("walnut").click();
    harness.run();
    assert_eq!(
        wood_node(&harness).inputs.get("ring_frequency"),
        Some(&Value::Float(0.4)),
        "the walnut preset"
    );
    press(&mut harness, Key::Z, true);
    assert_eq!(
        wood_node(&harness).inputs.get("ring_frequency"),
        Some(&Value::Float(0.7)),
        "a preset is one undo step"
    );
}

#[test]
fn the_add_node_search_finds_library_groups_and_places_them() {
    let dir = scratch("group-search");
    let mut harness = small_editor(&dir);
    let before = harness.state().document().graph.nodes.len();
    press(&mut harness, Key::Space, false);
    type_into_field(&mut harness, "ring_wood");
    harness.get_by_label("ring_wood").click();
    harness.run();
    let graph = &harness.state().document().graph;
    assert_eq!(graph.nodes.len(), before + 1);
    let placed = graph
        .nodes
        .iter()
        .find(|n| matches!(&n.kind, NodeKind::Group(g) if g.name == "ring_wood"));
    assert!(placed.is_some(), "a ring_wood group node");
    assert!(
        graph.groups.get("ring_wood").is_some_and(|g| g.linked),
        "a linked copy"
    );
    let pins = placed.unwrap().kind.signature();
    assert!(
        pins.input("ring_frequency").is_some(),
        "with the group's pins"
    );
}

#[test]
fn groups_nest_and_ungroup_inside_a_group() {
    let dir = scratch("group-nest");
    let mut harness = small_editor(&dir);
    let before = text(&harness);
    select_noise_and_shade(&mut harness);
    press(&mut harness, Key::G, true);
    press(&mut harness, Key::Tab, false);
    harness.run_steps(4);

    // Inside "group", the noise alone becomes "group_2", used by "group".
    select_node(&mut harness, "noise");
    press(&mut harness, Key::G, true);
    let graph = &harness.state().document().graph;
    assert!(graph.groups.contains_key("group_2"));
    let outer = &graph.groups["group"];
    assert!(
        outer
            .nodes
            .iter()
            .any(|n| matches!(&n.kind, NodeKind::Group(g) if g.name == "group_2")),
        "{outer:?}"
    );
    assert!(
        harness.state().live().errors.is_empty(),
        "the nested groups compile"
    );
    press(&mut harness, Key::Tab, false);
    assert_eq!(harness.state().group_path(), ["group", "group_2"]);
    assert!(
        harness.query_by_label("Graph").is_some(),
        "the breadcrumb shows"
    );
    press(&mut harness, Key::Tab, false);
    assert_eq!(harness.state().group_path(), ["group"]);

    // Back in "group" with group_2's node selected: Alt+G, then up and Alt+G again.
    key(&mut harness, Modifiers::ALT, Key::G);
    assert!(
        !harness
            .state()
            .document()
            .graph
            .groups
            .contains_key("group_2")
    );
    press(&mut harness, Key::Tab, false);
    assert!(harness.state().group_path().is_empty());
    key(&mut harness, Modifiers::ALT, Key::G);
    assert_eq!(
        text(&harness),
        before,
        "both ungroupings give the graph back"
    );
}

#[test]
fn the_group_input_node_renames_retunes_and_removes_the_group_inputs() {
    let dir = scratch("group-interface");
    let mut harness = editor(&dir, None);
    select_node(&mut harness, "wood");
    press(&mut harness, Key::Tab, false);
    harness.run_steps(4);
    click_node(&mut harness, "Group input");
    assert!(shows(&harness, "Group inputs"));

    // Rename: the field commits on Enter; the instance and the presets follow.
    let field = harness
        .get_all_by_role(egui::accesskit::Role::TextInput)
        .find(|node| node.value().as_deref() == Some("ring_frequency"))
        .expect("the name field of ring_frequency");
    field.focus();
    harness.run();
    harness.key_press_modifiers(Modifiers::COMMAND, Key::A);
    harness.event(egui::Event::Text("rings_per_unit".into()));
    harness.key_press(Key::Enter);
    harness.run();
    let graph = &harness.state().document().graph;
    let group = &graph.groups["ring_wood"];
    assert!(
        group
            .inputs
            .iter()
            .any(|input| input.name == "rings_per_unit")
    );
    assert!(!group.linked, "an edited library group is local now");
    assert!(graph.presets["oak"].contains_key("rings_per_unit"));
    assert!(shows(
        &harness,
        "renamed 'ring_frequency' to 'rings_per_unit'"
    ));
    assert!(
        shows(&harness, "Group inputs"),
        "the Group input node stays inspected"
    );

    // Retune: the first input's range switched off.
    harness
        .get_all_by_label("range")
        .next()
        .expect("a range checkbox")
        .click();
    harness.run();
    let group = &harness.state().document().graph.groups["ring_wood"];
    assert_eq!(group.inputs[0].range, None);

    // Remove the first input (its × button): its wires go, the pins keep its value.
    let before = harness.state().document().graph.groups["ring_wood"]
        .inputs
        .len();
    harness
        .get_all_by_label("×")
        .next()
        .expect("a remove button")
        .click();
    harness.run();
    let group = &harness.state().document().graph.groups["ring_wood"];
    assert_eq!(group.inputs.len(), before - 1);
    assert!(
        group
            .inputs
            .iter()
            .all(|input| input.name != "rings_per_unit")
    );
    let phase = group
        .nodes
        .iter()
        .find(|node| node.label == "ring phase")
        .unwrap();
    assert_eq!(phase.inputs.get("b"), Some(&Value::Float(0.5)));
    // One undo step each.
    press(&mut harness, Key::Z, true);
    let group = &harness.state().document().graph.groups["ring_wood"];
    assert_eq!(group.inputs.len(), before);
}

/// Group 'bark' holds a node of group 'grain', which holds one of 'bark': a graph that
/// loads but does not check, its top-level wire reading the output 'bark' declares.
pub(crate) const SELF_CONTAINING: &str = r#"(
    version: 2,
    name: "Loop",
    nodes: [
        (id: 1, label: "bark", kind: Group(name: "bark"), inputs: {}, position: (0.0, 0.0)),
        (id: 2, label: "material", kind: Material, inputs: {}, position: (400.0, 0.0)),
    ],
    wires: [
        (from: (node: 1, pin: "result"), to: (node: 2, pin: "albedo")),
    ],
    groups: {
        "bark": (outputs: [(name: "result", ty: Float)], nodes: [(id: 1, label: "grain", kind: Group(name: "grain"), inputs: {}, position: (0.0, 0.0))], wires: [(from: (node: 1, pin: "result"), to: (node: 0, pin: "result")), (from: (node: 0, pin: "scale"), to: (node: 1, pin: "scale"))]),
        "grain": (outputs: [(name: "result", ty: Float)], nodes: [(id: 1, label: "bark", kind: Group(name: "bark"), inputs: {}, position: (0.0, 0.0))], wires: [(from: (node: 1, pin: "result"), to: (node: 0, pin: "result"))]),
    },
)
"#;

#[test]
fn a_group_that_contains_itself_never_edits_the_document_and_says_why() {
    // The editor dropped the top-level wire (the group's pins never resolved) and
    // marked the graph edited: saving would have lost the wire.
    let dir = scratch("group-loop");
    let path = dir.join("loop.ron");
    std::fs::write(&path, SELF_CONTAINING).expect("the graph is written");
    let mut harness = editor(&dir, Some(path.clone()));
    let opened = to_ron(&veneer::graph::load(&path).expect("loads"));
    harness.run_steps(4);
    assert_eq!(text(&harness), opened);
    assert!(!harness.state().document().is_dirty());
    assert!(shows(&harness, "groups contain themselves"));
    // Inside the group and back: the wires the view cannot show stay too.
    select_node(&mut harness, "bark");
    press(&mut harness, Key::Tab, false);
    assert!(shows(&harness, "Group output"));
    press(&mut harness, Key::Tab, false);
    assert_eq!(text(&harness), opened);
    assert!(!harness.state().document().is_dirty());
}

/// A graph whose albedo is group `wide`'s result, `wide` declaring `inputs` inputs of
/// which the first scales the result.
fn wide_group(inputs: usize) -> String {
    let declared: Vec<String> = (0..inputs)
        .map(|k| format!("(name: \"i{k}\", ty: Float, default: Float(0.5))"))
        .collect();
    format!(
        "(\n    version: 2,\n    nodes: [\n        (id: 1, label: \"wide\", kind: Group(name: \"wide\"), inputs: {{}}, position: (0.0, 0.0)),\n        (id: 2, label: \"material\", kind: Material, inputs: {{}}, position: (400.0, 0.0)),\n    ],\n    wires: [\n        (from: (node: 1, pin: \"result\"), to: (node: 2, pin: \"albedo\")),\n    ],\n    groups: {{\n        \"wide\": (inputs: [{}], outputs: [(name: \"result\", ty: Float)], nodes: [(id: 1, kind: Math(op: Multiply, ty: Float), inputs: {{}}, position: (0.0, 0.0))], wires: [(from: (node: 0, pin: \"i0\"), to: (node: 1, pin: \"a\")), (from: (node: 1, pin: \"result\"), to: (node: 0, pin: \"result\"))]),\n    }},\n)\n",
        declared.join(", ")
    )
}

#[test]
fn a_group_with_more_inputs_than_a_group_may_show_opens_unchanged_and_says_why() {
    // A group of 10⁵ inputs kept the editor busy on every frame.
    let dir = scratch("group-wide");
    for (inputs, problem) in [
        (100_000, Some("more than the 1,024 a group may show")),
        (1_024, None),
    ] {
        let path = dir.join(format!("wide-{inputs}.ron"));
        std::fs::write(&path, wide_group(inputs)).expect("the graph is written");
        let opened = to_ron(&veneer::graph::load(&path).expect("loads"));
        let mut harness = editor(&dir, Some(path));
        harness.run_steps(4);
        assert_eq!(text(&harness), opened, "{inputs} inputs");
        assert!(!harness.state().document().is_dirty());
        match problem {
            Some(problem) => assert!(shows(&harness, problem), "{inputs} inputs"),
            None => assert!(harness.state().live().errors.is_empty(), "{inputs} inputs"),
        }
    }
}

#[test]
fn a_numerical_hazard_inside_a_group_is_marked_inside_it_and_on_the_group() {
    let dir = scratch("group-lint");
    let graph = crate::support::wood_with_a_hazard_inside();
    let path = dir.join("wood.ron");
    veneer::graph::save(&graph, &path).expect("the graph saves");
    let mut harness = editor(&dir, Some(path));
    select_node(&mut harness, "wood");
    assert!(
        shows(&harness, "node 'ring sharp'") && shows(&harness, "a hard step"),
        "the group node names the hazard inside it: {:?}",
        harness.state().live().warnings
    );
    press(&mut harness, Key::Tab, false);
    harness.run_steps(4);
    assert_eq!(harness.state().group_path(), ["ring_wood"]);
    select_node(&mut harness, "ring sharp");
    assert!(
        shows(&harness, "not a smooth one (in group 'wood')"),
        "inside, the node itself is marked"
    );
}
