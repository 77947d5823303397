//! Validation of a graph, topological ordering and pruning to what the output needs.

use super::kind::{MAX_OCTAVES, NodeKind};
use super::signature::{PinDefault, Signature};
use super::value::{Value, ValueType};
use super::{Graph, Node, NodeId};
use std::collections::{BTreeMap, BTreeSet};
use std::fmt;

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

/// A graph that passed the checks: the nodes the material output needs, in dependency order.
#[derive(Clone, Debug)]
pub struct CheckedGraph {
    pub name: String,
    /// Needed nodes, every node after the nodes it reads; the material node is last.
    pub order: Vec<CheckedNode>,
}

impl CheckedGraph {
    /// The position of node `id` in `order`.
    pub fn index_of(&self, id: NodeId) -> Option<usize> {
        self.order.iter().position(|checked| checked.node.id == id)
    }

    /// The material output node.
    pub fn material(&self) -> &CheckedNode {
        self.order
            .last()
            .expect("a checked graph ends with its material node")
    }
}

struct Checker<'g> {
    graph: &'g Graph,
    by_id: BTreeMap<NodeId, &'g Node>,
    errors: Vec<CheckError>,
}

impl<'g> Checker<'g> {
    fn error(&mut self, node: Option<&Node>, message: String) {
        self.errors.push(CheckError {
            node: node.map(|n| n.id),
            node_name: node.map(|n| n.to_string()),
            message,
        });
    }

    fn check_ids(&mut self) {
        let mut seen = BTreeSet::new();
        for node in &self.graph.nodes {
            if !seen.insert(node.id) {
                self.error(Some(node), format!("duplicate node id {}", node.id));
            }
        }
    }

    fn check_settings(&mut self, node: &Node) {
        use NodeKind::*;
        let vector_only = |ty: &ValueType| *ty != ValueType::Float;
        let problem = match &node.kind {
            Field { slot } if *slot > 3 => Some(format!(
                "field slot {slot} is out of range (expected 0 to 3)"
            )),
            Fbm { octaves, .. }
            | Turbulence { octaves, .. }
            | FractalSum { octaves, .. }
            | Worley { octaves, .. }
                if *octaves == 0 || *octaves > MAX_OCTAVES =>
            {
                Some(format!(
                    "octaves {octaves} is out of range (expected 1 to {MAX_OCTAVES})"
                ))
            }
            Length { ty } | Dot { ty } | Normalize { ty } | Split { ty } | Combine { ty }
                if !vector_only(ty) =>
            {
                Some(format!(
                    "type {ty} is not a vector (expected vec2, vec3 or color)"
                ))
            }
            ColorRamp { stops, .. } if stops.is_empty() => {
                Some("a colour ramp needs at least one stop".into())
            }
            ColorRamp { stops, .. } => {
                if stops.iter().any(|s| {
                    !s.position.is_finite()
                        || ![s.color.0, s.color.1, s.color.2]
                            .iter()
                            .all(|c| c.is_finite())
                }) {
                    Some("colour ramp stops must be finite".into())
                } else if stops
                    .windows(2)
                    .any(|pair| pair[1].position < pair[0].position)
                {
                    Some("colour ramp stops must be sorted by position".into())
                } else {
                    None
                }
            }
            _ => None,
        };
        if let Some(message) = problem {
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
        let mut fed = BTreeSet::new();
        for wire in &self.graph.wires {
            let (Some(from), Some(to)) = (
                self.by_id.get(&wire.from.node).copied(),
                self.by_id.get(&wire.to.node).copied(),
            ) else {
                let missing = if self.by_id.contains_key(&wire.from.node) {
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
            let Some((_, output)) = from
                .kind
                .signature()
                .output(&wire.from.pin)
                .map(|(i, p)| (i, *p))
            else {
                let signature = from.kind.signature();
                let names = signature.outputs.iter().map(|p| p.name);
                self.error(Some(from), no_pin("output", &wire.from.pin, names));
                continue;
            };
            let Some((_, input)) = to
                .kind
                .signature()
                .input(&wire.to.pin)
                .map(|(i, p)| (i, *p))
            else {
                let signature = to.kind.signature();
                let names = signature.inputs.iter().map(|p| p.name);
                self.error(Some(to), no_pin("input", &wire.to.pin, names));
                continue;
            };
            if !fed.insert((wire.to.node, wire.to.pin.clone())) {
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

    fn material_node(&mut self) -> Option<&'g Node> {
        let materials: Vec<&Node> = self
            .graph
            .nodes
            .iter()
            .filter(|node| node.kind == NodeKind::Material)
            .collect();
        match materials.as_slice() {
            [] => {
                self.error(None, "the graph has no Material output node".into());
                None
            }
            [one] => Some(one),
            [_, more @ ..] => {
                for extra in more {
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
    fn order_from(&mut self, root: &'g Node) -> Vec<&'g Node> {
        #[derive(Clone, Copy, PartialEq)]
        enum Mark {
            Visiting,
            Done,
        }
        let mut marks: BTreeMap<NodeId, Mark> = BTreeMap::new();
        let mut order = Vec::new();
        // Iterative depth-first search: (node, next input index to visit).
        let mut stack: Vec<(&Node, usize)> = vec![(root, 0)];
        marks.insert(root.id, Mark::Visiting);
        while let Some((node, next)) = stack.pop() {
            let inputs = node.kind.signature().inputs;
            if next == inputs.len() {
                marks.insert(node.id, Mark::Done);
                order.push(node);
                continue;
            }
            stack.push((node, next + 1));
            let Some(wire) = self.graph.wire_into(node.id, inputs[next].name) else {
                continue;
            };
            let Some(source) = self.by_id.get(&wire.from.node).copied() else {
                continue;
            };
            match marks.get(&source.id) {
                Some(Mark::Done) => {}
                Some(Mark::Visiting) => {
                    let start = stack
                        .iter()
                        .position(|(n, _)| n.id == source.id)
                        .unwrap_or(0);
                    let names: Vec<String> = stack[start..]
                        .iter()
                        .map(|(n, _)| format!("'{}'", n.display_name()))
                        .collect();
                    self.error(
                        Some(source),
                        format!(
                            "cycle: {} -> '{}'",
                            names.join(" -> "),
                            source.display_name()
                        ),
                    );
                }
                None => {
                    marks.insert(source.id, Mark::Visiting);
                    stack.push((source, 0));
                }
            }
        }
        order
    }

    fn resolve(&mut self, node: &Node, signature: &Signature) -> Vec<InputSource> {
        let mut sources = Vec::with_capacity(signature.inputs.len());
        for pin in &signature.inputs {
            let source = if let Some(wire) = self.graph.wire_into(node.id, pin.name) {
                let from = self.by_id[&wire.from.node];
                let (output, out_pin) = from
                    .kind
                    .signature()
                    .output(&wire.from.pin)
                    .map(|(i, p)| (i, *p))
                    .expect("wires were checked before resolution");
                InputSource::Wire {
                    node: from.id,
                    output,
                    ty: out_pin.ty,
                }
            } else if let Some(value) = node.inputs.get(pin.name) {
                InputSource::Const(value.convert(pin.ty))
            } else {
                match pin.default {
                    PinDefault::Const(value) => InputSource::Const(value),
                    PinDefault::Position => InputSource::Position,
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
/// Reports unknown pins, bad constants and settings, type mismatches, missing required
/// inputs and cycles, each naming its node. Nodes the output does not reach are pruned.
pub fn check(graph: &Graph) -> Result<CheckedGraph, Vec<CheckError>> {
    let mut checker = Checker {
        graph,
        by_id: BTreeMap::new(),
        errors: Vec::new(),
    };
    checker.check_ids();
    for problem in graph.preview.problems() {
        checker.error(None, problem);
    }
    for node in &graph.nodes {
        checker.by_id.entry(node.id).or_insert(node);
        checker.check_settings(node);
        checker.check_constants(node, &node.kind.signature());
    }
    checker.check_wires();
    let Some(material) = checker.material_node() else {
        return Err(checker.errors);
    };
    let needed = checker.order_from(material);
    if !checker.errors.is_empty() {
        return Err(checker.errors);
    }
    let mut order: Vec<CheckedNode> = Vec::with_capacity(needed.len());
    for node in needed {
        let signature = node.kind.signature();
        let inputs = checker.resolve(node, &signature);
        let used_outputs = vec![false; signature.outputs.len()];
        order.push(CheckedNode {
            node: node.clone(),
            signature,
            inputs,
            used_outputs,
        });
    }
    if !checker.errors.is_empty() {
        return Err(checker.errors);
    }
    let index: BTreeMap<NodeId, usize> = order
        .iter()
        .enumerate()
        .map(|(i, c)| (c.node.id, i))
        .collect();
    for i in 0..order.len() {
        for source in order[i].inputs.clone() {
            if let InputSource::Wire { node, output, .. } = source {
                order[index[&node]].used_outputs[output] = true;
            }
        }
    }
    Ok(CheckedGraph {
        name: graph.name.clone(),
        order,
    })
}

/// The message for a pin name the node does not have, listing the ones it has.
fn no_pin<'a>(side: &str, pin: &str, names: impl Iterator<Item = &'a str>) -> String {
    let names: Vec<&str> = names.collect();
    if names.is_empty() {
        format!("no {side} named '{pin}' (the node has no {side}s)")
    } else {
        format!("no {side} named '{pin}' ({side}s: {})", names.join(", "))
    }
}
