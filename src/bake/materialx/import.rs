//! `veneer import`: a MaterialX document back into a graph, where that is cheap: documents
//! whose node graph holds standard nodes Veneer has an equal for (found by inverting
//! [`super::standard::standard`] over the registry's kinds, so the two directions cannot
//! disagree) and Veneer's own node definitions (their `doc` names the kind and its
//! settings). The procedural tier's documents come back as the graph they were made from:
//! its `veneer_<pin>` outputs give the material, its heads' `uiname`, `xpos` and `ypos`
//! the labels and places, the position chain the preview's placement. Anything else —
//! a node no kind means, a texture, a cycle — is an error naming the node and its line.

use super::network::Source;
use super::standard::standard;
use crate::graph::group::Hint;
use crate::graph::parameters::Parameter;
use crate::graph::{Graph, Node, NodeId, PinRef, Shading, Wire};
use crate::nodes::NodeKind;
use crate::nodes::pins::PinDefault;
use crate::nodes::value::Value;
use roxmltree::Node as Element;
use std::collections::BTreeMap;

/// What an input of a MaterialX node gives a Veneer pin.
#[derive(Clone, Debug)]
enum Feed {
    Constant(Value),
    /// Output `output` of a Veneer node.
    Wire(NodeId, usize),
    /// An interface input of the node graph (an exposed parameter), its value and span.
    Parameter(String, Value, Option<(f64, f64)>),
    /// The shaded point's position.
    Position,
    /// An input of the group whose node graph is being read.
    Boundary(String),
}

/// What a MaterialX node became.
#[derive(Clone, Debug)]
enum Made {
    /// A Veneer node, and per MaterialX output name its output index.
    Node(NodeId, Vec<String>),
    /// The position (the chain that places it, or a `position` node).
    Position,
    /// Passes its input on (a `convert`: Veneer converts where a wire needs it).
    Through(Feed),
}

/// Reads the MaterialX document `text` (named `file` in messages) as a graph.
pub fn import(text: &str, file: &str) -> Result<Graph, String> {
    let document = roxmltree::Document::parse(text).map_err(|error| {
        let at = error.pos();
        format!("{file}:{}:{}: not XML: {error}", at.row, at.col)
    })?;
    let root = document.root_element();
    let at = |element: Element| {
        let position = document.text_pos_at(element.range().start);
        format!("{file}:{}:{}", position.row, position.col)
    };
    if root.tag_name().name() != "materialx" {
        return Err(format!(
            "{}: not a MaterialX document (its root is <{}>)",
            at(root),
            root.tag_name().name()
        ));
    }
    let shader = surface_shader(root);
    let graph_name = shader.and_then(|shader| {
        children(shader)
            .into_iter()
            .find_map(|input| input.attribute("nodegraph"))
    });
    let node_graph = (children(root).into_iter())
        .find(|e| {
            e.tag_name().name() == "nodegraph"
                && graph_name.is_none_or(|name| e.attribute("name") == Some(name))
        })
        .ok_or_else(|| format!("{}: the document has no node graph to import", at(root)))?;
    let mut importer = Importer::new(definitions(root), group_definitions(root), &at, None);
    for element in children(node_graph) {
        let name = element.attribute("name").unwrap_or_default().to_string();
        match element.tag_name().name() {
            "input" => {
                let value = value_of(element).map_err(|e| format!("{}: {e}", at(element)))?;
                let bound = |attribute| element.attribute(attribute)?.parse::<f64>().ok();
                let range = bound("uimin").zip(bound("uimax"));
                importer.interface.insert(name, (value, range));
            }
            "output" => {}
            _ => {
                if importer.elements.insert(name.clone(), element).is_some() {
                    return Err(format!("{}: two nodes are named '{name}'", at(element)));
                }
            }
        }
    }
    importer.next_id = 1
        + (importer.elements.keys())
            .filter_map(|name| exported_id(name))
            .max()
            .unwrap_or(0);
    // The material: from the `veneer_<pin>` outputs, else from what the surface reads.
    let outputs: Vec<Element> = (children(node_graph).into_iter())
        .filter(|e| e.tag_name().name() == "output")
        .collect();
    let material_pins = NodeKind::Material.definition().signature().inputs;
    let mut roots: Vec<(&'static str, Element)> = (material_pins.iter())
        .filter_map(|pin| {
            let name = format!("veneer_{}", pin.name);
            let output = outputs
                .iter()
                .find(|o| o.attribute("name") == Some(name.as_str()))?;
            Some((pin.name, *output))
        })
        .collect();
    let veneer_outputs = !roots.is_empty();
    let mut shading = Shading::MetallicRoughness;
    let mut constants = Vec::new();
    if let Some(shader) = shader {
        let from_surface = |input: Element| {
            let output = input.attribute("output")?;
            outputs
                .iter()
                .find(|o| o.attribute("name") == Some(output))
                .copied()
        };
        for input in children(shader) {
            let pin = match input.attribute("name").unwrap_or_default() {
                "base_color" => "albedo",
                "specular_roughness" | "roughness" => "roughness",
                "base_metalness" | "metallic" | "metalness" => "metallic",
                "emission_color" | "emissive" => "emission",
                _ => continue,
            };
            let Some(output) = from_surface(input) else {
                if let (false, Ok(value)) = (veneer_outputs, value_of(input)) {
                    constants.push((pin, Feed::Constant(value)));
                }
                continue;
            };
            // A Blinn-Phong material's display values are made linear for the surface.
            let reads = output
                .attribute("nodename")
                .and_then(|n| importer.elements.get(n));
            if pin == "albedo"
                && reads.is_some_and(|e| e.tag_name().name() == "srgb_texture_to_lin_rec709")
            {
                shading = Shading::BlinnPhong;
            }
            if !veneer_outputs && !roots.iter().any(|(root, _)| *root == pin) {
                roots.push((pin, output));
            }
        }
    }
    if roots.is_empty() && constants.is_empty() {
        return Err(format!(
            "{}: nothing in the node graph reaches a material",
            at(node_graph)
        ));
    }
    let mut feeds = Vec::new();
    for (pin, feed) in constants {
        feeds.push((
            material_pins
                .iter()
                .find(|p| p.name == pin)
                .expect("a material pin"),
            feed,
        ));
    }
    for (pin, output) in roots {
        let pin = material_pins
            .iter()
            .find(|p| p.name == pin)
            .expect("a material pin");
        if let Some(feed) = importer.feed(output) {
            feeds.push((pin, feed));
        }
    }
    // The material takes the first id no node has (where the export's material was, when
    // the graph's ids were dense).
    let material = (1..)
        .map(NodeId)
        .find(|id| !importer.graph.nodes.iter().any(|node| node.id == *id))
        .expect("a free id");
    let mut node = Node::new(material, NodeKind::Material);
    node.label = "material".into();
    if let Some(shader) = shader {
        let place = |attribute| shader.attribute(attribute)?.parse::<f32>().ok();
        node.label = shader.attribute("uiname").unwrap_or("material").to_string();
        node.position = place("xpos").zip(place("ypos")).unwrap_or_default();
    }
    importer.graph.nodes.push(node);
    for (pin, feed) in feeds {
        importer.connect(material, pin, feed);
    }
    if !importer.errors.is_empty() {
        return Err(importer.errors.join("\n"));
    }
    let mut graph = importer.graph;
    crate::graph::group::resolve(&mut graph);
    let exposed = crate::graph::parameters::exposed(&graph);
    graph.name = (children(root).into_iter())
        .find(|e| e.tag_name().name() == "surfacematerial")
        .and_then(|e| e.attribute("uiname").or(e.attribute("name")))
        .unwrap_or("imported")
        .to_string();
    graph.shading = shading;
    // The presets: each variant's values of interface inputs the graph reads.
    for variant in children(root)
        .into_iter()
        .filter(|e| e.tag_name().name() == "variantset")
        .flat_map(children)
    {
        let name = variant.attribute("name").unwrap_or_default().to_string();
        let values = (children(variant).into_iter())
            .filter_map(|input| Some((input.attribute("name")?.to_string(), value_of(input).ok()?)))
            .filter(|(parameter, _)| exposed.iter().any(|p| &p.name == parameter))
            .collect();
        graph.presets.insert(name, values);
    }
    // A document from elsewhere places no node: lay them out.
    if graph.nodes.iter().all(|node| node.position == (0.0, 0.0)) {
        crate::graph::layout::arrange(&mut graph);
    }
    crate::graph::check(&graph).map_err(|errors| {
        let messages: Vec<String> = errors.iter().map(ToString::to_string).collect();
        format!(
            "{file}: the imported graph does not check: {}",
            messages.join("; ")
        )
    })?;
    Ok(graph)
}

/// The node id a name the procedural tier wrote ends with (`rings_12`).
fn exported_id(name: &str) -> Option<u32> {
    name.rsplit_once('_')?.1.parse().ok()
}

/// The child elements of `element`.
fn children<'a, 'i>(element: Element<'a, 'i>) -> Vec<Element<'a, 'i>> {
    element.children().filter(Element::is_element).collect()
}

/// The surface shader the document's material reads, if any.
fn surface_shader<'a, 'i>(root: Element<'a, 'i>) -> Option<Element<'a, 'i>> {
    let material = root
        .children()
        .find(|e| e.tag_name().name() == "surfacematerial")?;
    let name = material
        .children()
        .find_map(|input| input.attribute("nodename"))?;
    root.children().find(|e| e.attribute("name") == Some(name))
}

/// Veneer's own definitions in the document: node category → kind (their `doc` ends with
/// the kind's settings as graph files write them) and its output names.
fn definitions(root: Element) -> BTreeMap<String, (NodeKind, Vec<String>)> {
    (root.children())
        .filter(|e| e.tag_name().name() == "nodedef")
        .filter_map(|nodedef| {
            let category = nodedef.attribute("node")?;
            let settings = nodedef.attribute("doc")?.split_once(" node: ")?.1;
            let kind: NodeKind = ron::from_str(settings).ok()?;
            let outputs = (nodedef.children())
                .filter(|e| e.tag_name().name() == "output")
                .filter_map(|e| e.attribute("name").map(str::to_string))
                .collect();
            Some((category.to_string(), (kind, outputs)))
        })
        .collect()
}

/// The value an element (an input) holds, by its MaterialX type.
fn value_of(element: Element) -> Result<Value, String> {
    let text = element.attribute("value").ok_or("it has no value")?;
    let ty = element.attribute("type").unwrap_or_default();
    let numbers: Result<Vec<f64>, _> = text.split(',').map(|n| n.trim().parse::<f64>()).collect();
    let numbers = numbers.map_err(|_| format!("'{text}' is not a {ty}"))?;
    match (ty, numbers.as_slice()) {
        ("float", [x]) => Ok(Value::Float(*x)),
        ("vector2", [x, y]) => Ok(Value::Vec2(*x, *y)),
        ("vector3", [x, y, z]) => Ok(Value::Vec3(*x, *y, *z)),
        ("color3", [r, g, b]) => Ok(Value::Color(*r, *g, *b)),
        _ => Err(format!("a {ty} of '{text}' has no Veneer value")),
    }
}

/// The document's node definitions implemented by a node graph (Veneer's groups):
/// node category → the definition and its node graph.
fn group_definitions<'a, 'i>(
    root: Element<'a, 'i>,
) -> BTreeMap<String, (Element<'a, 'i>, Element<'a, 'i>)> {
    let elements = children(root);
    (elements.iter())
        .filter(|e| e.tag_name().name() == "nodegraph")
        .filter_map(|graph| {
            let nodedef = graph.attribute("nodedef")?;
            let definition = (elements.iter()).find(|e| {
                e.tag_name().name() == "nodedef" && e.attribute("name") == Some(nodedef)
            })?;
            Some((
                definition.attribute("node")?.to_string(),
                (*definition, *graph),
            ))
        })
        .collect()
}

/// Whether a node definition's input is the shaded point's position.
fn is_position(input: Element) -> bool {
    input.attribute("defaultgeomprop") == Some("Pobject")
}

struct Importer<'a, 'i, 'f> {
    definitions: BTreeMap<String, (NodeKind, Vec<String>)>,
    /// Node graphs implementing definitions (groups), by node category.
    group_definitions: BTreeMap<String, (Element<'a, 'i>, Element<'a, 'i>)>,
    /// The group whose node graph this reads (its interface inputs are the group's), or
    /// none for the document's own node graph.
    group: Option<String>,
    /// The group's inputs that are the shaded point's position.
    position_inputs: Vec<String>,
    elements: BTreeMap<String, Element<'a, 'i>>,
    interface: BTreeMap<String, (Value, Option<(f64, f64)>)>,
    made: BTreeMap<String, Made>,
    /// The nodes being made, to find cycles.
    visiting: Vec<String>,
    graph: Graph,
    errors: Vec<String>,
    at: &'f dyn Fn(Element) -> String,
    next_id: u32,
}

impl<'a, 'i, 'f> Importer<'a, 'i, 'f> {
    /// An importer of a node graph: the document's (`group` none) or a group's.
    fn new(
        definitions: BTreeMap<String, (NodeKind, Vec<String>)>,
        group_definitions: BTreeMap<String, (Element<'a, 'i>, Element<'a, 'i>)>,
        at: &'f dyn Fn(Element) -> String,
        group: Option<String>,
    ) -> Self {
        Importer {
            definitions,
            group_definitions,
            group,
            position_inputs: Vec::new(),
            elements: BTreeMap::new(),
            interface: BTreeMap::new(),
            made: BTreeMap::new(),
            visiting: Vec::new(),
            graph: Graph::default(),
            errors: Vec::new(),
            at,
            next_id: 1,
        }
    }

    /// What input (or output) `element` feeds a pin.
    fn feed(&mut self, element: Element<'a, 'i>) -> Option<Feed> {
        if let Some(name) = element.attribute("interfacename") {
            if self.group.is_some() && self.interface.contains_key(name) {
                return Some(Feed::Boundary(name.to_string()));
            }
            if self.position_inputs.iter().any(|input| input == name) {
                return Some(Feed::Position);
            }
            let Some((value, range)) = self.interface.get(name) else {
                let at = (self.at)(element);
                self.errors.push(format!(
                    "{at}: reads '{name}', which the node graph's interface does not have"
                ));
                return None;
            };
            return Some(Feed::Parameter(name.to_string(), *value, *range));
        }
        if let Some(name) = element.attribute("nodename") {
            let made = self.make(name, element)?;
            return match made {
                Made::Position => Some(Feed::Position),
                Made::Through(feed) => Some(feed),
                Made::Node(id, outputs) => {
                    let index = match element.attribute("output") {
                        None => Some(0),
                        Some(output) => outputs.iter().position(|o| o == output),
                    };
                    let Some(index) = index else {
                        let output = element.attribute("output").unwrap_or_default();
                        let at = (self.at)(element);
                        self.errors.push(format!(
                            "{at}: reads output '{output}' of node '{name}', which has {}",
                            outputs.join(", ")
                        ));
                        return None;
                    };
                    Some(Feed::Wire(id, index))
                }
            };
        }
        match value_of(element) {
            Ok(value) => Some(Feed::Constant(value)),
            Err(error) => {
                self.errors.push(format!("{}: {error}", (self.at)(element)));
                None
            }
        }
    }

    /// The input `name` of `element`'s node.
    fn input(&self, element: Element<'a, 'i>, name: &str) -> Option<Element<'a, 'i>> {
        element
            .children()
            .find(|e| e.tag_name().name() == "input" && e.attribute("name") == Some(name))
    }

    /// Node `name` (read by `reader`), made once.
    fn make(&mut self, name: &str, reader: Element<'a, 'i>) -> Option<Made> {
        if let Some(made) = self.made.get(name) {
            return Some(made.clone());
        }
        if let Some(start) = self.visiting.iter().position(|n| n == name) {
            let mut cycle = self.visiting[start..].to_vec();
            cycle.push(name.to_string());
            self.errors.push(format!(
                "{}: the nodes form a cycle: {}",
                (self.at)(reader),
                cycle.join(" → ")
            ));
            return None;
        }
        let Some(&element) = self.elements.get(name) else {
            self.errors.push(format!(
                "{}: reads node '{name}', which the node graph does not have",
                (self.at)(reader)
            ));
            return None;
        };
        self.visiting.push(name.to_string());
        let made = self.make_new(name, element);
        self.visiting.pop();
        if let Some(made) = &made {
            self.made.insert(name.to_string(), made.clone());
        }
        made
    }

    fn make_new(&mut self, name: &str, element: Element<'a, 'i>) -> Option<Made> {
        let category = element.tag_name().name();
        let ty = element.attribute("type").unwrap_or_default();
        let first = |importer: &mut Self, input: &str| {
            let input = importer.input(element, input)?;
            importer.feed(input)
        };
        match category {
            "position" => return Some(Made::Position),
            "convert" => return first(self, "in").map(Made::Through),
            // A material value the export gave a node of its own (a constant, a parameter).
            "constant" if name.starts_with("material_") => {
                return first(self, "value").map(Made::Through);
            }
            // The position placed as the preview places the mesh.
            "multiply" | "add" if ty == "vector3" => {
                if let (Some(Feed::Position), Some(Feed::Constant(value))) =
                    (first(self, "in1"), first(self, "in2"))
                {
                    let [x, y, z] = value.components();
                    match category {
                        "multiply" => self.graph.preview.size = x,
                        _ => self.graph.preview.center = (x, y, z),
                    }
                    return Some(Made::Position);
                }
            }
            _ => {}
        }
        if category == "dot" {
            // A Position node's own `dot` reads the placed position: take the placement.
            let _ = first(self, "in");
        }
        // So does a group node's position input.
        if let Some(&(definition, _)) = self.group_definitions.get(category) {
            for position in children(definition).into_iter().filter(|e| is_position(*e)) {
                let _ = first(self, position.attribute("name").unwrap_or_default());
            }
        }
        let found = match self.group_definitions.get(category) {
            Some(&(definition, graph)) => self.import_group(category, definition, graph),
            None => self.kind_of(element),
        };
        let (kind, outputs, mx_inputs) = match found {
            Some(found) => found,
            None => {
                let at = (self.at)(element);
                self.errors.push(format!("{at}: node '{name}' (`{category}`, {ty}) has no Veneer equal: import reads standard nodes Veneer has and Veneer's own definitions"));
                return None;
            }
        };
        let id = exported_id(name)
            .filter(|id| !self.graph.nodes.iter().any(|n| n.id.0 == *id))
            .map(NodeId)
            .unwrap_or_else(|| {
                self.next_id += 1;
                NodeId(self.next_id - 1)
            });
        let mut node = Node::new(id, kind);
        node.label = element.attribute("uiname").unwrap_or(name).to_string();
        let place = |attribute| {
            element
                .attribute(attribute)
                .and_then(|v: &str| v.parse::<f32>().ok())
        };
        node.position = (place("xpos").unwrap_or(0.0), place("ypos").unwrap_or(0.0));
        self.graph.nodes.push(node);
        // A group node's pins are its definition's.
        crate::graph::group::resolve(&mut self.graph);
        let kind = &self.graph.nodes.last().expect("just pushed").kind;
        let pins = kind.definition().signature().inputs;
        for (pin, mx_input) in pins.iter().zip(mx_inputs) {
            let Some(input) = mx_input.and_then(|name| self.input(element, &name)) else {
                continue;
            };
            if let Some(feed) = self.feed(input) {
                self.connect(id, pin, feed);
            }
        }
        Some(Made::Node(id, outputs))
    }

    /// The kind `element` is, its MaterialX output names by Veneer output, and per input pin
    /// the MaterialX input feeding it (none: the pin keeps its default).
    #[allow(clippy::type_complexity)]
    fn kind_of(&self, element: Element) -> Option<(NodeKind, Vec<String>, Vec<Option<String>>)> {
        let category = element.tag_name().name();
        if let Some((kind, outputs)) = self.definitions.get(category) {
            let pins = kind.definition().signature().inputs;
            let inputs = pins.iter().map(|pin| Some(pin.name.to_string())).collect();
            return Some((kind.clone(), outputs.clone(), inputs));
        }
        if category == "dot" {
            let reads_position = self
                .input(element, "in")
                .and_then(|i| i.attribute("nodename"))
                .is_some_and(|n| {
                    self.elements.get(n).is_some_and(|e| {
                        matches!(e.tag_name().name(), "position" | "add" | "multiply")
                    })
                });
            if reads_position {
                return Some((NodeKind::Position, vec!["out".into()], Vec::new()));
            }
        }
        // The standard translation of every kind the registry knows, inverted; of the
        // kinds that match, the one fixing most inputs (`subtract` from 0 is a negation).
        let ty = element.attribute("type").unwrap_or_default();
        let matches = super::standard::kinds().iter().filter_map(|kind| {
            let pins = kind.definition().signature().inputs;
            let markers: Vec<Source> = (0..pins.len())
                .map(|k| Source::Value(format!("#{k}")))
                .collect();
            let translated = standard(kind, "probe", &markers)?;
            let [node] = translated.nodes.as_slice() else {
                return None;
            };
            if node.category != category || node.ty != ty {
                return None;
            }
            let mut inputs = vec![None; pins.len()];
            let mut fixed = 0;
            for input in &node.inputs {
                match &input.source {
                    Source::Value(text) if text.starts_with('#') => {
                        inputs[text[1..].parse::<usize>().ok()?] = Some(input.name.clone());
                    }
                    Source::Value(fixed_value) => {
                        let given = self.input(element, &input.name)?.attribute("value")?;
                        let numbers = |text: &str| -> Vec<f64> {
                            text.split(',')
                                .filter_map(|n| n.trim().parse().ok())
                                .collect()
                        };
                        if numbers(given) != numbers(fixed_value) {
                            return None;
                        }
                        fixed += 1;
                    }
                    _ => return None,
                }
            }
            let outputs = (translated.outputs.iter())
                .map(|output| match output {
                    Source::Output(_, name) => name.clone(),
                    _ => "out".to_string(),
                })
                .collect();
            Some((fixed, (kind, outputs, inputs)))
        });
        (matches.min_by_key(|(fixed, _)| std::cmp::Reverse(*fixed)))
            .map(|(_, (kind, outputs, inputs))| (kind.clone(), outputs, inputs))
    }

    /// Output `index` of node `id` made already.
    fn output_pin(&self, id: NodeId, index: usize) -> Option<crate::nodes::pins::OutputPin> {
        let node = self.graph.nodes.iter().find(|node| node.id == id)?;
        node.kind
            .definition()
            .signature()
            .outputs
            .get(index)
            .cloned()
    }

    /// Pin `pin` of node `id` fed by `feed`: a wire, a constant where it is not the
    /// default, a parameter, or nothing for the position where that is the default.
    fn connect(&mut self, id: NodeId, pin: &crate::nodes::pins::InputPin, feed: Feed) {
        let value = match feed {
            Feed::Wire(from, output) => {
                let Some(output) = self.output_pin(from, output) else {
                    return;
                };
                self.graph.wires.push(Wire {
                    from: PinRef::new(from, output.name),
                    to: PinRef::new(id, pin.name),
                });
                return;
            }
            Feed::Boundary(name) => {
                self.graph.wires.push(Wire {
                    from: PinRef::new(crate::graph::group::BOUNDARY, &name),
                    to: PinRef::new(id, pin.name),
                });
                return;
            }
            Feed::Position if pin.default == PinDefault::Position => return,
            Feed::Position => {
                let position = self.position_node();
                self.graph.wires.push(Wire {
                    from: PinRef::new(position, "position"),
                    to: PinRef::new(id, pin.name),
                });
                return;
            }
            // A group node's unwired inputs are exposed parameters already.
            Feed::Parameter(_, value, _) if self.is_group_node(id) => value,
            Feed::Parameter(name, value, range) => {
                // A colour is picked with a colour picker, anything else with sliders.
                let hint = match pin.ty {
                    crate::nodes::value::ValueType::Color => Hint::Colour,
                    _ => Hint::default(),
                };
                self.graph.parameters.push(Parameter {
                    name,
                    node: id,
                    pin: pin.name.to_string(),
                    range,
                    hint,
                });
                value
            }
            Feed::Constant(value) => value,
        };
        let value = value.convert(pin.ty);
        if pin.default != PinDefault::Const(value) {
            if let Some(node) = self.graph.nodes.iter_mut().find(|n| n.id == id) {
                node.inputs.insert(pin.name.to_string(), value);
            }
        }
    }

    /// Whether node `id` is a group node.
    fn is_group_node(&self, id: NodeId) -> bool {
        (self.graph.nodes.iter())
            .any(|node| node.id == id && matches!(node.kind, NodeKind::Group(_)))
    }

    /// The group that node definition `definition` (node `category`) implemented by
    /// `graph` stands for, read into the graph's groups once (named after the group its
    /// `doc` names, else the category): its node kind, output names and, per input pin,
    /// the input feeding it.
    #[allow(clippy::type_complexity)]
    fn import_group(
        &mut self,
        category: &str,
        definition: Element<'a, 'i>,
        graph: Element<'a, 'i>,
    ) -> Option<(NodeKind, Vec<String>, Vec<Option<String>>)> {
        let name = (definition.attribute("doc"))
            .and_then(|doc| doc.strip_prefix("Veneer's group '")?.strip_suffix('\''))
            .unwrap_or(category)
            .to_string();
        let declared = children(definition);
        let outputs: Vec<String> = (declared.iter())
            .filter(|e| e.tag_name().name() == "output")
            .filter_map(|e| e.attribute("name").map(str::to_string))
            .collect();
        let (positions, inputs): (Vec<Element>, Vec<Element>) = (declared.iter())
            .filter(|e| e.tag_name().name() == "input")
            .partition(|e| is_position(**e));
        let kind = NodeKind::Group(crate::nodes::Group::named(name.clone()));
        let pins = inputs
            .iter()
            .map(|e| e.attribute("name").map(str::to_string));
        let found = (kind.clone(), outputs.clone(), pins.collect());
        if self.graph.groups.contains_key(&name) {
            return Some(found);
        }
        if self.group.as_deref() == Some(name.as_str()) {
            let at = (self.at)(graph);
            self.errors
                .push(format!("{at}: group '{name}' contains itself"));
            return None;
        }
        let mut inner = Importer::new(
            self.definitions.clone(),
            self.group_definitions.clone(),
            self.at,
            Some(name.clone()),
        );
        inner.position_inputs = (positions.iter())
            .filter_map(|e| e.attribute("name").map(str::to_string))
            .collect();
        let mut group = crate::graph::group::GroupDef {
            linked: false,
            inputs: Vec::new(),
            outputs: Vec::new(),
            nodes: Vec::new(),
            wires: Vec::new(),
        };
        for input in inputs {
            let input_name = input.attribute("name").unwrap_or_default().to_string();
            let value = match value_of(input) {
                Ok(value) => value,
                Err(error) => {
                    self.errors.push(format!("{}: {error}", (self.at)(input)));
                    return None;
                }
            };
            let bound = |attribute| input.attribute(attribute)?.parse::<f64>().ok();
            let range = bound("uimin").zip(bound("uimax"));
            inner.interface.insert(input_name.clone(), (value, range));
            group.inputs.push(crate::graph::group::GroupInput {
                name: input_name,
                ty: value.ty(),
                default: value,
                range,
                hint: match value.ty() {
                    crate::nodes::value::ValueType::Color => Hint::Colour,
                    _ => Hint::default(),
                },
            });
        }
        for element in children(graph) {
            if !matches!(element.tag_name().name(), "input" | "output") {
                let element_name = element.attribute("name").unwrap_or_default().to_string();
                inner.elements.insert(element_name, element);
            }
        }
        inner.next_id = 1
            + (inner.elements.keys())
                .filter_map(|n| exported_id(n))
                .max()
                .unwrap_or(0);
        for output in children(graph)
            .into_iter()
            .filter(|e| e.tag_name().name() == "output")
        {
            let output_name = output.attribute("name").unwrap_or_default().to_string();
            match inner.feed(output) {
                Some(Feed::Wire(from, index)) => {
                    let Some(pin) = inner.output_pin(from, index) else {
                        continue;
                    };
                    group.outputs.push(crate::graph::group::GroupOutput {
                        name: output_name.clone(),
                        ty: pin.ty,
                    });
                    inner.graph.wires.push(Wire {
                        from: PinRef::new(from, pin.name),
                        to: PinRef::new(crate::graph::group::BOUNDARY, &output_name),
                    });
                }
                Some(_) => inner.errors.push(format!(
                    "{}: output '{output_name}' of group '{name}' reads no node",
                    (self.at)(output)
                )),
                None => {}
            }
        }
        self.errors.append(&mut inner.errors);
        self.graph.groups.append(&mut inner.graph.groups);
        group.nodes = inner.graph.nodes;
        group.wires = inner.graph.wires;
        group.canonicalize();
        self.graph.groups.insert(name, group);
        Some(found)
    }

    /// A Position node for pins that read the position without defaulting to it.
    fn position_node(&mut self) -> NodeId {
        if let Some(node) = self
            .graph
            .nodes
            .iter()
            .find(|n| n.kind == NodeKind::Position)
        {
            return node.id;
        }
        let id = NodeId(self.next_id);
        self.next_id += 1;
        let mut node = Node::new(id, NodeKind::Position);
        node.label = "position".into();
        self.graph.nodes.push(node);
        id
    }
}
