//! MaterialX export, baked tier (`veneer compile --target mtlx`): a MaterialX 1.39
//! document whose surface shader (`open_pbr_surface` by default, `gltf_pbr` or
//! `standard_surface`) reads the material's maps, baked as `veneer bake` bakes them,
//! through `image` nodes beside it. Colour maps carry their colour space (Blinn-Phong
//! materials hold display values, read as sRGB; metallic-roughness ones linear values),
//! roughness and metallic come out of the packed ORM map by `extract`, the normal map goes
//! through a `normalmap` node, a cut-out alpha through a threshold. A material that reads
//! distance or mesh fields is baked into its preview mesh's UV layout (the maps belong to
//! that mesh); any other over its preview square.

mod coverage;
mod custom;
mod groups;
mod import;
mod network;
mod procedural;
mod standard;

pub use coverage::coverage_table;
pub use import::import;
pub use network::{AlphaMap, Input, Maps, Network, Source, SurfaceModel, network};
pub use procedural::{ALBEDO_OUTPUT, Untranslatable};

use super::{BakeError, BakeSettings, BakeSurface, Format, Map, NormalConvention, bake};
use crate::codegen::{AlphaUse, Compiled};
use crate::fsutil::Naming;
use crate::graph::Shading;
use custom::Language;
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// How a MaterialX export keeps the material.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Tier {
    /// Every map baked, read by `image` nodes.
    #[default]
    Baked,
    /// The graph translated node by node (the shading normal's map baked); refused,
    /// naming the nodes, when a node cannot be translated.
    Procedural,
    /// Procedural where every node translates, else baked.
    Auto,
}

impl Tier {
    /// Every tier and its name on the command line.
    pub const ALL: [(Tier, &'static str); 3] = [
        (Tier::Baked, "baked"),
        (Tier::Procedural, "procedural"),
        (Tier::Auto, "auto"),
    ];

    /// The tier's name on the command line.
    pub fn name(self) -> &'static str {
        let (_, name) = (Self::ALL.iter())
            .find(|(tier, _)| *tier == self)
            .expect("listed");
        name
    }
}

/// What a MaterialX export bakes and wires.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaterialxSettings {
    pub tier: Tier,
    pub surface: SurfaceModel,
    /// Width and height of every map in pixels.
    pub size: u32,
    pub time: f32,
}

/// The maps an export may write beside the document, in the order they are wired.
const MAPS: [Map; 5] = [
    Map::Albedo,
    Map::Alpha,
    Map::Orm,
    Map::Emission,
    Map::Normal,
];

/// Every file an export to `path` may write, `path` itself first: the maps go beside it
/// as `<stem>_<map>.png` (alpha, emission and normal only when the material has them),
/// the procedural tier's node functions as `<stem>_veneer.glsl` and `.metal`.
pub fn materialx_files(path: &Path) -> Vec<PathBuf> {
    let stem = path.with_extension("");
    std::iter::once(path.to_path_buf())
        .chain(MAPS.map(|map| super::map_path(&stem, map, Format::Png8)))
        .chain(Language::ALL.map(|language| functions_path(path, language)))
        .collect()
}

/// Where the procedural tier's node functions in `language` go: `<stem>_veneer.glsl`,
/// `<stem>_veneer.metal`.
fn functions_path(path: &Path, language: Language) -> PathBuf {
    let stem = path.file_stem().unwrap_or_default().to_string_lossy();
    path.with_file_name(format!("{stem}_veneer.{}", language.extension()))
}

/// What a MaterialX export wrote.
#[derive(Debug)]
pub struct MaterialxExport {
    /// The files, the document first.
    pub files: Vec<PathBuf>,
    /// The tier the document has (`Auto` resolves to one of the others).
    pub tier: Tier,
    /// Under `Auto`, the nodes that made the export fall back to baked.
    pub untranslatable: Vec<Untranslatable>,
}

/// Exports `compiled` (parameters baked) as a MaterialX document at `path` with its maps
/// beside it, calling `progress(done, total)` as tiles render (answering `false` stops
/// the export, nothing written). The maps are baked into a temporary folder beside
/// `path` and everything is put in place together, so a failed export leaves no file.
pub fn export_materialx(
    gpu: &crate::render::GpuContext,
    compiled: &Compiled,
    settings: &MaterialxSettings,
    path: &Path,
    mut progress: impl FnMut(u64, u64) -> bool,
) -> Result<MaterialxExport, BakeError> {
    let folder = super::output_folder(path)?;
    let uses = compiled.uses();
    let stem_name = path
        .file_stem()
        .unwrap_or_default()
        .to_string_lossy()
        .into_owned();
    let normal_map = (uses.perturbs_normal())
        .then(|| super::map_path(Path::new(&stem_name), Map::Normal, Format::Png8))
        .map(|name| name.display().to_string());
    let mut untranslatable = Vec::new();
    let procedural = match settings.tier {
        Tier::Baked => None,
        Tier::Procedural | Tier::Auto => {
            match procedural::translate(
                compiled,
                &stem_name,
                settings.tier == Tier::Auto,
                settings.surface,
                normal_map.as_deref(),
            ) {
                Ok(procedural) => Some(procedural),
                Err(nodes) if settings.tier == Tier::Procedural => {
                    return Err(BakeError::Untranslatable(nodes));
                }
                Err(nodes) => {
                    untranslatable = nodes;
                    None
                }
            }
        }
    };
    let on_mesh = reads_mesh(compiled);
    let maps: Vec<Map> = MAPS
        .into_iter()
        .filter(|map| match map {
            // The procedural tier bakes the shading normal only.
            Map::Normal => uses.perturbs_normal(),
            _ if procedural.is_some() => false,
            Map::Alpha => uses.alpha != AlphaUse::Opaque,
            _ => true,
        })
        .collect();
    let surface = match on_mesh {
        true => BakeSurface::MeshUv(compiled.preview.mesh.clone()),
        false => BakeSurface::Plane(None),
    };
    let bake_settings = BakeSettings {
        surface,
        size: settings.size,
        maps,
        // As float, so emission past 1 can be scaled into the 8-bit map (every map is
        // then stored as the PNG `bake` would have written).
        format: Format::Exr,
        normal: NormalConvention::OpenGl,
        time: settings.time,
    };
    let write_error = |path: &Path| {
        let path = path.to_path_buf();
        move |error: std::io::Error| BakeError::Write { path, error }
    };
    let staging = tempfile::Builder::new()
        .prefix(".veneer-materialx-")
        .tempdir_in(folder)
        .map_err(write_error(folder))?;
    let stem = staging.path().join(&stem_name);
    let baked = match bake_settings.maps.is_empty() {
        true => Vec::new(),
        false => bake(gpu, compiled, &bake_settings, &stem, &mut progress)?,
    };
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    let mut wired = Vec::new();
    let mut strength = 1.0;
    for map in &baked {
        let read = |error: image::ImageError| BakeError::Write {
            path: map.path.clone(),
            error: std::io::Error::other(error),
        };
        let image = image::open(&map.path).map_err(read)?.to_rgba32f();
        let pixels: Vec<[f32; 4]> = image.pixels().map(|p| p.0).collect();
        // Emission as the glTF export keeps it: over its brightest channel, that
        // brightness past 1 a factor in the network; none where nothing glows.
        let pixels = match map.map {
            Map::Emission => match super::model::over_brightest(&pixels) {
                Some((scaled, factor)) => {
                    strength = factor;
                    scaled
                }
                None => continue,
            },
            _ => pixels,
        };
        let name = super::map_path(Path::new(&stem_name), map.map, Format::Png8);
        let png = super::model::png(map.map.name(), &pixels, settings.size, false)
            .map_err(write_error(&map.path))?;
        wired.push((map.map, name.display().to_string()));
        files.push((path.with_file_name(name), png));
    }
    let place = match on_mesh {
        true => format!("the UV layout of {}", compiled.preview.mesh),
        false => "the preview square".to_string(),
    };
    let (document, tier) = match procedural {
        Some(procedural) => {
            for (file, bytes) in &procedural.files {
                files.push((path.with_file_name(file), bytes.clone()));
            }
            for baked in &procedural.baked {
                let texture = bake_node(gpu, baked, settings, staging.path(), &mut progress)?;
                files.push((path.with_file_name(&baked.file), texture));
            }
            let file_name = |language| {
                let file = functions_path(path, language);
                file.file_name()
                    .unwrap_or_default()
                    .to_string_lossy()
                    .into_owned()
            };
            let mut definitions = String::new();
            for definition in &procedural.definitions {
                definitions.push_str(&definition.xml(file_name));
            }
            for group in groups::definitions(&procedural.groups) {
                definitions.push_str(&group.definition_xml());
            }
            let used = !procedural.definitions.is_empty();
            for language in Language::ALL.into_iter().filter(|_| used) {
                let file = functions_path(path, language);
                let text = custom::functions(&procedural.definitions, language)
                    .map_err(|error| write_error(&file)(std::io::Error::other(error)))?;
                files.push((file, text.into_bytes()));
            }
            let comment = comment(
                compiled,
                "its nodes translated",
                &wired,
                settings.size,
                &place,
            );
            let name = element_name(&compiled.checked.name);
            (
                xml(&procedural.network, &name, &comment, &definitions),
                Tier::Procedural,
            )
        }
        None => (
            document(compiled, settings, &wired, strength, &place),
            Tier::Baked,
        ),
    };
    let mut writes = vec![(path, Naming::Given, document.as_bytes())];
    writes.extend(
        (files.iter()).map(|(target, bytes)| (target.as_path(), Naming::Implied, bytes.as_slice())),
    );
    crate::fsutil::write_together(writes)
        .map_err(|(path, error)| BakeError::Write { path, error })?;
    Ok(MaterialxExport {
        files: std::iter::once(path.to_path_buf())
            .chain(files.into_iter().map(|(target, _)| target))
            .collect(),
        tier,
        untranslatable,
    })
}

/// The float (OpenEXR) texture of `baked`: its graph's albedo, baked over the preview
/// mesh's UV layout where the graph reads the mesh's fields, else over the preview
/// square, in `staging`.
fn bake_node(
    gpu: &crate::render::GpuContext,
    baked: &procedural::BakedNode,
    settings: &MaterialxSettings,
    staging: &Path,
    progress: impl FnMut(u64, u64) -> bool,
) -> Result<Vec<u8>, BakeError> {
    let options = crate::codegen::CompileOptions::default();
    let compiled = crate::codegen::compile(&baked.graph, &options).map_err(|error| {
        let error = std::io::Error::other(format!("cannot compile what it bakes: {error}"));
        BakeError::Write {
            path: PathBuf::from(&baked.file),
            error,
        }
    })?;
    let surface = match reads_mesh(&compiled) {
        true => BakeSurface::MeshUv(compiled.preview.mesh.clone()),
        false => BakeSurface::Plane(None),
    };
    let bake_settings = BakeSettings {
        surface,
        size: settings.size,
        maps: vec![Map::Albedo],
        format: Format::Exr,
        normal: NormalConvention::OpenGl,
        time: settings.time,
    };
    let stem = staging.join(Path::new(&baked.file).with_extension(""));
    let written = bake(gpu, &compiled, &bake_settings, &stem, progress)?;
    let file = &written.first().expect("the albedo map").path;
    std::fs::read(file).map_err(|error| BakeError::Write {
        path: file.clone(),
        error,
    })
}

/// Whether `compiled` reads distance or mesh fields (so bakes go over its preview mesh's
/// UV layout).
fn reads_mesh(compiled: &Compiled) -> bool {
    let uses = compiled.uses();
    uses.fields.iter().any(|&read| read) || uses.mesh_fields.iter().any(Option::is_some)
}

/// The document's opening comment: what made it and how (`how`: "its maps baked"),
/// with the size and place of any maps baked.
fn comment(
    compiled: &Compiled,
    how: &str,
    wired: &[(Map, String)],
    size: u32,
    place: &str,
) -> String {
    let title = attribute(&compiled.checked.name.replace("--", "-"));
    let version = env!("CARGO_PKG_VERSION");
    let maps = match wired {
        [] => String::new(),
        _ if how.contains("maps") => format!(" at {size}×{size} over {place}"),
        _ => format!(", its normal map baked at {size}×{size} over {place}"),
    };
    format!("{title}: exported by Veneer {version}, {how}{maps}.")
}

/// `text` escaped for an XML attribute value.
fn attribute(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('"', "&quot;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// `name` as a MaterialX element name: letters, digits and underscores, not starting
/// with a digit.
pub fn element_name(name: &str) -> String {
    let mut cleaned: String = name
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    if cleaned.is_empty() || cleaned.starts_with(|c: char| c.is_ascii_digit()) {
        cleaned.insert_str(0, "veneer_");
    }
    cleaned
}

/// The colour space of a colour map: Blinn-Phong materials hold display values (read as
/// sRGB, as glTF stores them), metallic-roughness ones linear values.
fn colour_space(shading: Shading) -> &'static str {
    match shading.is_linear() {
        true => "lin_rec709",
        false => "srgb_texture",
    }
}

/// The document: a node graph reading the maps (`wired`: each map and its file name; the
/// emission map's values times `strength`) and giving the surface inputs as outputs, the
/// surface shader and the material.
fn document(
    compiled: &Compiled,
    settings: &MaterialxSettings,
    wired: &[(Map, String)],
    strength: f32,
    place: &str,
) -> String {
    let file = |map: Map| {
        wired
            .iter()
            .find(|(wired, _)| *wired == map)
            .map(|(_, file)| file.clone())
    };
    let maps = Maps {
        base_color: file(Map::Albedo).expect("always baked"),
        colour_space: colour_space(compiled.checked.shading),
        alpha: file(Map::Alpha).map_or(AlphaMap::None, AlphaMap::Map),
        orm: file(Map::Orm).expect("always baked"),
        emission: file(Map::Emission).map(|path| (path, strength)),
        normal: file(Map::Normal),
    };
    let network = network(&maps, compiled.uses().alpha, settings.surface);
    let name = element_name(&compiled.checked.name);
    let comment = comment(compiled, "its maps baked", wired, settings.size, place);
    xml(&network, &name, &comment, "")
}

/// The name of the node graph output that gives `source` (a node's output) to the
/// surface.
fn graph_output(source: &Source) -> Option<String> {
    match source {
        Source::Node(node) => Some(format!("{node}_output")),
        Source::Output(node, output) => Some(format!("{node}_{output}_output")),
        _ => None,
    }
}

/// A MaterialX input element's attributes after its name and type: its value, or the
/// node it reads (through node graph `graph`'s outputs where the graph is given).
fn source_attributes(source: &Source, graph: Option<&str>) -> String {
    match (source, graph) {
        (Source::Value(value), _) => format!("value=\"{}\"", attribute(value)),
        (Source::Node(_) | Source::Output(..), Some(graph)) => {
            let output = graph_output(source).expect("a node's output");
            format!("nodegraph=\"{graph}\" output=\"{output}\"")
        }
        (Source::Node(node), None) => format!("nodename=\"{node}\""),
        (Source::Output(node, output), None) => {
            format!("nodename=\"{node}\" output=\"{output}\"")
        }
        (Source::Interface(name), _) => format!("interfacename=\"{name}\""),
        (Source::File { path, colour_space }, _) => {
            let space = colour_space
                .map(|s| format!(" colorspace=\"{s}\""))
                .unwrap_or_default();
            format!("value=\"{}\"{space}", attribute(path))
        }
    }
}

/// The attributes keeping a Veneer node's label and place (` uiname=… xpos=… ypos=…`).
fn ui_attributes(ui: &Option<(String, (f32, f32))>) -> String {
    (ui.as_ref())
        .map(|(label, (x, y))| {
            format!(" uiname=\"{}\" xpos=\"{x}\" ypos=\"{y}\"", attribute(label))
        })
        .unwrap_or_default()
}

/// An input element at `indent`, `extra` attributes after its source.
fn input_xml(text: &mut String, indent: &str, input: &Input, graph: Option<&str>, extra: &str) {
    let _ = writeln!(
        text,
        "{indent}<input name=\"{}\" type=\"{}\" {}{extra} />",
        input.name,
        input.ty,
        source_attributes(&input.source, graph)
    );
}

/// A node graph's output element: `output`'s name, type and the node output it gives.
fn output_xml(text: &mut String, output: &Input) {
    let reads = source_attributes(&output.source, None);
    let _ = writeln!(
        text,
        "    <output name=\"{}\" type=\"{}\" {reads} />",
        output.name, output.ty
    );
}

/// `nodes` as the elements of a node graph.
fn nodes_xml(text: &mut String, nodes: &[network::Node]) {
    for node in nodes {
        let ui = ui_attributes(&node.ui);
        let _ = writeln!(
            text,
            "    <{} name=\"{}\" type=\"{}\"{ui}>",
            node.category, node.name, node.ty
        );
        for input in &node.inputs {
            input_xml(text, "      ", input, None, "");
        }
        let _ = writeln!(text, "    </{}>", node.category);
    }
}

/// `network` as a MaterialX 1.39 document: `definitions` (elements of the document's own
/// node definitions, if any) first, then the nodes in node graph `NG_<name>` with its
/// interface inputs and an output per node the surface reads, surface shader `SR_<name>`
/// and material `<name>`.
pub fn xml(network: &Network, name: &str, comment: &str, definitions: &str) -> String {
    let mut text = String::new();
    let _ = writeln!(
        text,
        "<?xml version=\"1.0\"?>\n<!-- {} -->",
        comment.replace("--", "-")
    );
    let _ = writeln!(
        text,
        "<materialx version=\"1.39\" colorspace=\"lin_rec709\">"
    );
    text.push_str(definitions);
    let _ = writeln!(text, "  <nodegraph name=\"NG_{name}\">");
    for (input, range) in &network.interface {
        let span = range
            .map(|(low, high)| format!(" uimin=\"{low}\" uimax=\"{high}\""))
            .unwrap_or_default();
        input_xml(&mut text, "    ", input, None, &span);
    }
    nodes_xml(&mut text, &network.nodes);
    let graph = format!("NG_{name}");
    // One output per node output the surface reads, however many inputs read it.
    let mut given = std::collections::BTreeSet::new();
    for input in &network.surface_inputs {
        if let Some(output) = graph_output(&input.source)
            && given.insert(output.clone())
        {
            let reads = source_attributes(&input.source, None);
            let _ = writeln!(
                text,
                "    <output name=\"{output}\" type=\"{}\" {reads} />",
                input.ty
            );
        }
    }
    for output in &network.outputs {
        output_xml(&mut text, output);
    }
    let model = network.surface.node();
    let _ = writeln!(
        text,
        "  </nodegraph>\n  <{model} name=\"SR_{name}\" type=\"surfaceshader\"{}>",
        ui_attributes(&network.surface_ui)
    );
    for input in &network.surface_inputs {
        input_xml(&mut text, "    ", input, Some(&graph), "");
    }
    let title = (network.title.as_ref())
        .map(|title| format!(" uiname=\"{}\"", attribute(title)))
        .unwrap_or_default();
    let _ = writeln!(
        text,
        "  </{model}>\n  <surfacematerial name=\"{name}\" type=\"material\"{title}>"
    );
    let _ = writeln!(
        text,
        "    <input name=\"surfaceshader\" type=\"surfaceshader\" nodename=\"SR_{name}\" />"
    );
    text.push_str("  </surfacematerial>\n");
    if !network.variants.is_empty() {
        text.push_str("  <variantset name=\"presets\">\n");
        for (name, inputs) in &network.variants {
            let _ = writeln!(text, "    <variant name=\"{}\">", element_name(name));
            for input in inputs {
                input_xml(&mut text, "      ", input, None, "");
            }
            text.push_str("    </variant>\n");
        }
        text.push_str("  </variantset>\n");
    }
    text.push_str("</materialx>\n");
    text
}

/// Components of a value of type `ty` as MaterialX writes them (`0.1, 0.2, 0.3`).
pub fn value_text(components: &[f64; 3], ty: crate::nodes::value::ValueType) -> String {
    (components[..ty.width()].iter())
        .map(|x| format!("{x}"))
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_become_element_names_and_values_are_escaped() {
        assert_eq!(element_name("Wood (polished) #2"), "Wood__polished___2");
        assert_eq!(element_name("3 marbles"), "veneer_3_marbles");
        assert_eq!(element_name(""), "veneer_");
        assert_eq!(attribute("a \"b\" <&>"), "a &quot;b&quot; &lt;&amp;&gt;");
    }

    #[test]
    fn the_files_beside_are_named_after_the_document() {
        let files = materialx_files(Path::new("out/wood.mtlx"));
        assert_eq!(files[0], Path::new("out/wood.mtlx"));
        assert!(files.contains(&PathBuf::from("out/wood_albedo.png")));
        assert!(files.contains(&PathBuf::from("out/wood_orm.png")));
        assert!(files.contains(&PathBuf::from("out/wood_veneer.glsl")));
        assert!(files.contains(&PathBuf::from("out/wood_veneer.metal")));
        assert_eq!(files.len(), 3 + MAPS.len());
    }
}
