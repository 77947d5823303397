//! Editing inside a node group: the groups entered (the breadcrumb), and the graph view
//! of a group's definition — its nodes plus two boundary nodes, *Group input* (its
//! outputs are the group's inputs) and *Group output* (its inputs are the group's
//! outputs), each ending in an empty "+" pin: a wire dropped on it declares a new input
//! or output. Both boundary nodes carry the id [`BOUNDARY`], so the wires read back
//! from the view are the definition's wires as they are stored.

use crate::app::canvas::boundary::{ADD_PIN, Boundary, boundary, is_add_pin};
use crate::app::canvas::snarl_model::insert_graph;
use crate::app::widgets::input_value;
use crate::graph::group::{BOUNDARY, GroupDef, GroupInput, GroupOutput, Hint, group_name};
use crate::graph::{Graph, Node, NodeId, NodeKind, Value, ValueType};
use crate::nodes::Group;
use crate::nodes::pins::{InputPin, OutputPin, PinDefault, PinRange, Signature, intern};
use egui::Pos2;
use egui::emath::TSTransform;
use egui_snarl::{InPinId, OutPinId, Snarl};
use std::collections::{BTreeMap, BTreeSet};

/// One group entered.
#[derive(Clone, Debug)]
pub struct Level {
    /// The group's name in `graph.groups`.
    pub group: String,
    /// The instance it was entered through, in the level above.
    pub instance: NodeId,
    /// The level above's view, put back on leaving.
    pub view: TSTransform,
}

/// The groups entered, outermost first (empty: the top level).
#[derive(Clone, Debug, Default)]
pub struct Scope {
    pub levels: Vec<Level>,
}

impl Scope {
    /// The group shown, or `None` at the top level.
    pub fn current(&self) -> Option<&str> {
        self.levels.last().map(|level| level.group.as_str())
    }

    /// The level of the graph shown, as graph edits name it.
    pub fn level(&self) -> crate::graph::edit::Level {
        match self.current() {
            Some(name) => crate::graph::edit::Level::Group(name.to_string()),
            None => crate::graph::edit::Level::Top,
        }
    }

    /// Drops the levels from the first whose group `graph` no longer has (after an undo
    /// or a load); returns whether it dropped any.
    pub fn keep_existing(&mut self, graph: &Graph) -> bool {
        let kept = self
            .levels
            .iter()
            .take_while(|level| graph.groups.contains_key(&level.group))
            .count();
        let dropped = kept < self.levels.len();
        self.levels.truncate(kept);
        dropped
    }
}

/// The boundary node `side` of `definition`.
fn boundary_node(side: Boundary, definition: &GroupDef) -> Node {
    let add = || std::iter::once((intern(ADD_PIN), ValueType::Float));
    let inputs: Vec<InputPin> = definition
        .outputs
        .iter()
        .map(|output| (intern(&output.name), output.ty))
        .chain(add())
        .map(|(name, ty)| InputPin {
            name,
            ty,
            default: PinDefault::Required,
            range: PinRange::ANY,
            sampled: false,
            re_evaluated: false,
        })
        .collect();
    let outputs: Vec<OutputPin> = definition
        .inputs
        .iter()
        .map(|input| (intern(&input.name), input.ty))
        .chain(add())
        .map(|(name, ty)| crate::nodes::pins::output(name, ty))
        .collect();
    let pins = match side {
        Boundary::Input => Signature::new(Vec::new(), outputs),
        Boundary::Output => Signature::new(inputs, Vec::new()),
    };
    let mut node = Node::new(
        BOUNDARY,
        NodeKind::Group(Group {
            name: side.mark().to_string(),
            pins,
        }),
    );
    node.label = side.label().to_string();
    node
}

/// A snarl showing group `group` of `graph`: its nodes at their places, *Group input*
/// on their left and *Group output* on their right (its journal empty).
pub fn snarl_for_group(graph: &Graph, group: &str) -> Option<Snarl<Node>> {
    let definition = graph.groups.get(group)?;
    let crosses =
        |wire: &crate::graph::Wire| wire.from.node == BOUNDARY || wire.to.node == BOUNDARY;
    let inner = Graph {
        nodes: definition.nodes.clone(),
        wires: definition
            .wires
            .iter()
            .filter(|w| !crosses(w))
            .cloned()
            .collect(),
        ..Graph::default()
    };
    let mut snarl = Snarl::new();
    let ids = insert_graph(&mut snarl, &inner, |_, node| {
        (node.clone(), Pos2::new(node.position.0, node.position.1))
    });
    let xs = definition.nodes.iter().map(|node| node.position.0);
    let (left, right) = xs.fold((0.0f32, 0.0f32), |(l, r), x| (l.min(x), r.max(x)));
    let count = definition.nodes.len().max(1) as f32;
    let middle = definition
        .nodes
        .iter()
        .map(|node| node.position.1)
        .sum::<f32>()
        / count;
    // Clear of the nodes' widths (a group node with many inputs is wide).
    let input = snarl.insert_node(
        Pos2::new(left - 320.0, middle),
        boundary_node(Boundary::Input, definition),
    );
    let output = snarl.insert_node(
        Pos2::new(right + 480.0, middle),
        boundary_node(Boundary::Output, definition),
    );
    for wire in definition.wires.iter().filter(|w| crosses(w)) {
        let from = if wire.from.node == BOUNDARY {
            input
        } else {
            ids[&wire.from.node]
        };
        let to = if wire.to.node == BOUNDARY {
            output
        } else {
            ids[&wire.to.node]
        };
        let output = snarl[from]
            .kind
            .signature()
            .output(&wire.from.pin)
            .map(|(i, _)| i);
        let input = snarl[to]
            .kind
            .signature()
            .input(&wire.to.pin)
            .map(|(i, _)| i);
        if let (Some(output), Some(input)) = (output, input) {
            snarl.connect(OutPinId { node: from, output }, InPinId { node: to, input });
        }
    }
    // Building the view is no edit.
    snarl.take_journal();
    Some(snarl)
}

/// Whether group `outer` uses group `inner`, directly or through other groups (or is it).
pub fn uses(groups: &BTreeMap<String, GroupDef>, outer: &str, inner: &str) -> bool {
    let mut seen = BTreeSet::new();
    let mut stack = vec![outer];
    while let Some(name) = stack.pop() {
        if name == inner {
            return true;
        }
        if seen.insert(name)
            && let Some(definition) = groups.get(name)
        {
            stack.extend(definition.nodes.iter().filter_map(group_name));
        }
    }
    false
}

/// What a wire dropped on a "+" pin declares.
#[derive(Clone, Debug, PartialEq)]
pub enum Declared {
    /// A new group input (a wire from *Group input*'s "+").
    Input(GroupInput),
    /// A new group output (a wire into *Group output*'s "+").
    Output(GroupOutput),
}

impl Declared {
    /// The edit that declares it in group `group` of `graph`, after the pins there.
    pub fn edit(self, group: &str, graph: &Graph) -> crate::graph::edit::GraphEdit {
        let declared = graph.groups.get(group);
        let (index, pin) = match self {
            Declared::Input(input) => (
                declared.map_or(0, |group| group.inputs.len()),
                crate::graph::edit::GroupPin::Input(input),
            ),
            Declared::Output(output) => (
                declared.map_or(0, |group| group.outputs.len()),
                crate::graph::edit::GroupPin::Output(output),
            ),
        };
        crate::graph::edit::GraphEdit::AddGroupPin {
            group: group.to_string(),
            index,
            pin,
        }
    }
}

/// A wire from `from` to `to` where one end is a boundary node's "+": declares a group
/// input (from *Group input*'s "+") or output (into *Group output*'s "+") named after
/// the pin at the other end, gives the boundary node the new pin and wires it. Returns
/// the declaration, or `None` when neither end is a "+" (or both are).
pub fn expose(snarl: &mut Snarl<Node>, from: OutPinId, to: InPinId) -> Option<Declared> {
    let source = snarl[from.node].kind.signature().outputs[from.output];
    let target = snarl[to.node].kind.signature().inputs[to.input];
    match (
        is_add_pin(&snarl[from.node], source.name),
        is_add_pin(&snarl[to.node], target.name),
    ) {
        (true, false) => add_input(snarl, from.node, to),
        (false, true) => add_output(snarl, from, to.node),
        _ => None,
    }
}

/// A new input of the group on *Group input* `boundary`, wired to inner input `to`:
/// its name, type, current value (as default) and range.
fn add_input(
    snarl: &mut Snarl<Node>,
    boundary: egui_snarl::NodeId,
    to: InPinId,
) -> Option<Declared> {
    let target = snarl[to.node].kind.signature().inputs[to.input];
    let default = input_value(&snarl[to.node], target.name)
        .map(|(value, _)| value)
        .unwrap_or(Value::Float(0.0).convert(target.ty));
    let pins = boundary_pins(snarl, boundary)?;
    let name = free_name(pins.outputs.iter().map(|pin| pin.name), target.name);
    let at = pins.outputs.len() - 1;
    let pin = crate::nodes::pins::output(intern(&name), target.ty);
    pins.outputs.insert(at, pin);
    snarl.drop_inputs(to);
    snarl.connect(
        OutPinId {
            node: boundary,
            output: at,
        },
        to,
    );
    let range = (target.range.min.is_finite() && target.range.max.is_finite())
        .then_some((target.range.min, target.range.max));
    let hint = if target.ty == ValueType::Color {
        Hint::Colour
    } else {
        Hint::Slider
    };
    Some(Declared::Input(GroupInput {
        name,
        ty: target.ty,
        default,
        range,
        hint,
    }))
}

/// A new output of the group on *Group output* `boundary`, fed by inner output `from`.
fn add_output(
    snarl: &mut Snarl<Node>,
    from: OutPinId,
    boundary: egui_snarl::NodeId,
) -> Option<Declared> {
    let source = snarl[from.node].kind.signature().outputs[from.output];
    let pins = boundary_pins(snarl, boundary)?;
    let name = free_name(pins.inputs.iter().map(|pin| pin.name), source.name);
    let at = pins.inputs.len() - 1;
    let pin = InputPin {
        name: intern(&name),
        ty: source.ty,
        default: PinDefault::Required,
        range: PinRange::ANY,
        sampled: false,
        re_evaluated: false,
    };
    pins.inputs.insert(at, pin);
    snarl.connect(
        from,
        InPinId {
            node: boundary,
            input: at,
        },
    );
    Some(Declared::Output(GroupOutput {
        name,
        ty: source.ty,
    }))
}

/// The pins of boundary node `node`, to give it another.
fn boundary_pins(snarl: &mut Snarl<Node>, node: egui_snarl::NodeId) -> Option<&mut Signature> {
    match &mut snarl[node].kind {
        NodeKind::Group(group) => Some(&mut group.pins),
        _ => None,
    }
}

/// `base`, or `base_2`, `base_3`… — the first not among `taken`.
pub fn free_name<'a>(taken: impl Iterator<Item = &'a str>, base: &str) -> String {
    let taken: BTreeSet<&str> = taken.collect();
    if !taken.contains(base) {
        return base.to_string();
    }
    (2..)
        .map(|k| format!("{base}_{k}"))
        .find(|name| !taken.contains(name.as_str()))
        .unwrap_or_default()
}

/// The snarl id of the boundary node `side` in `snarl`.
pub fn boundary_in(snarl: &Snarl<Node>, side: Boundary) -> Option<egui_snarl::NodeId> {
    snarl
        .node_ids()
        .find(|(_, node)| boundary(node) == Some(side))
        .map(|(id, _)| id)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::app::canvas::snarl_model::graph_from_snarl;

    /// The wood preset, as the editor keeps it: one `ring_wood` group node.
    fn wood() -> Graph {
        let mut graph = crate::graph::preset("wood").expect("the wood preset");
        graph.canonicalize();
        graph
    }

    #[test]
    fn a_group_read_back_from_its_view_is_unchanged() {
        let graph = wood();
        let snarl = snarl_for_group(&graph, "ring_wood").expect("the group");
        let sides: Vec<_> = snarl.nodes().filter_map(boundary).collect();
        assert_eq!(sides, [Boundary::Input, Boundary::Output]);
        let definition = &graph.groups["ring_wood"];
        let stored = Graph {
            wires: definition.wires.clone(),
            ..Graph::default()
        };
        let view = graph_from_snarl(&snarl, &stored);
        let inner: Vec<Node> = view
            .nodes
            .into_iter()
            .filter(|node| boundary(node).is_none())
            .collect();
        assert!(inner == definition.nodes);
        assert!(view.wires == definition.wires);
    }

    #[test]
    fn a_wire_from_the_plus_pin_declares_an_input_with_the_pins_value() {
        let mut graph = wood();
        let mut snarl = snarl_for_group(&graph, "ring_wood").expect("the group");
        let input = boundary_in(&snarl, Boundary::Input).expect("Group input");
        let plus = snarl[input].kind.signature().outputs.len() - 1;
        let (shade, node) = snarl
            .node_ids()
            .find(|(_, node)| node.label == "tint shade")
            .expect("the tint shade");
        let b = node.kind.signature().input("b").expect("pin b").0;
        let from = OutPinId {
            node: input,
            output: plus,
        };
        let to = InPinId {
            node: shade,
            input: b,
        };
        let declared = expose(&mut snarl, from, to).expect("a declaration");
        let Declared::Input(declared_input) = &declared else {
            panic!("no input declared");
        };
        assert_eq!(declared_input.name, "b");
        assert_eq!(
            declared_input.default,
            Value::Float(0.95),
            "the pin's value"
        );
        let pins = snarl[input].kind.signature();
        assert_eq!(pins.outputs[plus].name, "b", "the new pin comes before +");
        assert_eq!(pins.outputs.last().map(|pin| pin.name), Some(ADD_PIN));
        let level = crate::graph::edit::Level::Group("ring_wood".into());
        let declare = declared.edit("ring_wood", &graph);
        crate::graph::edit::apply(&mut graph, declare).expect("declared");
        let journal = snarl.take_journal();
        let mut shown = crate::app::canvas::view_edits::Shown::of(&snarl);
        let before = graph.clone();
        let edits = crate::app::canvas::view_edits::edits_from_journal(
            &journal,
            &snarl,
            &mut shown,
            &level,
            |id| {
                before.groups["ring_wood"]
                    .nodes
                    .iter()
                    .find(|node| node.id == id)
            },
        );
        crate::graph::edit::apply(&mut graph, crate::graph::edit::GraphEdit::Batch(edits))
            .expect("the wire from the new input");
        let wires = &graph.groups["ring_wood"].wires;
        assert!(
            wires.iter().any(|wire| wire.from.node == BOUNDARY
                && wire.from.pin == "b"
                && wire.to.pin == "b")
        );
        assert!(
            crate::graph::group::flatten(&graph).is_ok(),
            "it still inlines"
        );
    }
}
