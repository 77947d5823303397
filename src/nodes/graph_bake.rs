//! The Graph bake node: one map of another graph file (its albedo, height, roughness …)
//! as a buffer over this material's domain, so materials compose: a stone material
//! baked into a wall's mortar, a bark material into a tree's. Like a group, the node
//! is expanded before a graph is checked (see `graph::graph_bakes`): the file's nodes
//! its map reads join this graph, feeding a Buffer node that takes the Graph bake's
//! place, so the evaluation, range and emission parts below never meet one.

use super::cpu::Eval;
use super::emit::Emit;
use super::formulas::real::{Real, V3};
use super::interval::Lanes;
use super::passes::{BufferFormat, EdgeMode, Filter, Resolution};
use super::pins::{Signature, output};
use super::ranges::Ranges;
use super::sampled::{Buffer, buffer_settings, image_node};
use super::settings::{Basis, Setting, choice};
use super::value::ValueType;
use super::{Catalogue, Category, Configure, Definition, Evaluate, NodeKind};
use serde::{Deserialize, Serialize};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather [$($units)*] [$($configured)* (GraphBake, graph_bake)] $($rest)*);
    };
}
pub(super) use kinds;

/// Which input of the other graph's Material node the bake takes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum BakedMap {
    #[default]
    Albedo,
    Alpha,
    Height,
    Roughness,
    Metallic,
    Emission,
    Occlusion,
    Specular,
    Shininess,
    Bump,
    Normal,
}

impl BakedMap {
    /// Every map, in menu order.
    pub const ALL: [BakedMap; 11] = [
        BakedMap::Albedo,
        BakedMap::Alpha,
        BakedMap::Height,
        BakedMap::Roughness,
        BakedMap::Metallic,
        BakedMap::Emission,
        BakedMap::Occlusion,
        BakedMap::Specular,
        BakedMap::Shininess,
        BakedMap::Bump,
        BakedMap::Normal,
    ];

    /// The Material node's input holding the map.
    pub fn pin(self) -> &'static str {
        match self {
            BakedMap::Albedo => "albedo",
            BakedMap::Alpha => "alpha",
            BakedMap::Height => "height",
            BakedMap::Roughness => "roughness",
            BakedMap::Metallic => "metallic",
            BakedMap::Emission => "emission",
            BakedMap::Occlusion => "occlusion",
            BakedMap::Specular => "specular",
            BakedMap::Shininess => "shininess",
            BakedMap::Bump => "bump",
            BakedMap::Normal => "normal",
        }
    }

    /// The type of the map's values: the Material input's.
    pub fn ty(self) -> ValueType {
        let signature = NodeKind::Material.definition().signature();
        let pin = signature.inputs.iter().find(|pin| pin.name == self.pin());
        pin.expect("every baked map is a Material input").ty
    }
}

/// A map of the graph in another file, rendered into a buffer over the domain (as a
/// Buffer node stores it) and read at the point.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
#[serde(default)]
pub struct GraphBake {
    /// The graph file, relative to this graph file's folder (`stone.ron`).
    pub path: String,
    pub map: BakedMap,
    pub resolution: Resolution,
    /// The side in texels when `resolution` is `Absolute`.
    pub size: u32,
    pub format: BufferFormat,
    pub edge: EdgeMode,
    pub filter: Filter,
}

impl Default for GraphBake {
    fn default() -> GraphBake {
        let buffer = Buffer::default();
        GraphBake {
            path: String::new(),
            map: BakedMap::default(),
            resolution: buffer.resolution,
            size: buffer.size,
            format: buffer.format,
            edge: buffer.edge,
            filter: buffer.filter,
        }
    }
}

impl GraphBake {
    /// The Buffer node that holds the map once the bake is expanded.
    pub fn buffer(&self) -> Buffer {
        Buffer {
            ty: self.map.ty(),
            resolution: self.resolution,
            size: self.size,
            format: self.format,
            edge: self.edge,
            filter: self.filter,
        }
    }
}

/// Why a Graph bake node reached a stage that works on expanded graphs.
const EXPANDED: &str = "graph bake nodes are expanded before a graph is checked";

impl Definition for GraphBake {
    fn title(&self) -> &'static str {
        "Graph bake"
    }
    image_node!();
    fn keywords(&self) -> &'static [&'static str] {
        &[
            "bake", "graph", "file", "material", "compose", "import", "map", "link",
        ]
    }
    fn signature(&self) -> Signature {
        Signature::new(Vec::new(), vec![output("value", self.map.ty())])
    }
    fn check(&self) -> Option<String> {
        // The file is read and checked against the graph's folder when the node is
        // expanded; here, only what needs no file.
        let path = (self.path.len() > 4096).then(|| {
            format!(
                "the path is {} bytes long, more than 4,096",
                self.path.len()
            )
        });
        path.or_else(|| self.buffer().check())
    }
    fn emit(&self, _: &mut Emit) {
        unreachable!("{EXPANDED}")
    }
    fn ranges(&self, _: &mut Ranges) -> Vec<Lanes> {
        unreachable!("{EXPANDED}")
    }
}

impl Evaluate for GraphBake {
    fn eval<R: Real>(&self, _: &Eval<R>) -> Vec<V3<R>> {
        unreachable!("{EXPANDED}")
    }
}

impl Configure for GraphBake {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        let GraphBake {
            path,
            map,
            resolution,
            size,
            format,
            edge,
            filter,
        } = self;
        let mut settings = vec![
            Setting::File {
                label: "graph",
                value: path,
                extensions: &["ron"],
            },
            choice("map", map, &BakedMap::ALL),
        ];
        settings.extend(buffer_settings(resolution, size, format, edge, filter));
        settings
    }
}

impl Catalogue for GraphBake {
    fn menu() -> Vec<(String, Self)> {
        vec![("Graph bake".into(), GraphBake::default())]
    }
    /// A bake needs a graph file beside its graph, which the per-kind tests do not
    /// have: tests/engine/graph_bakes.rs covers it.
    fn examples() -> Vec<Self> {
        Vec::new()
    }
}
