//! USD export (`veneer bake --usd OUT.usda|OUT.usdz`): the material baked onto its preview
//! mesh (or another, [`super::model`]) as a USD stage — the mesh with normals and `st`
//! texture coordinates, and one material bound to it with two surfaces: a
//! `UsdPreviewSurface` network of `UsdUVTexture`s, which every USD renderer reads, and the
//! same maps wired into MaterialX's `open_pbr_surface` (`outputs:mtlx:surface`, MaterialX
//! nodes as USD shaders) for renderers that read MaterialX. `.usda` is text with the PNGs
//! beside it; `.usdz` one package (an uncompressed zip, each file 64-byte aligned, the
//! layer first).

use super::BakeError;
use super::materialx::{
    AlphaMap, Input, Maps, Network, Source, SurfaceModel, element_name, network,
};
use super::model::{BakedModel, ModelSettings, Texture, bake_model, model_stem, textures_beside};
use crate::codegen::{AlphaUse, Compiled};
use crate::fsutil::Naming;
use crate::render::GpuContext;
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// Whether an export to `path` is one `.usdz` package (else `.usda` text with the PNGs
/// beside it).
fn packaged(path: &Path) -> bool {
    (path.extension().and_then(|e| e.to_str())).is_some_and(|e| e.eq_ignore_ascii_case("usdz"))
}

/// Every file an export to `path` may write, `path` itself first: a `.usda` has up to
/// four textures beside it (emission and normal only when the material has them).
pub fn usd_files(path: &Path) -> Vec<PathBuf> {
    let mut files = vec![path.to_path_buf()];
    if !packaged(path) {
        files.extend(textures_beside(path));
    }
    files
}

/// Exports `compiled` (parameters baked) to `path` (`.usda` with its PNGs beside it, or a
/// `.usdz` package), calling `progress(done, total)` as tiles render (answering `false`
/// stops the export, nothing written). Everything is put in place together; the paths
/// written come back, the layer first.
pub fn export_usd(
    gpu: &GpuContext,
    compiled: &Compiled,
    settings: &ModelSettings,
    path: &Path,
    progress: impl FnMut(u64, u64) -> bool,
) -> Result<Vec<PathBuf>, BakeError> {
    super::output_folder(path)?;
    let stem = model_stem(path);
    let model = bake_model(gpu, compiled, settings, &stem, path, progress)?;
    let textures: Vec<&Texture> = [Some(&model.base_color), Some(&model.orm)]
        .into_iter()
        .chain([
            model.emission.as_ref().map(|(t, _)| t),
            model.normal.as_ref(),
        ])
        .flatten()
        .collect();
    let layer = layer(&model, settings);
    let write = |files: Vec<(&Path, Naming, &[u8])>| {
        crate::fsutil::write_together(files)
            .map_err(|(path, error)| BakeError::Write { path, error })
    };
    if packaged(path) {
        let layer_name = format!("{stem}.usda");
        let entries: Vec<(&str, &[u8])> = std::iter::once((layer_name.as_str(), layer.as_bytes()))
            .chain(
                textures
                    .iter()
                    .map(|t| (t.file_name.as_str(), t.png.as_slice())),
            )
            .collect();
        let package = usdz(&entries);
        write(vec![(path, Naming::Given, &package)])?;
        return Ok(vec![path.to_path_buf()]);
    }
    let beside: Vec<PathBuf> = textures
        .iter()
        .map(|t| path.with_file_name(&t.file_name))
        .collect();
    let mut files = vec![(path, Naming::Given, layer.as_bytes())];
    files.extend(
        (beside.iter().zip(&textures))
            .map(|(target, t)| (target.as_path(), Naming::Implied, t.png.as_slice())),
    );
    write(files)?;
    Ok(std::iter::once(path.to_path_buf()).chain(beside).collect())
}

/// `values` as a USD array of tuples, `per` numbers each.
fn tuples(values: impl Iterator<Item = f32>, per: usize) -> String {
    let numbers: Vec<String> = values.map(|v| format!("{v}")).collect();
    let items: Vec<String> = numbers
        .chunks(per)
        .map(|c| format!("({})", c.join(", ")))
        .collect();
    format!("[{}]", items.join(", "))
}

/// The USD type of a MaterialX type.
fn usd_type(materialx: &str) -> &'static str {
    match materialx {
        "float" => "float",
        "integer" => "int",
        "color3" => "color3f",
        "color4" => "color4f",
        "vector3" => "float3",
        "filename" => "asset",
        _ => "token",
    }
}

/// A MaterialX input of `network` as a USD shader attribute, connections to prims under
/// `material`.
fn usd_input(input: &Input, material: &str) -> String {
    let ty = usd_type(input.ty);
    match &input.source {
        Source::Value(value) => format!("{ty} inputs:{} = {value}", input.name),
        Source::Node(node) => format!(
            "{ty} inputs:{}.connect = <{material}/{node}.outputs:out>",
            input.name
        ),
        Source::Output(node, output) => format!(
            "{ty} inputs:{}.connect = <{material}/{node}.outputs:{output}>",
            input.name
        ),
        Source::Interface(name) => format!(
            "{ty} inputs:{}.connect = <{material}.inputs:{name}>",
            input.name
        ),
        Source::File { path, colour_space } => {
            let space = colour_space
                .map(|s| format!(" (\n        colorSpace = \"{s}\"\n    )"))
                .unwrap_or_default();
            format!("{ty} inputs:{} = @./{path}@{space}", input.name)
        }
    }
}

/// The MaterialX network as USD shader prims under `material`, its surface `SR_<name>`.
fn materialx_prims(network: &Network, material: &str, name: &str) -> String {
    let mut text = String::new();
    for node in &network.nodes {
        let _ = writeln!(
            text,
            "def Shader \"{}\"\n{{\n    uniform token info:id = \"{}\"",
            node.name, node.nodedef
        );
        for input in &node.inputs {
            let _ = writeln!(text, "    {}", usd_input(input, material));
        }
        let _ = writeln!(text, "    {} outputs:out\n}}\n", usd_type(node.ty));
    }
    let _ = writeln!(
        text,
        "def Shader \"SR_{name}\"\n{{\n    uniform token info:id = \"{}\"",
        network.surface_nodedef()
    );
    for input in &network.surface_inputs {
        let _ = writeln!(text, "    {}", usd_input(input, material));
    }
    text.push_str("    token outputs:surface\n}\n");
    text
}

/// A `UsdUVTexture` prim reading `file` at the mesh's `st`.
fn uv_texture(
    name: &str,
    file: &str,
    colour_space: &str,
    material: &str,
    extra: &str,
    outputs: &str,
) -> String {
    format!(
        "def Shader \"{name}\"\n{{\n    uniform token info:id = \"UsdUVTexture\"\n    asset inputs:file = @./{file}@\n    token inputs:sourceColorSpace = \"{colour_space}\"\n    float2 inputs:st.connect = <{material}/TexCoords.outputs:result>\n    token inputs:wrapS = \"repeat\"\n    token inputs:wrapT = \"repeat\"\n{extra}{outputs}}}\n\n"
    )
}

/// The USD layer: the mesh, bound to a material with a preview surface and a MaterialX one.
fn layer(model: &BakedModel, settings: &ModelSettings) -> String {
    let name = element_name(&model.name);
    let root = format!("/{name}");
    let material = format!("{root}/Materials/{name}");
    let mesh = &model.mesh;
    let mut text = String::new();
    let title = model.name.replace('"', "'");
    let _ = writeln!(
        text,
        "#usda 1.0\n(\n    defaultPrim = \"{name}\"\n    doc = \"{title}: exported by Veneer {}, its maps baked at {size}×{size}\"\n    metersPerUnit = 1\n    upAxis = \"Y\"\n)\n",
        env!("CARGO_PKG_VERSION"),
        size = settings.size
    );
    let _ = writeln!(
        text,
        "def Xform \"{name}\" (\n    kind = \"component\"\n)\n{{"
    );
    let counts = vec!["3"; mesh.indices.len() / 3].join(", ");
    let indices: Vec<String> = mesh.indices.iter().map(u32::to_string).collect();
    // USD's st has v up the image; the baked maps have it down, as glTF.
    let st = tuples(mesh.uvs.iter().flat_map(|uv| [uv[0], 1.0 - uv[1]]), 2);
    let _ = writeln!(
        text,
        "    def Mesh \"Mesh\" (\n        prepend apiSchemas = [\"MaterialBindingAPI\"]\n    )\n    {{\n        uniform bool doubleSided = {}\n        int[] faceVertexCounts = [{counts}]\n        int[] faceVertexIndices = [{}]\n        rel material:binding = <{material}>\n        normal3f[] normals = {} (\n            interpolation = \"vertex\"\n        )\n        point3f[] points = {}\n        texCoord2f[] primvars:st = {st} (\n            interpolation = \"vertex\"\n        )\n        uniform token subdivisionScheme = \"none\"\n    }}\n",
        model.alpha != AlphaUse::Opaque,
        indices.join(", "),
        tuples(mesh.normals.iter().flatten().copied(), 3),
        tuples(mesh.positions.iter().flatten().copied(), 3),
    );
    let mut shaders = String::new();
    let mut surface = vec![
        format!("color3f inputs:diffuseColor.connect = <{material}/BaseColor.outputs:rgb>"),
        format!("float inputs:roughness.connect = <{material}/ORM.outputs:g>"),
        format!("float inputs:metallic.connect = <{material}/ORM.outputs:b>"),
        "int inputs:useSpecularWorkflow = 0".to_string(),
    ];
    if model.occluded {
        surface.push(format!(
            "float inputs:occlusion.connect = <{material}/ORM.outputs:r>"
        ));
    }
    match model.alpha {
        AlphaUse::Opaque => {}
        AlphaUse::Mask(cutoff) => surface.extend([
            format!("float inputs:opacity.connect = <{material}/BaseColor.outputs:a>"),
            format!("float inputs:opacityThreshold = {cutoff}"),
        ]),
        AlphaUse::Blend => surface.push(format!(
            "float inputs:opacity.connect = <{material}/BaseColor.outputs:a>"
        )),
    }
    let out = |outputs: &[(&str, &str)]| {
        outputs
            .iter()
            .map(|(ty, name)| format!("    {ty} outputs:{name}\n"))
            .collect::<String>()
    };
    shaders.push_str(&uv_texture(
        "BaseColor",
        &model.base_color.file_name,
        "sRGB",
        &material,
        "",
        &out(&[("float3", "rgb"), ("float", "a")]),
    ));
    shaders.push_str(&uv_texture(
        "ORM",
        &model.orm.file_name,
        "raw",
        &material,
        "",
        &out(&[("float", "r"), ("float", "g"), ("float", "b")]),
    ));
    if let Some((emission, strength)) = &model.emission {
        let scale = format!("    float4 inputs:scale = ({strength}, {strength}, {strength}, 1)\n");
        shaders.push_str(&uv_texture(
            "Emission",
            &emission.file_name,
            "sRGB",
            &material,
            &scale,
            &out(&[("float3", "rgb")]),
        ));
        surface.push(format!(
            "color3f inputs:emissiveColor.connect = <{material}/Emission.outputs:rgb>"
        ));
    }
    if let Some(normal) = &model.normal {
        let remap =
            "    float4 inputs:bias = (-1, -1, -1, 0)\n    float4 inputs:scale = (2, 2, 2, 1)\n";
        shaders.push_str(&uv_texture(
            "Normal",
            &normal.file_name,
            "raw",
            &material,
            remap,
            &out(&[("float3", "rgb")]),
        ));
        surface.push(format!(
            "normal3f inputs:normal.connect = <{material}/Normal.outputs:rgb>"
        ));
    }
    let surface: String = surface.iter().map(|line| format!("    {line}\n")).collect();
    let maps = Maps {
        base_color: model.base_color.file_name.clone(),
        colour_space: "srgb_texture",
        alpha: match model.alpha {
            AlphaUse::Opaque => AlphaMap::None,
            _ => AlphaMap::InBaseColor,
        },
        orm: model.orm.file_name.clone(),
        emission: model
            .emission
            .as_ref()
            .map(|(t, strength)| (t.file_name.clone(), *strength)),
        normal: model.normal.as_ref().map(|t| t.file_name.clone()),
    };
    let materialx = materialx_prims(
        &network(&maps, model.alpha, SurfaceModel::OpenPbr),
        &material,
        &name,
    );
    let inside = format!(
        "def Shader \"PreviewSurface\"\n{{\n    uniform token info:id = \"UsdPreviewSurface\"\n{surface}    token outputs:surface\n}}\n\ndef Shader \"TexCoords\"\n{{\n    uniform token info:id = \"UsdPrimvarReader_float2\"\n    string inputs:varname = \"st\"\n    float2 outputs:result\n}}\n\n{shaders}{materialx}"
    );
    // The shaders sit three levels down, inside the material.
    let inside: String = (inside.lines())
        .map(|line| match line.is_empty() {
            true => "\n".to_string(),
            false => format!("            {line}\n"),
        })
        .collect();
    let _ = writeln!(
        text,
        "    def Scope \"Materials\"\n    {{\n        def Material \"{name}\"\n        {{\n            token outputs:mtlx:surface.connect = <{material}/SR_{name}.outputs:surface>\n            token outputs:surface.connect = <{material}/PreviewSurface.outputs:surface>\n\n{inside}        }}\n    }}\n}}"
    );
    text
}

/// An uncompressed zip of `entries` (name, bytes) in order, each file's data starting
/// at a multiple of 64 bytes, as USDZ requires (the padding goes in the local header's
/// extra field).
fn usdz(entries: &[(&str, &[u8])]) -> Vec<u8> {
    let mut out = Vec::new();
    let mut central = Vec::new();
    for (name, data) in entries {
        let offset = out.len() as u32;
        // What the local and the central header both give, from the stored-data version
        // (2.0) on: flags, method (stored), time and date (1980-01-01), CRC, sizes, name length.
        let mut shared = vec![20, 0, 0, 0, 0, 0, 0, 0, 0x21, 0];
        shared.extend_from_slice(&crc32fast::hash(data).to_le_bytes());
        shared.extend_from_slice(&(data.len() as u32).to_le_bytes());
        shared.extend_from_slice(&(data.len() as u32).to_le_bytes());
        shared.extend_from_slice(&(name.len() as u16).to_le_bytes());
        // The extra field (id 0x1986, its size) pads the data to the alignment.
        let pad = (64 - (out.len() + 30 + name.len() + 4) % 64) % 64;
        out.extend_from_slice(&0x0403_4b50u32.to_le_bytes());
        out.extend_from_slice(&shared);
        out.extend_from_slice(&(4 + pad as u16).to_le_bytes());
        out.extend_from_slice(name.as_bytes());
        out.extend_from_slice(&0x1986u16.to_le_bytes());
        out.extend_from_slice(&(pad as u16).to_le_bytes());
        out.resize(out.len() + pad, 0);
        out.extend_from_slice(data);
        central.extend_from_slice(&0x0201_4b50u32.to_le_bytes());
        central.extend_from_slice(&[20, 0]); // made by version 2.0
        central.extend_from_slice(&shared);
        central.extend_from_slice(&[0; 12]); // extra, comment, disk, internal and external attributes
        central.extend_from_slice(&offset.to_le_bytes());
        central.extend_from_slice(name.as_bytes());
    }
    let start = out.len() as u32;
    let count = (entries.len() as u16).to_le_bytes();
    out.extend_from_slice(&central);
    out.extend_from_slice(&0x0605_4b50u32.to_le_bytes());
    out.extend_from_slice(&[0, 0, 0, 0]); // this disk, the directory's disk
    out.extend_from_slice(&count);
    out.extend_from_slice(&count);
    out.extend_from_slice(&(central.len() as u32).to_le_bytes());
    out.extend_from_slice(&start.to_le_bytes());
    out.extend_from_slice(&[0, 0]); // comment length
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_package_aligns_every_file_to_64_bytes_and_lists_them_in_order() {
        let entries: [(&str, &[u8]); 3] = [
            ("a.usda", b"#usda 1.0\n"),
            ("a_basecolor.png", &[7; 100]),
            ("b.png", &[]),
        ];
        let zip = usdz(&entries);
        let mut at = 0;
        for (name, data) in entries {
            assert_eq!(&zip[at..at + 4], &0x0403_4b50u32.to_le_bytes());
            let name_len = u16::from_le_bytes([zip[at + 26], zip[at + 27]]) as usize;
            let extra = u16::from_le_bytes([zip[at + 28], zip[at + 29]]) as usize;
            assert_eq!(&zip[at + 30..at + 30 + name_len], name.as_bytes());
            let start = at + 30 + name_len + extra;
            assert_eq!(start % 64, 0, "{name}");
            assert_eq!(&zip[start..start + data.len()], data);
            at = start + data.len();
        }
        // The central directory lists every entry at its local header.
        let end = zip.len() - 22;
        assert_eq!(&zip[end..end + 4], &0x0605_4b50u32.to_le_bytes());
        let count = u16::from_le_bytes([zip[end + 10], zip[end + 11]]) as usize;
        let size = u32::from_le_bytes(zip[end + 12..end + 16].try_into().unwrap()) as usize;
        let mut at = u32::from_le_bytes(zip[end + 16..end + 20].try_into().unwrap()) as usize;
        assert_eq!(at + size, end);
        assert_eq!(count, entries.len());
        for (name, _) in entries {
            assert_eq!(&zip[at..at + 4], &0x0201_4b50u32.to_le_bytes());
            let name_len = u16::from_le_bytes([zip[at + 28], zip[at + 29]]) as usize;
            let offset = u32::from_le_bytes(zip[at + 42..at + 46].try_into().unwrap()) as usize;
            assert_eq!(&zip[at + 46..at + 46 + name_len], name.as_bytes());
            assert_eq!(&zip[offset..offset + 4], &0x0403_4b50u32.to_le_bytes());
            at += 46 + name_len;
        }
        assert_eq!(at, end);
    }
}
