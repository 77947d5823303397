//! Group functions: each group a material uses is emitted once, as
//! `fn veneer_group_<name>(s: VeneerSurface, <arguments>) -> veneer_group_<name>_out`,
//! and each group node calls it. What leaves code out of a flattened graph applies in
//! a function too: only the outputs some instance reads are computed (and only the
//! nodes they need), and an input every instance gives the same constant is no
//! argument but that constant inside, where it folds with the rest.
//!
//! Modules with parameter slots (the editor's live preview) stay flattened: their slots
//! name the flattened nodes.

use super::body::{Emitter, GroupCall};
use super::naming::{Namer, comment};
use super::{CompileError, CompileOptions, SurfaceUse, WgslModule, assemble, counts};
use super::{ParamMode, parameter_members};
use crate::graph::check::{CheckedGraph, InputSource, check_body};
use crate::graph::group::{self, BOUNDARY, Bindings, GroupDef, Interface, Route};
use crate::graph::{Graph, Node, NodeId, NodeKind, PinRef, Value, Wire};
use crate::nodes::Constant;
use std::collections::BTreeMap;

/// One group node of a checked level: where each input gets its value, whether the
/// input holds an exposed parameter, and which outputs are read.
struct Site {
    inputs: Vec<InputSource>,
    bound: Vec<bool>,
    used: Vec<bool>,
}

/// A group's function as the module will have it.
struct Plan {
    name: String,
    /// The definition's nodes with one Constant node per input, checked towards the
    /// outputs read.
    checked: CheckedGraph,
    /// The Constant nodes that are arguments, and the argument names.
    arguments: BTreeMap<NodeId, String>,
    /// The arguments' types, in order.
    argument_types: Vec<crate::graph::ValueType>,
    /// Per output pin: the node and output index that compute it, when it is read.
    outputs: Vec<Option<(NodeId, usize)>>,
    call: GroupCall,
}

/// The module of `graph` with a function per group it uses, or `None` where the
/// graph has no group node or has an image node, the module has parameter
/// slots, or a level does not check
/// on its own (the flattened module is then the one).
pub(super) fn compile(
    graph: &Graph,
    flat: &CheckedGraph,
    options: &CompileOptions,
) -> Option<Result<WgslModule, CompileError>> {
    // A graph with an image node compiles inlined: a group function cannot read
    // buffers, and a group's unused pins may hold cuts the flat graph prunes.
    // So does a graph whose nodes re-evaluate inputs: a local frame's function cannot
    // read the arguments of the group function around it.
    let samples = (graph.groups.values().flat_map(|group| &group.nodes))
        .chain(&graph.nodes)
        .any(|node| node.kind.samples() || node.kind.re_evaluates());
    if options.params.has_slots()
        || samples
        || !graph.nodes.iter().any(|n| group::group_name(n).is_some())
    {
        return None;
    }
    let interfaces = group::interfaces(&graph.groups).ok()?;
    let top = check_body(graph, &[graph.material()?.id]).ok()?;
    let named = options.params == ParamMode::Named;
    let mut sites: BTreeMap<String, Vec<Site>> = BTreeMap::new();
    gather_sites(&top, named.then_some(&flat.bindings), &mut sites);
    let mut plans = Vec::new();
    let mut names = Namer::default();
    for name in outermost_first(&graph.groups) {
        let Some(group_sites) = sites.get(&name) else {
            continue;
        };
        let plan = plan(
            &name,
            &graph.groups[&name],
            &interfaces[&name],
            group_sites,
            &mut names,
        )?;
        gather_sites(&plan.checked, None, &mut sites);
        plans.push(plan);
    }

    counts::emitted();
    let uses = SurfaceUse::of(flat);
    let members = if named {
        parameter_members(&flat.parameters)
    } else {
        Vec::new()
    };
    let mut emitter = Emitter::new(
        options.params,
        uses.detail(options.detail),
        &flat.parameters,
        &members,
    );
    emitter.mesh_lanes = uses.mesh_fields;
    for plan in &mut plans {
        let call = std::mem::replace(&mut plan.call, placeholder_call());
        emitter.calls.insert(plan.name.clone(), call);
    }
    plans.sort_by(|a, b| a.name.cmp(&b.name));
    let mut functions = String::from("\n// ---- node groups\n");
    for plan in &plans {
        functions.push_str(&function_text(plan, &mut emitter, &interfaces[&plan.name]));
    }
    let (blocks, _) = emitter.body(&top, &flat.bindings, &BTreeMap::new());
    let around = super::Around {
        functions: &functions,
        buffers: "",
        entry: super::parts::Entry::MATERIAL,
    };
    Some(assemble(flat, emitter, around, &blocks, uses))
}

/// A call with nothing in it, left where a plan's call was moved out.
fn placeholder_call() -> GroupCall {
    GroupCall {
        function: String::new(),
        returns: String::new(),
        arguments: Vec::new(),
        members: Vec::new(),
    }
}

/// Adds the group nodes of `level` to `sites`; `bindings` say which constants hold
/// exposed parameters (named mode, top level).
fn gather_sites(
    level: &CheckedGraph,
    bindings: Option<&Bindings>,
    sites: &mut BTreeMap<String, Vec<Site>>,
) {
    for checked in &level.order {
        let NodeKind::Group(group) = &checked.node.kind else {
            continue;
        };
        let bound = checked
            .signature
            .inputs
            .iter()
            .map(|pin| {
                bindings.is_some_and(|b| b.contains_key(&(checked.node.id, pin.name.to_string())))
            })
            .collect();
        sites.entry(group.name.clone()).or_default().push(Site {
            inputs: checked.inputs.clone(),
            bound,
            used: checked.used_outputs.clone(),
        });
    }
}

/// The groups, each before the groups it contains.
fn outermost_first(groups: &BTreeMap<String, GroupDef>) -> Vec<String> {
    let nesting = crate::graph::nesting::nesting(groups);
    nesting
        .order
        .iter()
        .rev()
        .map(|name| name.to_string())
        .collect()
}

/// The constant every site gives input `k`, if they all give the same one and none
/// binds a parameter there.
fn shared_constant(sites: &[Site], k: usize) -> Option<Value> {
    let mut shared: Option<Value> = None;
    for site in sites {
        match (&site.inputs[k], site.bound[k]) {
            (InputSource::Const(value), false) if shared.is_none_or(|s| s == *value) => {
                shared = Some(*value);
            }
            _ => return None,
        }
    }
    shared
}

/// The function of group `name` for its `sites`.
fn plan(
    name: &str,
    definition: &GroupDef,
    interface: &Interface,
    sites: &[Site],
    names: &mut Namer,
) -> Option<Plan> {
    let base = definition.nodes.iter().map(|n| n.id.0).max().unwrap_or(0) + 1;
    let input_node = |k: usize| NodeId(base + k as u32);
    let mut body = Graph {
        nodes: definition.nodes.clone(),
        ..Graph::default()
    };
    let mut argument_names = Namer::default();
    let mut arguments = BTreeMap::new();
    let mut argument_pins = Vec::new();
    let mut argument_types = Vec::new();
    for (k, entry) in interface.inputs.iter().enumerate() {
        let mut node = Node::new(
            input_node(k),
            NodeKind::Constant(Constant { ty: entry.input.ty }),
        );
        node.label = entry.input.name.clone();
        let value = shared_constant(sites, k).unwrap_or(entry.input.default);
        node.inputs
            .insert("value".into(), value.convert(entry.input.ty));
        if shared_constant(sites, k).is_none() {
            arguments.insert(node.id, argument_names.name(&entry.input.name, k as u32));
            argument_pins.push(k);
            argument_types.push(entry.input.ty);
        }
        body.nodes.push(node);
        if let Route::Inherited { node, pin } = &entry.route {
            body.wires.push(Wire {
                from: PinRef::new(input_node(k), "value"),
                to: PinRef::new(*node, pin),
            });
        }
    }
    let input_index = |pin: &str| interface.input_index(pin);
    let mut sources: BTreeMap<&str, PinRef> = BTreeMap::new();
    for wire in &definition.wires {
        let from = if wire.from.node == BOUNDARY {
            PinRef::new(input_node(input_index(&wire.from.pin)?), "value")
        } else {
            wire.from.clone()
        };
        if wire.to.node == BOUNDARY {
            sources.insert(&wire.to.pin, from);
        } else {
            body.wires.push(Wire {
                from,
                to: wire.to.clone(),
            });
        }
    }
    let read = |k: usize| {
        sites
            .iter()
            .any(|site| site.used.get(k).copied().unwrap_or(false))
    };
    let sinks: Vec<NodeId> = interface
        .outputs
        .iter()
        .enumerate()
        .filter(|(k, _)| read(*k))
        .map(|(_, output)| sources.get(output.name.as_str()).map(|source| source.node))
        .collect::<Option<_>>()?;
    let mut checked = check_body(&body, &sinks).ok()?;
    let outputs: Vec<Option<(NodeId, usize)>> = interface
        .outputs
        .iter()
        .enumerate()
        .map(|(k, output)| {
            let source = sources.get(output.name.as_str())?;
            let index = checked.index_of(source.node)?;
            let (pin, _) = checked.order[index].signature.output(&source.pin)?;
            read(k).then_some((source.node, pin))
        })
        .collect();
    // What the function returns is read too (a group node there needs those outputs).
    for (node, pin) in outputs.iter().flatten() {
        if let Some(index) = checked.index_of(*node) {
            checked.order[index].used_outputs[*pin] = true;
        }
    }
    let function = format!("veneer_group_{}", names.name(name, 0));
    let mut member_names = Namer::default();
    let members = outputs
        .iter()
        .zip(&interface.outputs)
        .map(|(source, output)| source.map(|_| member_names.name(&output.name, 0)))
        .collect();
    Some(Plan {
        name: name.to_string(),
        checked,
        arguments,
        argument_types,
        outputs,
        call: GroupCall {
            returns: format!("{function}_out"),
            function,
            arguments: argument_pins,
            members,
        },
    })
}

/// The struct and function of `plan`.
fn function_text(plan: &Plan, emitter: &mut Emitter, interface: &Interface) -> String {
    let (blocks, emitted) = emitter.body(&plan.checked, &Bindings::new(), &plan.arguments);
    let call = &emitter.calls[&plan.name];
    let mut fields = String::new();
    let mut values = Vec::new();
    for ((source, member), output) in plan
        .outputs
        .iter()
        .zip(&call.members)
        .zip(&interface.outputs)
    {
        let (Some((node, pin)), Some(member)) = (source, member) else {
            continue;
        };
        fields.push_str(&format!("    {member}: {},\n", output.ty.wgsl()));
        let index = plan.checked.index_of(*node).unwrap_or_default();
        let from = plan.checked.order[index].signature.outputs[*pin].ty;
        let expression = emitted[index]
            .outputs
            .get(*pin)
            .cloned()
            .unwrap_or_default();
        values.push(super::emit::convert(expression, from, output.ty));
    }
    let mut parameters = vec!["s: VeneerSurface".to_string()];
    let mut described = Vec::new();
    for (argument, ty) in plan.arguments.values().zip(&plan.argument_types) {
        parameters.push(format!("{argument}: {}", ty.wgsl()));
        described.push(argument.clone());
    }
    let mut text = format!(
        "\nstruct {} {{\n{fields}}}\n\n// Group '{}': arguments {}.\nfn {}({}) -> {} {{\n",
        call.returns,
        comment(&plan.name),
        if described.is_empty() {
            "none".to_string()
        } else {
            described.join(", ")
        },
        call.function,
        parameters.join(", "),
        call.returns
    );
    for block in &blocks {
        text.push_str(&block.text);
    }
    text.push_str(&format!(
        "    return {}({});\n}}\n",
        call.returns,
        values.join(", ")
    ));
    text
}
