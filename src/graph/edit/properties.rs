//! Random runs of edits on the shipped presets, some in gestures, many of them refused:
//! a refused edit changes nothing, every edit keeps the graph canonical, undoing them
//! all gives back the preset exactly and redoing them all the graph they made.

use super::tests::adder;
use super::*;
use crate::graph::group::{GroupInput, GroupOutput, Hint, group_name};
use crate::graph::group_interface::Side;
use crate::graph::{AlphaMode, Frame, Node, NodeKind, PinRef, Shading, Value, ValueType, Wire};
use proptest::prelude::*;

/// The numbers one random edit is made from.
type Pick = (u8, u32, u32, u32);

/// The levels of `graph`: the top level, then its groups.
fn levels(graph: &Graph) -> Vec<Level> {
    let groups = graph.groups.keys().cloned().map(Level::Group);
    std::iter::once(Level::Top).chain(groups).collect()
}

/// The nodes and wires of `level`.
fn contents<'g>(graph: &'g Graph, level: &Level) -> (&'g [Node], &'g [Wire]) {
    match level.group().and_then(|name| graph.groups.get(name)) {
        Some(definition) => (&definition.nodes, &definition.wires),
        None => (&graph.nodes, &graph.wires),
    }
}

/// The `k`th of `items` (wrapping), if there are any.
fn nth<T>(items: &[T], k: u32) -> Option<&T> {
    (!items.is_empty()).then(|| &items[k as usize % items.len()])
}

/// A value of type `ty` made from `seed`.
fn value(ty: ValueType, seed: u32) -> Value {
    let x = f64::from(seed % 1000) / 100.0;
    Value::Float(x).convert(ty)
}

/// The id of a node of `nodes` picked by `seed`, or now and then one that is not there.
fn some_node(nodes: &[Node], seed: u32) -> NodeId {
    match nth(nodes, seed) {
        Some(node) if !seed.is_multiple_of(11) => node.id,
        _ => NodeId(seed % 50),
    }
}

/// An input or output (`side`) of a node of `nodes`, picked by `seed`.
fn some_pin(nodes: &[Node], seed: u32, side: Side) -> PinRef {
    let node = some_node(nodes, seed);
    let signature = nodes
        .iter()
        .find(|n| n.id == node)
        .map(|n| n.kind.signature());
    let pin = signature.and_then(|s| match side {
        Side::Input => nth(&s.inputs, seed / 7).map(|p| p.name),
        Side::Output => nth(&s.outputs, seed / 7).map(|p| p.name),
    });
    PinRef::new(node, pin.unwrap_or(side.word()))
}

/// A node kind from the registry's examples, picked by `seed` (no Material).
fn some_kind(seed: u32) -> NodeKind {
    let kinds: Vec<NodeKind> = NodeKind::examples()
        .into_iter()
        .filter(|kind| *kind != NodeKind::Material && group_name_of(kind).is_none())
        .collect();
    nth(&kinds, seed).cloned().expect("the registry has kinds")
}

fn group_name_of(kind: &NodeKind) -> Option<&str> {
    match kind {
        NodeKind::Group(group) => Some(&group.name),
        _ => None,
    }
}

/// An edit of `graph` made from `pick`: valid or not.
fn random_edit(graph: &Graph, (op, a, b, c): Pick) -> GraphEdit {
    let levels = levels(graph);
    let level = nth(&levels, a).cloned().unwrap_or(Level::Top);
    let (nodes, wires) = contents(graph, &level);
    let next = NodeId(nodes.iter().map(|n| n.id.0 + 1).max().unwrap_or(1));
    let groups: Vec<&String> = graph.groups.keys().collect();
    let group = nth(&groups, b).map_or("missing".to_string(), |g| g.to_string());
    let side = if c.is_multiple_of(2) {
        Side::Input
    } else {
        Side::Output
    };
    match op % 20 {
        0 => {
            let mut node = Node::new(
                if c.is_multiple_of(9) {
                    some_node(nodes, b)
                } else {
                    next
                },
                some_kind(b),
            );
            node.position = (b as f32 % 977.0 + 0.3, c as f32 % 613.0 - 0.6);
            let first = node.kind.signature().inputs.first().map(|pin| pin.name);
            let wires = first
                .map(|pin| Wire {
                    from: some_pin(nodes, c, Side::Output),
                    to: PinRef::new(node.id, pin),
                })
                .into_iter()
                .collect();
            let nodes = if c.is_multiple_of(5) {
                vec![node, adder(next.0 + 1)]
            } else {
                vec![node]
            };
            GraphEdit::AddNodes {
                level,
                nodes,
                wires,
            }
        }
        1 => {
            let mut gone = vec![some_node(nodes, b)];
            if c.is_multiple_of(3) {
                gone.push(some_node(nodes, c));
            }
            gone.dedup();
            GraphEdit::RemoveNodes { level, nodes: gone }
        }
        2 => GraphEdit::Connect {
            level,
            wire: Wire {
                from: some_pin(nodes, b, Side::Output),
                to: some_pin(nodes, c, Side::Input),
            },
        },
        3 => {
            let wire = nth(wires, b).cloned().filter(|_| !c.is_multiple_of(13));
            let wire = wire.unwrap_or_else(|| Wire {
                from: some_pin(nodes, b, Side::Output),
                to: some_pin(nodes, c, Side::Input),
            });
            GraphEdit::Disconnect {
                level,
                wires: vec![wire],
            }
        }
        4 => {
            let target = some_pin(nodes, b, Side::Input);
            let ty = nodes
                .iter()
                .find(|n| n.id == target.node)
                .and_then(|n| n.kind.signature().input(&target.pin).map(|(_, p)| p.ty))
                .unwrap_or(ValueType::Float);
            GraphEdit::SetInput {
                level,
                node: target.node,
                pin: target.pin,
                value: (!c.is_multiple_of(4)).then(|| value(ty, c)),
            }
        }
        5 => GraphEdit::SetLabel {
            level,
            node: some_node(nodes, b),
            label: format!("n{}", c % 5),
        },
        6 => {
            let node = some_node(nodes, b);
            let current = nodes.iter().find(|n| n.id == node).map(|n| &n.kind);
            let same: Vec<NodeKind> = NodeKind::examples()
                .into_iter()
                .filter(|k| {
                    current
                        .is_some_and(|cur| std::mem::discriminant(cur) == std::mem::discriminant(k))
                })
                .collect();
            let kind = nth(&same, c).cloned().unwrap_or_else(|| some_kind(c));
            GraphEdit::SetKind { level, node, kind }
        }
        7 => {
            let mut moves = vec![(
                some_node(nodes, b),
                (c as f32 % 300.0 + 0.5, b as f32 % 200.0),
            )];
            if c.is_multiple_of(2) {
                moves.push((some_node(nodes, c), (-(b as f32 % 90.0), 12.4)));
            }
            GraphEdit::MoveNodes { level, moves }
        }
        8 => GraphEdit::Arrange { level },
        9 => GraphEdit::Set(match b % 5 {
            0 => GraphSetting::Name(format!("graph {c}")),
            1 => GraphSetting::Alpha(
                [AlphaMode::Opaque, AlphaMode::Blend, AlphaMode::default()][c as usize % 3],
            ),
            2 => GraphSetting::Shading(Shading::ALL[c as usize % Shading::ALL.len()]),
            3 => GraphSetting::Frames(vec![Frame {
                title: "frame".into(),
                min: (0.0, 0.0),
                max: (c as f32 % 500.0, 200.0),
                color: (0.2, 0.4, 0.6),
            }]),
            _ => {
                let mut preview = graph.preview.clone();
                preview.size = f64::from(c % 20 + 1);
                GraphSetting::Preview(preview)
            }
        }),
        10 => {
            let presets: Vec<&String> = graph.presets.keys().collect();
            let name = nth(&presets, b).map_or("none".to_string(), |p| p.to_string());
            GraphEdit::ApplyPreset { name }
        }
        11 => {
            let name = format!("p{}", b % 4);
            let pin = match side {
                Side::Input => GroupPin::Input(GroupInput {
                    name,
                    ty: ValueType::Float,
                    default: value(ValueType::Float, c),
                    range: None,
                    hint: Hint::Slider,
                }),
                Side::Output => GroupPin::Output(GroupOutput {
                    name,
                    ty: ValueType::Color,
                }),
            };
            GraphEdit::AddGroupPin {
                group,
                index: (c / 2 % 4) as usize,
                pin,
            }
        }
        12 => GraphEdit::DropGroupPin {
            group,
            side,
            index: (c / 2 % 6) as usize,
        },
        13 => {
            let inputs = graph
                .groups
                .get(&group)
                .map(|g| g.inputs.clone())
                .unwrap_or_default();
            match nth(&inputs, c).cloned() {
                Some(mut input) => {
                    input.default = value(input.ty, c);
                    input.range = (c.is_multiple_of(3)).then_some((0.0, 2.0));
                    GraphEdit::SetGroupInput { group, input }
                }
                None => GraphEdit::SetLinked {
                    group,
                    linked: c.is_multiple_of(2),
                },
            }
        }
        14 | 15 => {
            let names: Vec<String> = graph.groups.get(&group).map_or(Vec::new(), |g| match side {
                Side::Input => g.inputs.iter().map(|i| i.name.clone()).collect(),
                Side::Output => g.outputs.iter().map(|o| o.name.clone()).collect(),
            });
            let name = nth(&names, c / 2).cloned().unwrap_or_else(|| "none".into());
            if op % 20 == 14 {
                GraphEdit::RenameGroupPin {
                    group,
                    side,
                    old: name,
                    new: format!("r{}", b % 3),
                }
            } else {
                GraphEdit::RemoveGroupPin { group, side, name }
            }
        }
        16 => {
            let mut chosen = std::collections::BTreeSet::from([some_node(nodes, b)]);
            if c.is_multiple_of(2) {
                chosen.insert(some_node(nodes, c));
            }
            GraphEdit::Group {
                level,
                nodes: chosen,
                name: format!("g{}", c % 3),
            }
        }
        17 => {
            let instances: Vec<NodeId> = nodes
                .iter()
                .filter(|n| group_name(n).is_some())
                .map(|n| n.id)
                .collect();
            let node = nth(&instances, b)
                .copied()
                .unwrap_or_else(|| some_node(nodes, b));
            GraphEdit::Ungroup { level, node }
        }
        18 => {
            let definition = graph
                .groups
                .get(&group)
                .filter(|_| c.is_multiple_of(2))
                .cloned()
                .map(Box::new);
            GraphEdit::SetGroup {
                name: format!("{group}_copy{}", b % 2),
                definition,
            }
        }
        _ => GraphEdit::Batch(vec![
            random_edit(graph, (b as u8 % 19, c, a, b)),
            random_edit(graph, (c as u8 % 19, a, c, b)),
        ]),
    }
}

/// The preset `k` (wrapping), canonical and resolved as the editor keeps it.
fn preset(k: usize) -> Graph {
    let (name, _) = crate::graph::PRESETS[k % crate::graph::PRESETS.len()];
    let mut graph = crate::graph::preset(name).expect("a shipped preset");
    crate::graph::group::resolve(&mut graph);
    graph.canonicalize();
    graph
}

fn picks() -> impl Strategy<Value = Vec<Pick>> {
    proptest::collection::vec((0u8..24, any::<u32>(), any::<u32>(), any::<u32>()), 1..32)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn undoing_every_edit_gives_back_the_preset_and_redoing_them_the_result(
        k in 0usize..64,
        picks in picks(),
    ) {
        let mut graph = preset(k);
        let original = graph.clone();
        let mut history = History::new();
        for pick in picks {
            match pick.0 {
                20 => history.begin_gesture(),
                21 => history.end_gesture(),
                _ => {
                    let edit = random_edit(&graph, pick);
                    let before = graph.clone();
                    if history.apply(&mut graph, edit.clone()).is_err() {
                        prop_assert!(graph == before, "a refused edit changed the graph: {edit:?}");
                    }
                    let mut canonical = graph.clone();
                    canonical.canonicalize();
                    prop_assert!(graph == canonical, "not canonical after {edit:?}");
                }
            }
        }
        let last = graph.clone();
        while let Some(undone) = history.undo(&mut graph) {
            prop_assert!(undone.is_ok(), "{undone:?}");
        }
        prop_assert!(graph == original, "undoing everything gives back the preset");
        while let Some(redone) = history.redo(&mut graph) {
            prop_assert!(redone.is_ok(), "{redone:?}");
        }
        prop_assert!(graph == last, "redoing everything gives back the result");
    }
}
