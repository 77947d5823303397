//! Mesh maps: what a mesh knows about itself — ambient occlusion, curvature, thickness,
//! object-space position and normal — baked per texel into its UV layout
//! (`veneer bake --mesh M --maps ao,curvature,…`), with no material. Occlusion and
//! thickness cast rays from every covered texel ([`crate::mesh_fields::Texels`]) and
//! pool each texel with its neighbours on the same surface; curvature is the convexity
//! field interpolated between vertices; position and normal are interpolated. Islands
//! are padded as the material bakes pad them.

use super::encode::encode;
use super::{BakeError, Format, UV_PADDING, fill_uncovered, output_folder};
use crate::fsutil::Naming;
use crate::mesh::Mesh;
use crate::mesh_fields::{MeshField, MeshFieldError, MeshFieldKind, Scene, Texels, cached};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// A map of the mesh itself.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum MeshMap {
    /// Ambient occlusion (grey): the open share of the hemisphere, cosine-weighted.
    Ao,
    /// Convexity at the settings' radius (grey): 0.5 flat, lighter on convex edges,
    /// darker in creases.
    Curvature,
    /// Thickness along the inward normal as a share of the settings' distance (grey).
    Thickness,
    /// Object-space position within the mesh's bounds, x, y, z in R, G, B (0.5 along an
    /// axis the mesh does not extend in).
    Position,
    /// Object-space unit normal, 0.5 + 0.5·n in R, G, B.
    WorldNormal,
}

impl MeshMap {
    /// Every mesh map, as named on the command line.
    pub const ALL: [MeshMap; 5] = [
        MeshMap::Ao,
        MeshMap::Curvature,
        MeshMap::Thickness,
        MeshMap::Position,
        MeshMap::WorldNormal,
    ];

    /// The map's name in file names and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            MeshMap::Ao => "ao",
            MeshMap::Curvature => "curvature",
            MeshMap::Thickness => "thickness",
            MeshMap::Position => "position",
            MeshMap::WorldNormal => "world-normal",
        }
    }

    /// The mesh field the map bakes, with `settings`'s rays, distance and radius.
    fn field(self, settings: &MeshMapSettings) -> Option<MeshField> {
        let kind = match self {
            MeshMap::Ao => MeshFieldKind::Occlusion,
            MeshMap::Curvature => MeshFieldKind::Convexity,
            MeshMap::Thickness => MeshFieldKind::Thickness,
            MeshMap::Position | MeshMap::WorldNormal => return None,
        };
        Some(MeshField {
            kind,
            radius: settings.radius,
            samples: settings.samples,
            distance: settings.distance,
        })
    }
}

/// How mesh maps are baked.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshMapSettings {
    /// Width and height of every map in texels.
    pub size: u32,
    pub format: Format,
    /// Rays per texel (occlusion and thickness), 1 to 4,096.
    pub samples: u32,
    /// How far rays look, in percent of the bounding radius, 1 to 400.
    pub distance: u32,
    /// Convexity's radius, in percent of the bounding radius, 1 to 100.
    pub radius: u32,
    /// How many texels around each texel its ray-cast value is pooled with (0: none).
    pub pooling: u32,
}

/// The most texels a pooling reaches, each way.
pub const MOST_POOLING: u32 = 8;

/// One mesh map written.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct BakedMeshMap {
    pub map: MeshMap,
    pub path: PathBuf,
    pub size: u32,
    pub format: Format,
    pub bytes: u64,
    /// Rays cast per covered texel (0 for maps that cast none).
    pub rays_per_texel: u32,
    /// Texels the mesh covers in the map.
    pub covered_texels: usize,
    /// Seconds the map's values took.
    pub seconds: f64,
}

/// The file a mesh map goes to: `<stem>_<map>.<ext>`.
pub fn mesh_map_path(stem: &Path, map: MeshMap, format: Format) -> PathBuf {
    super::named_path(stem, map.name(), format)
}

impl MeshMapSettings {
    /// Refuses sample counts, distances, radii and pooling outside their limits, naming
    /// the limits.
    pub fn validate(&self, maps: &[MeshMap]) -> Result<(), MeshFieldError> {
        for field in maps.iter().filter_map(|map| map.field(self)) {
            field.validate()?;
        }
        match self.pooling <= MOST_POOLING {
            true => Ok(()),
            false => Err(MeshFieldError::Setting {
                kind: "mesh maps",
                setting: "pooling",
                value: self.pooling,
                min: 0,
                max: MOST_POOLING,
            }),
        }
    }
}

/// Bakes `maps` of `mesh` (with a UV layout: [`Mesh::with_uv_layout`]) into
/// `<stem>_<map>.<ext>` for each of `stems`, calling `progress(done, total)` as texels
/// finish. Every map is put in place once all are written: on a failure none is.
pub fn bake_mesh_maps(
    mesh: &Mesh,
    maps: &[MeshMap],
    settings: &MeshMapSettings,
    stems: &[&Path],
    mut progress: impl FnMut(u64, u64),
) -> Result<Vec<BakedMeshMap>, BakeError> {
    settings
        .validate(maps)
        .map_err(|error| BakeError::MeshField(error.to_string()))?;
    for stem in stems {
        output_folder(stem)?;
    }
    let scene = Scene::new(mesh);
    let texels = Texels::new(mesh, &scene, settings.size);
    let covered = texels.texels.len();
    let total = (covered * maps.len()) as u64;
    let mut staged = Vec::new();
    let mut written = Vec::new();
    for (index, &map) in maps.iter().enumerate() {
        let started = Instant::now();
        let base = (index * covered) as u64;
        let report = |done: usize, _| progress(base + done as u64, total);
        let values = texel_values(mesh, &scene, &texels, map, settings, report)?;
        let seconds = started.elapsed().as_secs_f64();
        let mut image = texels.image(&values);
        fill_uncovered(&mut image, settings.size, UV_PADDING);
        for stem in stems {
            let path = mesh_map_path(stem, map, settings.format);
            let write_error = |error| BakeError::Write {
                path: path.clone(),
                error,
            };
            let file = crate::fsutil::stage(&path, Naming::Implied, |file| {
                encode(file, settings.size, settings.format, |emit| emit(&image))
            })
            .map_err(write_error)?;
            staged.push(file);
            written.push(BakedMeshMap {
                map,
                path,
                size: settings.size,
                format: settings.format,
                bytes: 0,
                rays_per_texel: match map {
                    MeshMap::Ao | MeshMap::Thickness => settings.samples,
                    _ => 0,
                },
                covered_texels: covered,
                seconds,
            });
        }
        progress(base + covered as u64, total);
    }
    crate::fsutil::commit(staged).map_err(|(path, error)| BakeError::Write { path, error })?;
    for map in &mut written {
        map.bytes = std::fs::metadata(&map.path).map_or(0, |m| m.len());
    }
    Ok(written)
}

/// The RGBA value of `map` at every covered texel.
fn texel_values(
    mesh: &Mesh,
    scene: &Scene,
    texels: &Texels,
    map: MeshMap,
    settings: &MeshMapSettings,
    progress: impl FnMut(usize, usize),
) -> Result<Vec<[f32; 4]>, BakeError> {
    let grey = |v: f32| [v, v, v, 1.0];
    let distance = settings.distance as f32 / 100.0;
    let pooled = |values: Vec<f32>| texels.pooled(&values, settings.pooling);
    Ok(match map {
        MeshMap::Ao => {
            let field = map.field(settings).expect("occlusion is a field");
            let open = texels.occlusion(scene, field.sampling(None), progress);
            pooled(open).into_iter().map(grey).collect()
        }
        MeshMap::Thickness => {
            let share = texels.thickness(scene, settings.samples, distance, progress);
            pooled(share).into_iter().map(grey).collect()
        }
        MeshMap::Curvature => {
            let field = map.field(settings).expect("convexity is a field");
            let per_vertex = cached(field, mesh, progress)
                .map_err(|error| BakeError::MeshField(error.to_string()))?;
            let per_vertex: Vec<[f32; 1]> = per_vertex.iter().map(|&c| [c]).collect();
            (texels.interpolated(mesh, &per_vertex).into_iter())
                .map(|[c]| grey(0.5 + 0.5 * c))
                .collect()
        }
        MeshMap::Position => {
            let (low, high) = bounds(mesh);
            (texels.interpolated(mesh, &mesh.positions).into_iter())
                .map(|p| {
                    let at = |k: usize| match high[k] > low[k] {
                        true => ((p[k] - low[k]) / (high[k] - low[k])).clamp(0.0, 1.0),
                        false => 0.5,
                    };
                    [at(0), at(1), at(2), 1.0]
                })
                .collect()
        }
        MeshMap::WorldNormal => (texels.points())
            .map(|(_, n)| [0.5 + 0.5 * n.x, 0.5 + 0.5 * n.y, 0.5 + 0.5 * n.z, 1.0])
            .collect(),
    })
}

/// The lowest and highest coordinates of `mesh`'s finite vertices, per axis.
fn bounds(mesh: &Mesh) -> ([f32; 3], [f32; 3]) {
    let finite = mesh
        .positions
        .iter()
        .filter(|p| p.iter().all(|c| c.is_finite()));
    finite.fold(([f32::MAX; 3], [f32::MIN; 3]), |(low, high), p| {
        (
            std::array::from_fn(|k| low[k].min(p[k])),
            std::array::from_fn(|k| high[k].max(p[k])),
        )
    })
}
