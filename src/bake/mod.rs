//! Baking: a material's outputs rendered into texture maps (albedo, alpha, height,
//! normal, specular, roughness) over a rectangle of the plane, as 8- or 16-bit PNG or
//! 32-bit float EXR. Maps are baked one at a time and converted in place, so an
//! 8192² bake stays near 1.3 GiB however many maps it writes.

mod maps;

pub use maps::{Map, NormalConvention, normal_map};

use crate::graph::Graph;
use crate::render::{FlatChannels, FlatRect, FlatRenderer, GpuContext};
use std::path::{Path, PathBuf};

/// File format of baked maps.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum Format {
    Png8,
    Png16,
    /// 32-bit float OpenEXR (RGBA).
    Exr,
}

impl Format {
    /// The file extension.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Png8 | Format::Png16 => "png",
            Format::Exr => "exr",
        }
    }
}

/// What to bake and how.
#[derive(Clone, Debug, PartialEq)]
pub struct BakeSettings {
    /// The plane rectangle covered (`None`: the graph's preview square).
    pub rect: Option<FlatRect>,
    pub size: u32,
    pub maps: Vec<Map>,
    pub format: Format,
    pub normal: NormalConvention,
    pub time: f32,
}

/// One map written by a bake.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct BakedMap {
    pub map: Map,
    pub path: PathBuf,
    pub size: u32,
    pub format: Format,
    pub bytes: u64,
}

/// A bake that failed.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct BakeError(pub String);

/// Bakes `graph` into `<stem>_<map>.<ext>` files, calling `progress(done, total)` as
/// tiles finish. Every file is written atomically: an interrupted bake leaves no
/// partial map.
pub fn bake(
    gpu: &GpuContext,
    graph: &Graph,
    settings: &BakeSettings,
    stem: &Path,
    mut progress: impl FnMut(u64, u64),
) -> Result<Vec<BakedMap>, BakeError> {
    let module =
        crate::codegen::compile_graph(graph).map_err(|error| BakeError(error.to_string()))?;
    let renderer =
        FlatRenderer::new(gpu, &module.source).map_err(|error| BakeError(error.to_string()))?;
    let rect = settings
        .rect
        .unwrap_or_else(|| crate::render::preview_rect(graph));
    let tile = u64::from(gpu.device.limits().max_texture_dimension_2d.min(2048));
    let tiles_per_pass = u64::from(settings.size).div_ceil(tile).pow(2);
    let total = tiles_per_pass * settings.maps.len() as u64;
    let mut written = Vec::new();
    for (index, map) in settings.maps.iter().enumerate() {
        let channels = match map {
            Map::Albedo | Map::Alpha => FlatChannels::AlbedoAlpha,
            Map::Specular | Map::Roughness => FlatChannels::SpecularShininess,
            Map::Height | Map::Normal => FlatChannels::HeightBump,
        };
        let base = index as u64 * tiles_per_pass;
        let pixels = renderer
            .render_channels(
                gpu,
                rect,
                settings.size,
                settings.time,
                channels,
                |done, _| progress(base + u64::from(done), total),
            )
            .map_err(|error| BakeError(error.to_string()))?;
        let name = format!(
            "{}_{}.{}",
            stem.file_name()
                .map(|n| n.to_string_lossy())
                .unwrap_or_default(),
            map.name(),
            settings.format.extension()
        );
        let path = stem.with_file_name(name);
        let spacing = (
            (rect.x1 - rect.x0) / f64::from(settings.size),
            (rect.z1 - rect.z0) / f64::from(settings.size),
        );
        let pixels = maps::convert(*map, pixels, settings.size, spacing, settings.normal);
        maps::write(&path, pixels, settings.size, settings.format)
            .map_err(|error| BakeError(format!("{}: {error}", path.display())))?;
        let bytes = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
        written.push(BakedMap {
            map: *map,
            path,
            size: settings.size,
            format: settings.format,
            bytes,
        });
    }
    Ok(written)
}
