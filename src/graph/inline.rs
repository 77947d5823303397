//! Inlining: group nodes replaced by their definitions' nodes, the one way every stage
//! meets groups (see `group`). The graph being inlined keeps its wires indexed by the
//! nodes they join and its group nodes in a queue, so that each instance costs what its
//! definition holds, never a pass over the whole graph: a graph that inlines to a
//! million nodes flattens in linear time.

use super::check::CheckError;
use super::group::{BOUNDARY, GroupDef, Interface, Route, analyse, group_name};
use super::names::{elided, shown};
use super::{Graph, Node, NodeId, Origin, PinRef, Value, Wire};
use rustc_hash::FxHashMap;
use std::borrow::Cow;
use std::collections::{BTreeMap, HashSet, VecDeque};

/// Which flat inputs hold the value of which exposed parameter: `(node, pin)` →
/// parameter name.
pub type Bindings = BTreeMap<(NodeId, String), String>;

/// The graph with every group instance inlined, recursively, and every Graph bake node
/// expanded (see `graph_bakes`): the graph every stage checks, evaluates and emits. Top-level nodes keep their ids; inlined nodes get fresh
/// ones and their [`Origin`]. A graph without group nodes is returned as it is.
pub fn flatten(graph: &Graph) -> Result<Cow<'_, Graph>, Vec<CheckError>> {
    Ok(flatten_traced(graph, BTreeMap::new())?.0)
}

/// [`flatten`], following the constants of `bindings` (top-level inputs named by
/// exposed parameters) to every flat input they end up in.
pub fn flatten_traced(
    graph: &Graph,
    bindings: Bindings,
) -> Result<(Cow<'_, Graph>, Bindings), Vec<CheckError>> {
    let (flat, bindings) = inline_groups(graph, bindings)?;
    if !super::graph_bakes::has_bakes(&flat) {
        return Ok((flat, bindings));
    }
    // The nodes a bake brings in are flat already.
    let expanded = super::graph_bakes::expand(&flat)?;
    Ok((Cow::Owned(expanded), bindings))
}

/// [`flatten_traced`] but for Graph bake nodes, which it leaves as they are.
fn inline_groups(
    graph: &Graph,
    mut bindings: Bindings,
) -> Result<(Cow<'_, Graph>, Bindings), Vec<CheckError>> {
    if !graph.nodes.iter().any(|node| group_name(node).is_some()) {
        return Ok((Cow::Borrowed(graph), bindings));
    }
    let analysis = analyse(&graph.groups);
    if let Some(error) = analysis.error {
        return Err(vec![error.into()]);
    }
    if let Some(error) = analysis.nesting.too_many_nodes(&graph.nodes) {
        return Err(vec![error.into()]);
    }
    let mut flat = Flat::new(graph.nodes.clone(), graph.wires.clone());
    let mut errors = Vec::new();
    while let Some(slot) = flat.pending.pop_front() {
        let instance = flat.remove_node(slot);
        let inlined = Inlining {
            groups: &graph.groups,
            interfaces: &analysis.interfaces,
            fresh: true,
        }
        .inline(&mut flat, instance, &mut bindings);
        if let Err(error) = inlined {
            errors.push(error);
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    let (nodes, wires) = flat.into_parts();
    let flat = Graph {
        version: graph.version,
        name: graph.name.clone(),
        preview: graph.preview.clone(),
        nodes,
        wires,
        frames: graph.frames.clone(),
        alpha: graph.alpha,
        shading: graph.shading,
        groups: BTreeMap::new(),
        parameters: graph.parameters.clone(),
        presets: graph.presets.clone(),
        folder: graph.folder.clone(),
    };
    Ok((Cow::Owned(flat), bindings))
}

/// Replaces group node `position` of `graph` by its definition's nodes, keeping their
/// ids where the graph does not use them (the editor's *Ungroup*). Returns the ids the
/// definition's nodes got, by their ids in the definition.
pub(super) fn dissolve(
    graph: &mut Graph,
    position: usize,
    interfaces: &BTreeMap<String, Interface>,
) -> Result<BTreeMap<NodeId, NodeId>, CheckError> {
    let mut flat = Flat::new(
        std::mem::take(&mut graph.nodes),
        std::mem::take(&mut graph.wires),
    );
    let instance = flat.remove_node(position);
    let inlined = Inlining {
        groups: &graph.groups,
        interfaces,
        fresh: false,
    }
    .inline(&mut flat, instance, &mut Bindings::new());
    (graph.nodes, graph.wires) = flat.into_parts();
    inlined
}

/// A graph being inlined: its nodes and wires in slots (emptied as they go), indexed.
struct Flat {
    nodes: Vec<Option<Node>>,
    /// The slots of the nodes with each id (several only in a graph the check refuses).
    slots: FxHashMap<NodeId, Vec<usize>>,
    /// How many nodes there are of each id, for the largest.
    ids: BTreeMap<u32, usize>,
    wires: Vec<Option<Wire>>,
    /// The slots of the wires at each node, either end (some of them gone).
    ends: FxHashMap<NodeId, Vec<usize>>,
    /// The slots of the group nodes not inlined yet, in the order they came.
    pending: VecDeque<usize>,
}

impl Flat {
    fn new(nodes: Vec<Node>, wires: Vec<Wire>) -> Flat {
        let mut flat = Flat {
            nodes: Vec::with_capacity(nodes.len()),
            slots: FxHashMap::default(),
            ids: BTreeMap::new(),
            wires: Vec::with_capacity(wires.len()),
            ends: FxHashMap::default(),
            pending: VecDeque::new(),
        };
        for node in nodes {
            flat.push_node(node);
        }
        for wire in wires {
            flat.push_wire(wire);
        }
        flat
    }

    fn push_node(&mut self, node: Node) {
        let slot = self.nodes.len();
        self.slots.entry(node.id).or_default().push(slot);
        *self.ids.entry(node.id.0).or_default() += 1;
        if group_name(&node).is_some() {
            self.pending.push_back(slot);
        }
        self.nodes.push(Some(node));
    }

    fn remove_node(&mut self, slot: usize) -> Node {
        let node = self.nodes[slot].take().expect("a node in the slot");
        if let Some(count) = self.ids.get_mut(&node.id.0) {
            *count -= 1;
            if *count == 0 {
                self.ids.remove(&node.id.0);
            }
        }
        node
    }

    /// The first node with `id`, as [`Graph::node_mut`] finds it.
    fn node_mut(&mut self, id: NodeId) -> Option<&mut Node> {
        let slot = self
            .slots
            .get(&id)?
            .iter()
            .copied()
            .find(|&slot| self.nodes[slot].is_some())?;
        self.nodes[slot].as_mut()
    }

    /// One past the largest id in use, as [`Graph::next_id`] gives it.
    fn next_id(&self) -> u32 {
        self.ids.keys().next_back().map_or(1, |id| id + 1)
    }

    fn has(&self, id: NodeId) -> bool {
        self.ids.contains_key(&id.0)
    }

    fn push_wire(&mut self, wire: Wire) {
        let slot = self.wires.len();
        self.ends.entry(wire.from.node).or_default().push(slot);
        if wire.to.node != wire.from.node {
            self.ends.entry(wire.to.node).or_default().push(slot);
        }
        self.wires.push(Some(wire));
    }

    /// Takes out the wires from or to node `id`, in their order.
    fn take_wires_at(&mut self, id: NodeId) -> Vec<Wire> {
        let mut slots = self.ends.remove(&id).unwrap_or_default();
        slots.sort_unstable();
        slots.dedup();
        slots
            .into_iter()
            .filter_map(|slot| self.wires[slot].take())
            .collect()
    }

    fn into_parts(self) -> (Vec<Node>, Vec<Wire>) {
        (
            self.nodes.into_iter().flatten().collect(),
            self.wires.into_iter().flatten().collect(),
        )
    }
}

/// What inlining reads: the definitions, their interfaces, and how it numbers the
/// nodes it brings in.
struct Inlining<'a> {
    groups: &'a BTreeMap<String, GroupDef>,
    interfaces: &'a BTreeMap<String, Interface>,
    /// Fresh ids after every id in the graph, the nodes remembering the groups they came
    /// from ([`flatten`]); else the definition's own ids where the graph does not use
    /// them ([`dissolve`]).
    fresh: bool,
}

impl Inlining<'_> {
    /// Replaces group node `instance` (already taken out of `flat`) by its
    /// definition's nodes, wiring what fed its inputs to the inner pins and what read
    /// its outputs from the inner outputs. Returns the ids the inner nodes got.
    fn inline(
        &self,
        flat: &mut Flat,
        instance: Node,
        bindings: &mut Bindings,
    ) -> Result<BTreeMap<NodeId, NodeId>, CheckError> {
        let failed = |message: String| CheckError {
            node: instance.origin.is_none().then_some(instance.id),
            node_name: Some(instance.to_string()),
            message,
        };
        let name = group_name(&instance).unwrap_or_default().to_string();
        let (Some(definition), Some(interface)) =
            (self.groups.get(&name), self.interfaces.get(&name))
        else {
            return Err(failed(format!(
                "no group named '{}' in the graph",
                shown(&name)
            )));
        };
        // A constant for an input the group no longer has (the library's group
        // changed, or an inner parameter was bound) is left alone, as a wire into it
        // is not. What fed the instance's inputs and read its outputs, taken out.
        let touching = flat.take_wires_at(instance.id);
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
        let definition_name = name.clone();
        let name = shown(&name);

        // The inner nodes, renumbered.
        let mut next = flat.next_id().max(
            definition
                .nodes
                .iter()
                .map(|node| node.id.0 + 1)
                .max()
                .unwrap_or(1),
        );
        let mut new_ids = BTreeMap::new();
        for node in &definition.nodes {
            if node.id == BOUNDARY {
                return Err(failed(format!(
                    "group '{name}' has a node with id {}, which stands for the group's boundary",
                    BOUNDARY.0
                )));
            }
            let id = if !self.fresh && !flat.has(node.id) {
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
        let path = instance
            .origin
            .as_ref()
            .map(|origin| origin.groups.clone())
            .unwrap_or_default()
            .within(format!("group '{}'", instance.display_name()));
        for node in &definition.nodes {
            let mut inner = node.clone();
            inner.id = new_ids[&node.id];
            if self.fresh {
                inner.origin = Some(Box::new(Origin {
                    groups: path.clone(),
                    id: node.id,
                    top: instance
                        .origin
                        .as_ref()
                        .map_or(instance.id, |outer| outer.top),
                    definition: definition_name.clone(),
                }));
                inner.position = instance.position;
            }
            flat.push_node(inner);
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

        // Writes what interface input `pin` carries into inner input `to`
        // (renumbered): what feeds the instance, else its constant, else the group's
        // default (which an inherited input's inner node holds already).
        let deliver =
            |flat: &mut Flat, bindings: &mut Bindings, pin: &str, to: PinRef, inherited: bool| {
                if let Some(from) = feeds.get(pin) {
                    flat.push_wire(Wire {
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
                set_constant(flat, &to, value);
            };

        for wire in &definition.wires {
            match (wire.from.node == BOUNDARY, wire.to.node == BOUNDARY) {
                (false, false) => {
                    let (from, to) = (inner_pin(&wire.from)?, inner_pin(&wire.to)?);
                    flat.push_wire(Wire { from, to });
                }
                (true, false) => {
                    if interface.input(&wire.from.pin).is_none() {
                        return Err(failed(format!(
                            "group '{name}' reads input '{}', which it does not declare",
                            shown(&wire.from.pin)
                        )));
                    }
                    let to = inner_pin(&wire.to)?;
                    deliver(flat, bindings, &wire.from.pin, to, false);
                }
                // Outputs are followed from the readers below.
                (_, true) => {}
            }
        }
        for entry in &interface.inputs {
            if let Route::Inherited { node, pin } = &entry.route {
                let to = PinRef::new(new_ids[node], pin);
                deliver(flat, bindings, &entry.input.name, to, true);
            }
        }
        let mut readers = touching
            .iter()
            .filter(|wire| wire.from.node == instance.id)
            .peekable();
        if readers.peek().is_none() {
            return Ok(new_ids);
        }
        let outputs: HashSet<&str> = interface.outputs.iter().map(|o| o.name.as_str()).collect();
        let mut sources: FxHashMap<&str, &PinRef> = FxHashMap::default();
        for wire in &definition.wires {
            if wire.to.node == BOUNDARY {
                sources.entry(wire.to.pin.as_str()).or_insert(&wire.from);
            }
        }
        for reader in readers {
            let output = &reader.from.pin;
            if !outputs.contains(output.as_str()) {
                return Err(failed(unknown_pin("output", output, interface)));
            }
            let source = sources.get(output.as_str()).ok_or_else(|| {
                failed(format!(
                    "group '{name}' output '{}' is not connected inside the group",
                    shown(output)
                ))
            })?;
            if source.node == BOUNDARY {
                deliver(flat, bindings, &source.pin, reader.to.clone(), false);
            } else {
                flat.push_wire(Wire {
                    from: inner_pin(source)?,
                    to: reader.to.clone(),
                });
            }
        }
        Ok(new_ids)
    }
}

/// Sets the constant of input `to`, in the type of the pin when the node has it.
fn set_constant(flat: &mut Flat, to: &PinRef, value: Value) {
    if let Some(node) = flat.node_mut(to.node) {
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
    let names: Vec<String> = if side == "input" {
        interface
            .inputs
            .iter()
            .map(|e| e.input.name.clone())
            .collect()
    } else {
        interface.outputs.iter().map(|o| o.name.clone()).collect()
    };
    format!(
        "the group has no {side} named '{}' ({side}s: {})",
        shown(pin),
        elided(names, ", ")
    )
}
