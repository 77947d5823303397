//! MaterialX export, procedural tier: Veneer's node groups as MaterialX node graphs. The
//! nodes inlined from one top-level group node are translated into a node graph of their
//! own, which implements a node definition (`ND_veneer_group_<name>`) whose inputs are the
//! group's inputs and whose outputs are the group's outputs; the group node becomes one
//! instance of it in the document's node graph, its inputs reading what the group node
//! read there (an exposed parameter through the interface, so an override still reaches
//! it). Instances of one group whose translations are equal share one definition.

use super::network::{Input, Node, Source, input, node};
use super::{attribute, nodes_xml, output_xml};
use crate::graph::NodeId;
use std::fmt::Write;

/// What an input of a group's node definition holds when an instance does not set it.
#[derive(Clone, Debug, PartialEq)]
pub enum Default {
    /// A constant, as MaterialX writes it.
    Value(String),
    /// The shaded point's object-space position (`defaultgeomprop="Pobject"`).
    Position,
    /// The type's zero.
    Zero,
}

/// One input of a group's node graph: its name and type, what the instance gives it
/// (`input.source`, in the document's node graph), its default and span.
#[derive(Clone, Debug, PartialEq)]
pub struct GroupInput {
    pub input: Input,
    pub default: Default,
    pub range: Option<(f64, f64)>,
}

/// The nodes translated from one top-level group node, as a node graph.
#[derive(Clone, Debug, PartialEq)]
pub struct GroupGraph {
    /// The group's definition name in the Veneer graph.
    pub group: String,
    /// The group node's id in the Veneer graph.
    pub instance: NodeId,
    /// The instance's node name in the document's node graph.
    pub instance_name: String,
    /// The group node's label and place.
    pub ui: Option<(String, (f32, f32))>,
    pub nodes: Vec<Node>,
    pub inputs: Vec<GroupInput>,
    /// The outputs: name, type and the node inside that gives it.
    pub outputs: Vec<Input>,
    /// The node category of the definition it instantiates, once assigned (see
    /// [`assign_categories`]).
    pub category: String,
}

impl GroupGraph {
    /// An empty node graph for group node `instance` (of group `group`, named
    /// `instance_name` in the document's node graph).
    pub fn new(
        group: &str,
        instance: NodeId,
        instance_name: String,
        ui: Option<(String, (f32, f32))>,
    ) -> GroupGraph {
        GroupGraph {
            group: group.to_string(),
            instance,
            instance_name,
            ui,
            nodes: Vec::new(),
            inputs: Vec::new(),
            outputs: Vec::new(),
            category: String::new(),
        }
    }

    /// The input reading `outer` (a source in the document's node graph) as type `ty`,
    /// made when new (named `wanted`, or that with a number where the name is taken):
    /// the source the nodes inside read.
    pub fn input(
        &mut self,
        wanted: &str,
        ty: &'static str,
        outer: Source,
        default: Default,
        range: Option<(f64, f64)>,
    ) -> Source {
        if let Some(given) =
            (self.inputs.iter()).find(|given| given.input.source == outer && given.input.ty == ty)
        {
            return Source::Interface(given.input.name.clone());
        }
        let taken: Vec<&str> = (self.inputs.iter())
            .map(|given| given.input.name.as_str())
            .chain(self.outputs.iter().map(|output| output.name.as_str()))
            .collect();
        let name = unique(wanted, &taken);
        self.inputs.push(GroupInput {
            input: input(&name, ty, outer),
            default,
            range,
        });
        Source::Interface(name)
    }

    /// The output giving `inner` (a source inside) as type `ty`, made when new (named
    /// `wanted`, or that with a number where the name is taken): the source the
    /// document's node graph reads.
    pub fn output(&mut self, wanted: &str, ty: &'static str, inner: Source) -> Source {
        let name = match (self.outputs.iter()).find(|output| output.source == inner) {
            Some(output) => output.name.clone(),
            None => {
                let taken: Vec<&str> = (self.inputs.iter())
                    .map(|given| given.input.name.as_str())
                    .chain(self.outputs.iter().map(|output| output.name.as_str()))
                    .collect();
                let name = unique(wanted, &taken);
                self.outputs.push(input(&name, ty, inner));
                name
            }
        };
        Source::Output(self.instance_name.clone(), name)
    }

    /// The node type of an instance: its output's, or `multioutput`.
    fn ty(&self) -> &'static str {
        match self.outputs.as_slice() {
            [one] => one.ty,
            _ => "multioutput",
        }
    }

    /// The instance in the document's node graph.
    pub fn instance_node(&self) -> Node {
        let inputs = (self.inputs.iter())
            .map(|given| given.input.clone())
            .collect();
        let mut instance = node(
            &self.instance_name,
            &self.category,
            self.ty(),
            &format!("ND_{}", self.category),
            inputs,
        );
        instance.ui.clone_from(&self.ui);
        instance
    }

    /// Whether `other` translates to the same definition (nodes, inputs, outputs).
    fn same_definition(&self, other: &GroupGraph) -> bool {
        let signature = |graph: &GroupGraph| -> Vec<(String, &'static str, Default)> {
            (graph.inputs.iter())
                .map(|given| {
                    (
                        given.input.name.clone(),
                        given.input.ty,
                        given.default.clone(),
                    )
                })
                .collect()
        };
        self.group == other.group
            && self.nodes == other.nodes
            && self.outputs == other.outputs
            && signature(self) == signature(other)
    }

    /// The `<nodedef>` and the `<nodegraph>` implementing it.
    pub fn definition_xml(&self) -> String {
        let category = &self.category;
        let mut text = format!(
            "  <nodedef name=\"ND_{category}\" node=\"{category}\" nodegroup=\"procedural\" doc=\"{}\">\n",
            attribute(&format!("Veneer's group '{}'", self.group))
        );
        for given in &self.inputs {
            let default = match &given.default {
                Default::Value(value) => format!(" value=\"{}\"", attribute(value)),
                Default::Position => " defaultgeomprop=\"Pobject\"".to_string(),
                Default::Zero => String::new(),
            };
            let span = (given.range)
                .map(|(low, high)| format!(" uimin=\"{low}\" uimax=\"{high}\""))
                .unwrap_or_default();
            let _ = writeln!(
                text,
                "    <input name=\"{}\" type=\"{}\"{default}{span} />",
                given.input.name, given.input.ty
            );
        }
        for output in &self.outputs {
            let _ = writeln!(
                text,
                "    <output name=\"{}\" type=\"{}\" />",
                output.name, output.ty
            );
        }
        text.push_str("  </nodedef>\n");
        let _ = writeln!(
            text,
            "  <nodegraph name=\"NG_{category}\" nodedef=\"ND_{category}\">"
        );
        nodes_xml(&mut text, &self.nodes);
        for output in &self.outputs {
            output_xml(&mut text, output);
        }
        text.push_str("  </nodegraph>\n");
        text
    }
}

/// `wanted`, or `wanted_2`, `wanted_3`, … where `taken` has it.
fn unique(wanted: &str, taken: &[&str]) -> String {
    (1..)
        .map(|k| match k {
            1 => wanted.to_string(),
            k => format!("{wanted}_{k}"),
        })
        .find(|name| !taken.contains(&name.as_str()))
        .expect("a free name")
}

/// Gives each group graph the node category of its definition: `veneer_group_<group>`,
/// numbered where instances of one group translate differently (their unused outputs
/// left out, say).
pub fn assign_categories(graphs: &mut [GroupGraph]) {
    for k in 0..graphs.len() {
        let earlier = (0..k).find(|&j| graphs[j].same_definition(&graphs[k]));
        graphs[k].category = match earlier {
            Some(j) => graphs[j].category.clone(),
            None => {
                let base = format!("veneer_group_{}", super::element_name(&graphs[k].group));
                let taken: Vec<&str> = (graphs[..k].iter())
                    .map(|graph| graph.category.as_str())
                    .collect();
                unique(&base, &taken)
            }
        };
    }
}

/// Makes the document's node graph read an instance with one output as a node of that
/// output's type (by its name alone, as MaterialX wants of a single output): in its
/// `nodes`, the instances' inputs and the `sources` given.
pub fn name_single_outputs<'s>(
    graphs: &mut [GroupGraph],
    nodes: &mut [Node],
    sources: impl Iterator<Item = &'s mut Source>,
) {
    let single: Vec<String> = (graphs.iter())
        .filter(|graph| graph.outputs.len() == 1)
        .map(|graph| graph.instance_name.clone())
        .collect();
    let read = |source: &mut Source| {
        if let Source::Output(node, _) = source
            && single.contains(node)
        {
            *source = Source::Node(node.clone());
        }
    };
    let inputs = (nodes.iter_mut())
        .flat_map(|node| node.inputs.iter_mut())
        .chain(
            graphs
                .iter_mut()
                .flat_map(|graph| (graph.inputs.iter_mut()).map(|given| &mut given.input)),
        );
    inputs.for_each(|input| read(&mut input.source));
    sources.for_each(read);
}

/// The definitions `graphs` instantiate, each once, in order.
pub fn definitions(graphs: &[GroupGraph]) -> Vec<&GroupGraph> {
    let mut definitions: Vec<&GroupGraph> = Vec::new();
    for graph in graphs {
        if !definitions.iter().any(|d| d.category == graph.category) {
            definitions.push(graph);
        }
    }
    definitions
}
