//! High to low: the normals and heights of a detailed mesh baked into the UV layout of
//! a coarse one (`veneer bake --mesh LOW --from HIGH --maps normal,height`). From every
//! texel of the low mesh a ray starts at the cage, `cage` out along the low mesh's
//! normal, and runs inwards through the surface to `cage` inside it; the first surface
//! of the high mesh it meets gives the texel its height (how far out of the low surface
//! the high one lies, along the normal) and its normal, written in the low mesh's
//! tangent frame (the tangents glTF exports carry). A texel whose ray meets nothing is
//! a miss: it reads flat, and the bake reports how many there are.

use super::encode::encode;
use super::{BakeError, Format, NormalConvention, UV_PADDING, fill_uncovered, output_folder};
use crate::fsutil::Naming;
use crate::mesh::Mesh;
use crate::mesh_fields::{Scene, Texels};
use glam::{Vec3, Vec3A};
use std::ops::RangeInclusive;
use std::path::{Path, PathBuf};

/// A map a transfer bakes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum TransferMap {
    /// The high mesh's normals in the low mesh's tangent frame.
    Normal,
    /// The high surface's height above the low one along its normal: 0.5 on it, 1 at the
    /// cage outside, 0 at the cage inside.
    Height,
}

impl TransferMap {
    /// The map's name in file names and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            TransferMap::Normal => "normal",
            TransferMap::Height => "height",
        }
    }
}

/// How a transfer is baked.
#[derive(Clone, Debug, PartialEq)]
pub struct TransferSettings {
    /// Width and height of the maps in texels.
    pub size: u32,
    pub format: Format,
    /// How far out of the low surface rays start and how far into it they reach, in
    /// percent of the low mesh's bounding radius.
    pub cage: u32,
    pub convention: NormalConvention,
}

/// Cage distances accepted, in percent of the low mesh's bounding radius.
pub const CAGES: RangeInclusive<u32> = 1..=100;

/// A transfer's maps, written.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Transferred {
    /// The files written: `(map, path, bytes)`.
    pub maps: Vec<(TransferMap, PathBuf, u64)>,
    /// Texels of the low mesh's layout.
    pub covered_texels: usize,
    /// Of those, the texels whose ray met no surface of the high mesh.
    pub missed_texels: usize,
    /// The cage distance in the meshes' units.
    pub cage: f64,
    /// The lowest and highest heights met, in the meshes' units.
    pub heights: (f64, f64),
}

impl Transferred {
    /// The share of covered texels whose ray missed.
    pub fn missed_share(&self) -> f64 {
        self.missed_texels as f64 / self.covered_texels.max(1) as f64
    }
}

/// What one texel's ray found: the high mesh's unit normal (object space) and its
/// height above the low surface in the unit frame, or nothing.
type Found = Option<(Vec3A, f32)>;

/// Bakes `maps` of `high` onto the UV layout of `low` (with one: [`Mesh::with_uv_layout`])
/// into `<stem>_<map>.<ext>`, both meshes as their files place them. Refused when no
/// texel's ray meets the high mesh; otherwise the misses are counted in the result.
/// Both maps are put in place together, or neither.
pub fn transfer(
    low: &Mesh,
    high: &Mesh,
    maps: &[TransferMap],
    settings: &TransferSettings,
    stem: &Path,
    progress: impl FnMut(usize, usize),
) -> Result<Transferred, BakeError> {
    if !CAGES.contains(&settings.cage) {
        return Err(BakeError::MeshField(format!(
            "cage {} is outside {} to {} (percent of the low mesh's bounding radius)",
            settings.cage,
            CAGES.start(),
            CAGES.end()
        )));
    }
    output_folder(stem)?;
    let low_scene = Scene::new(low);
    let high_scene = Scene::in_frame(high, low_scene.frame());
    let texels = Texels::new(low, &low_scene, settings.size);
    let normals = crate::mesh::unit_normals(low);
    let tangents: Vec<[f32; 4]> = crate::mesh::vertex_tangents(low, &normals);
    let tangents = texels.interpolated(low, &tangents);
    let cage = settings.cage as f32 / 100.0;
    let found: Vec<Found> = texels.cast(
        |point| {
            let origin = point.position + point.normal * cage;
            let hit =
                high_scene
                    .bvh()
                    .nearest(origin.into(), (-point.normal).into(), 2.0 * cage)?;
            Some((high_scene.normal_at(&hit), cage - hit.distance))
        },
        progress,
    );
    let missed_texels = found.iter().filter(|f| f.is_none()).count();
    if missed_texels == found.len() {
        return Err(BakeError::MeshField(format!(
            "no ray from the low mesh's {} texels met the high mesh within the cage (±{:.4} in the meshes' units): do the two meshes overlap? Raise --cage if the high one lies farther off; nothing was baked",
            found.len(),
            f64::from(cage) / low_scene.frame().scale
        )));
    }
    let points: Vec<(Vec3A, Vec3A)> = texels.points().collect();
    let tangent_space = |k: usize, normal: Vec3A| {
        let n = points[k].1;
        let [tx, ty, tz, w] = tangents[k];
        let t = Vec3A::new(tx, ty, tz);
        let t = (t - n * n.dot(t)).normalize_or(n.any_orthonormal_vector());
        let b = n.cross(t) * w.signum();
        let up = match settings.convention {
            NormalConvention::OpenGl => normal.dot(b),
            NormalConvention::DirectX => -normal.dot(b),
        };
        Vec3::new(normal.dot(t), up, normal.dot(n))
    };
    let pixels = |map: TransferMap| -> Vec<[f32; 4]> {
        (found.iter().enumerate())
            .map(|(k, found)| match (map, found) {
                (TransferMap::Normal, Some((normal, _))) => {
                    let n = tangent_space(k, *normal).normalize_or(Vec3::Z);
                    [0.5 + 0.5 * n.x, 0.5 + 0.5 * n.y, 0.5 + 0.5 * n.z, 1.0]
                }
                (TransferMap::Normal, None) => [0.5, 0.5, 1.0, 1.0],
                (TransferMap::Height, found) => {
                    let height = found.map_or(0.0, |(_, h)| h);
                    let v = 0.5 + 0.5 * height / cage;
                    [v, v, v, 1.0]
                }
            })
            .collect()
    };
    let mut staged = Vec::new();
    let mut written = Vec::new();
    for &map in maps {
        let mut image = texels.image(&pixels(map));
        fill_uncovered(&mut image, settings.size, UV_PADDING);
        let path = super::named_path(stem, map.name(), settings.format);
        let file = crate::fsutil::stage(&path, Naming::Implied, |file| {
            encode(file, settings.size, settings.format, |emit| emit(&image))
        })
        .map_err(|error| BakeError::Write {
            path: path.clone(),
            error,
        })?;
        staged.push(file);
        written.push(path);
    }
    crate::fsutil::commit(staged).map_err(|(path, error)| BakeError::Write { path, error })?;
    let to_units = |unit: f32| f64::from(unit) / low_scene.frame().scale;
    let heights = (found.iter().flatten()).fold((f64::MAX, f64::MIN), |(lo, hi), (_, h)| {
        (lo.min(to_units(*h)), hi.max(to_units(*h)))
    });
    Ok(Transferred {
        maps: (maps.iter().zip(written))
            .map(|(&map, path)| {
                let bytes = std::fs::metadata(&path).map_or(0, |m| m.len());
                (map, path, bytes)
            })
            .collect(),
        covered_texels: found.len(),
        missed_texels,
        cage: to_units(cage),
        heights,
    })
}
