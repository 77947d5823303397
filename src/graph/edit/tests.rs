//! Each edit carried out, undone and redone: the graph stays canonical, the inverse
//! gives back an equal graph, the change is the right kind, and a refused edit changes
//! nothing.

use super::*;
use crate::graph::group::{BOUNDARY, GroupOutput};
use crate::graph::group_interface::Side;
use crate::graph::{AlphaMode, Frame, MathOp, Node, NodeKind, PinRef, Value, ValueType, Wire};
use crate::nodes::{Constant, Math};

/// The wood preset as the editor keeps it: one `ring_wood` group node (linked to the
/// library) and the material.
pub(super) fn wood() -> Graph {
    let mut graph = crate::graph::preset("wood").expect("the wood preset");
    graph.canonicalize();
    graph
}

/// A float Math node adding its inputs.
pub(super) fn adder(id: u32) -> Node {
    let kind = NodeKind::Math(Math {
        op: MathOp::Add,
        ty: ValueType::Float,
    });
    Node::new(NodeId(id), kind)
}

/// A constant, then `count - 1` adders each fed by the one before, 200 units apart.
pub(super) fn chain(count: u32) -> Graph {
    let mut graph = Graph::default();
    let constant = Node::new(
        NodeId(1),
        NodeKind::Constant(Constant {
            ty: ValueType::Float,
        }),
    );
    graph.nodes.push(constant);
    for k in 2..=count {
        let mut node = adder(k);
        node.position = (200.0 * k as f32, 0.0);
        graph.nodes.push(node);
        let from = if k == 2 { "value" } else { "result" };
        graph.wires.push(wire(k - 1, from, k, "a"));
    }
    graph.canonicalize();
    graph
}

/// A wire from `from`.`output` to `to`.`input`.
pub(super) fn wire(from: u32, output: &str, to: u32, input: &str) -> Wire {
    Wire {
        from: PinRef::new(NodeId(from), output),
        to: PinRef::new(NodeId(to), input),
    }
}

/// Applies `edit`, checks the graph stays canonical, that the inverse gives back the
/// graph before and that the inverse's inverse gives back the graph after; returns what
/// the edit did.
pub(super) fn round_trip(graph: &mut Graph, edit: GraphEdit) -> Applied {
    let before = graph.clone();
    let applied = apply(graph, edit).expect("the edit applies");
    let after = graph.clone();
    let mut canonical = after.clone();
    canonical.canonicalize();
    assert_eq!(after, canonical, "the edit keeps the graph canonical");
    let undone = apply(graph, applied.inverse.clone()).expect("the inverse applies");
    assert!(*graph == before, "the inverse gives back the graph before");
    apply(graph, undone.inverse).expect("redo applies");
    assert!(*graph == after, "redo gives back the graph after");
    applied
}

/// Applies `edit`, which must be refused, leaving the graph as it was.
fn refused(graph: &mut Graph, edit: GraphEdit) -> EditError {
    let before = graph.clone();
    let error = apply(graph, edit).expect_err("the edit is refused");
    assert!(*graph == before, "a refused edit ({error}) changes nothing");
    error
}

fn group_level() -> Level {
    Level::Group("ring_wood".into())
}

#[test]
fn added_nodes_go_in_id_order_and_removing_them_undoes_it() {
    let mut graph = chain(4);
    let mut first = adder(10);
    first.position = (10.4, -3.6);
    let applied = round_trip(
        &mut graph,
        GraphEdit::AddNodes {
            level: Level::Top,
            nodes: vec![first, adder(7)],
            wires: vec![wire(4, "result", 7, "a"), wire(7, "result", 10, "b")],
        },
    );
    assert_eq!(applied.changes, [Change::Structure]);
    assert!(applied.recompiles());
    assert_eq!(
        applied.inverse,
        GraphEdit::RemoveNodes {
            level: Level::Top,
            nodes: vec![NodeId(7), NodeId(10)],
        }
    );
    let ids: Vec<u32> = graph.nodes.iter().map(|node| node.id.0).collect();
    assert_eq!(ids, [1, 2, 3, 4, 7, 10]);
    assert_eq!(graph.node(NodeId(10)).unwrap().position, (10.0, -4.0));
}

#[test]
fn bad_additions_are_refused_with_their_reason() {
    let mut graph = chain(3);
    let add = |nodes: Vec<Node>, wires: Vec<Wire>| GraphEdit::AddNodes {
        level: Level::Top,
        nodes,
        wires,
    };
    let error = refused(&mut graph, add(vec![adder(2)], vec![]));
    assert_eq!(error.to_string(), "the graph has a node #2 already");
    let error = refused(&mut graph, add(vec![adder(5), adder(5)], vec![]));
    assert!(matches!(error, EditError::DuplicateId { .. }));
    let error = refused(
        &mut graph,
        add(vec![adder(5)], vec![wire(5, "out", 3, "b")]),
    );
    assert_eq!(error.to_string(), "the graph: node #5 has no output 'out'");
    let error = refused(
        &mut graph,
        add(vec![adder(5)], vec![wire(1, "value", 2, "b")]),
    );
    assert!(matches!(error, EditError::StrayWire { .. }), "{error}");
    let error = refused(
        &mut graph,
        add(vec![adder(5)], vec![wire(5, "result", 3, "a")]),
    );
    assert!(matches!(error, EditError::InputWired { .. }), "{error}");
    let into_itself = vec![wire(5, "result", 6, "a"), wire(6, "result", 5, "a")];
    let error = refused(&mut graph, add(vec![adder(5), adder(6)], into_itself));
    assert!(matches!(error, EditError::Cycle { .. }), "{error}");
    // Inside a group, id 0 is the boundary's.
    let mut graph = wood();
    let edit = GraphEdit::AddNodes {
        level: group_level(),
        nodes: vec![adder(0)],
        wires: vec![],
    };
    assert!(matches!(
        refused(&mut graph, edit),
        EditError::BoundaryId { .. }
    ));
}

#[test]
fn a_group_node_added_takes_its_groups_pins_and_cannot_hold_itself() {
    let mut graph = wood();
    let mut node = Node::new(
        NodeId(9),
        NodeKind::Group(crate::nodes::Group::named("ring_wood".into())),
    );
    node.label = "second".into();
    round_trip(
        &mut graph,
        GraphEdit::AddNodes {
            level: Level::Top,
            nodes: vec![node.clone()],
            wires: vec![],
        },
    );
    let first = graph.node(NodeId(1)).unwrap();
    assert_eq!(graph.node(NodeId(9)).unwrap().kind, first.kind);
    let inside = GraphEdit::AddNodes {
        level: group_level(),
        nodes: vec![node],
        wires: vec![],
    };
    let error = refused(&mut graph, inside);
    assert!(
        error.to_string().contains("would contain itself"),
        "{error}"
    );
}

#[test]
fn removed_nodes_come_back_with_their_wires_from_a_small_inverse() {
    let mut graph = chain(10_000);
    let applied = round_trip(
        &mut graph,
        GraphEdit::RemoveNodes {
            level: Level::Top,
            nodes: vec![NodeId(5_000)],
        },
    );
    // The inverse holds what was removed, not the graph.
    let GraphEdit::Restore { nodes, wires, .. } = &applied.inverse else {
        panic!("{:?}", applied.inverse);
    };
    assert_eq!(nodes.len(), 1);
    assert_eq!(
        *wires,
        [
            wire(4_999, "result", 5_000, "a"),
            wire(5_000, "result", 5_001, "a")
        ]
    );
    let error = refused(
        &mut graph,
        GraphEdit::RemoveNodes {
            level: Level::Top,
            nodes: vec![NodeId(3), NodeId(20_000)],
        },
    );
    assert_eq!(error.to_string(), "the graph has no node #20000");
}

#[test]
fn restoring_what_is_there_is_refused() {
    let mut graph = chain(3);
    let node = graph.nodes[1].clone();
    let edit = GraphEdit::Restore {
        level: Level::Top,
        nodes: vec![node],
        wires: vec![],
    };
    assert!(matches!(
        refused(&mut graph, edit),
        EditError::DuplicateId { .. }
    ));
    let edit = GraphEdit::Restore {
        level: Level::Top,
        nodes: vec![],
        wires: vec![wire(1, "value", 2, "a")],
    };
    assert!(matches!(
        refused(&mut graph, edit),
        EditError::WireExists { .. }
    ));
}

#[test]
fn connecting_replaces_the_wire_into_the_input_and_undo_puts_it_back() {
    let mut graph = chain(4);
    let applied = round_trip(
        &mut graph,
        GraphEdit::Connect {
            level: Level::Top,
            wire: wire(1, "value", 3, "a"),
        },
    );
    assert_eq!(applied.changes, [Change::Structure]);
    assert!(
        graph
            .wire_into(NodeId(3), "a")
            .is_some_and(|w| w.from.node == NodeId(1))
    );
    assert_eq!(graph.wires.len(), 3, "the wire from #2 was replaced");
    // The same wire again changes nothing.
    let again = apply(
        &mut graph,
        GraphEdit::Connect {
            level: Level::Top,
            wire: wire(1, "value", 3, "a"),
        },
    );
    assert_eq!(again.map(|applied| applied.changes), Ok(vec![]));
}

#[test]
fn wires_that_close_a_cycle_or_mismatch_types_are_refused() {
    let mut graph = chain(4);
    let connect = |wire| GraphEdit::Connect {
        level: Level::Top,
        wire,
    };
    let error = refused(&mut graph, connect(wire(4, "result", 2, "b")));
    assert_eq!(
        error.to_string(),
        "the graph: the wire from #4.result to #2.b would close a cycle"
    );
    let error = refused(&mut graph, connect(wire(3, "result", 3, "b")));
    assert!(matches!(error, EditError::Cycle { .. }));
    let error = refused(&mut graph, connect(wire(9, "result", 3, "b")));
    assert_eq!(error.to_string(), "the graph has no node #9");
    // A vec3 does not go into a float.
    let mut graph = wood();
    let vec3 = GraphEdit::Connect {
        level: group_level(),
        wire: wire(0, "trunk_axis", 9, "a"),
    };
    let error = refused(&mut graph, vec3);
    assert!(matches!(error, EditError::Types { .. }), "{error}");
    // Through a group's boundary is no cycle: an input passed straight to an output.
    let output = GroupOutput {
        name: "passed".into(),
        ty: ValueType::Float,
    };
    let through = GraphEdit::Batch(vec![
        GraphEdit::AddGroupPin {
            group: "ring_wood".into(),
            index: 2,
            pin: GroupPin::Output(output),
        },
        GraphEdit::Connect {
            level: group_level(),
            wire: wire(0, "taper", 0, "passed"),
        },
    ]);
    round_trip(&mut graph, through);
}

#[test]
fn disconnecting_removes_wires_that_are_there() {
    let mut graph = chain(4);
    let wires = vec![wire(1, "value", 2, "a"), wire(3, "result", 4, "a")];
    let applied = round_trip(
        &mut graph,
        GraphEdit::Disconnect {
            level: Level::Top,
            wires,
        },
    );
    assert_eq!(applied.changes, [Change::Structure]);
    assert_eq!(graph.wires, [wire(2, "result", 3, "a")]);
    let twice = vec![wire(2, "result", 3, "a"), wire(2, "result", 3, "a")];
    let error = refused(
        &mut graph,
        GraphEdit::Disconnect {
            level: Level::Top,
            wires: twice,
        },
    );
    assert!(matches!(error, EditError::UnknownWire { .. }));
}

#[test]
fn a_value_set_is_a_value_change_and_none_clears_it() {
    let mut graph = chain(3);
    let set = |value| GraphEdit::SetInput {
        level: Level::Top,
        node: NodeId(2),
        pin: "b".into(),
        value,
    };
    let applied = round_trip(&mut graph, set(Some(Value::Float(0.25))));
    let slot = Change::Value {
        level: Level::Top,
        node: NodeId(2),
        pin: "b".into(),
    };
    assert_eq!(applied.changes, std::slice::from_ref(&slot));
    assert!(!applied.recompiles());
    assert_eq!(applied.inverse, set(None));
    let cleared = round_trip(&mut graph, set(None));
    assert_eq!(cleared.changes, [slot]);
    assert!(graph.node(NodeId(2)).unwrap().inputs.is_empty());
    let same = apply(&mut graph, set(None)).expect("applies");
    assert!(same.changes.is_empty(), "nothing changed");
    let error = refused(
        &mut graph,
        GraphEdit::SetInput {
            level: Level::Top,
            node: NodeId(2),
            pin: "c".into(),
            value: None,
        },
    );
    assert_eq!(error.to_string(), "the graph: node #2 has no input 'c'");
}

#[test]
fn labels_and_moves_are_layout_changes() {
    let mut graph = chain(3);
    let label = round_trip(
        &mut graph,
        GraphEdit::SetLabel {
            level: Level::Top,
            node: NodeId(3),
            label: "sum".into(),
        },
    );
    assert_eq!(label.changes, [Change::Layout]);
    let moved = round_trip(
        &mut graph,
        GraphEdit::MoveNodes {
            level: Level::Top,
            moves: vec![(NodeId(1), (-20.3, 40.6)), (NodeId(3), (1.0, 2.0))],
        },
    );
    assert_eq!(moved.changes, [Change::Layout]);
    assert_eq!(graph.node(NodeId(1)).unwrap().position, (-20.0, 41.0));
    let error = refused(
        &mut graph,
        GraphEdit::MoveNodes {
            level: Level::Top,
            moves: vec![(NodeId(1), (0.0, 0.0)), (NodeId(8), (0.0, 0.0))],
        },
    );
    assert!(matches!(error, EditError::UnknownNode { .. }));
    let mut graph = wood();
    let arranged = round_trip(
        &mut graph,
        GraphEdit::Arrange {
            level: group_level(),
        },
    );
    assert_eq!(arranged.changes, [Change::Layout]);
}

#[test]
fn settings_change_in_place_but_a_node_keeps_its_kind() {
    let mut graph = chain(3);
    let subtract = NodeKind::Math(Math {
        op: MathOp::Subtract,
        ty: ValueType::Float,
    });
    let applied = round_trip(
        &mut graph,
        GraphEdit::SetKind {
            level: Level::Top,
            node: NodeId(2),
            kind: subtract,
        },
    );
    assert_eq!(applied.changes, [Change::Structure]);
    let error = refused(
        &mut graph,
        GraphEdit::SetKind {
            level: Level::Top,
            node: NodeId(2),
            kind: NodeKind::Material,
        },
    );
    assert_eq!(
        error.to_string(),
        "the graph: node #2 is a Math; a node keeps its kind (and a group node its group)"
    );
}

#[test]
fn graph_settings_swap_and_frames_are_layout() {
    let mut graph = wood();
    let alpha = round_trip(
        &mut graph,
        GraphEdit::Set(GraphSetting::Alpha(AlphaMode::Blend)),
    );
    assert_eq!(alpha.changes, [Change::Settings]);
    let frame = Frame {
        title: "rings".into(),
        min: (0.0, 0.0),
        max: (100.0, 50.0),
        color: (0.5, 0.6, 0.9),
    };
    let frames = round_trip(
        &mut graph,
        GraphEdit::Set(GraphSetting::Frames(vec![frame])),
    );
    assert_eq!(frames.changes, [Change::Layout]);
    let name = round_trip(&mut graph, GraphEdit::Set(GraphSetting::Name("Oak".into())));
    assert_eq!(name.changes, [Change::Settings]);
}

#[test]
fn a_preset_sets_values_and_undo_sets_them_back() {
    let mut graph = wood();
    let applied = round_trip(
        &mut graph,
        GraphEdit::ApplyPreset {
            name: "walnut".into(),
        },
    );
    assert!(!applied.changes.is_empty());
    assert!(
        applied
            .changes
            .iter()
            .all(|change| matches!(change, Change::Value { .. })),
        "{:?}",
        applied.changes
    );
    let error = refused(
        &mut graph,
        GraphEdit::ApplyPreset {
            name: "teak".into(),
        },
    );
    assert!(
        error
            .to_string()
            .starts_with("no parameter preset named 'teak'"),
        "{error}"
    );
}

#[test]
fn editing_inside_a_linked_group_makes_it_local_and_undo_links_it_again() {
    let mut graph = wood();
    assert!(graph.groups["ring_wood"].linked);
    round_trip(
        &mut graph,
        GraphEdit::SetInput {
            level: group_level(),
            node: NodeId(30),
            pin: "b".into(),
            value: Some(Value::Float(0.3)),
        },
    );
    assert!(!graph.groups["ring_wood"].linked);
    let relinked = round_trip(
        &mut graph,
        GraphEdit::SetLinked {
            group: "ring_wood".into(),
            linked: true,
        },
    );
    assert_eq!(relinked.changes, [Change::Settings]);
}

#[test]
fn an_edit_that_changes_nothing_leaves_a_linked_group_linked() {
    // (Found by the property test: the group was made local by an edit that the
    // history, seeing no change, never recorded, so undo could not link it again.)
    let mut graph = wood();
    let kind = graph.groups["ring_wood"].nodes[4].kind.clone();
    let applied = apply(
        &mut graph,
        GraphEdit::SetKind {
            level: group_level(),
            node: NodeId(5),
            kind,
        },
    )
    .expect("applies");
    assert!(applied.changes.is_empty());
    assert!(graph.groups["ring_wood"].linked);
}

#[test]
fn a_declared_input_shows_on_the_group_node_until_undone() {
    let mut graph = wood();
    let input = crate::graph::group::GroupInput {
        name: "tint_amount".into(),
        ty: ValueType::Float,
        default: Value::Float(0.1),
        range: None,
        hint: Default::default(),
    };
    let declared = GraphEdit::Batch(vec![
        GraphEdit::AddGroupPin {
            group: "ring_wood".into(),
            index: 9,
            pin: GroupPin::Input(input.clone()),
        },
        GraphEdit::Connect {
            level: group_level(),
            wire: wire(0, "tint_amount", 30, "b"),
        },
    ]);
    let applied = round_trip(&mut graph, declared);
    assert_eq!(applied.changes, [Change::Structure]);
    let pins = graph.node(NodeId(1)).unwrap().kind.signature();
    assert!(
        pins.input("tint_amount").is_some(),
        "the group node shows it"
    );
    let mut changed = input;
    changed.range = Some((0.0, 1.0));
    round_trip(
        &mut graph,
        GraphEdit::SetGroupInput {
            group: "ring_wood".into(),
            input: changed,
        },
    );
    let edit = GraphEdit::DropGroupPin {
        group: "ring_wood".into(),
        side: Side::Input,
        index: 10,
    };
    assert!(matches!(
        refused(&mut graph, edit),
        EditError::UnknownGroupPin { .. }
    ));
}

#[test]
fn renaming_and_removing_a_groups_pins_are_undone_whole() {
    let mut graph = wood();
    let renamed = round_trip(
        &mut graph,
        GraphEdit::RenameGroupPin {
            group: "ring_wood".into(),
            side: Side::Input,
            old: "ring_frequency".into(),
            new: "rings_per_unit".into(),
        },
    );
    assert!(renamed.recompiles());
    assert!(graph.presets["oak"].contains_key("rings_per_unit"));
    round_trip(
        &mut graph,
        GraphEdit::RemoveGroupPin {
            group: "ring_wood".into(),
            side: Side::Output,
            name: "albedo".into(),
        },
    );
    let error = refused(
        &mut graph,
        GraphEdit::RenameGroupPin {
            group: "ring_wood".into(),
            side: Side::Input,
            old: "taper".into(),
            new: "2x".into(),
        },
    );
    assert!(matches!(error, EditError::Refused(_)));
}

#[test]
fn grouping_and_ungrouping_at_the_top_and_inside_a_group() {
    let mut graph = wood();
    let inner = [NodeId(9), NodeId(10)].into_iter().collect();
    round_trip(
        &mut graph,
        GraphEdit::Group {
            level: group_level(),
            nodes: inner,
            name: "warps".into(),
        },
    );
    let definition = &graph.groups["ring_wood"];
    let instance = definition.nodes.last().expect("the new group node");
    assert_eq!(crate::graph::group::group_name(instance), Some("warps"));
    assert_eq!(graph.groups["warps"].nodes.len(), 2);
    let instance = instance.id;
    let error = refused(
        &mut graph,
        GraphEdit::Group {
            level: group_level(),
            nodes: [BOUNDARY].into_iter().collect(),
            name: "edge".into(),
        },
    );
    assert_eq!(
        error.to_string(),
        "group 'ring_wood': node id #0 stands for the group's inputs and outputs"
    );
    round_trip(
        &mut graph,
        GraphEdit::Ungroup {
            level: group_level(),
            node: instance,
        },
    );
    round_trip(
        &mut graph,
        GraphEdit::Ungroup {
            level: Level::Top,
            node: NodeId(1),
        },
    );
    assert!(graph.groups.is_empty(), "the group went with its last node");
    let error = refused(
        &mut graph,
        GraphEdit::Group {
            level: Level::Top,
            nodes: [NodeId(2)].into_iter().collect(),
            name: "material".into(),
        },
    );
    assert_eq!(
        error.to_string(),
        "the Material node cannot go into a group"
    );
}

#[test]
fn a_groups_definition_comes_and_goes_whole() {
    let mut graph = wood();
    let copy = graph.groups["ring_wood"].clone();
    let applied = round_trip(
        &mut graph,
        GraphEdit::SetGroup {
            name: "ring_wood_2".into(),
            definition: Some(Box::new(copy)),
        },
    );
    assert_eq!(
        applied.inverse,
        GraphEdit::SetGroup {
            name: "ring_wood_2".into(),
            definition: None,
        }
    );
}

#[test]
fn a_batch_is_all_or_nothing() {
    let mut graph = chain(3);
    let batch = GraphEdit::Batch(vec![
        GraphEdit::SetLabel {
            level: Level::Top,
            node: NodeId(1),
            label: "start".into(),
        },
        GraphEdit::RemoveNodes {
            level: Level::Top,
            nodes: vec![NodeId(2)],
        },
        GraphEdit::SetLabel {
            level: Level::Top,
            node: NodeId(2),
            label: "gone".into(),
        },
    ]);
    let error = refused(&mut graph, batch);
    assert_eq!(error.to_string(), "the graph has no node #2");
    let error = refused(
        &mut graph,
        GraphEdit::RemoveNodes {
            level: Level::Group("bark".into()),
            nodes: vec![],
        },
    );
    assert_eq!(error.to_string(), "no group named 'bark'");
}

/// Removing a node a parameter exposes takes the parameter and its preset values with
/// it, so the graph still checks (before, the material stopped compiling: "parameter
/// 'bumpScale' exposes node #14, which the graph does not have"); undo puts them back.
/// Removing the wood's group node forgets the presets' values of the parameters its
/// inputs exposed.
#[test]
fn removing_an_exposed_node_takes_its_parameter_and_preset_values() {
    let mut graph = crate::graph::preset("thesis_c2_sand_water").expect("the C.2 preset");
    graph.canonicalize();
    let parameter = (graph.parameters.iter())
        .find(|p| p.name == "distanceThreshold")
        .expect("the preset exposes the listing's threshold")
        .clone();
    (graph.presets.get_mut("glossy").expect("a glossy preset"))
        .insert(parameter.name.clone(), Value::Float(0.5));
    round_trip(
        &mut graph,
        GraphEdit::RemoveNodes {
            level: Level::Top,
            nodes: vec![parameter.node],
        },
    );
    assert!(graph.parameters.iter().all(|p| p.name != parameter.name));
    assert!(
        graph
            .presets
            .values()
            .all(|v| !v.contains_key(&parameter.name))
    );
    crate::graph::check(&graph).expect("the graph still checks");

    let mut graph = wood();
    let group = graph
        .nodes
        .iter()
        .find(|node| matches!(node.kind, NodeKind::Group(_)))
        .expect("the wood's group")
        .id;
    round_trip(
        &mut graph,
        GraphEdit::RemoveNodes {
            level: Level::Top,
            nodes: vec![group],
        },
    );
    assert!(graph.presets.values().all(|values| values.is_empty()));
    crate::graph::check(&graph).expect("the presets still check");
}
