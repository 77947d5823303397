//! MaterialX export, baked tier (`veneer compile --target mtlx`): a MaterialX 1.39
//! document whose surface shader (`open_pbr_surface` by default, `gltf_pbr` or
//! `standard_surface`) reads the material's maps, baked as `veneer bake` bakes them,
//! through `image` nodes beside it. Colour maps carry their colour space (Blinn-Phong
//! materials hold display values, read as sRGB; metallic-roughness ones linear values),
//! roughness and metallic come out of the packed ORM map by `extract`, the normal map goes
//! through a `normalmap` node, a cut-out alpha through a threshold. A material that reads
//! distance or mesh fields is baked into its preview mesh's UV layout (the maps belong to
//! that mesh); any other over its preview square.

use super::{BakeError, BakeSettings, BakeSurface, Format, Map, NormalConvention, bake};
use crate::codegen::{AlphaUse, Compiled};
use crate::fsutil::Naming;
use crate::graph::Shading;
use std::fmt::Write;
use std::path::{Path, PathBuf};

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
        let (_, _, node) = Self::ALL
            .iter()
            .find(|(model, _, _)| *model == self)
            .expect("listed");
        node
    }
}

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
        format: Format::Png8,
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
    let baked = bake(
        gpu,
        compiled,
        &bake_settings,
        &staging.path().join(&stem_name),
        progress,
    )?;
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    let mut wired = Vec::new();
    for map in &baked {
        let bytes = std::fs::read(&map.path).map_err(write_error(&map.path))?;
        // An emission map that is black everywhere is left out, as glTF leaves it.
        if map.map == Map::Emission && is_black(&bytes) {
            continue;
        }
        let name = map.path.file_name().unwrap_or_default().to_owned();
        wired.push((map.map, name.to_string_lossy().into_owned()));
        files.push((path.with_file_name(name), bytes));
    }
    let place = match on_mesh {
        true => format!("the UV layout of {}", compiled.preview.mesh),
        false => "the preview square".to_string(),
    };
    let document = document(compiled, settings, &wired, &place);
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

/// Whether an 8-bit PNG holds nothing but black (one that does not decode counts as not).
fn is_black(png: &[u8]) -> bool {
    image::load_from_memory(png)
        .map(|image| image.to_rgb8().pixels().all(|p| p.0 == [0, 0, 0]))
        .unwrap_or(false)
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
fn element_name(name: &str) -> String {
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

/// The document: a node graph reading the maps (`wired`: each map and its file name) and
/// giving the surface inputs as outputs, the surface shader and the material.
fn document(
    compiled: &Compiled,
    settings: &MaterialxSettings,
    wired: &[(Map, String)],
    place: &str,
) -> String {
    let name = element_name(&compiled.checked.name);
    let uses = compiled.uses();
    let has = |map: Map| {
        wired
            .iter()
            .find(|(wired, _)| *wired == map)
            .map(|(_, file)| attribute(file))
    };
    let space = colour_space(compiled.checked.shading);
    let mut graph = String::new();
    let mut image = |node: &str, ty: &str, file: &str, space: Option<&str>| {
        let space = space
            .map(|s| format!(" colorspace=\"{s}\""))
            .unwrap_or_default();
        let _ = writeln!(
            graph,
            "    <image name=\"{node}\" type=\"{ty}\">\n      <input name=\"file\" type=\"filename\" value=\"{file}\"{space} />\n    </image>"
        );
    };
    let albedo = has(Map::Albedo).expect("always baked");
    let orm = has(Map::Orm).expect("always baked");
    image("albedo", "color3", &albedo, Some(space));
    image("orm", "vector3", &orm, None);
    let alpha = has(Map::Alpha);
    if let Some(file) = &alpha {
        image("alpha_texture", "float", file, None);
    }
    let emission = has(Map::Emission);
    if let Some(file) = &emission {
        image("emission", "color3", file, Some(space));
    }
    let normal = has(Map::Normal);
    if let Some(file) = &normal {
        image("normal_texture", "vector3", file, None);
    }
    let mut nodes = String::new();
    for (channel, index) in [("occlusion", 0), ("roughness", 1), ("metallic", 2)] {
        let _ = writeln!(
            nodes,
            "    <extract name=\"{channel}\" type=\"float\">\n      <input name=\"in\" type=\"vector3\" nodename=\"orm\" />\n      <input name=\"index\" type=\"integer\" value=\"{index}\" />\n    </extract>"
        );
    }
    if normal.is_some() {
        nodes.push_str("    <normalmap name=\"normal\" type=\"vector3\">\n      <input name=\"in\" type=\"vector3\" nodename=\"normal_texture\" />\n    </normalmap>\n");
    }
    // A cut-out keeps what reaches the cutoff and drops the rest, as the preview does.
    let cutout = match uses.alpha {
        AlphaUse::Mask(cutoff) if settings.surface != SurfaceModel::GltfPbr => Some(cutoff),
        _ => None,
    };
    let opacity_node = match (alpha.is_some(), cutout) {
        (false, _) => None,
        (true, None) => Some("alpha_texture"),
        (true, Some(cutoff)) => {
            let _ = writeln!(
                nodes,
                "    <ifgreatereq name=\"alpha\" type=\"float\">\n      <input name=\"value1\" type=\"float\" nodename=\"alpha_texture\" />\n      <input name=\"value2\" type=\"float\" value=\"{cutoff}\" />\n      <input name=\"in1\" type=\"float\" value=\"1\" />\n      <input name=\"in2\" type=\"float\" value=\"0\" />\n    </ifgreatereq>"
            );
            Some("alpha")
        }
    };
    let opacity_node = match (opacity_node, settings.surface) {
        // Standard Surface's opacity is a colour.
        (Some(node), SurfaceModel::StandardSurface) => {
            let _ = writeln!(
                nodes,
                "    <convert name=\"opacity\" type=\"color3\">\n      <input name=\"in\" type=\"float\" nodename=\"{node}\" />\n    </convert>"
            );
            Some("opacity")
        }
        (node, _) => node,
    };
    // Each surface input: (its name in the model, type, the graph node giving it).
    let mut inputs: Vec<(&str, &str, &str)> = Vec::new();
    let mut constants: Vec<(&str, &str, String)> = Vec::new();
    match settings.surface {
        SurfaceModel::OpenPbr => {
            inputs.extend([
                ("base_color", "color3", "albedo"),
                ("specular_roughness", "float", "roughness"),
                ("base_metalness", "float", "metallic"),
            ]);
            if normal.is_some() {
                inputs.push(("geometry_normal", "vector3", "normal"));
            }
            if let Some(node) = opacity_node {
                inputs.push(("geometry_opacity", "float", node));
            }
            if emission.is_some() {
                inputs.push(("emission_color", "color3", "emission"));
                constants.push(("emission_luminance", "float", "1".into()));
            }
        }
        SurfaceModel::GltfPbr => {
            inputs.extend([
                ("base_color", "color3", "albedo"),
                ("roughness", "float", "roughness"),
                ("metallic", "float", "metallic"),
                ("occlusion", "float", "occlusion"),
            ]);
            if normal.is_some() {
                inputs.push(("normal", "vector3", "normal"));
            }
            if let Some(node) = opacity_node {
                inputs.push(("alpha", "float", node));
                let (mode, cutoff) = match uses.alpha {
                    AlphaUse::Mask(cutoff) => (1, Some(cutoff)),
                    _ => (2, None),
                };
                constants.push(("alpha_mode", "integer", mode.to_string()));
                if let Some(cutoff) = cutoff {
                    constants.push(("alpha_cutoff", "float", cutoff.to_string()));
                }
            }
            if emission.is_some() {
                inputs.push(("emissive", "color3", "emission"));
            }
        }
        SurfaceModel::StandardSurface => {
            constants.push(("base", "float", "1".into()));
            inputs.extend([
                ("base_color", "color3", "albedo"),
                ("specular_roughness", "float", "roughness"),
                ("metalness", "float", "metallic"),
            ]);
            if normal.is_some() {
                inputs.push(("normal", "vector3", "normal"));
            }
            if let Some(node) = opacity_node {
                inputs.push(("opacity", "color3", node));
            }
            if emission.is_some() {
                inputs.push(("emission_color", "color3", "emission"));
                constants.push(("emission", "float", "1".into()));
            }
        }
    }
    let mut outputs = String::new();
    let mut shader = String::new();
    for (input, ty, node) in &inputs {
        let _ = writeln!(
            outputs,
            "    <output name=\"{input}_output\" type=\"{ty}\" nodename=\"{node}\" />"
        );
        let _ = writeln!(
            shader,
            "    <input name=\"{input}\" type=\"{ty}\" nodegraph=\"NG_{name}\" output=\"{input}_output\" />"
        );
    }
    for (input, ty, value) in &constants {
        let _ = writeln!(
            shader,
            "    <input name=\"{input}\" type=\"{ty}\" value=\"{value}\" />"
        );
    }
    let model = settings.surface.node();
    let size = settings.size;
    let title = attribute(&compiled.checked.name.replace("--", "-"));
    let version = env!("CARGO_PKG_VERSION");
    [
        "<?xml version=\"1.0\"?>\n".to_string(),
        format!("<!-- {title}: exported by Veneer {version}, its maps baked at {size}×{size} over {place}. -->\n"),
        "<materialx version=\"1.39\" colorspace=\"lin_rec709\">\n".to_string(),
        format!("  <nodegraph name=\"NG_{name}\">\n{graph}{nodes}{outputs}  </nodegraph>\n"),
        format!("  <{model} name=\"SR_{name}\" type=\"surfaceshader\">\n{shader}  </{model}>\n"),
        format!("  <surfacematerial name=\"{name}\" type=\"material\">\n"),
        format!("    <input name=\"surfaceshader\" type=\"surfaceshader\" nodename=\"SR_{name}\" />\n"),
        "  </surfacematerial>\n</materialx>\n".to_string(),
    ]
    .concat()
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
