//! MaterialX export, procedural tier: the checked graph (groups inlined) translated node
//! by node into one node graph, every kind the standard library means the same thing as
//! written with standard nodes ([`super::standard`]), every other one that is a function
//! of its inputs alone as a node definition of Veneer's own ([`super::custom`]); the
//! graph's exposed parameters become the node graph's interface inputs, so an override
//! (`--set`) survives as a material parameter. The material's outputs are wired into the
//! surface as the baked tier wires its maps, except the shading normal, which Veneer
//! takes from the height across neighbouring texels: that one map is baked.

use super::custom::{CustomDef, mx_type};
use super::groups::{Default, GroupGraph};
use super::network::{
    Input, Network, Node, Source, SurfaceFields, SurfaceModel, input, node, wire,
};
use super::standard::{Translated, standard};
use crate::bitmaps::linear_to_srgb;
use crate::codegen::AlphaUse;
use crate::graph::check::{CheckedGraph, InputSource};
use crate::graph::group::{BOUNDARY, GroupSource};
use crate::graph::{NodeId, Preview, Shading};
use crate::nodes::NodeKind;
use crate::nodes::pins::{InputPin, PinDefault};
use crate::nodes::value::{Value, ValueType};
use std::collections::BTreeMap;

/// A graph translated into MaterialX: the network and the definitions its nodes use.
pub struct Procedural {
    pub network: Network,
    /// Veneer's own node definitions, each once, in the order first used.
    pub definitions: Vec<CustomDef>,
    /// The nodes reading the mesh's fields, each read from a texture to bake.
    pub baked: Vec<BakedNode>,
    /// Files the document reads that the translation made (the Image nodes' bitmaps),
    /// by name beside the document.
    pub files: Vec<(String, Vec<u8>)>,
    /// The top-level group nodes' node graphs, their categories assigned.
    pub groups: Vec<GroupGraph>,
}

/// An output of a node that the document reads from a texture: a distance or mesh field
/// (over the preview mesh's UV layout), or under `--tier auto` a node that does not
/// translate (over the preview square), baked as float.
#[derive(Clone, Debug)]
pub struct BakedNode {
    /// The node and everything upstream of it, the output wired into the albedo of a
    /// material of its own.
    pub graph: crate::graph::Graph,
    /// The texture's file name, beside the document.
    pub file: String,
}

/// A node the procedural tier cannot translate: its name in messages and why.
#[derive(Clone, Debug, PartialEq)]
pub struct Untranslatable {
    pub node: String,
    pub reason: String,
}

impl std::fmt::Display for Untranslatable {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "node '{}' {}", self.node, self.reason)
    }
}

/// The node giving Veneer's position of the shaded point in the document's node graph.
const POSITION: &str = "surface_position";

/// The name of the extra node graph output giving the material's albedo as Veneer
/// computes it (before a Blinn-Phong material's display values are made linear), so the
/// pattern can be checked against `veneer render --flat`.
pub const ALBEDO_OUTPUT: &str = "veneer_albedo";

/// The graph's nodes as MaterialX nodes, as they are translated.
struct Translator<'g> {
    graph: &'g CheckedGraph,
    /// Where the surface sits in texture space: Veneer's position is the object's
    /// times `size` plus `center`.
    placement: ([f64; 3], f64),
    /// The document's file stem, which baked textures' names start with.
    stem: &'g str,
    /// The preview (mesh, fields, placement) and the graph's folder, which baked
    /// textures' graphs keep.
    preview: &'g Preview,
    folder: &'g crate::graph::Folder,
    /// Whether a node that does not translate is baked into textures (`--tier auto`)
    /// rather than reported.
    bake_untranslatable: bool,
    /// The graph's groups before inlining.
    groups: &'g GroupSource,
    baked: Vec<BakedNode>,
    files: Vec<(String, Vec<u8>)>,
    /// The nodes of the document's node graph.
    nodes: Vec<Node>,
    /// The nodes inlined from each top-level group node, as a node graph, by its id.
    parts: BTreeMap<NodeId, GroupGraph>,
    definitions: Vec<CustomDef>,
    /// What gives each output of each translated node.
    outputs: BTreeMap<NodeId, Vec<Source>>,
    /// The exposed parameters read, by element name: type and value, and span.
    interface: BTreeMap<String, (Input, Option<(f64, f64)>)>,
    untranslatable: Vec<Untranslatable>,
}

impl Translator<'_> {
    /// The top-level group node whose node graph node `id` goes into, if any.
    fn owner(&self, id: NodeId) -> Option<NodeId> {
        let k = self.graph.index_of(id)?;
        let origin = self.graph.order[k].node.origin.as_ref()?;
        self.groups
            .instances
            .contains_key(&origin.top)
            .then_some(origin.top)
    }

    /// The node graph of top-level group node `instance`, made when first met.
    fn part(&mut self, instance: NodeId) -> &mut GroupGraph {
        let groups = self.groups;
        self.parts.entry(instance).or_insert_with(|| {
            let node = &groups.instances[&instance];
            let group = crate::graph::group::group_name(node).unwrap_or_default();
            let label = match node.label.is_empty() {
                true => group,
                false => node.label.as_str(),
            };
            let name = format!("{}_{}", super::element_name(label), instance.0);
            let ui = Some((node.label.clone(), node.position));
            GroupGraph::new(group, instance, name, ui)
        })
    }

    /// Where the nodes of `owner` (a top-level group node, or none) go.
    fn nodes_of(&mut self, owner: Option<NodeId>) -> &mut Vec<Node> {
        match owner {
            Some(instance) => &mut self.part(instance).nodes,
            None => &mut self.nodes,
        }
    }

    /// The group definition node `id` sits directly in (not in a group nested in it),
    /// with its id there.
    fn definition_of(&self, id: NodeId) -> Option<(&crate::graph::group::GroupDef, NodeId)> {
        let k = self.graph.index_of(id)?;
        let origin = self.graph.order[k].node.origin.as_ref()?;
        if origin.groups.instances().len() != 1 {
            return None;
        }
        let definition = self.groups.definitions.get(&origin.definition)?;
        Some((definition, origin.id))
    }

    /// The name of the group output that output `output` of node `id` gives: the
    /// definition's, where a wire takes it to the group's boundary, else the node's
    /// name and the pin's.
    fn group_output_name(&self, id: NodeId, output: usize) -> String {
        let k = self.graph.index_of(id).expect("a checked node");
        let checked = &self.graph.order[k];
        let pin = checked.signature.outputs[output].name;
        let declared = self.definition_of(id).and_then(|(definition, inner)| {
            (definition.wires.iter())
                .find(|w| w.from.node == inner && w.from.pin == pin && w.to.node == BOUNDARY)
                .map(|w| w.to.pin.clone())
        });
        declared.unwrap_or_else(|| format!("{}_{pin}", node_label(&checked.node)))
    }

    /// The name of the group input that pin `pin` of node `id` (named `name` in the
    /// document) reads: the definition's, where a wire brings it from the group's
    /// boundary, else the node's name and the pin's.
    fn group_input_name(&self, id: NodeId, name: &str, pin: &str) -> String {
        let declared = self.definition_of(id).and_then(|(definition, inner)| {
            (definition.wires.iter())
                .find(|w| w.to.node == inner && w.to.pin == pin && w.from.node == BOUNDARY)
                .map(|w| w.from.pin.clone())
        });
        declared.unwrap_or_else(|| format!("{name}_{pin}"))
    }

    /// `source` (a source in the document's node graph) as an input of `owner`'s node
    /// graph named `wanted`, of type `ty`; as it is where `owner` is the document's.
    fn carry_into(
        &mut self,
        owner: Option<NodeId>,
        wanted: &str,
        ty: ValueType,
        source: Source,
    ) -> Source {
        let Some(instance) = owner else {
            return source;
        };
        let groups = self.groups;
        let group = self.part(instance).group.clone();
        let declared = (groups.definitions.get(&group))
            .and_then(|definition| definition.inputs.iter().find(|input| input.name == wanted));
        let (default, range) = match (&source, declared) {
            (_, Some(declared)) => (
                Default::Value(super::value_text(&declared.default.components(), ty)),
                declared.range,
            ),
            (Source::Node(node), None) if node == POSITION => (Default::Position, None),
            _ => (Default::Zero, None),
        };
        self.part(instance)
            .input(wanted, mx_type(ty), source, default, range)
    }

    /// The source of `pin` of node `id` (named `name` in the document; read from
    /// `source`), converted to the pin's type; `None` when it reads a node that did not
    /// translate.
    fn argument(
        &mut self,
        id: NodeId,
        name: &str,
        pin: &InputPin,
        source: &InputSource,
    ) -> Option<Source> {
        let owner = self.owner(id);
        Some(match source {
            InputSource::Wire { node, output, ty } => {
                let from = self.outputs.get(node)?.get(*output)?.clone();
                let from_owner = self.owner(*node);
                let source = match from_owner {
                    Some(instance) if from_owner != owner => {
                        let wanted = self.group_output_name(*node, *output);
                        self.part(instance).output(&wanted, mx_type(*ty), from)
                    }
                    _ => from,
                };
                let source = match from_owner == owner {
                    true => source,
                    false => {
                        let wanted = self.group_input_name(id, name, pin.name);
                        self.carry_into(owner, &wanted, *ty, source)
                    }
                };
                let converted = format!("{name}_{}", pin.name);
                self.convert(source, *ty, pin.ty, &converted, owner)
            }
            InputSource::Const(value) => self.constant(id, pin, value, owner),
            InputSource::Position => {
                let position = self.surface_position();
                self.carry_into(owner, "position", ValueType::Vec3, position)
            }
        })
    }

    /// Gives each group's node graph every output its definition declares that the
    /// translated nodes give (so an import gets the group's interface back), and puts
    /// its inputs and outputs in the definition's order.
    fn complete_parts(&mut self) {
        let (graph, groups) = (self.graph, self.groups);
        for checked in &graph.order {
            let Some(origin) = checked.node.origin.as_deref() else {
                continue;
            };
            let definition = groups.definitions.get(&origin.definition);
            let (Some(definition), true) = (
                definition.filter(|_| self.parts.contains_key(&origin.top)),
                origin.groups.instances().len() == 1,
            ) else {
                continue;
            };
            let declared = (definition.wires.iter())
                .filter(|wire| wire.from.node == origin.id && wire.to.node == BOUNDARY);
            for wire in declared {
                let outputs = &checked.signature.outputs;
                let Some(j) = outputs.iter().position(|pin| pin.name == wire.from.pin) else {
                    continue;
                };
                let given = self.outputs.get(&checked.node.id).and_then(|o| o.get(j));
                if let Some(source) = given.cloned() {
                    let ty = mx_type(outputs[j].ty);
                    self.part(origin.top).output(&wire.to.pin, ty, source);
                }
            }
        }
        for part in self.parts.values_mut() {
            let Some(definition) = groups.definitions.get(&part.group) else {
                continue;
            };
            let input_rank =
                |name: &str| (definition.inputs.iter()).position(|input| input.name == name);
            let output_rank =
                |name: &str| (definition.outputs.iter()).position(|output| output.name == name);
            // Declared ones first, the others as met.
            part.inputs
                .sort_by_key(|given| input_rank(&given.input.name).map_or(usize::MAX, |k| k));
            part.outputs
                .sort_by_key(|output| output_rank(&output.name).map_or(usize::MAX, |k| k));
        }
    }

    /// Veneer's position of the shaded point: the object-space position placed as the
    /// preview places the mesh (times `size`, plus `center`), made once.
    fn surface_position(&mut self) -> Source {
        if !self.nodes.iter().any(|node| node.name == POSITION) {
            let (center, size) = self.placement;
            let constant = |v: [f64; 3], ty| Source::Value(super::value_text(&v, ty));
            let object = Source::Value("object".into());
            let mut steps = vec![(
                "position",
                "ND_position_vector3",
                vec![input("space", "string", object)],
            )];
            if size != 1.0 {
                let scale = constant([size; 3], ValueType::Float);
                steps.push((
                    "multiply",
                    "ND_multiply_vector3FA",
                    vec![input("in2", "float", scale)],
                ));
            }
            if center != [0.0; 3] {
                let offset = constant(center, ValueType::Vec3);
                steps.push((
                    "add",
                    "ND_add_vector3",
                    vec![input("in2", "vector3", offset)],
                ));
            }
            let last = steps.len() - 1;
            let mut previous: Option<String> = None;
            for (k, (category, nodedef, mut inputs)) in steps.into_iter().enumerate() {
                let name = match k == last {
                    true => POSITION.to_string(),
                    false => format!("{POSITION}_{k}"),
                };
                if let Some(previous) = previous.take() {
                    inputs.insert(0, input("in1", "vector3", Source::Node(previous)));
                }
                self.nodes
                    .push(node(&name, category, "vector3", nodedef, inputs));
                previous = Some(name);
            }
        }
        Source::Node(POSITION.into())
    }

    /// A constant input of node `id` (in `owner`'s node graph): the exposed parameter it
    /// holds, if any, else its value.
    fn constant(
        &mut self,
        id: NodeId,
        pin: &InputPin,
        value: &Value,
        owner: Option<NodeId>,
    ) -> Source {
        let parameter = (self.graph.bindings.get(&(id, pin.name.to_string())))
            .and_then(|name| self.graph.parameters.iter().find(|p| &p.name == name))
            .filter(|parameter| parameter.ty == pin.ty);
        let text = |value: &Value, ty| super::value_text(&value.components(), ty);
        match parameter {
            Some(parameter) => {
                let name = super::element_name(&parameter.name);
                let value = Source::Value(text(&parameter.value, parameter.ty));
                let entry = input(&name, mx_type(parameter.ty), value);
                let range = parameter.range;
                self.interface.entry(name.clone()).or_insert((entry, range));
                // In a group's node graph, the group input holding it.
                let wanted = match parameter.target.node {
                    target if Some(target) == owner => parameter.target.pin.clone(),
                    _ => name.clone(),
                };
                let ty = parameter.ty;
                self.carry_into(owner, &wanted, ty, Source::Interface(name))
            }
            None => Source::Value(text(value, pin.ty)),
        }
    }

    /// `source` of type `from` as type `to`, through a `convert` node named `name` in
    /// `owner`'s node graph.
    fn convert(
        &mut self,
        source: Source,
        from: ValueType,
        to: ValueType,
        name: &str,
        owner: Option<NodeId>,
    ) -> Source {
        if mx_type(from) == mx_type(to) {
            return source;
        }
        let (from, to) = (mx_type(from), mx_type(to));
        let nodedef = format!("ND_convert_{from}_{to}");
        let name = format!("{name}_as_{to}");
        self.nodes_of(owner).push(node(
            &name,
            "convert",
            to,
            &nodedef,
            vec![input("in", from, source)],
        ));
        Source::Node(name)
    }

    /// Checked node `k` cannot be translated, for `reason`.
    fn untranslatable(&mut self, k: usize, reason: String) {
        self.untranslatable.push(Untranslatable {
            node: self.graph.order[k].node.label.clone(),
            reason,
        });
    }

    /// How the names of files beside the document made for nodes of `owner` start: the
    /// document's stem, and in a group's node graph the instance's name too (the files
    /// of two instances may differ).
    fn file_stem(&mut self, owner: Option<NodeId>) -> String {
        match owner {
            Some(instance) => {
                let stem = self.stem;
                format!("{stem}_{}", self.part(instance).instance_name)
            }
            None => self.stem.to_string(),
        }
    }

    /// Checked node `k` (named `name`, in `owner`'s node graph) read from textures of its
    /// outputs, one per output some node reads (`<stem>_<name>.exr`, or
    /// `<stem>_<name>_<output>.exr`), each baked from the node and its upstream.
    fn baked_texture(
        &mut self,
        k: usize,
        name: &str,
        owner: Option<NodeId>,
    ) -> Result<Translated, String> {
        let stem = self.file_stem(owner);
        let checked = &self.graph.order[k];
        let outputs = &checked.signature.outputs;
        let mut translated = Translated {
            nodes: Vec::new(),
            outputs: Vec::new(),
        };
        for (j, pin) in outputs.iter().enumerate() {
            let image = match outputs.len() {
                1 => name.to_string(),
                _ => format!("{name}_{}", pin.name),
            };
            translated.outputs.push(Source::Node(image.clone()));
            if !checked.used_outputs.get(j).copied().unwrap_or(true) {
                continue;
            }
            if pin.ty == ValueType::Vec2 {
                return Err(format!(
                    "its output '{}' is a vector2, which no baked texture holds",
                    pin.name
                ));
            }
            let file = format!("{stem}_{image}.exr");
            let graph = upstream(self.graph, k, j, self.preview, self.folder);
            self.baked.push(BakedNode {
                graph,
                file: file.clone(),
            });
            let read = Source::File {
                path: file,
                colour_space: None,
            };
            let ty = mx_type(pin.ty);
            let inputs = vec![input("file", "filename", read)];
            translated
                .nodes
                .push(node(&image, "image", ty, &format!("ND_image_{ty}"), inputs));
        }
        Ok(translated)
    }

    /// The name of checked node `k` in `owner`'s node graph: its label and its id, in
    /// a group's node graph its id in the group's definition (so instances of one group
    /// translate alike), made unique where nested groups give two nodes one.
    fn node_name(&mut self, k: usize, owner: Option<NodeId>) -> String {
        let node = &self.graph.order[k].node;
        let label = node_label(node);
        let Some(origin) = node.origin.as_ref().filter(|_| owner.is_some()) else {
            return format!("{label}_{}", node.id.0);
        };
        let local = format!("{label}_{}", origin.id.0);
        let flat = format!("{local}_{}", node.id.0);
        match self.nodes_of(owner).iter().any(|node| node.name == local) {
            true => flat,
            false => local,
        }
    }

    /// Translates checked node `k` of the order.
    fn node(&mut self, k: usize) {
        let graph = self.graph;
        let checked = &graph.order[k];
        let id = checked.node.id;
        let owner = self.owner(id);
        let name = self.node_name(k, owner);
        let pins = &checked.signature.inputs;
        let mut arguments = Vec::with_capacity(pins.len());
        for (pin, source) in pins.iter().zip(&checked.inputs) {
            match self.argument(id, &name, pin, source) {
                Some(argument) => arguments.push(argument),
                // Reads a node that did not translate: that one is reported.
                None => return,
            }
        }
        let kind = &checked.node.kind;
        let translated = match route(kind) {
            // The node of its own (a `dot`) keeps the Position node in an import.
            Route::Standard if *kind == NodeKind::Position => {
                let position = self.surface_position();
                let position = self.carry_into(owner, "position", ValueType::Vec3, position);
                let position = vec![input("in", "vector3", position)];
                Translated {
                    nodes: vec![node(&name, "dot", "vector3", "ND_dot_vector3", position)],
                    outputs: vec![Source::Node(name.clone())],
                }
            }
            Route::Standard => standard(kind, &name, &arguments).expect("routed as standard"),
            Route::Bitmap(settings) => {
                let bitmap = self
                    .graph
                    .bitmaps
                    .get(&id)
                    .expect("the checked graph's bitmap");
                let stem = format!("{}_{name}", self.file_stem(owner));
                let (file, bytes, colour_space) = bitmap_texture(bitmap, &stem);
                self.files.push((file.clone(), bytes));
                super::standard::image(&name, &settings, &file, colour_space)
            }
            Route::Texture => match self.baked_texture(k, &name, owner) {
                Ok(translated) => translated,
                Err(reason) => return self.untranslatable(k, reason),
            },
            Route::Definition(definition) => {
                let translated = definition.instance(&name, pins, arguments);
                if !self
                    .definitions
                    .iter()
                    .any(|d| d.category == definition.category)
                {
                    self.definitions.push(*definition);
                }
                translated
            }
            Route::None(reason) if !self.bake_untranslatable => {
                return self.untranslatable(k, reason);
            }
            Route::None(reason) => match self.baked_texture(k, &name, owner) {
                Ok(translated) => translated,
                Err(why) => return self.untranslatable(k, format!("{reason}, and {why}")),
            },
        };
        let mut nodes = translated.nodes;
        // Inlined nodes sit where their group node does: inside a group's node graph,
        // where they sit in the definition.
        let place = (self.definition_of(id).filter(|_| owner.is_some()))
            .and_then(|(definition, inner)| definition.nodes.iter().find(|n| n.id == inner))
            .map_or(checked.node.position, |node| node.position);
        if let Some(head) = nodes.iter_mut().find(|node| node.name == name) {
            head.ui = Some((checked.node.label.clone(), place));
        }
        self.nodes_of(owner).extend(nodes);
        self.outputs.insert(id, translated.outputs);
    }
}

/// A node's label as an element name, its kind's name where it has none.
fn node_label(node: &crate::graph::Node) -> String {
    match node.label.is_empty() {
        true => super::element_name(node.kind.name()),
        false => super::element_name(&node.label),
    }
}

/// How a node kind with its settings reaches MaterialX.
pub enum Route {
    /// Standard nodes that mean the same ([`super::standard`]).
    Standard,
    /// An `image` node reading the node's bitmap, written beside the document.
    Bitmap(crate::nodes::bitmap::ImageFile),
    /// An `image` node reading the node's output baked over the preview mesh's UV
    /// layout (a distance or mesh field: a property of the mesh, not of the point).
    Texture,
    /// A node definition of Veneer's own.
    Definition(Box<CustomDef>),
    /// No way: why.
    None(String),
}

/// How `kind` is translated.
pub fn route(kind: &NodeKind) -> Route {
    let pins = kind.definition().signature().inputs.len();
    let placeholders = vec![Source::Value("0".into()); pins];
    match kind {
        NodeKind::Position => Route::Standard,
        NodeKind::ImageFile(settings) => Route::Bitmap(settings.clone()),
        NodeKind::Field(_) | NodeKind::MeshField(_) => Route::Texture,
        _ if standard(kind, "node", &placeholders).is_some() => Route::Standard,
        _ => match CustomDef::new(kind) {
            Ok(definition) => Route::Definition(Box::new(definition)),
            Err(reason) => Route::None(reason),
        },
    }
}

/// `compiled`'s checked graph (shown as its preview places it, its presets becoming
/// variants of the interface's values) translated for `surface`; `normal_map` is the
/// baked normal map's file, when the material perturbs the normal; baked textures' names
/// start with `stem`. The nodes that cannot be translated come back instead, each named
/// with the reason, unless `bake_untranslatable` asks for their textures.
pub fn translate(
    compiled: &crate::codegen::Compiled,
    stem: &str,
    bake_untranslatable: bool,
    surface: SurfaceModel,
    normal_map: Option<&str>,
) -> Result<Procedural, Vec<Untranslatable>> {
    let (graph, preview, folder) = (&compiled.checked, &compiled.preview, &compiled.folder);
    let (presets, alpha) = (&compiled.presets, compiled.uses().alpha);
    let (cx, cy, cz) = preview.center;
    let mut translator = Translator {
        graph,
        placement: ([cx, cy, cz], preview.size),
        stem,
        preview,
        folder,
        bake_untranslatable,
        groups: &compiled.groups,
        baked: Vec::new(),
        files: Vec::new(),
        nodes: Vec::new(),
        parts: BTreeMap::new(),
        definitions: Vec::new(),
        outputs: BTreeMap::new(),
        interface: BTreeMap::new(),
        untranslatable: Vec::new(),
    };
    let material = graph.order.len() - 1;
    for k in 0..material {
        translator.node(k);
    }
    let checked = graph.material();
    let mut pins = BTreeMap::new();
    for (pin, source) in checked.signature.inputs.iter().zip(&checked.inputs) {
        if let Some(argument) = translator.argument(checked.node.id, "material", pin, source) {
            pins.insert(pin.name, argument);
        }
    }
    if !translator.untranslatable.is_empty() {
        return Err(translator.untranslatable);
    }
    translator.complete_parts();
    let (mut nodes, baked, files) = (translator.nodes, translator.baked, translator.files);
    let mut groups: Vec<GroupGraph> = translator.parts.into_values().collect();
    super::groups::assign_categories(&mut groups);
    super::groups::name_single_outputs(&mut groups, &mut nodes, pins.values_mut());
    nodes.extend(groups.iter().map(GroupGraph::instance_node));
    let pin = |name: &str| pins.get(name).cloned().expect("the material node's pins");
    // Nodes of the material's own: named apart from the graph's (which end in `_<id>`).
    let mut add = |name: &str, category: &str, ty: &'static str, nodedef: &str, inputs| {
        nodes.push(node(name, category, ty, nodedef, inputs));
        Source::Node(name.to_string())
    };
    // Each of the material's values that is not its default, as a node graph output
    // `veneer_<pin>` (a constant or a parameter through a `constant` node), so an import
    // finds the material; the albedo always.
    let mut outputs = Vec::new();
    for material_pin in &checked.signature.inputs {
        let source = pin(material_pin.name);
        let ty = mx_type(material_pin.ty);
        let default = match &material_pin.default {
            PinDefault::Const(value) => Some(Source::Value(super::value_text(
                &value.components(),
                material_pin.ty,
            ))),
            _ => None,
        };
        if material_pin.name != "albedo" && Some(&source) == default.as_ref() {
            continue;
        }
        let source = match source {
            Source::Node(_) | Source::Output(..) => source,
            other => add(
                &format!("material_{}", material_pin.name),
                "constant",
                ty,
                &format!("ND_constant_{ty}"),
                vec![input("value", ty, other)],
            ),
        };
        outputs.push(input(&format!("veneer_{}", material_pin.name), ty, source));
    }
    // What the surface reads of a material value: its output's node, or its default.
    let value = |name: &str| {
        (outputs.iter())
            .find(|output| output.name.strip_prefix("veneer_") == Some(name))
            .map_or_else(|| pin(name), |output| output.source.clone())
    };
    let raw_albedo = value("albedo");
    let linear = graph.shading.is_linear();
    let albedo = match linear {
        true => raw_albedo.clone(),
        false => add(
            "albedo_linear",
            "srgb_texture_to_lin_rec709",
            "color3",
            "ND_srgb_texture_to_lin_rec709_color3",
            vec![input("in", "color3", raw_albedo.clone())],
        ),
    };
    // Under Blinn-Phong, roughness from the shininess n as sqrt(2 / (n + 2)), as `bake`
    // makes its roughness map.
    let roughness = match graph.shading {
        Shading::MetallicRoughness => value("roughness"),
        _ => {
            let sum = add(
                "shininess_plus_two",
                "add",
                "float",
                "ND_add_float",
                vec![
                    input("in1", "float", value("shininess")),
                    input("in2", "float", Source::Value("2".into())),
                ],
            );
            let ratio = add(
                "two_over_shininess",
                "divide",
                "float",
                "ND_divide_float",
                vec![
                    input("in1", "float", Source::Value("2".into())),
                    input("in2", "float", sum),
                ],
            );
            add(
                "roughness_from_shininess",
                "sqrt",
                "float",
                "ND_sqrt_float",
                vec![input("in", "float", ratio)],
            )
        }
    };
    let black = Source::Value(super::value_text(&[0.0; 3], ValueType::Color));
    let emission = match (value("emission"), value("emission_strength")) {
        (emission, _) if emission == black => None,
        (emission, Source::Value(one)) if one == "1" => Some(emission),
        (emission, strength) => Some(add(
            "emission_scaled",
            "multiply",
            "color3",
            "ND_multiply_color3FA",
            vec![
                input("in1", "color3", emission),
                input("in2", "float", strength),
            ],
        )),
    };
    let normal = normal_map.map(|path| {
        nodes.extend(super::network::normal_map_nodes(path));
        Source::Node("normal".into())
    });
    let fields = SurfaceFields {
        albedo,
        roughness,
        metallic: value("metallic"),
        occlusion: value("occlusion"),
        alpha: (alpha != AlphaUse::Opaque).then(|| value("alpha")),
        emission,
        normal,
    };
    let mut network = wire(nodes, fields, alpha, surface, outputs);
    // Only the textures of nodes the surface still reads (a field that shapes the height
    // alone is in the baked normal map).
    let read: Vec<&str> = (network.nodes.iter())
        .chain(groups.iter().flat_map(|group| &group.nodes))
        .flat_map(|node| &node.inputs)
        .filter_map(|input| match &input.source {
            Source::File { path, .. } => Some(path.as_str()),
            _ => None,
        })
        .collect();
    let baked = (baked.into_iter())
        .filter(|baked| read.contains(&baked.file.as_str()))
        .collect();
    let files = (files.into_iter())
        .filter(|(file, _)| read.contains(&file.as_str()))
        .collect();
    network.interface = translator.interface.into_values().collect();
    network.title = Some(graph.name.clone());
    // The presets, as values of the interface inputs they set.
    for (preset, values) in presets {
        let inputs: Vec<Input> = (values.iter())
            .filter_map(|(parameter, value)| {
                let name = super::element_name(parameter);
                let (interface, _) = network.interface.iter().find(|(i, _)| i.name == name)?;
                let ty = graph.parameters.iter().find(|p| &p.name == parameter)?.ty;
                let text = super::value_text(&value.convert(ty).components(), ty);
                Some(input(&name, interface.ty, Source::Value(text)))
            })
            .collect();
        if !inputs.is_empty() {
            network.variants.push((preset.clone(), inputs));
        }
    }
    network.surface_ui = Some((checked.node.label.clone(), checked.node.position));
    Ok(Procedural {
        network,
        definitions: translator.definitions,
        baked,
        files,
        groups,
    })
}

/// The texels of an Image node's bitmap as a file named `stem` plus its extension, and the
/// colour space to read it in: an 8-bit PNG where that holds every texel exactly (sRGB
/// encoded when the file was), else OpenEXR floats, as Veneer reads them.
fn bitmap_texture(
    bitmap: &crate::bitmaps::Bitmap,
    stem: &str,
) -> (String, Vec<u8>, Option<&'static str>) {
    use crate::bitmaps::srgb_to_linear;
    let encode = |lane: f32, k: usize| match bitmap.from_srgb && k < 3 {
        true => linear_to_srgb(lane),
        false => lane,
    };
    let decode = |byte: u8, k: usize| match bitmap.from_srgb && k < 3 {
        true => srgb_to_linear(f32::from(byte) / 255.0),
        false => f32::from(byte) / 255.0,
    };
    let bytes: Option<Vec<u8>> = (bitmap.texels.iter())
        .flat_map(|texel| texel.iter().enumerate())
        .map(|(k, &lane)| {
            let byte = (encode(lane, k).clamp(0.0, 1.0) * 255.0).round() as u8;
            (decode(byte, k) == lane).then_some(byte)
        })
        .collect();
    let (width, height) = (bitmap.width, bitmap.height);
    let mut out = std::io::Cursor::new(Vec::new());
    match bytes {
        Some(bytes) => {
            let image = image::RgbaImage::from_raw(width, height, bytes).expect("sized");
            image
                .write_to(&mut out, image::ImageFormat::Png)
                .expect("in memory");
            let space = bitmap.from_srgb.then_some("srgb_texture");
            (format!("{stem}.png"), out.into_inner(), space)
        }
        None => {
            let floats = bitmap.texels.iter().flatten().copied().collect();
            let image = image::Rgba32FImage::from_raw(width, height, floats).expect("sized");
            image
                .write_to(&mut out, image::ImageFormat::OpenExr)
                .expect("in memory");
            (format!("{stem}.exr"), out.into_inner(), None)
        }
    }
}

/// The graph baking output `output` of checked node `k`: the node and every node upstream
/// of it as they are (ids, settings, constants), that output wired into the albedo of a
/// material of its own, with `graph`'s preview and folder.
fn upstream(
    graph: &CheckedGraph,
    k: usize,
    output: usize,
    preview: &Preview,
    folder: &crate::graph::Folder,
) -> crate::graph::Graph {
    use crate::graph::{Graph, PinRef, Wire};
    let mut needed = vec![k];
    let mut kept = std::collections::BTreeSet::new();
    let mut wires = Vec::new();
    while let Some(k) = needed.pop() {
        if !kept.insert(k) {
            continue;
        }
        let checked = &graph.order[k];
        for (_, pin, from, from_output, _) in checked.wired_inputs() {
            let Some(from_k) = graph.index_of(from) else {
                continue;
            };
            let from_pin = graph.order[from_k].signature.outputs[from_output].name;
            wires.push(Wire {
                from: PinRef::new(from, from_pin),
                to: PinRef::new(checked.node.id, pin.name),
            });
            needed.push(from_k);
        }
    }
    let mut nodes: Vec<crate::graph::Node> = (kept.iter())
        .map(|&k| crate::graph::Node {
            origin: None,
            ..graph.order[k].node.clone()
        })
        .collect();
    let material = NodeId(1 + nodes.iter().map(|node| node.id.0).max().unwrap_or(0));
    nodes.push(crate::graph::Node::new(material, NodeKind::Material));
    let node = &graph.order[k];
    wires.push(Wire {
        from: PinRef::new(node.node.id, node.signature.outputs[output].name),
        to: PinRef::new(material, "albedo"),
    });
    Graph {
        name: node.node.label.clone(),
        preview: preview.clone(),
        nodes,
        wires,
        folder: folder.clone(),
        ..Graph::default()
    }
}
