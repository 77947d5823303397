//! Node groups (material functions): their definitions, the pins their instances
//! show, and inlining, the one way every stage meets them. A group's definition is a
//! subgraph whose wires reach its inputs and outputs through the [`BOUNDARY`] node id;
//! an instance is a node of kind [`NodeKind::Group`] naming the definition.
//!
//! Exposure: an instance's unwired inputs stay exposed through every level above it.
//! Inside a definition, an inner instance's unwired inputs become inputs of the outer
//! group too (its *inherited* inputs); at the top level they are the graph's exposed
//! parameters. Wiring an input binds it.

use super::check::CheckError;
use super::names::shown;
use super::nesting::{self, Nesting};
use super::{Graph, Node, NodeId, NodeKind, PinRef, Value, ValueType, Wire};
use crate::nodes::Group;
use crate::nodes::pins::{InputPin, PinDefault, PinRange, Signature, intern};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet};

pub use super::inline::{Bindings, flatten, flatten_traced};
pub use super::nesting::{MAX_GROUP_DEPTH, MAX_INLINED_NODES};

/// The node id that stands for a group's boundary in its definition's wires: a wire
/// from `(BOUNDARY, "x")` reads group input `x`, a wire to `(BOUNDARY, "y")` feeds
/// group output `y`. No node of a definition may use it.
pub const BOUNDARY: NodeId = NodeId(0);

/// A node group: a subgraph with named, typed inputs and outputs.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GroupDef {
    /// Whether the definition follows the library group of the same name: loading the
    /// graph takes the library's current version (see `graph::library`). *Make local*
    /// clears it.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub linked: bool,
    #[serde(default)]
    pub inputs: Vec<GroupInput>,
    #[serde(default)]
    pub outputs: Vec<GroupOutput>,
    pub nodes: Vec<Node>,
    #[serde(default)]
    pub wires: Vec<Wire>,
}

impl GroupDef {
    /// Puts the nodes and wires in their canonical order (as [`Graph::canonicalize`]).
    pub fn canonicalize(&mut self) {
        super::canonical_order(&mut self.nodes, &mut self.wires);
    }
}

/// A graph's group definitions and its top-level group nodes: what the stages that keep
/// groups after inlining need (a MaterialX export writes each group as a node graph).
#[derive(Clone, Debug, Default)]
pub struct GroupSource {
    /// The definitions, by name.
    pub definitions: BTreeMap<String, GroupDef>,
    /// The top-level group nodes, by id.
    pub instances: BTreeMap<NodeId, Node>,
}

impl GroupSource {
    /// The groups of `graph`.
    pub fn of(graph: &Graph) -> GroupSource {
        GroupSource {
            definitions: graph.groups.clone(),
            instances: (graph.nodes.iter())
                .filter(|node| group_name(node).is_some())
                .map(|node| (node.id, node.clone()))
                .collect(),
        }
    }
}

/// One declared input of a group: an exposed parameter of every instance that leaves
/// it unwired.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GroupInput {
    pub name: String,
    pub ty: ValueType,
    /// The value an instance uses when it neither wires nor sets the input.
    pub default: Value,
    /// The span the inspector and engines offer (inclusive), if the group limits it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub range: Option<(f64, f64)>,
    /// How an editor shows the value.
    #[serde(default, skip_serializing_if = "Hint::is_default")]
    pub hint: Hint,
}

/// How an editor offers an exposed parameter.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub enum Hint {
    /// A number (or vector) dragged within its range.
    #[default]
    Slider,
    /// A colour picker.
    Colour,
    /// On (1) or off (0).
    Toggle,
    /// One of named options, stored as the option's index.
    Choice(Vec<String>),
}

impl GroupInput {
    /// The span an instance's pin offers: the input's range, else any value.
    pub fn pin_range(&self) -> PinRange {
        match self.range {
            Some((min, max)) => PinRange {
                min,
                max,
                soft_min: min,
                soft_max: max,
            },
            None => PinRange::ANY,
        }
    }
}

impl Hint {
    fn is_default(&self) -> bool {
        *self == Hint::Slider
    }

    /// The hint's name in descriptions (`slider`, `colour`, `toggle`, `choice`).
    pub fn name(&self) -> &'static str {
        match self {
            Hint::Slider => "slider",
            Hint::Colour => "colour",
            Hint::Toggle => "toggle",
            Hint::Choice(_) => "choice",
        }
    }
}

/// One output of a group.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GroupOutput {
    pub name: String,
    pub ty: ValueType,
}

/// Where an input of a group's interface goes inside the definition.
#[derive(Clone, Debug, PartialEq)]
pub enum Route {
    /// A declared input: the definition's wires from the boundary read it.
    Declared,
    /// An unwired input of inner instance `node`, exposed through this group.
    Inherited { node: NodeId, pin: String },
}

/// One input of a group's interface.
#[derive(Clone, Debug, PartialEq)]
pub struct InterfaceInput {
    pub input: GroupInput,
    pub route: Route,
    /// The nested groups an inherited input comes from, outermost first (empty for a
    /// declared input).
    pub path: Vec<String>,
}

/// The pins an instance of a group shows: its declared inputs, then the inputs it
/// inherits from unwired inner instances, then its outputs.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Interface {
    pub inputs: Vec<InterfaceInput>,
    pub outputs: Vec<GroupOutput>,
    /// The position in `inputs` of the first input of each name.
    by_name: HashMap<String, usize>,
}

impl Interface {
    /// The interface of a definition's declared pins alone.
    fn declared(definition: &GroupDef) -> Interface {
        let mut interface = Interface {
            outputs: definition.outputs.clone(),
            ..Interface::default()
        };
        for input in &definition.inputs {
            interface.push(InterfaceInput {
                input: input.clone(),
                route: Route::Declared,
                path: Vec::new(),
            });
        }
        interface
    }

    fn push(&mut self, entry: InterfaceInput) {
        let position = self.inputs.len();
        self.by_name
            .entry(entry.input.name.clone())
            .or_insert(position);
        self.inputs.push(entry);
    }

    /// The signature of an instance.
    pub fn signature(&self) -> Signature {
        let inputs = self
            .inputs
            .iter()
            .map(|entry| {
                let input = &entry.input;
                InputPin {
                    name: intern(&input.name),
                    ty: input.ty,
                    default: PinDefault::Const(input.default.convert(input.ty)),
                    range: input.pin_range(),
                    sampled: false,
                    re_evaluated: false,
                }
            })
            .collect();
        let outputs = self
            .outputs
            .iter()
            .map(|output| crate::nodes::pins::output(intern(&output.name), output.ty))
            .collect();
        Signature::new(inputs, outputs)
    }

    /// The input called `name`.
    pub fn input(&self, name: &str) -> Option<&InterfaceInput> {
        self.input_index(name).map(|k| &self.inputs[k])
    }

    /// The position in `inputs` of the input called `name`.
    pub fn input_index(&self, name: &str) -> Option<usize> {
        self.by_name.get(name).copied()
    }
}

/// The group an instance node names, if it is one.
pub fn group_name(node: &Node) -> Option<&str> {
    match &node.kind {
        NodeKind::Group(group) => Some(&group.name),
        _ => None,
    }
}

/// What is wrong with the graph's groups: unknown groups, groups that contain
/// themselves, nest too deep or have too many pins.
#[derive(Clone, Debug, PartialEq)]
pub struct GroupError {
    /// The node the problem is at, named as messages name it.
    pub node_name: Option<String>,
    pub message: String,
}

impl From<GroupError> for CheckError {
    fn from(error: GroupError) -> CheckError {
        CheckError {
            node: None,
            node_name: error.node_name,
            message: error.message,
        }
    }
}

/// The most inputs, and the most outputs, an instance of a group shows (its declared
/// and inherited inputs together): an editor draws a pin for each, and every level
/// that inherits them repeats them.
pub const MAX_GROUP_PINS: usize = 1_024;

/// The interface of every group of `groups`, each computed after the groups it uses.
/// A cycle of group references is an error naming the groups, as are an inner node
/// naming a group that does not exist, groups nested more than
/// [`nesting::MAX_GROUP_DEPTH`] deep and a group with more than [`MAX_GROUP_PINS`]
/// inputs or outputs.
pub fn interfaces(
    groups: &BTreeMap<String, GroupDef>,
) -> Result<BTreeMap<String, Interface>, GroupError> {
    let analysis = analyse(groups);
    match analysis.error {
        Some(error) => Err(error),
        None => Ok(analysis.interfaces),
    }
}

/// The groups of a graph as far as they resolve.
pub(super) struct Analysis<'g> {
    pub nesting: Nesting<'g>,
    /// The interfaces of the groups that nest properly and have at most
    /// [`MAX_GROUP_PINS`] inputs and outputs.
    pub interfaces: BTreeMap<String, Interface>,
    /// The first problem found.
    pub error: Option<GroupError>,
}

/// Walks the nesting of `groups` and computes the interface of every group that nests
/// properly, inner groups first.
pub(super) fn analyse(groups: &BTreeMap<String, GroupDef>) -> Analysis<'_> {
    let nesting = nesting::nesting(groups);
    let mut error = nesting.error.clone();
    let mut done: BTreeMap<String, Interface> = BTreeMap::new();
    for name in &nesting.order {
        match interface_of(name, &groups[*name], &done) {
            Ok(Some(interface)) => {
                done.insert(name.to_string(), interface);
            }
            Ok(None) => {}
            Err(problem) => {
                error.get_or_insert(problem);
            }
        }
    }
    Analysis {
        nesting,
        interfaces: done,
        error,
    }
}

/// The interface of group `name`, whose inner groups' interfaces are in `done` (`None`
/// when one of them is not: its problem is reported already).
fn interface_of(
    name: &str,
    definition: &GroupDef,
    done: &BTreeMap<String, Interface>,
) -> Result<Option<Interface>, GroupError> {
    let limit = crate::messages::thousands(MAX_GROUP_PINS);
    let too_many = |what: String| GroupError {
        node_name: None,
        message: format!("group '{}' has {what}", shown(name)),
    };
    for (side, count) in [
        ("outputs", definition.outputs.len()),
        ("inputs", definition.inputs.len()),
    ] {
        if count > MAX_GROUP_PINS {
            let count = crate::messages::thousands(count);
            return Err(too_many(format!(
                "{count} {side}, more than the {limit} a group may show"
            )));
        }
    }
    let wired: HashSet<(NodeId, &str)> = definition
        .wires
        .iter()
        .map(|wire| (wire.to.node, wire.to.pin.as_str()))
        .collect();
    let mut interface = Interface::declared(definition);
    let mut inner: Vec<&Node> = definition.nodes.iter().collect();
    inner.sort_by_key(|node| node.id);
    for node in inner {
        let Some(used) = group_name(node) else {
            continue;
        };
        let Some(used_interface) = done.get(used) else {
            return Ok(None);
        };
        for entry in &used_interface.inputs {
            let pin = &entry.input.name;
            if wired.contains(&(node.id, pin.as_str())) {
                continue;
            }
            if interface.inputs.len() == MAX_GROUP_PINS {
                return Err(too_many(format!(
                    "more inputs than the {limit} a group may show, with those it \
                     inherits from the groups inside it"
                )));
            }
            let mut input = entry.input.clone();
            if let Some(value) = node.inputs.get(pin) {
                input.default = value.convert(input.ty);
            }
            input.name = free_name(&interface, pin, node);
            let mut path = vec![used.to_string()];
            path.extend(entry.path.iter().cloned());
            interface.push(InterfaceInput {
                input,
                route: Route::Inherited {
                    node: node.id,
                    pin: pin.clone(),
                },
                path,
            });
        }
    }
    Ok(Some(interface))
}

/// `pin` if no input of `interface` has that name yet, else the name qualified by the
/// inner instance it comes from.
fn free_name(interface: &Interface, pin: &str, node: &Node) -> String {
    let taken = |name: &str| interface.input(name).is_some();
    let candidates = [
        pin.to_string(),
        format!("{}.{pin}", node.display_name()),
        format!("#{}.{pin}", node.id.0),
    ];
    candidates
        .into_iter()
        .find(|name| !taken(name))
        .unwrap_or_else(|| format!("#{}.{pin}.{}", node.id.0, interface.inputs.len()))
}

/// Fills in the pins of every group node of the graph (top level and inside groups)
/// from the current definitions. Best effort: a group that does not resolve (see
/// [`interfaces`]) shows its declared pins, or none past [`MAX_GROUP_PINS`], and the
/// check says why.
pub fn resolve(graph: &mut Graph) {
    let analysis = analyse(&graph.groups);
    let signatures: BTreeMap<String, Signature> = graph
        .groups
        .iter()
        .map(|(name, definition)| {
            let signature = match analysis.interfaces.get(name) {
                Some(interface) => interface.signature(),
                None if definition.inputs.len() <= MAX_GROUP_PINS
                    && definition.outputs.len() <= MAX_GROUP_PINS =>
                {
                    Interface::declared(definition).signature()
                }
                None => Signature::default(),
            };
            (name.clone(), signature)
        })
        .collect();
    drop(analysis);
    let nodes = graph.nodes.iter_mut().chain(
        graph
            .groups
            .values_mut()
            .flat_map(|definition| definition.nodes.iter_mut()),
    );
    for node in nodes {
        if let NodeKind::Group(group) = &mut node.kind
            && let Some(signature) = signatures.get(group.name.as_str())
        {
            group.pins = signature.clone();
        }
    }
}

/// Turns `selection` (nodes of the top level, not the material) into group `name` and
/// puts one instance of it in their place; returns the instance's id. Every wire that
/// enters the selection becomes an input (one per source pin, named after the first pin
/// it feeds), every output read outside becomes an output, named after the node that
/// feeds it (and its pin, when the node has several outputs).
pub fn group_nodes(
    graph: &mut Graph,
    selection: &BTreeSet<NodeId>,
    name: &str,
) -> Result<NodeId, String> {
    let chosen: Vec<&Node> = graph
        .nodes
        .iter()
        .filter(|node| selection.contains(&node.id))
        .collect();
    if chosen.is_empty() {
        return Err("select the nodes to group first".into());
    }
    if chosen.iter().any(|node| node.kind == NodeKind::Material) {
        return Err("the Material node cannot go into a group".into());
    }
    if graph.groups.contains_key(name) {
        return Err(format!("a group named '{name}' exists already"));
    }
    super::names::file_name_part("group", name)?;
    let inside = |id: NodeId| selection.contains(&id);
    let output_type = |pin: &PinRef| {
        graph
            .node(pin.node)
            .and_then(|node| {
                let signature = node.kind.signature();
                signature.output(&pin.pin).map(|(_, output)| output.ty)
            })
            .unwrap_or(ValueType::Float)
    };
    let mut definition = GroupDef {
        linked: false,
        inputs: Vec::new(),
        outputs: Vec::new(),
        nodes: chosen.iter().map(|node| (*node).clone()).collect(),
        wires: Vec::new(),
    };
    let instance = graph.next_id();
    let mut outer = Vec::new();
    let mut sources: BTreeMap<PinRef, String> = BTreeMap::new();
    let mut results: BTreeMap<PinRef, String> = BTreeMap::new();
    let mut wires = graph.wires.clone();
    wires.sort();
    for wire in wires {
        match (inside(wire.from.node), inside(wire.to.node)) {
            (true, true) => definition.wires.push(wire),
            (false, false) => outer.push(wire),
            (false, true) => {
                let input = match sources.get(&wire.from) {
                    Some(input) => input.clone(),
                    None => {
                        let input = unique(&wire.to.pin, |n| {
                            definition.inputs.iter().any(|i| i.name == n)
                        });
                        let ty = output_type(&wire.from);
                        definition.inputs.push(GroupInput {
                            name: input.clone(),
                            ty,
                            default: Value::Float(0.0).convert(ty),
                            range: None,
                            hint: Hint::default(),
                        });
                        outer.push(Wire {
                            from: wire.from.clone(),
                            to: PinRef::new(instance, &input),
                        });
                        sources.insert(wire.from.clone(), input.clone());
                        input
                    }
                };
                definition.wires.push(Wire {
                    from: PinRef::new(BOUNDARY, &input),
                    to: wire.to,
                });
            }
            (true, false) => {
                let output = match results.get(&wire.from) {
                    Some(output) => output.clone(),
                    None => {
                        let output = unique(&output_name(graph, &wire.from), |n| {
                            definition.outputs.iter().any(|o| o.name == n)
                        });
                        definition.outputs.push(GroupOutput {
                            name: output.clone(),
                            ty: output_type(&wire.from),
                        });
                        definition.wires.push(Wire {
                            from: wire.from.clone(),
                            to: PinRef::new(BOUNDARY, &output),
                        });
                        results.insert(wire.from.clone(), output.clone());
                        output
                    }
                };
                outer.push(Wire {
                    from: PinRef::new(instance, &output),
                    to: wire.to,
                });
            }
        }
    }
    let count = chosen.len() as f32;
    let centre = chosen.iter().fold((0.0, 0.0), |(x, y), node| {
        (x + node.position.0 / count, y + node.position.1 / count)
    });
    graph.nodes.retain(|node| !inside(node.id));
    let mut node = Node::new(instance, NodeKind::Group(Group::named(name.to_string())));
    node.label = name.to_string();
    node.position = centre;
    graph.nodes.push(node);
    graph.wires = outer;
    graph.groups.insert(name.to_string(), definition);
    resolve(graph);
    graph.canonicalize();
    Ok(instance)
}

/// The name of a group output fed by `pin`: the feeding node's name (its label, or its
/// kind's title), with the pin's name when the node has more than one output.
fn output_name(graph: &Graph, pin: &PinRef) -> String {
    let Some(node) = graph.node(pin.node) else {
        return pin.pin.clone();
    };
    let name = node.display_name();
    if node.kind.signature().outputs.len() > 1 {
        format!("{name} {}", pin.pin)
    } else {
        name.to_string()
    }
}

/// `base`, or `base_2`, `base_3`, … — the first that `taken` refuses.
fn unique(base: &str, taken: impl Fn(&str) -> bool) -> String {
    if !taken(base) {
        return base.to_string();
    }
    (2..)
        .map(|k| format!("{base}_{k}"))
        .find(|name| !taken(name))
        .unwrap_or_default()
}

/// Dissolves group node `instance` into its definition's nodes, keeping their ids
/// where the graph does not use them; the definition is dropped when no other node
/// uses it, and the parameter presets forget the parameters the node exposed (as they
/// do a removed group input's). Returns the ids of the nodes it put in the graph.
pub fn ungroup(graph: &mut Graph, instance: NodeId) -> Result<Vec<NodeId>, String> {
    let position = graph
        .nodes
        .iter()
        .position(|node| node.id == instance && group_name(node).is_some())
        .ok_or_else(|| format!("node {instance} is not a group"))?;
    let interfaces = interfaces(&graph.groups).map_err(|error| error.message)?;
    let name = group_name(&graph.nodes[position])
        .unwrap_or_default()
        .to_string();
    let before = super::parameters::exposed_names(graph);
    let inlined =
        super::inline::dissolve(graph, position, &interfaces).map_err(|error| error.to_string())?;
    super::parameters::forget_removed(graph, &before);
    let used = graph
        .nodes
        .iter()
        .any(|node| group_name(node) == Some(&name))
        || graph.groups.iter().any(|(other, def)| {
            *other != name && def.nodes.iter().any(|n| group_name(n) == Some(&name))
        });
    if !used {
        graph.groups.remove(&name);
    }
    graph.canonicalize();
    Ok(inlined.into_values().collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Groups `g0` › `g1` › … nested `depth` deep, the innermost holding a Time node.
    fn chain(depth: usize) -> BTreeMap<String, GroupDef> {
        (0..depth)
            .map(|level| {
                let kind = if level + 1 == depth {
                    NodeKind::Time
                } else {
                    NodeKind::Group(Group::named(format!("g{}", level + 1)))
                };
                let definition = GroupDef {
                    linked: false,
                    inputs: Vec::new(),
                    outputs: Vec::new(),
                    nodes: vec![Node::new(NodeId(1), kind)],
                    wires: Vec::new(),
                };
                (format!("g{level}"), definition)
            })
            .collect()
    }

    #[test]
    fn groups_nested_a_hundred_thousand_deep_are_refused_without_recursion() {
        // The interfaces were computed recursively: 16,000 levels overflowed the stack.
        let error = interfaces(&chain(100_000)).expect_err("too deep");
        assert!(
            error
                .message
                .starts_with("groups nest 100,000 levels deep, more than 32: 'g0' › 'g1'"),
            "{}",
            error.message
        );
        assert_eq!(
            interfaces(&chain(MAX_GROUP_DEPTH)).map(|all| all.len()),
            Ok(MAX_GROUP_DEPTH)
        );
        // Nor does resolving such a graph, as loading it does.
        let mut graph = Graph {
            groups: chain(100_000),
            ..Graph::default()
        };
        graph.add("top", NodeKind::Group(Group::named("g0".into())));
        resolve(&mut graph);
    }

    #[test]
    fn outputs_are_named_after_the_nodes_that_feed_them() {
        let noise = || {
            NodeKind::Noise(crate::nodes::Noise {
                basis: crate::graph::Basis::Gradient,
                period: 0,
            })
        };
        let mut graph = Graph::default();
        let grain = graph.add("grain", noise());
        let pores = graph.add("", noise());
        let also_grain = graph.add("grain", noise());
        let material = graph.add("material", NodeKind::Material);
        graph.connect(grain, "value", material, "albedo");
        graph.connect(pores, "value", material, "roughness");
        graph.connect(also_grain, "value", material, "bump");
        let selection = BTreeSet::from([grain, pores, also_grain]);
        group_nodes(&mut graph, &selection, "wood").expect("groups");
        let names: Vec<&str> = graph.groups["wood"]
            .outputs
            .iter()
            .map(|output| output.name.as_str())
            .collect();
        assert_eq!(names, ["grain", "Noise", "grain_2"]);
    }
}
