//! Baking: a material's outputs rendered into texture maps (albedo, alpha, height,
//! normal, specular, roughness) over a rectangle of the plane or into a mesh's UV
//! layout, as 8- or 16-bit PNG or 32-bit float EXR. Maps are baked one at a time, each
//! as a pipeline: bands of rows render on the GPU while the band before is converted and
//! encoded on other threads, so over a plane an EXR bake holds two bands at any size (a
//! PNG bake also its 8- or 16-bit samples). UV bakes hold the whole map, to pad its islands.

pub mod bitmap_seams;
mod encode;
mod exr_rle;
mod gltf;
mod maps;
mod materialx;
mod mesh_maps;
mod model;
mod pipeline;
mod texel_fields;
pub mod tile;
mod transfer;
mod usd;

pub use gltf::{Packaging, export_gltf, gltf_files};
pub use maps::{Converter, Map, NormalConvention, fill_uncovered};
pub use materialx::{
    ALBEDO_OUTPUT, MaterialxExport, MaterialxSettings, SurfaceModel, Tier, coverage_table,
    export_materialx, import as import_materialx, materialx_files,
};
pub use mesh_maps::{
    BakedMeshMap, MOST_POOLING, MeshMap, MeshMapSettings, bake_mesh_maps, mesh_map_path,
};
pub use model::{ModelFormat, ModelSettings};
use pipeline::MapTarget;
pub use transfer::{CAGES, TransferMap, TransferSettings, Transferred, transfer};
pub use usd::{export_usd, usd_files};

use crate::codegen::Compiled;
use crate::render::{FlatRect, FlatRenderer, GpuContext, GpuMesh, RenderError, UvRenderer};
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
    /// The most bytes a pixel of a map takes in a file of this format: uncompressed
    /// RGB for PNG, RGBA f32 for EXR (RLE can only lose on noise).
    fn max_bytes_per_pixel(self) -> u64 {
        match self {
            Format::Png8 => 3,
            Format::Png16 => 6,
            Format::Exr => 16,
        }
    }

    /// The file extension.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Png8 | Format::Png16 => "png",
            Format::Exr => "exr",
        }
    }
}

/// Where a bake samples the material.
#[derive(Clone, Debug, PartialEq)]
pub enum BakeSurface {
    /// Over a rectangle of a plane (`None`: the graph's preview square); tileable when the
    /// graph is periodic over the rectangle.
    Plane(Option<FlatRect>),
    /// Over a rectangle of a plane (`None`: the unit square, x and z from 0 to 1 at
    /// y = 0) as one tile of a repeating texture: before anything is written, each map's
    /// opposite edges are checked to continue each other ([`tile::Seams`]; a bake whose
    /// seams pass [`tile::SEAM_TOLERANCE`] is refused), and normal maps take their
    /// differences across the edges, so they tile too.
    Tile(Option<FlatRect>),
    /// Into the UV layout of a primitive or a mesh file (an automatic atlas when it has
    /// none, [`crate::mesh::Mesh::with_uv_atlas`]), placed as the graph's preview places
    /// it. Seams are padded by growing covered texels outwards.
    MeshUv(String),
}

/// How many texels a UV bake grows its islands by, so filtering never reaches the background.
const UV_PADDING: u32 = 8;

/// What to bake and how.
#[derive(Clone, Debug, PartialEq)]
pub struct BakeSettings {
    pub surface: BakeSurface,
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
    /// How far the map's opposite edges are from continuing each other (tiles only).
    pub seams: Option<tile::Seams>,
}

/// A bake that failed: refused before any work (outputs, memory), a render that failed,
/// or a map that could not be written.
#[derive(Debug, thiserror::Error)]
pub enum BakeError {
    /// The folder a map would go to is missing or not a folder.
    #[error("{folder}: {why}; nothing was baked")]
    Folder { folder: PathBuf, why: &'static str },
    /// A folder's disk lacks room for the maps at their largest.
    #[error(
        "{folder}: the maps take up to {} and its disk has {} free; nothing was baked",
        crate::fsutil::gibibytes(*.needed),
        crate::fsutil::gibibytes(*.free)
    )]
    NoSpace {
        folder: PathBuf,
        needed: u64,
        free: u64,
    },
    /// The GPU, the mesh or its fields failed, or the bake is too large for memory.
    #[error(transparent)]
    Render(#[from] RenderError),
    /// A map could not be converted, encoded or written.
    #[error("{path}: {error}")]
    Write {
        path: PathBuf,
        #[source]
        error: std::io::Error,
    },
    /// Nodes the MaterialX export's procedural tier cannot translate, each with why.
    #[error(
        "cannot translate to MaterialX nodes: {}; export it with --tier baked (or auto); nothing was written",
        .0.iter().map(ToString::to_string).collect::<Vec<_>>().join("; ")
    )]
    Untranslatable(Vec<materialx::Untranslatable>),
    /// The thread writing a map panicked.
    #[error("{path}: the map writer panicked")]
    WriterPanicked { path: PathBuf },
    /// A tile's maps whose opposite edges do not continue each other, with their seams.
    #[error(
        "the maps do not tile: {}; the tile passes at seams up to {}. Give every noise a period (in cells) that its scale spans a whole number of times over the tile; nothing was baked",
        .0.iter().map(|(map, seams)| format!("the {} map's edges differ by up to {} left/right and {} top/bottom", map.name(), tile::seam_text(seams.left_right), tile::seam_text(seams.top_bottom))).collect::<Vec<_>>().join(", "),
        tile::SEAM_TOLERANCE
    )]
    NotTileable(Vec<(Map, tile::Seams)>),
    /// Buffers that wrap (so every map reads them across the tile's edges as if they
    /// went on) but do not repeat over the tile: their seam lies inside the maps.
    #[error(
        "the maps do not tile: {}; the buffers wrap across the tile's edges, so their seams are inside every map. Give every noise upstream of them a period (in cells) that its scale spans a whole number of times over the tile; nothing was baked",
        .0.iter().map(|seam| format!("the buffer of {} differs by up to {} left/right and {} top/bottom from itself a tile on", seam.pass, tile::seam_text(seam.left_right), tile::seam_text(seam.top_bottom))).collect::<Vec<_>>().join(", ")
    )]
    BuffersNotTileable(Vec<crate::render::WrapSeam>),
    /// A mesh map's settings are out of their limits, or its field cannot be computed.
    #[error("{0}; nothing was baked")]
    MeshField(String),
    /// Whoever asked for the export took it back; nothing was written.
    #[error("cancelled; nothing was written")]
    Cancelled,
}

/// The renderer of a bake's surface.
enum Surface {
    Plane(FlatRenderer, FlatRect),
    Uv(UvRenderer, GpuMesh),
}

/// The unit square a tile bakes over by default: x and z from 0 to 1 at y = 0.
pub const UNIT_TILE: FlatRect = FlatRect {
    x0: 0.0,
    z0: 0.0,
    x1: 1.0,
    z1: 1.0,
    y: 0.0,
};

/// The file a bake writes `map` to: `<stem>_<map>.<ext>`.
pub fn map_path(stem: &Path, map: Map, format: Format) -> PathBuf {
    named_path(stem, map.name(), format)
}

/// `<stem>_<name>.<ext>`.
fn named_path(stem: &Path, name: &str, format: Format) -> PathBuf {
    let stem_name = stem
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    stem.with_file_name(format!("{stem_name}_{name}.{}", format.extension()))
}

/// Checks, before anything renders, that every file the bakes of `stems` would write
/// has a folder to go to, and that each folder's disk has room for the maps at their
/// largest. (That no two bakes write one file is the output plan's to check:
/// [`crate::fsutil::OutputPlan`].)
pub fn check_outputs(stems: &[&Path], settings: &BakeSettings) -> Result<(), BakeError> {
    let mut needed: std::collections::BTreeMap<&Path, u64> = Default::default();
    let map_bytes = u64::from(settings.size).pow(2) * settings.format.max_bytes_per_pixel();
    for &stem in stems {
        let folder = output_folder(stem)?;
        *needed.entry(folder).or_default() += map_bytes * settings.maps.len() as u64;
    }
    for (folder, bytes) in needed {
        if let Some(free) = crate::fsutil::free_space(folder)
            && bytes > free
        {
            return Err(BakeError::NoSpace {
                folder: folder.to_path_buf(),
                needed: bytes,
                free,
            });
        }
    }
    Ok(())
}

/// The folder a file at `path` goes to (`.` for a bare name), refused unless it is an
/// existing folder.
fn output_folder(path: &Path) -> Result<&Path, BakeError> {
    let folder = match path.parent() {
        Some(folder) if !folder.as_os_str().is_empty() => folder,
        _ => Path::new("."),
    };
    if folder.is_dir() {
        return Ok(folder);
    }
    let why = if folder.exists() {
        "is not a folder"
    } else {
        "does not exist"
    };
    Err(BakeError::Folder {
        folder: folder.to_path_buf(),
        why,
    })
}

/// Bakes a compiled material (parameters baked, the default) into `<stem>_<map>.<ext>`
/// files, calling `progress(done, total)` as tiles finish; when it answers `false` the
/// bake stops ([`BakeError::Cancelled`]). The maps are put in place together once all
/// are written: a bake that fails, is cancelled or is interrupted leaves none of its
/// maps, and the old ones as they were. Maps are files Veneer names itself: a link or
/// special file at one's path is refused ([`crate::fsutil::Naming::Implied`]).
pub fn bake(
    gpu: &GpuContext,
    compiled: &Compiled,
    settings: &BakeSettings,
    stem: &Path,
    mut progress: impl FnMut(u64, u64) -> bool,
) -> Result<Vec<BakedMap>, BakeError> {
    crate::render::baked_parameters(compiled)?;
    // Whether whoever asked still wants the maps, as `progress` last answered.
    let wanted = std::cell::Cell::new(true);
    let (module, preview) = (&compiled.module, &compiled.preview);
    let size = settings.size;
    let placement = crate::render::texture_placement(preview);
    let tile = crate::render::tile_size(gpu);
    // Progress before the maps' tiles: casting a UV bake's texel fields counts as a
    // map's worth of tiles.
    let mut lead = 0u64;
    let (surface, spacing) = match &settings.surface {
        BakeSurface::Plane(rect) | BakeSurface::Tile(rect) => {
            let rect = match settings.surface {
                BakeSurface::Tile(_) => rect.unwrap_or(UNIT_TILE),
                _ => rect.unwrap_or_else(|| crate::render::preview_rect(preview)),
            };
            let spacing = (
                (rect.x1 - rect.x0) / f64::from(size),
                (rect.z1 - rect.z0) / f64::from(size),
            );
            (
                Surface::Plane(FlatRenderer::for_compiled(gpu, compiled)?, rect),
                spacing,
            )
        }
        BakeSurface::MeshUv(name) => {
            // A mesh without a UV layout gets an atlas, after its fields are solved on the
            // connected mesh.
            let mesh = crate::render::mesh_with_fields(preview, name, &module.uses, |_, _| {})?
                .with_uv_layout(size);
            // The UV square is taken to span the preview square: normals are approximate.
            let texel = 2.0 * preview.size / f64::from(size);
            let mut renderer = UvRenderer::new(gpu, &module.source)?;
            let per_map = u64::from(size.div_ceil(tile)).pow(2);
            let all = per_map * (settings.maps.len() as u64 + 1);
            let lanes = &module.uses.mesh_fields;
            let cast = texel_fields::texel_fields(&mesh, lanes, size, |done, texels| {
                wanted.set(progress(per_map * done as u64 / texels.max(1) as u64, all));
            });
            if !wanted.get() {
                return Err(BakeError::Cancelled);
            }
            if let Some(fields) = cast {
                renderer.set_texel_fields(gpu, &fields);
                lead = per_map;
            }
            let gpu_mesh = GpuMesh::new(&gpu.device, &mesh);
            let passes = crate::render::mesh_passes(
                gpu,
                compiled,
                &gpu_mesh,
                placement,
                size,
                settings.time,
            )?;
            if let Some(passes) = &passes {
                renderer.bind_passes(gpu, passes);
            }
            (Surface::Uv(renderer, gpu_mesh), (texel, texel))
        }
    };
    let band_rows = band_rows(size, tile);
    if let Surface::Plane(..) = surface {
        check_memory(size, band_rows, settings.format)?;
    }
    let tiles_per_pass = match surface {
        Surface::Plane(..) => u64::from(size.div_ceil(tile)) * u64::from(size.div_ceil(band_rows)),
        Surface::Uv(..) => u64::from(size.div_ceil(tile)).pow(2),
    };
    let total = lead + tiles_per_pass * settings.maps.len() as u64;
    let edges = match (&surface, &settings.surface) {
        (Surface::Plane(flat, rect), BakeSurface::Tile(_)) => {
            let (size, time) = (settings.size, settings.time);
            let edges = tile::TileEdges::check(gpu, flat, *rect, size, time, &settings.maps)?;
            let failing = edges.failing(&settings.maps);
            if !failing.is_empty() {
                return Err(BakeError::NotTileable(failing));
            }
            let buffers = flat.wrap_seams(gpu, *rect, time)?;
            let failing: Vec<_> = (buffers.into_iter())
                .filter(|seam| seam.left_right.max(seam.top_bottom) > tile::SEAM_TOLERANCE)
                .collect();
            if !failing.is_empty() {
                return Err(BakeError::BuffersNotTileable(failing));
            }
            Some(edges)
        }
        _ => None,
    };
    let beyond = edges.as_ref().and_then(tile::TileEdges::heights_beyond);
    let paths: Vec<_> = (settings.maps.iter())
        .map(|map| map_path(stem, *map, settings.format))
        .collect();
    let targets: Vec<_> = (settings.maps.iter().zip(&paths))
        .map(|(map, path)| MapTarget {
            path,
            map: *map,
            shading: compiled.checked.shading,
            size,
            format: settings.format,
            spacing,
            convention: settings.normal,
            beyond: beyond.as_ref(),
        })
        .collect();
    let overlap = settings.format == Format::Exr;
    let baked = pipeline::bake_maps(&targets, overlap, |index, sink| {
        let channels = targets[index].map.channels();
        let base = lead + index as u64 * tiles_per_pass;
        let report = |done: u32, _| wanted.set(progress(base + u64::from(done), total));
        let sink = &mut |first_row, band| {
            if !wanted.get() {
                return Err(RenderError::Stopped("the bake was cancelled"));
            }
            sink(first_row, band)
        };
        match &surface {
            Surface::Plane(flat, rect) => flat.render_channel_bands(
                gpu,
                *rect,
                size,
                settings.time,
                channels,
                band_rows,
                report,
                sink,
            ),
            Surface::Uv(uv, mesh) => {
                let mut pixels = uv.render_channels(
                    gpu,
                    mesh,
                    placement,
                    size,
                    settings.time,
                    channels,
                    report,
                )?;
                fill_uncovered(&mut pixels, size, UV_PADDING);
                sink(0, pixels).map(drop)
            }
        }
    });
    match baked {
        Err(_) if !wanted.get() => return Err(BakeError::Cancelled),
        other => other?,
    }
    let written = (settings.maps.iter().zip(paths))
        .map(|(map, path)| BakedMap {
            map: *map,
            bytes: std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0),
            path,
            size,
            format: settings.format,
            seams: edges.as_ref().and_then(|edges| edges.seams(*map)),
        })
        .collect();
    Ok(written)
}

/// Bytes of each band buffer a plane bake renders into.
const BAND_BYTES: u64 = 128 << 20;

/// Rows per band of a `size`² plane bake in tiles of `tile`²: as many as fit
/// [`BAND_BYTES`] at four f32 per pixel, at most a tile.
pub fn band_rows(size: u32, tile: u32) -> u32 {
    let rows = BAND_BYTES / (u64::from(size.max(1)) * 16);
    (rows.min(u64::from(tile)) as u32).max(1)
}

/// Refuses, before any work, a plane bake the machine lacks the memory for: the bands in
/// flight (one rendering, one waiting and one converting per map being written; two
/// maps at once for EXR), and for PNG the samples and the compressed stream.
fn check_memory(size: u32, band_rows: u32, format: Format) -> Result<(), BakeError> {
    let pixels = u64::from(size) * u64::from(size);
    let (stream, bands_in_flight) = match format {
        Format::Png8 => (2 * 3 * pixels, 3),
        Format::Png16 => (2 * 6 * pixels, 3),
        Format::Exr => (0, 5),
    };
    let bands = bands_in_flight * u64::from(size) * u64::from(band_rows) * 16;
    crate::render::ensure_memory(size, bands + stream).map_err(BakeError::from)
}
