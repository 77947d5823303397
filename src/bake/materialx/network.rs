//! The MaterialX node network that wires a baked material's maps into a surface shader:
//! `image` nodes reading the maps, `extract` splitting the packed ORM map, `normalmap`,
//! a threshold for a cut-out, and the surface shader's inputs. The MaterialX document
//! ([`super::document`]) and the USD export's MaterialX material (`bake::usd`) write the
//! same network, each in its own syntax.

use crate::codegen::AlphaUse;

/// The surface shader of MaterialX's standard library the maps are wired into.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SurfaceModel {
    /// OpenPBR Surface (`open_pbr_surface`), the ASWF's shared surface model.
    OpenPbr,
    /// glTF's metallic-roughness model (`gltf_pbr`): also occlusion and the alpha mode.
    GltfPbr,
    /// Autodesk Standard Surface (`standard_surface`).
    StandardSurface,
}

impl SurfaceModel {
    /// Every model: its name on the command line and its node in MaterialX.
    pub const ALL: [(SurfaceModel, &'static str, &'static str); 3] = [
        (SurfaceModel::OpenPbr, "open-pbr", "open_pbr_surface"),
        (SurfaceModel::GltfPbr, "gltf-pbr", "gltf_pbr"),
        (
            SurfaceModel::StandardSurface,
            "standard-surface",
            "standard_surface",
        ),
    ];

    /// The MaterialX node (`open_pbr_surface`, …).
    pub fn node(self) -> &'static str {
        let (_, _, node) = (Self::ALL.iter())
            .find(|(model, _, _)| *model == self)
            .expect("listed");
        node
    }
}

/// Where an input's value comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum Source {
    /// A constant, as MaterialX writes it (`1`, `0.5`).
    Value(String),
    /// The output of another node of the network.
    Node(String),
    /// Output `output` of a node of the network with several.
    Output(String, String),
    /// An input of the node graph's interface (an exposed parameter).
    Interface(String),
    /// An image file beside the document, and its colour space (none: raw data).
    File {
        path: String,
        colour_space: Option<&'static str>,
    },
}

/// One input of a node.
#[derive(Clone, Debug, PartialEq)]
pub struct Input {
    pub name: String,
    /// The MaterialX type (`float`, `color3`, `vector3`, `integer`, `filename`).
    pub ty: &'static str,
    pub source: Source,
}

impl Input {
    /// The node the input reads, if it reads one.
    pub fn node(&self) -> Option<&str> {
        match &self.source {
            Source::Node(node) | Source::Output(node, _) => Some(node),
            _ => None,
        }
    }
}

/// One node: its name in the network, its category (`image`), its output type and the
/// node definition it instantiates (`ND_image_color3`).
#[derive(Clone, Debug, PartialEq)]
pub struct Node {
    pub name: String,
    pub category: String,
    pub ty: &'static str,
    pub nodedef: String,
    pub inputs: Vec<Input>,
    /// The Veneer node it stands for, when it is that node's head: its label and place
    /// on the canvas (`uiname`, `xpos`, `ypos`), which an import restores.
    pub ui: Option<(String, (f32, f32))>,
}

/// The nodes reading and combining the maps, and the surface shader reading them.
#[derive(Clone, Debug, PartialEq)]
pub struct Network {
    pub nodes: Vec<Node>,
    pub surface: SurfaceModel,
    /// The surface shader's inputs, each a node of `nodes` or a constant.
    pub surface_inputs: Vec<Input>,
    /// The node graph's inputs (exposed parameters), each with its value and the span
    /// offered (`uimin`, `uimax`).
    pub interface: Vec<(Input, Option<(f64, f64)>)>,
    /// Outputs of the node graph besides those the surface reads, by name.
    pub outputs: Vec<Input>,
    /// The graph's own name, kept as the material's `uiname` (element names are
    /// identifiers).
    pub title: Option<String>,
    /// The material node's label and place, kept on the surface shader.
    pub surface_ui: Option<(String, (f32, f32))>,
    /// Named sets of interface values (the graph's presets), as one `variantset`.
    pub variants: Vec<(String, Vec<Input>)>,
}

/// Where a baked material's alpha is.
#[derive(Clone, Debug, PartialEq)]
pub enum AlphaMap {
    /// The material's alpha never shows.
    None,
    /// A grey map of its own.
    Map(String),
    /// The base colour map's alpha channel.
    InBaseColor,
}

/// The maps of a baked material, by file name.
#[derive(Clone, Debug, PartialEq)]
pub struct Maps {
    pub base_color: String,
    /// The colour space of the base colour and emission maps.
    pub colour_space: &'static str,
    pub alpha: AlphaMap,
    /// Occlusion, roughness, metallic in R, G, B.
    pub orm: String,
    /// The emission map and the factor it is multiplied by.
    pub emission: Option<(String, f32)>,
    /// An OpenGL-convention tangent-space normal map.
    pub normal: Option<String>,
}

/// An input of a node.
pub fn input(name: &str, ty: &'static str, source: Source) -> Input {
    Input {
        name: name.to_string(),
        ty,
        source,
    }
}

/// A node of the standard library: its name, category, type, definition and inputs.
pub fn node(
    name: &str,
    category: &str,
    ty: &'static str,
    nodedef: &str,
    inputs: Vec<Input>,
) -> Node {
    Node {
        name: name.to_string(),
        category: category.to_string(),
        ty,
        nodedef: nodedef.to_string(),
        inputs,
        ui: None,
    }
}

/// An `image` node reading `path`.
fn image(
    name: &'static str,
    ty: &'static str,
    nodedef: &'static str,
    path: &str,
    colour_space: Option<&'static str>,
) -> Node {
    let file = Source::File {
        path: path.to_string(),
        colour_space,
    };
    node(
        name,
        "image",
        ty,
        nodedef,
        vec![input("file", "filename", file)],
    )
}

/// The nodes reading OpenGL-convention tangent-space normal map `path` as a shading
/// normal: `normal_texture` and `normal` (a `normalmap` node).
pub fn normal_map_nodes(path: &str) -> [Node; 2] {
    [
        image("normal_texture", "vector3", "ND_image_vector3", path, None),
        node(
            "normal",
            "normalmap",
            "vector3",
            "ND_normalmap_float",
            vec![input(
                "in",
                "vector3",
                Source::Node("normal_texture".into()),
            )],
        ),
    ]
}

/// The network wiring `maps` into `surface`, with the material's `alpha` use.
pub fn network(maps: &Maps, alpha: AlphaUse, surface: SurfaceModel) -> Network {
    let space = Some(maps.colour_space);
    let mut nodes = Vec::new();
    let mut alpha_node = None;
    match &maps.alpha {
        AlphaMap::InBaseColor => {
            nodes.push(image(
                "base_color_texture",
                "color4",
                "ND_image_color4",
                &maps.base_color,
                space,
            ));
            nodes.push(node(
                "albedo",
                "convert",
                "color3",
                "ND_convert_color4_color3",
                vec![input(
                    "in",
                    "color4",
                    Source::Node("base_color_texture".into()),
                )],
            ));
            nodes.push(node(
                "alpha_texture",
                "extract",
                "float",
                "ND_extract_color4",
                vec![
                    input("in", "color4", Source::Node("base_color_texture".into())),
                    input("index", "integer", Source::Value("3".into())),
                ],
            ));
            alpha_node = Some("alpha_texture");
        }
        other => {
            nodes.push(image(
                "albedo",
                "color3",
                "ND_image_color3",
                &maps.base_color,
                space,
            ));
            if let AlphaMap::Map(path) = other {
                nodes.push(image(
                    "alpha_texture",
                    "float",
                    "ND_image_float",
                    path,
                    None,
                ));
                alpha_node = Some("alpha_texture");
            }
        }
    }
    nodes.push(image("orm", "vector3", "ND_image_vector3", &maps.orm, None));
    for (channel, index) in [("occlusion", 0), ("roughness", 1), ("metallic", 2)] {
        nodes.push(node(
            channel,
            "extract",
            "float",
            "ND_extract_vector3",
            vec![
                input("in", "vector3", Source::Node("orm".into())),
                input("index", "integer", Source::Value(index.to_string())),
            ],
        ));
    }
    let emission = maps.emission.as_ref().map(|(path, factor)| {
        if *factor == 1.0 {
            nodes.push(image("emission", "color3", "ND_image_color3", path, space));
        } else {
            nodes.push(image(
                "emission_texture",
                "color3",
                "ND_image_color3",
                path,
                space,
            ));
            nodes.push(node(
                "emission",
                "multiply",
                "color3",
                "ND_multiply_color3FA",
                vec![
                    input("in1", "color3", Source::Node("emission_texture".into())),
                    input("in2", "float", Source::Value(factor.to_string())),
                ],
            ));
        }
        "emission"
    });
    let normal = maps.normal.as_ref().map(|path| {
        nodes.extend(normal_map_nodes(path));
        "normal"
    });
    let node_source = |name: &str| Source::Node(name.to_string());
    let fields = SurfaceFields {
        albedo: node_source("albedo"),
        roughness: node_source("roughness"),
        metallic: node_source("metallic"),
        occlusion: node_source("occlusion"),
        alpha: alpha_node.map(node_source),
        emission: emission.map(node_source),
        normal: normal.map(node_source),
    };
    wire(nodes, fields, alpha, surface, Vec::new())
}

/// Where each input of the surface comes from: a node of the network or a constant.
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceFields {
    /// The base colour, linear.
    pub albedo: Source,
    pub roughness: Source,
    pub metallic: Source,
    pub occlusion: Source,
    /// The opacity, when the material's alpha shows.
    pub alpha: Option<Source>,
    /// The light given off, when the material glows.
    pub emission: Option<Source>,
    /// The shading normal, when the material perturbs it.
    pub normal: Option<Source>,
}

/// The network of `nodes` with `fields` (nodes' outputs or constants: the surface reads
/// the node graph's outputs, never its interface) wired into `surface` (the material's
/// `alpha` use deciding a cut-out) and the node graph's other `outputs`, and only the
/// nodes these read kept.
pub fn wire(
    mut nodes: Vec<Node>,
    fields: SurfaceFields,
    alpha: AlphaUse,
    surface: SurfaceModel,
    outputs: Vec<Input>,
) -> Network {
    let SurfaceFields {
        albedo,
        roughness,
        metallic,
        occlusion,
        alpha: mut opacity,
        emission,
        normal,
    } = fields;
    // A cut-out keeps what reaches the cutoff and drops the rest, as the preview does
    // (glTF's model has an alpha mode of its own).
    if let (Some(value), AlphaUse::Mask(cutoff), false) =
        (opacity.clone(), alpha, surface == SurfaceModel::GltfPbr)
    {
        nodes.push(node(
            "alpha",
            "ifgreatereq",
            "float",
            "ND_ifgreatereq_float",
            vec![
                input("value1", "float", value),
                input("value2", "float", Source::Value(cutoff.to_string())),
                input("in1", "float", Source::Value("1".into())),
                input("in2", "float", Source::Value("0".into())),
            ],
        ));
        opacity = Some(Source::Node("alpha".into()));
    }
    let connect = |name, ty, source: &Source| input(name, ty, source.clone());
    let constant = |name, ty, value: &str| input(name, ty, Source::Value(value.to_string()));
    let mut inputs = Vec::new();
    match surface {
        SurfaceModel::OpenPbr => {
            inputs.extend([
                connect("base_color", "color3", &albedo),
                connect("specular_roughness", "float", &roughness),
                connect("base_metalness", "float", &metallic),
            ]);
            inputs.extend(normal.map(|n| connect("geometry_normal", "vector3", &n)));
            inputs.extend(opacity.map(|a| connect("geometry_opacity", "float", &a)));
            if let Some(e) = emission {
                inputs.extend([
                    connect("emission_color", "color3", &e),
                    constant("emission_luminance", "float", "1"),
                ]);
            }
        }
        SurfaceModel::GltfPbr => {
            inputs.extend([
                connect("base_color", "color3", &albedo),
                connect("roughness", "float", &roughness),
                connect("metallic", "float", &metallic),
                connect("occlusion", "float", &occlusion),
            ]);
            inputs.extend(normal.map(|n| connect("normal", "vector3", &n)));
            if let Some(a) = opacity {
                inputs.push(connect("alpha", "float", &a));
                match alpha {
                    AlphaUse::Mask(cutoff) => inputs.extend([
                        constant("alpha_mode", "integer", "1"),
                        constant("alpha_cutoff", "float", &cutoff.to_string()),
                    ]),
                    _ => inputs.push(constant("alpha_mode", "integer", "2")),
                }
            }
            inputs.extend(emission.map(|e| connect("emissive", "color3", &e)));
        }
        SurfaceModel::StandardSurface => {
            inputs.extend([
                constant("base", "float", "1"),
                connect("base_color", "color3", &albedo),
                connect("specular_roughness", "float", &roughness),
                connect("metalness", "float", &metallic),
            ]);
            inputs.extend(normal.map(|n| connect("normal", "vector3", &n)));
            if let Some(a) = opacity {
                // Standard Surface's opacity is a colour.
                nodes.push(node(
                    "opacity",
                    "convert",
                    "color3",
                    "ND_convert_float_color3",
                    vec![input("in", "float", a)],
                ));
                inputs.push(input("opacity", "color3", Source::Node("opacity".into())));
            }
            if let Some(e) = emission {
                inputs.extend([
                    connect("emission_color", "color3", &e),
                    constant("emission", "float", "1"),
                ]);
            }
        }
    }
    // Only what the surface and the other outputs read (OpenPBR and Standard Surface
    // have no occlusion).
    let mut needed: Vec<String> = (inputs.iter().chain(&outputs).filter_map(Input::node))
        .map(str::to_string)
        .collect();
    let mut read = std::collections::BTreeSet::new();
    while let Some(name) = needed.pop() {
        if read.insert(name.clone()) {
            let node =
                (nodes.iter().find(|node| node.name == name)).expect("a node of the network");
            needed.extend(
                node.inputs
                    .iter()
                    .filter_map(Input::node)
                    .map(str::to_string),
            );
        }
    }
    nodes.retain(|node| read.contains(&node.name));
    Network {
        nodes,
        surface,
        surface_inputs: inputs,
        interface: Vec::new(),
        outputs,
        title: None,
        surface_ui: None,
        variants: Vec::new(),
    }
}

impl Network {
    /// The node definition of the surface shader (`ND_open_pbr_surface_surfaceshader`).
    pub fn surface_nodedef(&self) -> String {
        format!("ND_{}_surfaceshader", self.surface.node())
    }
}
