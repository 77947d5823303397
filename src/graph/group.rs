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
use super::{Graph, Node, NodeId, NodeKind, Origin, PinRef, Value, ValueType, Wire};
use crate::nodes::Group;
use crate::nodes::pins::{InputPin, OutputPin, PinDefault, PinRange, Signature, intern};
use serde::{Deserialize, Serialize};
use std::borrow::Cow;
use std::collections::{BTreeMap, BTreeSet};

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
}

impl Interface {
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
                }
            })
            .collect();
        let outputs = self
            .outputs
            .iter()
            .map(|output| OutputPin {
                name: intern(&output.name),
                ty: output.ty,
            })
            .collect();
        Signature::new(inputs, outputs)
    }

    /// The input called `name`.
    pub fn input(&self, name: &str) -> Option<&InterfaceInput> {
        self.inputs.iter().find(|entry| entry.input.name == name)
    }
}

/// The group an instance node names, if it is one.
pub fn group_name(node: &Node) -> Option<&str> {
    match &node.kind {
        NodeKind::Group(group) => Some(&group.name),
        _ => None,
    }
}

/// Whether a wire feeds input `pin` of `node` among `wires`.
fn wired(wires: &[Wire], node: NodeId, pin: &str) -> bool {
    wires
        .iter()
        .any(|wire| wire.to.node == node && wire.to.pin == pin)
}

/// What is wrong with the graph's groups: unknown groups and groups that contain
/// themselves.
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

/// The interface of every group of `groups`, each computed after the groups it uses.
/// A cycle of group references is an error naming the groups, as is an inner node
/// naming a group that does not exist.
pub fn interfaces(
    groups: &BTreeMap<String, GroupDef>,
) -> Result<BTreeMap<String, Interface>, GroupError> {
    let mut done: BTreeMap<String, Interface> = BTreeMap::new();
    for name in groups.keys() {
        let mut stack = Vec::new();
        interface_of(name, groups, &mut done, &mut stack)?;
    }
    Ok(done)
}

/// Computes the interface of group `name` (and, first, of the groups it uses).
fn interface_of(
    name: &str,
    groups: &BTreeMap<String, GroupDef>,
    done: &mut BTreeMap<String, Interface>,
    stack: &mut Vec<String>,
) -> Result<(), GroupError> {
    if done.contains_key(name) {
        return Ok(());
    }
    if let Some(start) = stack.iter().position(|entry| entry == name) {
        let cycle: Vec<String> = stack[start..]
            .iter()
            .chain(std::iter::once(&name.to_string()))
            .map(|group| format!("'{group}'"))
            .collect();
        return Err(GroupError {
            node_name: None,
            message: format!(
                "groups contain themselves: {} (a group cannot be used inside itself)",
                cycle.join(" › ")
            ),
        });
    }
    let definition = &groups[name];
    stack.push(name.to_string());
    let mut interface = Interface {
        inputs: definition
            .inputs
            .iter()
            .map(|input| InterfaceInput {
                input: input.clone(),
                route: Route::Declared,
                path: Vec::new(),
            })
            .collect(),
        outputs: definition.outputs.clone(),
    };
    let mut inner: Vec<&Node> = definition.nodes.iter().collect();
    inner.sort_by_key(|node| node.id);
    for node in inner {
        let Some(used) = group_name(node) else {
            continue;
        };
        if !groups.contains_key(used) {
            return Err(GroupError {
                node_name: Some(format!("group '{name}' › {node}")),
                message: format!("no group named '{used}' in the graph"),
            });
        }
        interface_of(used, groups, done, stack)?;
        for entry in &done[used].inputs {
            let pin = &entry.input.name;
            if wired(&definition.wires, node.id, pin) {
                continue;
            }
            let mut input = entry.input.clone();
            if let Some(value) = node.inputs.get(pin) {
                input.default = value.convert(input.ty);
            }
            input.name = free_name(&interface, pin, node);
            let mut path = vec![used.to_string()];
            path.extend(entry.path.iter().cloned());
            interface.inputs.push(InterfaceInput {
                input,
                route: Route::Inherited {
                    node: node.id,
                    pin: pin.clone(),
                },
                path,
            });
        }
    }
    stack.pop();
    done.insert(name.to_string(), interface);
    Ok(())
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
/// from the current definitions. Best effort: a graph whose groups do not resolve keeps
/// the pins it had, and [`flatten`] reports why.
pub fn resolve(graph: &mut Graph) {
    let Ok(interfaces) = interfaces(&graph.groups) else {
        return;
    };
    let signatures: BTreeMap<&String, Signature> = interfaces
        .iter()
        .map(|(name, interface)| (name, interface.signature()))
        .collect();
    let nodes = graph.nodes.iter_mut().chain(
        graph
            .groups
            .values_mut()
            .flat_map(|definition| definition.nodes.iter_mut()),
    );
    for node in nodes {
        if let NodeKind::Group(group) = &mut node.kind
            && let Some(signature) = signatures.get(&group.name)
        {
            group.pins = signature.clone();
        }
    }
}

/// How inlining numbers the nodes it brings in.
#[derive(Clone, Copy, PartialEq)]
enum Ids {
    /// Fresh ids after every id in the graph; the nodes remember the groups they came
    /// from ([`flatten`]).
    Fresh,
    /// The definition's own ids where the graph does not use them ([`ungroup`]).
    Kept,
}

/// The graph with every group instance inlined, recursively: the graph every stage
/// checks, evaluates and emits. Top-level nodes keep their ids; inlined nodes get fresh
/// ones and their [`Origin`]. A graph without group nodes is returned as it is.
pub fn flatten(graph: &Graph) -> Result<Cow<'_, Graph>, Vec<CheckError>> {
    Ok(flatten_traced(graph, BTreeMap::new())?.0)
}

/// Which flat inputs hold the value of which exposed parameter: `(node, pin)` →
/// parameter name.
pub type Bindings = BTreeMap<(NodeId, String), String>;

/// [`flatten`], following the constants of `bindings` (top-level inputs named by
/// exposed parameters) to every flat input they end up in.
pub fn flatten_traced(
    graph: &Graph,
    mut bindings: Bindings,
) -> Result<(Cow<'_, Graph>, Bindings), Vec<CheckError>> {
    if !graph.nodes.iter().any(|node| group_name(node).is_some()) {
        return Ok((Cow::Borrowed(graph), bindings));
    }
    let interfaces = interfaces(&graph.groups).map_err(|error| vec![error.into()])?;
    let mut flat = graph.clone();
    flat.groups.clear();
    let mut errors = Vec::new();
    while let Some(position) = flat
        .nodes
        .iter()
        .position(|node| group_name(node).is_some())
    {
        let instance = flat.nodes.remove(position);
        if let Err(error) = inline(
            &mut flat,
            instance,
            &graph.groups,
            &interfaces,
            Ids::Fresh,
            &mut bindings,
        ) {
            errors.push(error);
        }
    }
    if errors.is_empty() {
        Ok((Cow::Owned(flat), bindings))
    } else {
        Err(errors)
    }
}

/// Replaces group node `instance` (already taken out of `graph.nodes`) by its
/// definition's nodes, wiring what fed its inputs to the inner pins and what read its
/// outputs from the inner outputs. Returns the ids the inner nodes got.
fn inline(
    graph: &mut Graph,
    instance: Node,
    groups: &BTreeMap<String, GroupDef>,
    interfaces: &BTreeMap<String, Interface>,
    ids: Ids,
    bindings: &mut Bindings,
) -> Result<BTreeMap<NodeId, NodeId>, CheckError> {
    let failed = |message: String| CheckError {
        node: instance.origin.is_none().then_some(instance.id),
        node_name: Some(instance.to_string()),
        message,
    };
    let name = group_name(&instance).unwrap_or_default().to_string();
    let (Some(definition), Some(interface)) = (groups.get(&name), interfaces.get(&name)) else {
        return Err(failed(format!("no group named '{name}' in the graph")));
    };
    // A constant for an input the group no longer has (the library's group changed,
    // or an inner parameter was bound) is left alone, as a wire into it is not.
    // What fed the instance's inputs and read its outputs, taken out of the graph.
    let (touching, wires): (Vec<Wire>, Vec<Wire>) = std::mem::take(&mut graph.wires)
        .into_iter()
        .partition(|wire| wire.from.node == instance.id || wire.to.node == instance.id);
    graph.wires = wires;
    let feeds: BTreeMap<&str, &PinRef> = touching
        .iter()
        .filter(|wire| wire.to.node == instance.id)
        .map(|wire| (wire.to.pin.as_str(), &wire.from))
        .collect();
    for pin in feeds.keys() {
        if interface.input(pin).is_none() {
            return Err(failed(unknown_pin("input", pin, interface)));
        }
    }

    // The inner nodes, renumbered.
    let mut next = graph.next_id().0.max(
        definition
            .nodes
            .iter()
            .map(|node| node.id.0 + 1)
            .max()
            .unwrap_or(1),
    );
    let taken: BTreeSet<NodeId> = graph.nodes.iter().map(|node| node.id).collect();
    let mut new_ids = BTreeMap::new();
    for node in &definition.nodes {
        if node.id == BOUNDARY {
            return Err(failed(format!(
                "group '{name}' has a node with id {}, which stands for the group's boundary",
                BOUNDARY.0
            )));
        }
        let id = if ids == Ids::Kept && !taken.contains(&node.id) {
            node.id
        } else {
            next += 1;
            NodeId(next - 1)
        };
        if new_ids.insert(node.id, id).is_some() {
            return Err(failed(format!(
                "group '{name}' has two nodes with id {}",
                node.id.0
            )));
        }
    }
    let path = {
        let mut groups = instance
            .origin
            .as_ref()
            .map(|origin| origin.groups.clone())
            .unwrap_or_default();
        groups.push(format!("group '{}'", instance.display_name()));
        groups
    };
    for node in &definition.nodes {
        let mut inner = node.clone();
        inner.id = new_ids[&node.id];
        if ids == Ids::Fresh {
            inner.origin = Some(Box::new(Origin {
                groups: path.clone(),
                id: node.id,
            }));
            inner.position = instance.position;
        }
        graph.nodes.push(inner);
    }
    let inner_pin = |pin: &PinRef| -> Result<PinRef, CheckError> {
        let id = new_ids.get(&pin.node).ok_or_else(|| {
            failed(format!(
                "group '{name}' has a wire at node id {}, which it does not have",
                pin.node.0
            ))
        })?;
        Ok(PinRef::new(*id, &pin.pin))
    };

    // Writes what interface input `pin` carries into inner input `to` (renumbered):
    // what feeds the instance, else its constant, else the group's default (which an
    // inherited input's inner node holds already).
    let deliver =
        |graph: &mut Graph, bindings: &mut Bindings, pin: &str, to: PinRef, inherited: bool| {
            if let Some(from) = feeds.get(pin) {
                graph.wires.push(Wire {
                    from: (*from).clone(),
                    to,
                });
                return;
            }
            let binding = bindings.get(&(instance.id, pin.to_string())).cloned();
            let value = match instance.inputs.get(pin) {
                Some(value) => *value,
                None if inherited && binding.is_none() => return,
                None => interface
                    .input(pin)
                    .map(|entry| entry.input.default)
                    .unwrap_or(Value::Float(0.0)),
            };
            if let Some(binding) = binding {
                bindings.insert((to.node, to.pin.clone()), binding);
            }
            set_constant(graph, &to, value);
        };

    for wire in &definition.wires {
        match (wire.from.node == BOUNDARY, wire.to.node == BOUNDARY) {
            (false, false) => {
                let (from, to) = (inner_pin(&wire.from)?, inner_pin(&wire.to)?);
                graph.wires.push(Wire { from, to });
            }
            (true, false) => {
                if interface.input(&wire.from.pin).is_none() {
                    return Err(failed(format!(
                        "group '{name}' reads input '{}', which it does not declare",
                        wire.from.pin
                    )));
                }
                let to = inner_pin(&wire.to)?;
                deliver(graph, bindings, &wire.from.pin, to, false);
            }
            // Outputs are followed from the readers below.
            (_, true) => {}
        }
    }
    for entry in &interface.inputs {
        if let Route::Inherited { node, pin } = &entry.route {
            let to = PinRef::new(new_ids[node], pin);
            deliver(graph, bindings, &entry.input.name, to, true);
        }
    }
    for reader in touching.iter().filter(|wire| wire.from.node == instance.id) {
        let output = &reader.from.pin;
        if !interface.outputs.iter().any(|o| &o.name == output) {
            return Err(failed(unknown_pin("output", output, interface)));
        }
        let source = definition
            .wires
            .iter()
            .find(|wire| wire.to.node == BOUNDARY && &wire.to.pin == output)
            .ok_or_else(|| {
                failed(format!(
                    "group '{name}' output '{output}' is not connected inside the group"
                ))
            })?;
        if source.from.node == BOUNDARY {
            deliver(graph, bindings, &source.from.pin, reader.to.clone(), false);
        } else {
            graph.wires.push(Wire {
                from: inner_pin(&source.from)?,
                to: reader.to.clone(),
            });
        }
    }
    Ok(new_ids)
}

/// Sets the constant of input `to`, in the type of the pin when the node has it.
fn set_constant(graph: &mut Graph, to: &PinRef, value: Value) {
    if let Some(node) = graph.node_mut(to.node) {
        let ty = node
            .kind
            .signature()
            .input(&to.pin)
            .map(|(_, pin)| pin.ty)
            .unwrap_or(value.ty());
        node.inputs.insert(to.pin.clone(), value.convert(ty));
    }
}

/// The message for a pin the group does not have, listing the ones it has.
fn unknown_pin(side: &str, pin: &str, interface: &Interface) -> String {
    let names: Vec<&str> = if side == "input" {
        interface
            .inputs
            .iter()
            .map(|e| e.input.name.as_str())
            .collect()
    } else {
        interface.outputs.iter().map(|o| o.name.as_str()).collect()
    };
    format!(
        "the group has no {side} named '{pin}' ({side}s: {})",
        names.join(", ")
    )
}

/// Turns `selection` (nodes of the top level, not the material) into group `name` and
/// puts one instance of it in their place; returns the instance's id. Every wire that
/// enters the selection becomes an input (one per source pin, named after the first pin
/// it feeds), every output read outside becomes an output.
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
                        let output = unique(&wire.from.pin, |n| {
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
/// uses it. Returns the ids of the nodes it put in the graph.
pub fn ungroup(graph: &mut Graph, instance: NodeId) -> Result<Vec<NodeId>, String> {
    let position = graph
        .nodes
        .iter()
        .position(|node| node.id == instance && group_name(node).is_some())
        .ok_or_else(|| format!("node {instance} is not a group"))?;
    let interfaces = interfaces(&graph.groups).map_err(|error| error.message)?;
    let node = graph.nodes.remove(position);
    let name = group_name(&node).unwrap_or_default().to_string();
    let groups = graph.groups.clone();
    let inlined = inline(
        graph,
        node,
        &groups,
        &interfaces,
        Ids::Kept,
        &mut Bindings::new(),
    )
    .map_err(|error| error.to_string())?;
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
