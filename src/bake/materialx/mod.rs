//! MaterialX export, baked tier (`veneer compile --target mtlx`): a MaterialX 1.39
//! document whose surface shader (`open_pbr_surface` by default, `gltf_pbr` or
//! `standard_surface`) reads the material's maps, baked as `veneer bake` bakes them,
//! through `image` nodes beside it. Colour maps carry their colour space (Blinn-Phong
//! materials hold display values, read as sRGB; metallic-roughness ones linear values),
//! roughness and metallic come out of the packed ORM map by `extract`, the normal map goes
//! through a `normalmap` node, a cut-out alpha through a threshold. A material that reads
//! distance or mesh fields is baked into its preview mesh's UV layout (the maps belong to
//! that mesh); any other over its preview square.

mod network;

pub use network::{AlphaMap, Input, Maps, Network, Source, SurfaceModel, network};

use super::{BakeError, BakeSettings, BakeSurface, Format, Map, NormalConvention, bake};
use crate::codegen::{AlphaUse, Compiled};
use crate::fsutil::Naming;
use crate::graph::Shading;
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// What a MaterialX export bakes and wires.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaterialxSettings {
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
/// as `<stem>_<map>.png` (alpha, emission and normal only when the material has them).
pub fn materialx_files(path: &Path) -> Vec<PathBuf> {
    let stem = path.with_extension("");
    std::iter::once(path.to_path_buf())
        .chain(MAPS.map(|map| super::map_path(&stem, map, Format::Png8)))
        .collect()
}

/// Exports `compiled` (parameters baked) as a MaterialX document at `path` with its maps
/// beside it, calling `progress(done, total)` as tiles render (answering `false` stops
/// the export, nothing written). The maps are baked into a temporary folder beside
/// `path` and everything is put in place together, so a failed export leaves no file.
/// The paths written come back, the document first.
pub fn export_materialx(
    gpu: &crate::render::GpuContext,
    compiled: &Compiled,
    settings: &MaterialxSettings,
    path: &Path,
    progress: impl FnMut(u64, u64) -> bool,
) -> Result<Vec<PathBuf>, BakeError> {
    let folder = super::output_folder(path)?;
    let uses = compiled.uses();
    let on_mesh =
        uses.fields.iter().any(|&read| read) || uses.mesh_fields.iter().any(Option::is_some);
    let maps: Vec<Map> = MAPS
        .into_iter()
        .filter(|map| match map {
            Map::Alpha => uses.alpha != AlphaUse::Opaque,
            Map::Normal => uses.perturbs_normal(),
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
    let stem_name = path
        .file_stem()
        .unwrap_or_default()
        .to_string_lossy()
        .into_owned();
    let stem = staging.path().join(&stem_name);
    let baked = bake(gpu, compiled, &bake_settings, &stem, progress)?;
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
    let document = document(compiled, settings, &wired, strength, &place);
    let mut writes = vec![(path, Naming::Given, document.as_bytes())];
    writes.extend(
        (files.iter()).map(|(target, bytes)| (target.as_path(), Naming::Implied, bytes.as_slice())),
    );
    crate::fsutil::write_together(writes)
        .map_err(|(path, error)| BakeError::Write { path, error })?;
    Ok(std::iter::once(path.to_path_buf())
        .chain(files.into_iter().map(|(target, _)| target))
        .collect())
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
    let title = attribute(&compiled.checked.name.replace("--", "-"));
    let (version, size) = (env!("CARGO_PKG_VERSION"), settings.size);
    let comment = format!(
        "{title}: exported by Veneer {version}, its maps baked at {size}×{size} over {place}."
    );
    xml(&network, &name, &comment)
}

/// A MaterialX input element's attributes after its name and type: its value, or the
/// node it reads (`output` names the node graph output where the graph is given).
fn source_attributes(source: &Source, graph: Option<&str>) -> String {
    match (source, graph) {
        (Source::Value(value), _) => format!("value=\"{}\"", attribute(value)),
        (Source::Node(node), None) => format!("nodename=\"{node}\""),
        (Source::Node(node), Some(graph)) => {
            format!("nodegraph=\"{graph}\" output=\"{node}_output\"")
        }
        (Source::File { path, colour_space }, _) => {
            let space = colour_space
                .map(|s| format!(" colorspace=\"{s}\""))
                .unwrap_or_default();
            format!("value=\"{}\"{space}", attribute(path))
        }
    }
}

/// `network` as a MaterialX 1.39 document: the nodes in node graph `NG_<name>` with an
/// output per node the surface reads, surface shader `SR_<name>` and material `<name>`.
pub fn xml(network: &Network, name: &str, comment: &str) -> String {
    let mut text = String::new();
    let _ = writeln!(
        text,
        "<?xml version=\"1.0\"?>\n<!-- {} -->",
        comment.replace("--", "-")
    );
    let _ = writeln!(
        text,
        "<materialx version=\"1.39\" colorspace=\"lin_rec709\">\n  <nodegraph name=\"NG_{name}\">"
    );
    for node in &network.nodes {
        let _ = writeln!(
            text,
            "    <{} name=\"{}\" type=\"{}\">",
            node.category, node.name, node.ty
        );
        for input in &node.inputs {
            let _ = writeln!(
                text,
                "      <input name=\"{}\" type=\"{}\" {} />",
                input.name,
                input.ty,
                source_attributes(&input.source, None)
            );
        }
        let _ = writeln!(text, "    </{}>", node.category);
    }
    let graph = format!("NG_{name}");
    // One output per node the surface reads, however many inputs read it.
    let mut given = std::collections::BTreeSet::new();
    for input in &network.surface_inputs {
        if let Source::Node(node) = input.source
            && given.insert(node)
        {
            let _ = writeln!(
                text,
                "    <output name=\"{node}_output\" type=\"{}\" nodename=\"{node}\" />",
                input.ty
            );
        }
    }
    let model = network.surface.node();
    let _ = writeln!(
        text,
        "  </nodegraph>\n  <{model} name=\"SR_{name}\" type=\"surfaceshader\">"
    );
    for input in &network.surface_inputs {
        let _ = writeln!(
            text,
            "    <input name=\"{}\" type=\"{}\" {} />",
            input.name,
            input.ty,
            source_attributes(&input.source, Some(&graph))
        );
    }
    let _ = writeln!(
        text,
        "  </{model}>\n  <surfacematerial name=\"{name}\" type=\"material\">"
    );
    let _ = writeln!(
        text,
        "    <input name=\"surfaceshader\" type=\"surfaceshader\" nodename=\"SR_{name}\" />"
    );
    text.push_str("  </surfacematerial>\n</materialx>\n");
    text
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
        assert_eq!(files.len(), 1 + MAPS.len());
    }
}
