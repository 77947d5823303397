//! Validation of a graph, topological ordering and pruning to what the output needs.

use super::ids::IdIndex;
use super::{Graph, MAX_PATH_CHARS, MAX_TEXT_CHARS, Node, NodeId, Wire, clip};
use super::{InputPin, NodeKind, PinDefault, Signature, Value, ValueType};
use crate::bitmaps::Bitmap;
use std::collections::BTreeMap;
use std::fmt;
use std::sync::Arc;

/// One problem found in a graph, attached to the node it concerns when there is one.
#[derive(Clone, Debug, PartialEq)]
pub struct CheckError {
    pub node: Option<NodeId>,
    /// The node as named in messages: `node 'label' (#id)`.
    pub node_name: Option<String>,
    pub message: String,
}

impl fmt::Display for CheckError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.node_name {
            Some(name) => write!(f, "{name}: {}", self.message),
            None => f.write_str(&self.message),
        }
    }
}

/// Where a node input gets its value.
#[derive(Clone, Debug, PartialEq)]
pub enum InputSource {
    /// An output of an earlier node: its id, output index and type.
    Wire {
        node: NodeId,
        output: usize,
        ty: ValueType,
    },
    /// A constant, already converted to the pin's type.
    Const(Value),
    /// The surface position.
    Position,
}

/// A node that survived pruning, with every input resolved.
#[derive(Clone, Debug)]
pub struct CheckedNode {
    pub node: Node,
    pub signature: Signature,
    /// One entry per input pin, in signature order.
    pub inputs: Vec<InputSource>,
    /// Which outputs some later node reads.
    pub used_outputs: Vec<bool>,
}

impl CheckedNode {
    /// The wired inputs: each one's index, pin, and the node, output and type it reads.
    pub fn wired_inputs(
        &self,
    ) -> impl Iterator<Item = (usize, &InputPin, NodeId, usize, ValueType)> {
        let pins = self.signature.inputs.iter().zip(&self.inputs).enumerate();
        pins.filter_map(|(k, (pin, source))| match *source {
            InputSource::Wire { node, output, ty } => Some((k, pin, node, output, ty)),
            _ => None,
        })
    }

    /// Where input pin `name` gets its value.
    pub fn input(&self, name: &str) -> Option<&InputSource> {
        let (index, _) = self.signature.input(name)?;
        self.inputs.get(index)
    }
}

/// A graph that passed the checks: the nodes the material output needs, in dependency order.
#[derive(Clone, Debug)]
pub struct CheckedGraph {
    pub name: String,
    /// How the material's alpha shows (the graph's setting).
    pub alpha: super::AlphaMode,
    /// The lighting model (the graph's setting).
    pub shading: super::Shading,
    /// Needed nodes, every node after the nodes it reads; the material node is last.
    /// Group nodes are inlined: nodes from groups carry their [`super::Origin`].
    pub order: Vec<CheckedNode>,
    /// The parameters the graph exposes.
    pub parameters: Vec<super::parameters::Exposed>,
    /// Which inputs of the flattened nodes hold which exposed parameter's value.
    pub bindings: super::group::Bindings,
    /// The bitmap each Image node reads, decoded from its file.
    pub bitmaps: BTreeMap<NodeId, Arc<Bitmap>>,
    /// The position of each node in `order`.
    index: IdIndex,
}

impl CheckedGraph {
    /// The position of node `id` in `order`.
    pub fn index_of(&self, id: NodeId) -> Option<usize> {
        self.index.get(id)
    }

    /// The nodes at positions `keep` (ascending) of the order, as a graph of their own
    /// (one pass of a multi-pass material): wires from nodes left out stay, naming
    /// nodes the subset does not hold.
    pub fn subset(&self, keep: &[usize]) -> CheckedGraph {
        let order: Vec<CheckedNode> = keep.iter().map(|&k| self.order[k].clone()).collect();
        let max_id = order.iter().map(|checked| checked.node.id).max();
        let mut index = IdIndex::new(order.len(), max_id);
        for (position, checked) in order.iter().enumerate() {
            index.insert_first(checked.node.id, position);
        }
        CheckedGraph {
            order,
            index,
            ..self.clone_settings()
        }
    }

    /// The graph's settings and parameters without its nodes.
    fn clone_settings(&self) -> CheckedGraph {
        CheckedGraph {
            name: self.name.clone(),
            alpha: self.alpha,
            shading: self.shading,
            order: Vec::new(),
            parameters: self.parameters.clone(),
            bindings: self.bindings.clone(),
            bitmaps: self.bitmaps.clone(),
            index: IdIndex::new(0, None),
        }
    }

    /// The material output node.
    pub fn material(&self) -> &CheckedNode {
        self.order
            .last()
            .expect("a checked graph ends with its material node")
    }
}

/// A node, its signature and its index in the file.
type Entry<'g> = (&'g Node, &'g Signature, usize);

struct Checker<'g> {
    graph: &'g Graph,
    /// The signature of each node of the graph, in file order.
    signatures: &'g [Signature],
    /// The first node with each id, as its index in the file.
    by_id: IdIndex,
    /// Where each node's input pins start in `wires_into` (by index in the file).
    first_pin: Vec<usize>,
    /// The first wire into each input pin of each node, as [`Graph::wire_into`] finds it.
    wires_into: Vec<Option<&'g Wire>>,
    errors: Vec<CheckError>,
}

impl<'g> Checker<'g> {
    /// The (first) node with `id` and its signature.
    fn lookup(&self, id: NodeId) -> Option<Entry<'g>> {
        let index = self.by_id.get(id)?;
        Some((&self.graph.nodes[index], &self.signatures[index], index))
    }

    /// The slot in `wires_into` of input `pin` of the node at `index`.
    fn pin_slot(&self, index: usize, pin: usize) -> usize {
        self.first_pin[index] + pin
    }

    /// Indexes the first wire into each input pin (whatever it comes from).
    fn index_wires(&mut self) {
        for wire in &self.graph.wires {
            let Some((_, signature, index)) = self.lookup(wire.to.node) else {
                continue;
            };
            if let Some((pin, _)) = signature.input(&wire.to.pin) {
                let slot = self.pin_slot(index, pin);
                self.wires_into[slot].get_or_insert(wire);
            }
        }
    }

    fn error(&mut self, node: Option<&Node>, message: String) {
        self.errors.push(CheckError {
            node: node.map(|n| n.id),
            node_name: node.map(|n| n.to_string()),
            message,
        });
    }

    /// Refuses a material that reads more distinct mesh fields than the lanes of
    /// `VeneerSurface.fields` its distance fields leave free, naming the first node past
    /// the limit and the fields read.
    fn check_mesh_fields(&mut self, order: &[CheckedNode]) {
        use crate::nodes::mesh_field::{MESH_LANES, fields_read};
        let kinds = || order.iter().map(|checked| &checked.node.kind);
        let read = fields_read(kinds());
        let distances = crate::codegen::distance_slots(kinds())
            .iter()
            .filter(|&&taken| taken)
            .count();
        let free = MESH_LANES - distances;
        let Some(beyond) = read.get(free) else {
            return;
        };
        let node = order.iter().find_map(|checked| match &checked.node.kind {
            NodeKind::MeshField(field) if field.key() == *beyond => Some(&checked.node),
            _ => None,
        });
        let names: Vec<String> = read.iter().map(|field| field.to_string()).collect();
        self.error(
            node,
            format!(
                "the material reads {} different mesh fields ({}), and its distance fields \
                 leave {free} of a mesh's {MESH_LANES} field lanes free: read the same field \
                 (kind and settings) from several nodes",
                read.len(),
                names.join(", ")
            ),
        );
    }

    /// Refuses texts longer than [`MAX_TEXT_CHARS`] (a mesh path: [`MAX_PATH_CHARS`]),
    /// which would otherwise be copied into shader code and messages.
    fn check_text(&mut self) {
        let graph = self.graph;
        let too_long = |text: &str, max: usize| clip(text, max).1;
        if too_long(&graph.name, MAX_TEXT_CHARS) {
            self.error(
                None,
                long_text("the graph name", &graph.name, MAX_TEXT_CHARS),
            );
        }
        if too_long(&graph.preview.mesh, MAX_PATH_CHARS) {
            let message = long_text("the preview mesh name", &graph.preview.mesh, MAX_PATH_CHARS);
            self.error(None, message);
        }
        for frame in &graph.frames {
            if too_long(&frame.title, MAX_TEXT_CHARS) {
                self.error(
                    None,
                    long_text("a frame title", &frame.title, MAX_TEXT_CHARS),
                );
            }
        }
        for node in &graph.nodes {
            if too_long(&node.label, MAX_TEXT_CHARS) {
                self.error(
                    Some(node),
                    long_text("the label", &node.label, MAX_TEXT_CHARS),
                );
            }
        }
    }

    /// Reports repeated ids and indexes the nodes by id.
    fn check_ids(&mut self) {
        for (index, node) in self.graph.nodes.iter().enumerate() {
            if !self.by_id.insert_first(node.id, index) {
                self.error(Some(node), format!("duplicate node id {}", node.id));
            }
        }
    }

    fn check_settings(&mut self, node: &Node) {
        if let Some(message) = node.kind.definition().check() {
            self.error(Some(node), message);
        }
    }

    fn check_constants(&mut self, node: &Node, signature: &Signature) {
        for (pin, value) in &node.inputs {
            match signature.input(pin) {
                None => self.error(
                    Some(node),
                    no_pin("input", pin, signature.inputs.iter().map(|p| p.name)),
                ),
                Some((_, input)) if !value.ty().converts_to(input.ty) => self.error(
                    Some(node),
                    format!(
                        "input '{pin}' expects {} but the file gives a {}",
                        input.ty,
                        value.ty()
                    ),
                ),
                Some(_) if !value.is_finite() => {
                    self.error(Some(node), format!("input '{pin}' is not finite"))
                }
                Some(_)
                    if value
                        .components()
                        .iter()
                        .any(|c| c.abs() > f64::from(f32::MAX)) =>
                {
                    self.error(
                        Some(node),
                        format!(
                            "input '{pin}' is {value:?}, beyond the f32 range (±3.4e38) that \
                             shaders compute in"
                        ),
                    )
                }
                Some(_) => {}
            }
        }
    }

    fn check_wires(&mut self) {
        let mut fed = vec![false; self.wires_into.len()];
        for wire in &self.graph.wires {
            let (Some((from, from_signature, _)), Some((to, to_signature, to_index))) =
                (self.lookup(wire.from.node), self.lookup(wire.to.node))
            else {
                let missing = if self.by_id.get(wire.from.node).is_some() {
                    wire.to.node
                } else {
                    wire.from.node
                };
                self.error(
                    None,
                    format!("a wire refers to node {missing}, which does not exist"),
                );
                continue;
            };
            let Some((_, output)) = from_signature.output(&wire.from.pin) else {
                let names = from_signature.outputs.iter().map(|p| p.name);
                self.error(Some(from), no_pin("output", &wire.from.pin, names));
                continue;
            };
            let Some((pin, input)) = to_signature.input(&wire.to.pin) else {
                let names = to_signature.inputs.iter().map(|p| p.name);
                self.error(Some(to), no_pin("input", &wire.to.pin, names));
                continue;
            };
            let slot = self.pin_slot(to_index, pin);
            if std::mem::replace(&mut fed[slot], true) {
                self.error(
                    Some(to),
                    format!("input '{}' has more than one wire", wire.to.pin),
                );
            }
            if !output.ty.converts_to(input.ty) {
                self.error(
                    Some(to),
                    format!(
                        "type mismatch: input '{}' expects {} but {} output '{}' gives {}",
                        input.name, input.ty, from, output.name, output.ty
                    ),
                );
            }
        }
    }

    fn material_node(&mut self) -> Option<Entry<'g>> {
        let materials: Vec<Entry<'g>> = self
            .graph
            .nodes
            .iter()
            .zip(self.signatures)
            .enumerate()
            .filter(|(_, (node, _))| node.kind == NodeKind::Material)
            .map(|(index, (node, signature))| (node, signature, index))
            .collect();
        match materials.as_slice() {
            [] => {
                self.error(None, "the graph has no Material output node".into());
                None
            }
            [one] => Some(*one),
            [_, more @ ..] => {
                for (extra, _, _) in more {
                    self.error(
                        Some(extra),
                        "a graph has exactly one Material output node".into(),
                    );
                }
                None
            }
        }
    }

    /// Nodes reachable backwards from `root`, each after its inputs; reports cycles.
    fn order_from(&mut self, root: Entry<'g>) -> Vec<Entry<'g>> {
        #[derive(Clone, Copy, PartialEq)]
        enum Mark {
            Unseen,
            /// On the stack, at this position.
            Visiting(usize),
            Done,
        }
        // By index in the file.
        let mut marks = vec![Mark::Unseen; self.graph.nodes.len()];
        let mut order = Vec::new();
        // Iterative depth-first search: (node, next input index to visit). A node keeps
        // its position on the stack while it is visited.
        let mut stack: Vec<(Entry<'g>, usize)> = vec![(root, 0)];
        marks[root.2] = Mark::Visiting(0);
        while let Some((entry, next)) = stack.pop() {
            let (_, signature, index) = entry;
            let inputs = &signature.inputs;
            if next == inputs.len() {
                marks[index] = Mark::Done;
                order.push(entry);
                continue;
            }
            stack.push((entry, next + 1));
            let Some(wire) = self.wires_into[self.pin_slot(index, next)] else {
                continue;
            };
            let Some(source_entry) = self.lookup(wire.from.node) else {
                continue;
            };
            let source = source_entry.0;
            match &marks[source_entry.2] {
                Mark::Done => {}
                Mark::Visiting(start) => {
                    let path = cycle_path(&stack[*start..]);
                    let message = match re_evaluated_step(&stack[*start..]) {
                        Some((reader, pin)) => format!(
                            "cycle through the re-evaluated input '{pin}' of '{reader}' (the pattern it places reads the node placing it): {path} -> '{}'",
                            source.display_name()
                        ),
                        None => format!("cycle: {path} -> '{}'", source.display_name()),
                    };
                    self.error(Some(source), message);
                }
                Mark::Unseen => {
                    marks[source_entry.2] = Mark::Visiting(stack.len());
                    stack.push((source_entry, 0));
                }
            }
        }
        order
    }

    fn resolve(&mut self, (node, signature, index): Entry<'g>) -> Vec<InputSource> {
        let mut sources = Vec::with_capacity(signature.inputs.len());
        for (k, pin) in signature.inputs.iter().enumerate() {
            let wire = self.wires_into[self.pin_slot(index, k)];
            // Wires were checked before resolution: the node and its output exist.
            let from = wire.and_then(|wire| {
                let (from, signature, _) = self.lookup(wire.from.node)?;
                let (output, out_pin) = signature.output(&wire.from.pin)?;
                Some(InputSource::Wire {
                    node: from.id,
                    output,
                    ty: out_pin.ty,
                })
            });
            let source = if let Some(from) = from {
                from
            } else if pin.sampled {
                // A buffer is rendered from a wire's upstream: a constant has none.
                self.error(
                    Some(node),
                    format!(
                        "input '{}' ({}) is read as a buffer and must be connected",
                        pin.name, pin.ty
                    ),
                );
                InputSource::Const(Value::Float(0.0).convert(pin.ty))
            } else if let (Some(value), false) = (
                node.inputs.get(pin.name),
                matches!(pin.default, PinDefault::Builtin(_)),
            ) {
                InputSource::Const(value.convert(pin.ty))
            } else {
                match pin.default {
                    PinDefault::Const(value) => InputSource::Const(value),
                    PinDefault::Position => InputSource::Position,
                    PinDefault::Builtin(_) => InputSource::Const(Value::Float(0.0).convert(pin.ty)),
                    PinDefault::Required => {
                        self.error(
                            Some(node),
                            format!("input '{}' ({}) must be connected", pin.name, pin.ty),
                        );
                        InputSource::Const(Value::Float(0.0).convert(pin.ty))
                    }
                }
            };
            sources.push(source);
        }
        sources
    }
}

/// Checks a graph and orders the nodes its material output needs.
///
/// Checks what the graph declares first (group names and pins, exposed parameters and
/// presets), then inlines its groups (a group that contains itself, an unknown group or
/// pin, nesting past [`super::nesting::MAX_GROUP_DEPTH`] are errors naming the groups),
/// then reports unknown pins, bad constants and settings,
/// type mismatches, missing required inputs and cycles, each naming its node (inside
/// groups: `group 'bark' › node 'grain' (#3)`). Nodes the output does not reach are
/// pruned.
pub fn check(graph: &Graph) -> Result<CheckedGraph, Vec<CheckError>> {
    let parameters = super::parameters::ByName::of(graph);
    let mut errors = super::declarations::problems(graph, &parameters);
    let parameters = parameters.into_list();
    let seeds = super::parameters::bindings(&parameters);
    let (flat, bindings) = match super::group::flatten_traced(graph, seeds) {
        Ok(flat) => flat,
        Err(mut more) => {
            errors.append(&mut more);
            return Err(errors);
        }
    };
    let mut checked = match check_flat(&flat) {
        Ok(checked) if errors.is_empty() => checked,
        Ok(_) => return Err(errors),
        Err(mut more) => {
            errors.append(&mut more);
            return Err(errors);
        }
    };
    checked.parameters = parameters;
    checked.bindings = bindings;
    Ok(checked)
}

/// [`check`] of a graph without group nodes.
fn check_flat(graph: &Graph) -> Result<CheckedGraph, Vec<CheckError>> {
    check_towards(graph, None)
}

/// Checks one level of a graph as it stands, group nodes included (their pins resolved),
/// keeping the nodes that `sinks` need, each after its inputs: the body of a group's
/// function in generated code. The last node is not a material node.
pub fn check_body(graph: &Graph, sinks: &[NodeId]) -> Result<CheckedGraph, Vec<CheckError>> {
    check_towards(graph, Some(sinks))
}

/// Checks `graph` and orders what its material node (`sinks` `None`) or `sinks` need.
fn check_towards(graph: &Graph, sinks: Option<&[NodeId]>) -> Result<CheckedGraph, Vec<CheckError>> {
    let signatures: Vec<Signature> = graph.nodes.iter().map(|n| n.kind.signature()).collect();
    let mut first_pin = Vec::with_capacity(graph.nodes.len() + 1);
    first_pin.push(0);
    for signature in &signatures {
        first_pin.push(first_pin.last().copied().unwrap_or(0) + signature.inputs.len());
    }
    let max_id = graph.nodes.iter().map(|node| node.id).max();
    let mut checker = Checker {
        graph,
        signatures: &signatures,
        by_id: IdIndex::new(graph.nodes.len(), max_id),
        wires_into: vec![None; first_pin.last().copied().unwrap_or(0)],
        first_pin,
        errors: Vec::new(),
    };
    checker.check_text();
    checker.check_ids();
    for problem in graph.preview.problems() {
        checker.error(None, problem);
    }
    if let super::AlphaMode::Mask { cutoff } = graph.alpha
        && !(0.0..=1.0).contains(&cutoff)
    {
        checker.error(
            None,
            format!("the alpha cutoff {cutoff} must be a number from 0 to 1"),
        );
    }
    checker.index_wires();
    for (node, signature) in graph.nodes.iter().zip(&signatures) {
        checker.check_settings(node);
        checker.check_constants(node, signature);
    }
    checker.check_wires();
    let needed = match sinks {
        None => {
            let Some(material) = checker.material_node() else {
                return Err(checker.errors);
            };
            checker.order_from(material)
        }
        Some(sinks) => {
            let mut seen = std::collections::BTreeSet::new();
            let mut needed = Vec::new();
            for sink in sinks {
                if let Some(entry) = checker.lookup(*sink) {
                    let order = checker.order_from(entry);
                    needed.extend(order.into_iter().filter(|entry| seen.insert(entry.2)));
                }
            }
            needed
        }
    };
    if !checker.errors.is_empty() {
        return Err(checker.errors);
    }
    let mut order: Vec<CheckedNode> = Vec::with_capacity(needed.len());
    for entry in needed {
        let (node, signature, _) = entry;
        let inputs = checker.resolve(entry);
        let used_outputs = vec![false; signature.outputs.len()];
        order.push(CheckedNode {
            node: node.clone(),
            signature: signature.clone(),
            inputs,
            used_outputs,
        });
    }
    if sinks.is_none() {
        checker.check_mesh_fields(&order);
    }
    if !checker.errors.is_empty() {
        return Err(checker.errors);
    }
    let mut index = IdIndex::new(order.len(), max_id);
    for (position, checked) in order.iter().enumerate() {
        index.insert_first(checked.node.id, position);
    }
    for i in 0..order.len() {
        for k in 0..order[i].inputs.len() {
            if let InputSource::Wire { node, output, .. } = order[i].inputs[k]
                && let Some(source) = index.get(node)
            {
                order[source].used_outputs[output] = true;
            }
        }
    }
    let bitmaps = read_bitmaps(graph, &order)?;
    Ok(CheckedGraph {
        name: graph.name.clone(),
        alpha: graph.alpha,
        shading: graph.shading,
        order,
        parameters: Vec::new(),
        bindings: Default::default(),
        bitmaps,
        index,
    })
}

/// The bitmaps the Image nodes of `order` read, from files relative to the graph's
/// folder; a file that cannot be used is an error naming the node and the file.
fn read_bitmaps(
    graph: &Graph,
    order: &[CheckedNode],
) -> Result<BTreeMap<NodeId, Arc<Bitmap>>, Vec<CheckError>> {
    let mut bitmaps = BTreeMap::new();
    let mut errors = Vec::new();
    for checked in order {
        let Some(source) = checked.node.kind.definition().bitmap() else {
            continue;
        };
        let linear = graph.shading.is_linear();
        match crate::bitmaps::load(
            graph.folder.path(),
            source.path,
            source.colour_space,
            linear,
        ) {
            Ok(bitmap) => {
                bitmaps.insert(checked.node.id, bitmap);
            }
            Err(message) => errors.push(CheckError {
                node: Some(checked.node.id),
                node_name: Some(checked.node.to_string()),
                message,
            }),
        }
    }
    if errors.is_empty() {
        Ok(bitmaps)
    } else {
        Err(errors)
    }
}

/// The nodes of a cycle (the search stack from where it closes) as `'a' -> 'b' -> …`,
/// the middle of a long one left out.
fn cycle_path(stack: &[(Entry, usize)]) -> String {
    let names = stack
        .iter()
        .map(|((node, _, _), _)| format!("'{}'", node.display_name()));
    super::names::elided(names.collect(), " -> ")
}

/// The first node of a cycle (the search stack from where it closes) that reaches the
/// next through a re-evaluated input, and that input's name.
fn re_evaluated_step<'g>(stack: &[(Entry<'g>, usize)]) -> Option<(&'g str, &'static str)> {
    stack.iter().find_map(|((node, signature, _), next)| {
        let pin = signature.inputs.get(next.checked_sub(1)?)?;
        pin.re_evaluated.then(|| (node.display_name(), pin.name))
    })
}

/// The message for a text longer than `max` characters.
fn long_text(what: &str, text: &str, max: usize) -> String {
    format!(
        "{what} is {} characters long (at most {max})",
        crate::messages::thousands(text.chars().count())
    )
}

/// The message for a pin name the node does not have, listing the ones it has.
fn no_pin<'a>(side: &str, pin: &str, names: impl Iterator<Item = &'a str>) -> String {
    let (pin, cut) = clip(pin, MAX_TEXT_CHARS);
    let pin = format!("{pin}{}", if cut { "…" } else { "" });
    let names: Vec<&str> = names.collect();
    if names.is_empty() {
        format!("no {side} named '{pin}' (the node has no {side}s)")
    } else {
        format!("no {side} named '{pin}' ({side}s: {})", names.join(", "))
    }
}
