//! glTF 2.0 export (`veneer bake --gltf`): a material baked into the UV layout of its
//! preview mesh (or another mesh) and wired into a `pbrMetallicRoughness` material —
//! base colour (sRGB), occlusion-roughness-metallic packed as glTF reads it (R, G, B),
//! an OpenGL-convention normal map, emission with `KHR_materials_emissive_strength`
//! past 1 — on that mesh with its normals, UVs and tangents. A mesh without UVs gets an
//! automatic atlas ([`crate::mesh::Mesh::with_uv_atlas`]).

mod document;

pub use document::Packaging;
use document::{MaterialData, MeshData, Texture};

use super::maps::{Converter, Map, NormalConvention, fill_uncovered};
use super::{BakeError, UV_PADDING};
use crate::codegen::{AlphaUse, Compiled};
use crate::fsutil::Naming;
use crate::graph::Shading;
use crate::render::{FlatChannels, GpuContext, GpuMesh, UvRenderer};
use serde_json::json;
use std::path::{Path, PathBuf};

/// What a glTF export bakes.
#[derive(Clone, Debug, PartialEq)]
pub struct GltfSettings {
    /// The primitive or mesh file to export (`None`: the graph's preview mesh).
    pub mesh: Option<String>,
    /// Width and height of every texture in pixels.
    pub size: u32,
    pub time: f32,
}

/// How the material's colours are stored in 8-bit sRGB textures: a metallic-roughness
/// material's albedo and emission are linear and get the sRGB transfer function; a
/// Blinn-Phong material's are the display values the seeds' lighting shows and are
/// stored as they are.
fn encode_colour(shading: Shading, linear: f32) -> f32 {
    let c = linear.clamp(0.0, 1.0);
    if !shading.is_linear() {
        c
    } else if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// Occlusion below this counts (an 8-bit step under 1).
const OCCLUDED: f32 = 1.0 - 1.0 / 512.0;

/// How an export to `path` is packaged: `.gltf` with its buffer and PNGs beside it, or
/// else (`.glb`, any other name) one binary file.
fn packaging(path: &Path) -> Packaging {
    match path.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("gltf") => Packaging::Separate,
        _ => Packaging::Binary,
    }
}

/// The stem the files beside a `.gltf` are named after, and its nodes and meshes.
fn stem(path: &Path) -> String {
    (path.file_stem())
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// What the textures beside a `.gltf` hold, named `<stem>_<what>.png`.
const BASE_COLOR: &str = "basecolor";
const ORM: &str = "orm";
const EMISSION: &str = "emission";
const NORMAL: &str = "normal";
const TEXTURES: [&str; 4] = [BASE_COLOR, ORM, EMISSION, NORMAL];

fn texture_name(stem: &str, what: &str) -> String {
    format!("{stem}_{what}.png")
}

/// Every file an export to `path` may write, `path` itself first: a `.gltf` has its
/// buffer and up to four textures beside it (emission and normal only when the material
/// has them).
pub fn gltf_files(path: &Path) -> Vec<PathBuf> {
    let mut files = vec![path.to_path_buf()];
    if packaging(path) == Packaging::Separate {
        let stem = stem(path);
        let beside = |name: String| path.with_file_name(name);
        files.push(beside(document::buffer_name(&stem)));
        files.extend(TEXTURES.map(|what| beside(texture_name(&stem, what))));
    }
    files
}

/// Exports `compiled` (parameters baked) to `path` (`.glb`, or `.gltf` with its buffer and
/// PNGs beside it), calling `progress(done, total)` as tiles render: once it answers
/// `false`, the export stops after the map being rendered ([`BakeError::Cancelled`],
/// nothing written). The files are put in
/// place together once all are written, so a failed export leaves none of them; the
/// files beside a `.gltf` are named by Veneer and never written through links
/// ([`crate::fsutil::Naming::Implied`]). The paths written come back, the document first.
pub fn export_gltf(
    gpu: &GpuContext,
    compiled: &Compiled,
    settings: &GltfSettings,
    path: &Path,
    mut progress: impl FnMut(u64, u64) -> bool,
) -> Result<Vec<PathBuf>, BakeError> {
    crate::render::baked_parameters(compiled)?;
    let packaging = packaging(path);
    super::output_folder(path)?;
    let (module, preview) = (&compiled.module, &compiled.preview);
    let uses = module.uses;
    let name = settings.mesh.as_deref().unwrap_or(&preview.mesh);
    // A mesh whose UV layout does not give each point texels of its own (none, one
    // past the unit square, overlapping faces) gets an atlas, after its fields are
    // solved on the connected mesh: the document carries the mesh with its maps.
    let mesh = crate::render::mesh_with_fields(preview, name, &uses, |_, _| {})?
        .with_own_texels(settings.size);
    let shading = compiled.checked.shading;
    let wants_normal = uses.perturbs_normal();
    let mut passes = vec![
        FlatChannels::AlbedoAlpha,
        FlatChannels::MetallicRoughness,
        FlatChannels::Emission,
    ];
    if wants_normal {
        passes.push(FlatChannels::HeightBump);
    }
    let size = settings.size;
    let per_pass = u64::from(size.div_ceil(crate::render::tile_size(gpu))).pow(2);
    let mut renderer = UvRenderer::new(gpu, &module.source)?;
    // Casting the texel fields counts as a pass's worth of tiles before the passes.
    let mut lead = 0;
    let mut wanted = true;
    let all = per_pass * (passes.len() as u64 + 1);
    let cast = super::texel_fields::texel_fields(&mesh, &uses.mesh_fields, size, |done, texels| {
        wanted &= progress(per_pass * done as u64 / texels.max(1) as u64, all);
    });
    if let Some(fields) = cast {
        renderer.set_texel_fields(gpu, &fields);
        lead = per_pass;
    }
    let gpu_mesh = GpuMesh::new(&gpu.device, &mesh);
    let placement = crate::render::texture_placement(preview);
    let buffers =
        crate::render::mesh_passes(gpu, compiled, &gpu_mesh, placement, size, settings.time)?;
    if let Some(buffers) = &buffers {
        renderer.bind_passes(gpu, buffers);
    }
    let total = lead + per_pass * passes.len() as u64;
    let mut rendered = Vec::new();
    for (index, channels) in passes.iter().enumerate() {
        if !wanted {
            return Err(BakeError::Cancelled);
        }
        let base = lead + index as u64 * per_pass;
        let report = |done: u32, _| wanted &= progress(base + u64::from(done), total);
        let mut pixels = renderer.render_channels(
            gpu,
            &gpu_mesh,
            placement,
            size,
            settings.time,
            *channels,
            report,
        )?;
        fill_uncovered(&mut pixels, size, UV_PADDING);
        rendered.push(pixels);
    }
    if !wanted {
        return Err(BakeError::Cancelled);
    }
    let stem = stem(path);
    let texture_name = |what: &str| texture_name(&stem, what);
    let write_error = |error: std::io::Error| BakeError::Write {
        path: path.to_path_buf(),
        error,
    };

    let mut material = json!({ "name": compiled.checked.name.clone() });
    let mut textures = Vec::new();
    let mut extensions = Vec::new();
    // Base colour, with alpha where the material's alpha shows.
    let alpha = uses.alpha;
    let colour = |v: f32| encode_colour(shading, v);
    let base: Vec<[f32; 4]> = (rendered[0].iter())
        .map(|p| [colour(p[0]), colour(p[1]), colour(p[2]), p[3]])
        .collect();
    textures.push(Texture {
        file_name: texture_name(BASE_COLOR),
        png: png(BASE_COLOR, &base, size, alpha != AlphaUse::Opaque).map_err(write_error)?,
    });
    material["pbrMetallicRoughness"] = json!({ "baseColorTexture": { "index": 0 } });
    match alpha {
        AlphaUse::Opaque => {}
        AlphaUse::Mask(cutoff) => {
            material["alphaMode"] = json!("MASK");
            material["alphaCutoff"] = json!(cutoff);
        }
        AlphaUse::Blend => material["alphaMode"] = json!("BLEND"),
    }
    if alpha != AlphaUse::Opaque {
        // The preview draws the back faces of what can be cut away or seen through.
        material["doubleSided"] = json!(true);
    }
    // Occlusion, roughness, metallic in one texture.
    let orm = convert(Map::Orm, shading, size, (1.0, 1.0), &rendered[1]);
    let occluded = orm.iter().any(|p| p[0] < OCCLUDED);
    textures.push(Texture {
        file_name: texture_name(ORM),
        png: png(ORM, &orm, size, false).map_err(write_error)?,
    });
    material["pbrMetallicRoughness"]["metallicRoughnessTexture"] = json!({ "index": 1 });
    if occluded {
        material["occlusionTexture"] = json!({ "index": 1 });
    }
    // Emission: the texture holds emission / its largest channel, the factor and the
    // strength the rest.
    let brightest = rendered[2]
        .iter()
        .flat_map(|p| [p[0], p[1], p[2]])
        .fold(0.0f32, f32::max);
    if brightest > 0.0 {
        let scale = brightest.max(1.0);
        let emission: Vec<[f32; 4]> = (rendered[2].iter())
            .map(|p| {
                [
                    colour(p[0] / scale),
                    colour(p[1] / scale),
                    colour(p[2] / scale),
                    1.0,
                ]
            })
            .collect();
        material["emissiveTexture"] = json!({ "index": textures.len() });
        material["emissiveFactor"] = json!([1.0, 1.0, 1.0]);
        textures.push(Texture {
            file_name: texture_name(EMISSION),
            png: png(EMISSION, &emission, size, false).map_err(write_error)?,
        });
        if scale > 1.0 {
            material["extensions"] =
                json!({ "KHR_materials_emissive_strength": { "emissiveStrength": scale } });
            extensions.push("KHR_materials_emissive_strength");
        }
    }
    let normals = crate::mesh::unit_normals(&mesh);
    let tangents = wants_normal.then(|| crate::mesh::vertex_tangents(&mesh, &normals));
    if wants_normal {
        let texel = 2.0 * preview.size / f64::from(size);
        let normal = convert(Map::Normal, shading, size, (texel, texel), &rendered[3]);
        material["normalTexture"] = json!({ "index": textures.len() });
        textures.push(Texture {
            file_name: texture_name(NORMAL),
            png: png(NORMAL, &normal, size, false).map_err(write_error)?,
        });
    }
    let data = MeshData {
        positions: mesh.positions,
        normals: normals.iter().map(|n| n.to_array()).collect(),
        tangents,
        uvs: mesh.uvs,
        indices: mesh.indices,
    };
    let material = MaterialData {
        json: material,
        extensions,
        textures,
    };
    let files = document::document(&stem, &data, &material, packaging);
    // The document is the file the user named; the rest go beside it.
    let targets: Vec<(PathBuf, Naming)> = (files.iter().enumerate())
        .map(|(index, (file_name, _))| match index {
            0 => (path.to_path_buf(), Naming::Given),
            _ => (path.with_file_name(file_name), Naming::Implied),
        })
        .collect();
    let writes = (targets.iter().zip(&files))
        .map(|((target, naming), (_, bytes))| (target.as_path(), *naming, bytes.as_slice()));
    crate::fsutil::write_together(writes)
        .map_err(|(path, error)| BakeError::Write { path, error })?;
    Ok(targets.into_iter().map(|(target, _)| target).collect())
}

/// A whole `map` (OpenGL-convention normals, as glTF requires) from its rendered
/// outputs, texels `spacing` apart.
fn convert(
    map: Map,
    shading: Shading,
    size: u32,
    spacing: (f64, f64),
    pixels: &[[f32; 4]],
) -> Vec<[f32; 4]> {
    let mut converted = Vec::with_capacity(pixels.len());
    let mut converter = Converter::new(map, shading, size, spacing, NormalConvention::OpenGl);
    let mut collect = |rows: &[[f32; 4]]| {
        converted.extend_from_slice(rows);
        Ok::<(), std::convert::Infallible>(())
    };
    let mut band = pixels.to_vec();
    let Ok(()) = converter.band(&mut band, &mut collect);
    let Ok(()) = converter.finish(&mut collect);
    converted
}

/// An 8-bit PNG (RGB, or RGBA with `alpha`) of values in [0, 1], rows from the top, of the
/// texture `what`; a non-finite sample fails it.
fn png(what: &str, pixels: &[[f32; 4]], size: u32, alpha: bool) -> std::io::Result<Vec<u8>> {
    use image::ImageEncoder;
    if let Some(why) = crate::render::non_finite(what, pixels, size as usize, 0) {
        return Err(std::io::Error::other(why));
    }
    let channels = if alpha { 4 } else { 3 };
    let samples: Vec<u8> = (pixels.iter())
        .flat_map(|p| {
            p[..channels]
                .iter()
                .map(|v| (255.0 * v.clamp(0.0, 1.0)).round() as u8)
                .collect::<Vec<_>>()
        })
        .collect();
    let mut bytes = Vec::new();
    let colour = if alpha {
        image::ExtendedColorType::Rgba8
    } else {
        image::ExtendedColorType::Rgb8
    };
    image::codecs::png::PngEncoder::new(&mut bytes)
        .write_image(&samples, size, size, colour)
        .map_err(std::io::Error::other)?;
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    /// A texture with a non-finite sample is refused by name (a PNG would show it black).
    #[test]
    fn a_texture_with_a_non_finite_sample_is_refused_by_name() {
        let pixels = [[0.5, 0.5, 0.5, 1.0], [0.5, f32::NAN, 0.5, 1.0]].repeat(2);
        let error = super::png("orm", &pixels, 2, false).expect_err("refused");
        assert!(error.to_string().contains("orm map"), "{error}");
        assert!(super::png("orm", &[[0.5; 4]; 4], 2, false).is_ok());
    }
}
