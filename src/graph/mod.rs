//! The graph model: nodes, pins, wires, their checks and their file format.

pub mod check;
mod declarations;
pub mod edit;
mod field;
pub mod frames;
pub mod graph_bakes;
pub mod group;
pub mod group_interface;
mod ids;
mod inline;
mod io;
pub mod keys;
pub mod layout;
pub mod library;
pub mod names;
pub mod nesting;
mod node_file;
pub mod parameters;
mod part;
mod presets;
mod preview;
mod shading;
pub use shading::Shading;

pub use crate::nodes::pins::{InputPin, OutputPin, PinDefault, PinRange, Signature};
pub use crate::nodes::settings::{
    Basis, FeaturePoints, FractalMode, MAX_OCTAVES, MAX_OCTAVES_UI, MAX_RAMP_STOPS, MathOp, Metric,
    RampInterpolation, RampStop, UnaryOp, WorleyFeature,
};
pub use crate::nodes::value::{Value, ValueType};
pub use crate::nodes::{Category, NodeKind};
pub use check::{CheckError, CheckedGraph, check};
pub use field::{FieldSource, HeatOptions, Method, TimeFactorError};
pub use io::{CURRENT_VERSION, LoadError, from_ron, load, save, to_ron};
pub use presets::{PRESETS, preset};

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::fmt;
use std::path::{Path, PathBuf};

/// The most characters of a node label, graph name, frame title or pin name: a label
/// names variables in generated WGSL and every text appears in messages, so a longer one
/// is refused by the check (naming its node) instead of being copied into megabytes of
/// shader and error text.
pub const MAX_TEXT_CHARS: usize = 256;

/// The most characters of the preview's mesh name (a primitive or a file path).
pub const MAX_PATH_CHARS: usize = 4096;

/// `text` cut to its first `max` characters, and whether anything was cut.
pub fn clip(text: &str, max: usize) -> (&str, bool) {
    match text.char_indices().nth(max) {
        Some((end, _)) => (&text[..end], true),
        None => (text, false),
    }
}

/// A node's stable identifier: unique in its graph, never reused while the node lives.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(transparent)]
pub struct NodeId(pub u32);

impl fmt::Display for NodeId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "#{}", self.0)
    }
}

/// One node of a material graph. A file may leave out its label, inputs and position;
/// one that gives an input twice is refused (see `node_file.rs`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "node_file::NodeFile")]
pub struct Node {
    pub id: NodeId,
    /// The artist's name for the node; also names its variables in generated WGSL.
    pub label: String,
    pub kind: NodeKind,
    /// Constant values of unconnected inputs that differ from, or pin down, the defaults.
    pub inputs: BTreeMap<String, Value>,
    /// Position in the editor canvas.
    pub position: (f32, f32),
    /// Where a node inlined from a group came from (see [`group::flatten`]); `None` for
    /// the nodes of a file. Not stored.
    #[serde(skip)]
    pub origin: Option<Box<Origin>>,
}

/// The group path of a node inlined from a group, so messages point into the group:
/// `group 'bark' › node 'grain' (#3)`.
#[derive(Clone, Debug, PartialEq)]
pub struct Origin {
    /// The group instances it sits in.
    pub groups: GroupPath,
    /// Its id inside its group's definition.
    pub id: NodeId,
    /// The top level's group node it was inlined from (the outermost instance).
    pub top: NodeId,
    /// The name of the group definition it sits in (the innermost instance's).
    pub definition: String,
}

/// Group instances, one inside the other, each as `group 'label'`: shown outermost
/// first, `group 'bark' › group 'grain'`. The nodes inlined from one instance share its
/// path, and a path inside it adds one link, so a deep graph stores each instance once.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GroupPath(Option<std::sync::Arc<PathLink>>);

/// One instance of a [`GroupPath`] and the path it sits in.
#[derive(Debug, PartialEq)]
pub struct PathLink {
    outer: GroupPath,
    instance: String,
}

impl GroupPath {
    /// This path with `instance` inside its innermost instance.
    pub fn within(&self, instance: String) -> GroupPath {
        GroupPath(Some(std::sync::Arc::new(PathLink {
            outer: self.clone(),
            instance,
        })))
    }

    /// The instances, outermost first.
    pub fn instances(&self) -> Vec<&str> {
        let mut instances = Vec::new();
        let mut link = self.0.as_deref();
        while let Some(step) = link {
            instances.push(step.instance.as_str());
            link = step.outer.0.as_deref();
        }
        instances.reverse();
        instances
    }
}

impl fmt::Display for GroupPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.instances().join(" › "))
    }
}

impl Node {
    /// A node of `kind` with default inputs.
    pub fn new(id: NodeId, kind: NodeKind) -> Node {
        Node {
            id,
            label: String::new(),
            kind,
            inputs: BTreeMap::new(),
            position: (0.0, 0.0),
            origin: None,
        }
    }

    /// The label (its first [`MAX_TEXT_CHARS`] characters), or the kind's title when the
    /// label is empty.
    pub fn display_name(&self) -> &str {
        if self.label.is_empty() {
            self.kind.title()
        } else {
            clip(&self.label, MAX_TEXT_CHARS).0
        }
    }

    /// The title the editor shows: the label, or the title the kind's definition shows
    /// for its settings (a math node's operation, "Divide", as the add-node menu names
    /// it; else the kind's title).
    pub fn title(&self) -> String {
        if self.label.is_empty() {
            self.kind.definition().shown_title()
        } else {
            self.display_name().to_string()
        }
    }
}

impl Node {
    /// Where the node is, for generated comments: `#3`, or inside groups
    /// `group 'bark' › #3`.
    pub fn reference(&self) -> String {
        match &self.origin {
            Some(origin) => format!("{} › {}", origin.groups, origin.id),
            None => self.id.to_string(),
        }
    }
}

impl fmt::Display for Node {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let name = self.display_name();
        let cut = if name.len() < self.label.len() {
            "…"
        } else {
            ""
        };
        match &self.origin {
            Some(origin) => write!(f, "{} › node '{name}{cut}' ({})", origin.groups, origin.id),
            None => write!(f, "node '{name}{cut}' ({})", self.id),
        }
    }
}

/// One end of a wire: a node and the name of one of its pins.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct PinRef {
    pub node: NodeId,
    pub pin: String,
}

impl PinRef {
    /// A reference to `pin` of `node`.
    pub fn new(node: NodeId, pin: &str) -> PinRef {
        PinRef {
            node,
            pin: pin.to_string(),
        }
    }
}

/// A wire from an output pin to an input pin.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct Wire {
    pub from: PinRef,
    pub to: PinRef,
}

/// How the material is shown on a mesh: which mesh, and where the mesh sits in
/// texture space (object-space position = mesh position * size + center).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Preview {
    pub mesh: String,
    pub center: (f64, f64, f64),
    pub size: f64,
    /// The geodesic distance fields of the mesh, in slot order (`Field` nodes read slot
    /// k from `fields[k]`); at most four.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub fields: Vec<FieldSource>,
    /// Whether a displaced material's mesh is refined where its height needs it (the
    /// thesis's adaptive tessellation); `None` draws the mesh's own triangles.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tessellation: Option<Tessellation>,
}

/// Adaptive tessellation of displaced meshes: edges are halved until the displaced
/// surface is within `tolerance` pixels of its triangles on screen, at most `levels`
/// times.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Tessellation {
    /// Pixels the drawn triangles may stray from the displaced surface.
    #[serde(default = "Tessellation::default_tolerance")]
    pub tolerance: f64,
    /// The most times an edge of the mesh is halved.
    #[serde(default = "Tessellation::default_levels")]
    pub levels: u32,
}

impl Tessellation {
    fn default_tolerance() -> f64 {
        0.5
    }

    fn default_levels() -> u32 {
        6
    }

    /// The most triangles a refined mesh may have (about 100 MB of vertices).
    pub const MAX_TRIANGLES: usize = 2_000_000;

    /// The refinement these settings ask for.
    pub fn refinement(&self) -> crate::mesh::Refinement {
        crate::mesh::Refinement {
            tolerance_px: self.tolerance as f32,
            max_levels: self.levels,
            max_triangles: Tessellation::MAX_TRIANGLES,
        }
    }
}

impl Default for Tessellation {
    fn default() -> Tessellation {
        Tessellation {
            tolerance: Tessellation::default_tolerance(),
            levels: Tessellation::default_levels(),
        }
    }
}

impl Default for Preview {
    fn default() -> Preview {
        Preview {
            mesh: "sphere".to_string(),
            center: (0.0, 0.0, 0.0),
            size: 1.0,
            fields: Vec::new(),
            tessellation: None,
        }
    }
}

/// A material graph as stored in a `.ron` file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Graph {
    /// File format version.
    pub version: u32,
    /// Human-readable name of the material.
    #[serde(default)]
    pub name: String,
    #[serde(default)]
    pub preview: Preview,
    pub nodes: Vec<Node>,
    #[serde(default)]
    pub wires: Vec<Wire>,
    /// Comment frames drawn behind groups of nodes in the editor.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub frames: Vec<Frame>,
    /// How the material's alpha shows: cut out below a cutoff (the default), blended,
    /// or ignored.
    #[serde(
        default,
        skip_serializing_if = "AlphaMode::is_default",
        deserialize_with = "AlphaMode::read"
    )]
    pub alpha: AlphaMode,
    /// How the preview lights the material: Blinn-Phong (the seeds', the default) or
    /// metallic-roughness (glTF 2.0's PBR model).
    #[serde(default, skip_serializing_if = "Shading::is_default")]
    pub shading: Shading,
    /// Node groups (material functions) the graph's group nodes use, by name.
    #[serde(
        default,
        skip_serializing_if = "BTreeMap::is_empty",
        deserialize_with = "keys::unique"
    )]
    pub groups: BTreeMap<String, group::GroupDef>,
    /// Top-level input pins exposed as named parameters (group nodes' unwired inputs
    /// are exposed too; see [`parameters::exposed`]).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub parameters: Vec<parameters::Parameter>,
    /// Named sets of parameter values ("oak", "walnut"), by name.
    #[serde(
        default,
        skip_serializing_if = "BTreeMap::is_empty",
        deserialize_with = "presets_file"
    )]
    pub presets: BTreeMap<String, BTreeMap<String, Value>>,
    /// The folder of the file the graph was read from or saved to, which Image nodes'
    /// paths are relative to; not stored in the file.
    #[serde(skip)]
    pub folder: Folder,
}

/// Where a graph's file is (see [`Graph::folder`]): the current folder for a graph not
/// from a file. Not part of what a graph is: two graphs of the same content are equal
/// wherever their files are.
#[derive(Clone, Debug, Default)]
pub struct Folder(pub Option<PathBuf>);

impl Folder {
    /// The folder (`.` when none is known).
    pub fn path(&self) -> &Path {
        self.0.as_deref().unwrap_or(Path::new("."))
    }

    /// The folder of `file` (a graph file's path).
    pub fn of_file(file: &Path) -> Folder {
        Folder(Some(match file.parent() {
            Some(parent) if !parent.as_os_str().is_empty() => parent.to_path_buf(),
            _ => PathBuf::from("."),
        }))
    }
}

impl PartialEq for Folder {
    fn eq(&self, _: &Folder) -> bool {
        true
    }
}

/// How a material's alpha shows where it is below 1 (glTF's `alphaMode`, Blender's
/// blend mode). Wherever the alpha can fall below 1, the preview draws back faces too,
/// so the inside of a mesh shows through what is cut away or see-through.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum AlphaMode {
    /// Alpha is ignored: the surface is opaque everywhere.
    Opaque,
    /// The surface is cut out where the alpha is below `cutoff`, opaque elsewhere.
    Mask { cutoff: f64 },
    /// The surface is as opaque as its alpha: what is behind shows through in
    /// proportion (the thesis's figure 5.7).
    Blend,
}

impl AlphaMode {
    /// The cutoff of the default mode (what the preview always did).
    pub const DEFAULT_CUTOFF: f64 = 0.5;

    fn is_default(&self) -> bool {
        *self == AlphaMode::default()
    }

    /// Reads the mode as files write it, `Mask(cutoff: 0.5)`, or as DESIGN.md first
    /// gave it, `Mask((cutoff: 0.5))`.
    fn read<'de, D: serde::Deserializer<'de>>(deserializer: D) -> Result<AlphaMode, D::Error> {
        /// The mode with the cutoff in a struct of its own.
        #[derive(Deserialize)]
        #[serde(rename = "AlphaMode")]
        enum Nested {
            Opaque,
            Mask(Cutoff),
            Blend,
        }
        #[derive(Deserialize)]
        struct Cutoff {
            cutoff: f64,
        }
        let raw = Box::<ron::value::RawValue>::deserialize(deserializer)?;
        raw.into_rust::<AlphaMode>()
            .or_else(|error| {
                let nested = raw.into_rust::<Nested>().map_err(|_| error)?;
                Ok(match nested {
                    Nested::Opaque => AlphaMode::Opaque,
                    Nested::Mask(Cutoff { cutoff }) => AlphaMode::Mask { cutoff },
                    Nested::Blend => AlphaMode::Blend,
                })
            })
            .map_err(|error: ron::error::SpannedError| serde::de::Error::custom(error.code))
    }
}

impl Default for AlphaMode {
    fn default() -> AlphaMode {
        AlphaMode::Mask {
            cutoff: AlphaMode::DEFAULT_CUTOFF,
        }
    }
}

/// A titled, coloured box behind a group of nodes: a comment in the editor, no effect
/// on the material.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Frame {
    pub title: String,
    /// Canvas corners (top-left and bottom-right).
    pub min: (f32, f32),
    pub max: (f32, f32),
    /// Tint (sRGB, 0–1).
    pub color: (f32, f32, f32),
}

impl Default for Graph {
    fn default() -> Graph {
        Graph {
            version: io::PLAIN_VERSION,
            name: String::new(),
            preview: Preview::default(),
            nodes: vec![],
            wires: vec![],
            frames: vec![],
            alpha: AlphaMode::default(),
            shading: Shading::default(),
            groups: BTreeMap::new(),
            parameters: Vec::new(),
            presets: BTreeMap::new(),
            folder: Folder::default(),
        }
    }
}

impl Graph {
    /// Makes `folder` the graph's folder, rewriting the relative paths of its file
    /// settings (Image nodes, also inside groups) so that they name the same files from
    /// there: what saving a graph into another folder does.
    pub fn move_to(&mut self, folder: Folder) {
        let from = self.folder.path().to_path_buf();
        let to = folder.path().to_path_buf();
        let nodes = (self.nodes.iter_mut()).chain(
            self.groups
                .values_mut()
                .flat_map(|group| group.nodes.iter_mut()),
        );
        for node in nodes {
            for setting in node.kind.settings() {
                if let crate::nodes::settings::Setting::File { value, .. } = setting
                    && !value.trim().is_empty()
                    && Path::new(value.as_str()).is_relative()
                {
                    let file = from.join(value.as_str());
                    *value = crate::bitmaps::relative_to(&to, &file)
                        .to_string_lossy()
                        .into_owned();
                }
            }
        }
        self.folder = folder;
    }

    /// The graph's Material node (the first, should a graph that does not check have
    /// several).
    pub fn material(&self) -> Option<&Node> {
        self.nodes
            .iter()
            .find(|node| node.kind == NodeKind::Material)
    }

    /// The node with `id`.
    pub fn node(&self, id: NodeId) -> Option<&Node> {
        self.nodes.iter().find(|node| node.id == id)
    }

    /// The node with `id`, mutably.
    pub fn node_mut(&mut self, id: NodeId) -> Option<&mut Node> {
        self.nodes.iter_mut().find(|node| node.id == id)
    }

    /// An id no node uses yet.
    pub fn next_id(&self) -> NodeId {
        NodeId(
            self.nodes
                .iter()
                .map(|node| node.id.0 + 1)
                .max()
                .unwrap_or(1),
        )
    }

    /// Adds a node and returns its id.
    pub fn add(&mut self, label: &str, kind: NodeKind) -> NodeId {
        let id = self.next_id();
        let mut node = Node::new(id, kind);
        node.label = label.to_string();
        self.nodes.push(node);
        id
    }

    /// Sets the constant of an unconnected input.
    pub fn set_input(&mut self, id: NodeId, pin: &str, value: Value) {
        if let Some(node) = self.node_mut(id) {
            node.inputs.insert(pin.to_string(), value);
        }
    }

    /// Connects an output pin to an input pin, replacing any wire into that input.
    pub fn connect(&mut self, from: NodeId, from_pin: &str, to: NodeId, to_pin: &str) {
        let to = PinRef::new(to, to_pin);
        self.wires.retain(|wire| wire.to != to);
        self.wires.push(Wire {
            from: PinRef::new(from, from_pin),
            to,
        });
    }

    /// The wire feeding an input pin, if any.
    pub fn wire_into(&self, node: NodeId, pin: &str) -> Option<&Wire> {
        self.wires
            .iter()
            .find(|wire| wire.to.node == node && wire.to.pin == pin)
    }

    /// Puts nodes and wires in their canonical order, and nodes on whole canvas units
    /// (as the editor places them), so that saving is deterministic.
    pub fn canonicalize(&mut self) {
        canonical_order(&mut self.nodes, &mut self.wires);
        for definition in self.groups.values_mut() {
            definition.canonicalize();
        }
    }

    /// Whether the graph uses what version 2 of the file format added (groups,
    /// parameters, parameter presets).
    pub fn uses_groups(&self) -> bool {
        !self.groups.is_empty() || !self.parameters.is_empty() || !self.presets.is_empty()
    }
}

/// Reads a graph's presets: each preset, and each parameter in one, named once.
fn presets_file<'de, D: serde::Deserializer<'de>>(
    deserializer: D,
) -> Result<BTreeMap<String, BTreeMap<String, Value>>, D::Error> {
    /// One preset's values, each parameter named once.
    #[derive(Deserialize)]
    #[serde(transparent)]
    struct Values(#[serde(deserialize_with = "keys::unique")] BTreeMap<String, Value>);
    let presets: BTreeMap<String, Values> = keys::unique(deserializer)?;
    Ok(presets
        .into_iter()
        .map(|(name, Values(values))| (name, values))
        .collect())
}

/// Sorts `nodes` by id and `wires` (dropping repeats), and puts every node on whole
/// canvas units: the canonical form of a graph's or a group's contents.
pub(crate) fn canonical_order(nodes: &mut [Node], wires: &mut Vec<Wire>) {
    nodes.sort_by_key(|node| node.id);
    for node in nodes.iter_mut() {
        node.position = (node.position.0.round(), node.position.1.round());
    }
    wires.sort();
    wires.dedup();
}
