//! The code of one function body: each checked node's statements in order, constant
//! subgraphs folded to literals, inputs as literals, parameter slots or members of the
//! exposed parameters, and group nodes as calls of their group's function.

use super::parts::Block;
use super::{Emitted, ParamMode, ParamSlot, fold, input_expression, member_expression, naming};
use crate::graph::check::{CheckedGraph, InputSource};
use crate::graph::frames::Frames;
use crate::graph::group::Bindings;
use crate::graph::parameters::{Exposed, Member};
use crate::graph::{NodeId, NodeKind};
use crate::nodes::emit::{self, Detail, Emit};
use crate::nodes::mesh_field::MeshLanes;
use naming::Namer;
use rustc_hash::{FxHashMap, FxHashSet};
use std::collections::BTreeMap;

/// How a group's function is called: its name, the struct it returns, which inputs of
/// a group node are its arguments (by pin index) and which outputs the struct has.
pub struct GroupCall {
    pub function: String,
    pub returns: String,
    pub arguments: Vec<usize>,
    /// Per output pin of a group node, the struct member holding it (if any instance
    /// reads it).
    pub members: Vec<Option<String>>,
}

/// The frame a body's nodes are emitted in: the graph's frames, the names of their
/// functions, and the instance's identifier inside a local frame's function.
#[derive(Clone, Copy)]
struct Frame<'f> {
    frames: &'f Frames,
    functions: &'f [String],
    instance: Option<&'static str>,
}

/// What every body of one module shares: the modes, the slots and library items
/// gathered so far, and how to call each group.
pub struct Emitter<'a> {
    pub mode: ParamMode,
    pub detail: Detail,
    /// Parameter slots (slot modes), in order.
    pub params: Vec<ParamSlot>,
    /// The slots before this one belong to earlier modules of the same material (its
    /// passes): they share one numbering, so one buffer of values serves every module.
    pub first_slot: usize,
    /// Library items the bodies call, each once, in the order first called.
    pub roots: Vec<String>,
    called: FxHashSet<String>,
    /// The exposed parameters and their members (named mode).
    pub parameters: &'a [Exposed],
    pub members: &'a [Member],
    /// The position of each parameter in `parameters`, by name.
    parameter_index: FxHashMap<&'a str, usize>,
    /// Group functions by group name.
    pub calls: BTreeMap<String, GroupCall>,
    /// What each wired sampled input reads, by node and pin index: the arguments
    /// `texture, edge` of its buffer (multi-pass materials).
    pub sampled: FxHashMap<(NodeId, usize), String>,
    /// The arguments `texture, edge` of the bitmap each Image node reads.
    pub sources: FxHashMap<NodeId, String>,
    /// Which mesh field each lane of `VeneerSurface.fields` holds.
    pub mesh_lanes: MeshLanes,
    /// The functions of the local frames the bodies hold (see `graph::frames`), their
    /// text in the order emitted.
    pub local_functions: String,
    /// The names of the local frames' functions, unique in the module.
    local_names: Namer,
}

impl<'a> Emitter<'a> {
    /// An emitter for a module of these modes and parameters.
    pub fn new(
        mode: ParamMode,
        detail: Detail,
        parameters: &'a [Exposed],
        members: &'a [Member],
    ) -> Emitter<'a> {
        Emitter {
            mode,
            detail,
            params: Vec::new(),
            first_slot: 0,
            roots: Vec::new(),
            called: FxHashSet::default(),
            parameters,
            members,
            parameter_index: parameters
                .iter()
                .enumerate()
                .rev()
                .map(|(k, p)| (p.name.as_str(), k))
                .collect(),
            calls: BTreeMap::new(),
            sampled: FxHashMap::default(),
            sources: FxHashMap::default(),
            mesh_lanes: MeshLanes::default(),
            local_functions: String::new(),
            local_names: Namer::default(),
        }
    }

    /// The member expression of the parameter held by input `pin` of `node`, if the
    /// module binds parameters by name and `bindings` say the input holds one.
    fn bound(
        &self,
        bindings: &Bindings,
        node: NodeId,
        pin: &crate::graph::InputPin,
        source: &InputSource,
    ) -> Option<String> {
        if self.mode != ParamMode::Named || !matches!(source, InputSource::Const(_)) {
            return None;
        }
        let name = bindings.get(&(node, pin.name.to_string()))?;
        let k = *self.parameter_index.get(name.as_str())?;
        Some(member_expression(
            &self.members[k].name,
            self.parameters[k].ty,
            pin.ty,
        ))
    }

    /// The blocks of `graph`'s nodes evaluated at the shaded point, in order, and what
    /// each node left for its readers (nothing for nodes only local frames hold). Nodes
    /// in `arguments` stand for a function's arguments: their output is the argument.
    /// The local frames' functions go to [`Emitter::local_functions`].
    pub fn body(
        &mut self,
        graph: &CheckedGraph,
        bindings: &Bindings,
        arguments: &BTreeMap<NodeId, String>,
    ) -> (Vec<Block>, Vec<Emitted>) {
        let frames = Frames::of(graph);
        let functions: Vec<String> = (frames.locals.iter())
            .map(|local| {
                let source = graph.order[local.source].node.display_name();
                format!(
                    "veneer_local_{}",
                    self.local_names.name(source, local.source as u32)
                )
            })
            .collect();
        let frame = Frame {
            frames: &frames,
            functions: &functions,
            instance: None,
        };
        for (local, function) in frames.locals.iter().zip(&functions) {
            let inner = Frame {
                instance: Some("instance"),
                ..frame
            };
            let (blocks, emitted) = self.nodes(graph, bindings, arguments, &local.nodes, inner);
            let value = emitted[local.source].outputs.get(local.output).cloned();
            let value = emit::convert(value.unwrap_or_default(), local.from, local.ty);
            let source = &graph.order[local.source].node;
            let mut text = format!(
                "\n// The pattern '{}' ({}) re-evaluates per instance: the surface moved into the instance's frame.\nfn {function}(s: VeneerSurface, instance: veneer_instance) -> {} {{\n",
                naming::comment(source.display_name()),
                naming::comment(&source.reference()),
                local.ty.wgsl()
            );
            for block in &blocks {
                text.push_str(&block.text);
            }
            text.push_str(&format!("    return {value};\n}}\n"));
            self.local_functions.push_str(&text);
            self.use_item("veneer_instance");
        }
        self.nodes(graph, bindings, arguments, &frames.main, frame)
    }

    /// Library item `item` is called (each listed once, in the order first called).
    fn use_item(&mut self, item: &str) {
        if self.called.insert(item.to_string()) {
            self.roots.push(item.to_string());
        }
    }

    /// The blocks of the nodes at `positions` (ascending) of `graph` in `frame`, and
    /// what each left for its readers (by position; nothing for the others).
    fn nodes(
        &mut self,
        graph: &CheckedGraph,
        bindings: &Bindings,
        arguments: &BTreeMap<NodeId, String>,
        positions: &[usize],
        frame: Frame,
    ) -> (Vec<Block>, Vec<Emitted>) {
        let mut namer = Namer::default();
        for name in arguments.values() {
            namer.reserve(name);
        }
        // A local frame's function takes the instance under this name.
        namer.reserve("instance");
        let mut emitted: Vec<Emitted> = Vec::with_capacity(graph.order.len());
        emitted.resize_with(graph.order.len(), Emitted::default);
        let mut blocks: Vec<Block> = Vec::new();
        for &at in positions {
            let checked = &graph.order[at];
            let node = &checked.node;
            if let Some(argument) = arguments.get(&node.id) {
                emitted[at] = Emitted {
                    outputs: vec![argument.clone()],
                    folded: None,
                    block: None,
                };
                continue;
            }
            let from: Vec<Option<&Emitted>> = checked
                .inputs
                .iter()
                .map(|source| match source {
                    InputSource::Wire { node, .. } => graph.index_of(*node).map(|i| &emitted[i]),
                    _ => None,
                })
                .collect();
            let bound: Vec<Option<String>> = checked
                .signature
                .inputs
                .iter()
                .zip(&checked.inputs)
                .map(|(pin, source)| self.bound(bindings, node.id, pin, source))
                .collect();
            if matches!(self.mode, ParamMode::Baked | ParamMode::Named)
                && let Some(values) = fold(checked, &from, &bound)
            {
                let outputs = checked
                    .signature
                    .outputs
                    .iter()
                    .zip(&values)
                    .map(|(pin, lanes)| emit::lanes_literal(pin.ty, *lanes))
                    .collect();
                emitted[at] = Emitted {
                    outputs,
                    folded: Some(values),
                    block: None,
                };
                continue;
            }
            let inputs: Vec<String> = checked
                .inputs
                .iter()
                .zip(&checked.signature.inputs)
                .zip(&from)
                .zip(&bound)
                .enumerate()
                .map(|(k, (((source, pin), from), bound))| match bound {
                    Some(expression) => expression.clone(),
                    None if pin.sampled => self.sampled[&(node.id, k)].clone(),
                    None if matches!(pin.default, crate::graph::PinDefault::Builtin(_)) => {
                        String::new()
                    }
                    None => {
                        let slots = self.mode.has_slots().then_some(&mut self.params);
                        input_expression(source, pin, node.id, *from, slots)
                    }
                })
                .collect();
            let reads: Vec<usize> = from.iter().filter_map(|from| (*from)?.block).collect();
            let name = match node.kind {
                NodeKind::Material => String::new(),
                _ => namer.name(node.display_name(), node.id.0),
            };
            // (Only a node that re-evaluates inputs looks its frames up: most nodes do
            // not, and a graph may have a million.)
            let locals: Vec<Option<&str>> = if frame.frames.sites.is_empty() {
                Vec::new()
            } else {
                (0..inputs.len())
                    .map(|k| {
                        let local = frame.frames.sites.get(&(at, k))?;
                        Some(frame.functions[*local].as_str())
                    })
                    .collect()
            };
            let code = match &node.kind {
                NodeKind::Group(group) => self.call(&group.name, &inputs, &name),
                kind => {
                    let mut io = Emit::new(
                        &checked.signature.inputs,
                        &inputs,
                        &checked.signature.outputs,
                        &name,
                        self.detail,
                    )
                    .with_source(self.sources.get(&node.id).map(String::as_str))
                    .with_mesh_lanes(self.mesh_lanes)
                    .in_frame(&locals, frame.instance);
                    kind.definition().emit(&mut io);
                    io.finish()
                }
            };
            if !code.statements.is_empty() {
                let mut text = format!(
                    "    // {} '{}' ({})\n",
                    node.kind.title(),
                    naming::comment(node.display_name()),
                    naming::comment(&node.reference())
                );
                for statement in &code.statements {
                    text.push_str("    ");
                    text.push_str(statement);
                    text.push('\n');
                }
                blocks.push(Block {
                    node: node.id,
                    text,
                    binding: code.binding.map(|ty| (name, ty)),
                    reads,
                });
            }
            for item in &code.library {
                self.use_item(item);
            }
            emitted[at] = Emitted {
                outputs: code.outputs,
                folded: None,
                block: (!code.statements.is_empty()).then(|| blocks.len() - 1),
            };
        }
        (blocks, emitted)
    }

    /// The call of group `group`'s function with the node's input expressions, bound to
    /// `name`; its outputs are members of the returned struct.
    fn call(&self, group: &str, inputs: &[String], name: &str) -> emit::NodeCode {
        let Some(call) = self.calls.get(group) else {
            unreachable!("every group a body calls has its function");
        };
        let mut arguments = vec!["s".to_string()];
        arguments.extend(call.arguments.iter().map(|&k| inputs[k].clone()));
        let returns: &'static str = crate::nodes::pins::intern(&call.returns);
        emit::NodeCode {
            statements: vec![format!(
                "let {name} = {}({});",
                call.function,
                arguments.join(", ")
            )],
            outputs: call
                .members
                .iter()
                .map(|member| {
                    member
                        .as_ref()
                        .map(|member| format!("{name}.{member}"))
                        .unwrap_or_default()
                })
                .collect(),
            library: Vec::new(),
            binding: Some(returns),
        }
    }
}
