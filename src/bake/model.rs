//! A material baked onto a mesh for the model formats (glTF, USD): the mesh (its
//! preview mesh or another, given an automatic atlas when its UV layout does not give each
//! point texels of its own) with unit normals, UVs and, where a normal map is wired,
//! tangents, and the material's textures in its UV layout as 8-bit PNGs — base colour
//! (sRGB-encoded, with alpha where it shows), occlusion-roughness-metallic packed in R, G,
//! B, emission normalised by its brightest channel (the strength beside it) and an
//! OpenGL-convention normal map.

use super::maps::{Converter, Map, NormalConvention, fill_uncovered};
use super::{BakeError, UV_PADDING};
use crate::codegen::{AlphaUse, Compiled};
use crate::graph::Shading;
use crate::render::{FlatChannels, GpuContext, GpuMesh, UvRenderer};

/// A model format: a mesh with the material baked into its UV layout.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModelFormat {
    /// glTF 2.0 (`.glb`, or `.gltf` with its files beside it).
    Gltf,
    /// USD (`.usdz`, or `.usda` with its PNGs beside it).
    Usd,
}

impl ModelFormat {
    /// The format's name, as menus and messages give it.
    pub fn name(self) -> &'static str {
        match self {
            ModelFormat::Gltf => "glTF",
            ModelFormat::Usd => "USD",
        }
    }

    /// The heading of its export dialog and file browser.
    pub fn title(self) -> &'static str {
        match self {
            ModelFormat::Gltf => "Export glTF",
            ModelFormat::Usd => "Export USD",
        }
    }

    /// The extension of its one-file form.
    pub fn extension(self) -> &'static str {
        match self {
            ModelFormat::Gltf => "glb",
            ModelFormat::Usd => "usdz",
        }
    }

    /// Why a model cannot be written to `path`, if it cannot: standard output (`-`, which
    /// would name files `-_basecolor.png`); for USD also a folder or an extension USD
    /// would not read as what is written. (A glTF binary may go to a device; what cannot
    /// be written there is refused as it is written.)
    pub fn refuses(self, path: &std::path::Path) -> Option<String> {
        let usage = match self {
            ModelFormat::Gltf => {
                "give a file name ending in .glb (one file) or .gltf (its files beside it)"
            }
            ModelFormat::Usd => {
                "give a file name ending in .usdz (one package) or .usda (text, its PNGs beside it)"
            }
        };
        let extension = (path.extension().and_then(|e| e.to_str())).map(str::to_ascii_lowercase);
        if path.as_os_str() == "-" {
            Some(format!(
                "a {} export writes files, not a stream: {usage}",
                self.name()
            ))
        } else if self == ModelFormat::Gltf {
            None
        } else if path.is_dir() || path.as_os_str().as_encoded_bytes().ends_with(b"/") {
            Some(format!("is a folder: {usage}"))
        } else if !matches!(extension.as_deref(), Some("usda" | "usd" | "usdz")) {
            Some(format!(
                "not a USD file name: {usage} (.usd is written as text)"
            ))
        } else {
            None
        }
    }

    /// Every file an export to `path` may write, `path` itself first.
    pub fn files(self, path: &std::path::Path) -> Vec<std::path::PathBuf> {
        match self {
            ModelFormat::Gltf => super::gltf_files(path),
            ModelFormat::Usd => super::usd_files(path),
        }
    }

    /// Exports `compiled` to `path` in this format ([`super::export_gltf`],
    /// [`super::export_usd`]); the paths written come back, the document first.
    pub fn export(
        self,
        gpu: &GpuContext,
        compiled: &Compiled,
        settings: &ModelSettings,
        path: &std::path::Path,
        progress: impl FnMut(u64, u64) -> bool,
    ) -> Result<Vec<std::path::PathBuf>, BakeError> {
        match self {
            ModelFormat::Gltf => super::export_gltf(gpu, compiled, settings, path, progress),
            ModelFormat::Usd => super::export_usd(gpu, compiled, settings, path, progress),
        }
    }
}

/// What a model export bakes.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelSettings {
    /// The primitive or mesh file to export (`None`: the graph's preview mesh).
    pub mesh: Option<String>,
    /// Width and height of every texture in pixels.
    pub size: u32,
    pub time: f32,
}

/// One triangle mesh as the model formats hold it.
pub struct MeshData {
    pub positions: Vec<[f32; 3]>,
    /// Unit normals.
    pub normals: Vec<[f32; 3]>,
    /// Unit tangents with their bitangent sign; `None` when no normal texture needs them.
    pub tangents: Option<Vec<[f32; 4]>>,
    /// Texture coordinates, v down the image (glTF's convention).
    pub uvs: Vec<[f32; 2]>,
    pub indices: Vec<u32>,
}

/// A PNG texture and the file name it has beside the model.
pub struct Texture {
    pub file_name: String,
    pub png: Vec<u8>,
}

/// A material baked onto a mesh.
pub struct BakedModel {
    /// The graph's name.
    pub name: String,
    pub mesh: MeshData,
    /// RGB, plus alpha where the material's alpha shows.
    pub base_color: Texture,
    /// Occlusion, roughness, metallic in R, G, B.
    pub orm: Texture,
    /// Whether some texel is occluded (below an 8-bit step under 1).
    pub occluded: bool,
    /// The emission texture (emission over its brightest channel) and that brightness
    /// where past 1 (else 1); `None` where nothing glows.
    pub emission: Option<(Texture, f32)>,
    /// Where the shading normal is perturbed.
    pub normal: Option<Texture>,
    pub alpha: AlphaUse,
}

/// How the material's colours are stored in 8-bit sRGB textures: a metallic-roughness
/// material's albedo and emission are linear and get the sRGB transfer function; a
/// Blinn-Phong material's are the display values the seeds' lighting shows and are
/// stored as they are.
fn encode_colour(shading: Shading, linear: f32) -> f32 {
    let c = linear.clamp(0.0, 1.0);
    match shading.is_linear() {
        true => crate::bitmaps::linear_to_srgb(c),
        false => c,
    }
}

/// Occlusion below this counts (an 8-bit step under 1).
const OCCLUDED: f32 = 1.0 - 1.0 / 512.0;

/// What the textures beside a model hold, named `<stem>_<what>.png`.
const BASE_COLOR: &str = "basecolor";
const ORM: &str = "orm";
const EMISSION: &str = "emission";
const NORMAL: &str = "normal";
const TEXTURES: [&str; 4] = [BASE_COLOR, ORM, EMISSION, NORMAL];

/// The file name of texture `what` of a model named `stem`.
pub fn texture_name(stem: &str, what: &str) -> String {
    format!("{stem}_{what}.png")
}

/// The name a model written to `path` goes by: its file stem, which its textures are
/// named after.
pub fn model_stem(path: &std::path::Path) -> String {
    (path.file_stem())
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// Every texture a model written to `path` may have beside it.
pub fn textures_beside(path: &std::path::Path) -> impl Iterator<Item = std::path::PathBuf> {
    let stem = model_stem(path);
    TEXTURES
        .map(move |what| path.with_file_name(texture_name(&stem, what)))
        .into_iter()
}

/// Bakes `compiled` (parameters baked) onto the mesh `settings` names, its textures named
/// after `stem`, calling `progress(done, total)` as tiles render: once it answers
/// `false`, the bake stops after the pass being rendered ([`BakeError::Cancelled`]).
/// `on_error` names the file a texture that cannot be encoded is reported against.
pub fn bake_model(
    gpu: &GpuContext,
    compiled: &Compiled,
    settings: &ModelSettings,
    stem: &str,
    on_error: &std::path::Path,
    mut progress: impl FnMut(u64, u64) -> bool,
) -> Result<BakedModel, BakeError> {
    crate::render::baked_parameters(compiled)?;
    let (module, preview) = (&compiled.module, &compiled.preview);
    let uses = module.uses;
    let name = settings.mesh.as_deref().unwrap_or(&preview.mesh);
    // A mesh whose UV layout does not give each point texels of its own (none, one
    // past the unit square, overlapping faces) gets an atlas, after its fields are
    // solved on the connected mesh: the model carries the mesh with its maps.
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
    let write_error = |error: std::io::Error| BakeError::Write {
        path: on_error.to_path_buf(),
        error,
    };
    let texture = |what: &str, pixels: &[[f32; 4]], alpha: bool| {
        Ok::<_, BakeError>(Texture {
            file_name: texture_name(stem, what),
            png: png(what, pixels, size, alpha).map_err(write_error)?,
        })
    };
    let colour = |v: f32| encode_colour(shading, v);
    let base: Vec<[f32; 4]> = (rendered[0].iter())
        .map(|p| [colour(p[0]), colour(p[1]), colour(p[2]), p[3]])
        .collect();
    let base_color = texture(BASE_COLOR, &base, uses.alpha != AlphaUse::Opaque)?;
    let orm = convert(Map::Orm, shading, size, (1.0, 1.0), &rendered[1]);
    let occluded = orm.iter().any(|p| p[0] < OCCLUDED);
    let orm = texture(ORM, &orm, false)?;
    // Emission: the texture holds emission / its largest channel, the strength the rest.
    let emission = match over_brightest(&rendered[2]) {
        Some((pixels, strength)) => {
            let encoded: Vec<[f32; 4]> = (pixels.iter())
                .map(|p| [colour(p[0]), colour(p[1]), colour(p[2]), 1.0])
                .collect();
            Some((texture(EMISSION, &encoded, false)?, strength))
        }
        None => None,
    };
    let normals = crate::mesh::unit_normals(&mesh);
    let tangents = wants_normal.then(|| crate::mesh::vertex_tangents(&mesh, &normals));
    let normal = match wants_normal {
        true => {
            let texel = 2.0 * preview.size / f64::from(size);
            let pixels = convert(Map::Normal, shading, size, (texel, texel), &rendered[3]);
            Some(texture(NORMAL, &pixels, false)?)
        }
        false => None,
    };
    Ok(BakedModel {
        name: compiled.checked.name.clone(),
        mesh: MeshData {
            positions: mesh.positions,
            normals: normals.iter().map(|n| n.to_array()).collect(),
            tangents,
            uvs: mesh.uvs,
            indices: mesh.indices,
        },
        base_color,
        orm,
        occluded,
        emission,
        normal,
        alpha: uses.alpha,
    })
}

/// Emission (RGB of `pixels`) over its brightest channel where that passes 1, and the
/// factor it was divided by (1 where nothing passes 1), so an 8-bit texture times the
/// factor keeps glow brighter than 1; `None` where nothing glows.
pub(super) fn over_brightest(pixels: &[[f32; 4]]) -> Option<(Vec<[f32; 4]>, f32)> {
    let brightest = (pixels.iter())
        .flat_map(|p| [p[0], p[1], p[2]])
        .fold(0.0f32, f32::max);
    if brightest <= 0.0 {
        return None;
    }
    let strength = brightest.max(1.0);
    let scaled = (pixels.iter())
        .map(|p| [p[0] / strength, p[1] / strength, p[2] / strength, 1.0])
        .collect();
    Some((scaled, strength))
}

/// A whole `map` (OpenGL-convention normals) from its rendered outputs, texels `spacing`
/// apart.
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
pub(super) fn png(
    what: &str,
    pixels: &[[f32; 4]],
    size: u32,
    alpha: bool,
) -> std::io::Result<Vec<u8>> {
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
