//! Mesh fields: what a surface knows about itself, per vertex, for materials to read
//! (a Mesh field node) and for bakes — how convex it is, how occluded, how thick. Each
//! is computed once per mesh and setting, from the mesh as loaded: curvatures over the
//! welded mesh (seams do not cut them), ray-cast fields from every vertex with its own
//! normal (hard edges keep their faces' normals). Distances and radii are set in
//! percent of the mesh's bounding radius, so a field means the same on any mesh scale.

mod cache;
mod curvature;
mod features;
mod occlusion;
mod rays;
mod scene;
mod texels;
mod thickness;

pub use cache::cached;
pub use curvature::{Curvatures, MeanCurvature, convexity, curvatures, sturdy_mean_curvature};
pub use features::{Feature, distance_to};
pub use occlusion::{Estimate, Sampling, occlusion, occlusion_at};
pub use scene::{Frame, Scene};
pub use texels::Texels;
pub use thickness::{CONE_HALF_ANGLE, thickness};

use crate::geodesic::{HeatError, welded_for_distances};
use crate::mesh::Mesh;
use serde::{Deserialize, Serialize};
use std::ops::RangeInclusive;

/// The lanes of `VeneerSurface.fields`, which distance fields and mesh fields share.
pub const MESH_LANES: usize = 4;

/// Which mesh field each lane of `VeneerSurface.fields` holds (`None`: a distance
/// field's, or unused).
pub type MeshLanes = [Option<MeshField>; MESH_LANES];

/// Computes the fields of `lanes` over `mesh` into those lanes of `mesh.fields`
/// (created, zero, when the mesh has no distance fields; left as they are when no lane
/// is used), with progress as `(done, total)` vertices over every field. Distance
/// fields go in first ([`crate::geodesic::attach_fields`] replaces `mesh.fields`).
pub fn attach_mesh_fields(
    mesh: &mut Mesh,
    lanes: &MeshLanes,
    mut progress: impl FnMut(usize, usize),
) -> Result<(), MeshFieldError> {
    let used: Vec<(usize, MeshField)> = lanes
        .iter()
        .enumerate()
        .filter_map(|(lane, field)| field.map(|field| (lane, field)))
        .collect();
    if used.is_empty() {
        return Ok(());
    }
    let count = mesh.positions.len();
    let total = count * used.len();
    let mut attached = std::mem::take(&mut mesh.fields);
    attached.resize(count, [0.0; MESH_LANES]);
    for (done, &(lane, field)) in used.iter().enumerate() {
        let values = cache::cached(field, mesh, |d, _| progress(done * count + d, total))?;
        for (vertex, &value) in attached.iter_mut().zip(values.iter()) {
            vertex[lane] = value;
        }
        progress((done + 1) * count, total);
    }
    mesh.fields = attached;
    Ok(())
}

/// What a mesh field measures (also `veneer mesh-field --kind`, in kebab case).
#[derive(
    Clone,
    Copy,
    Debug,
    PartialEq,
    Eq,
    Hash,
    PartialOrd,
    Ord,
    Serialize,
    Deserialize,
    clap::ValueEnum,
)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum MeshFieldKind {
    /// How convex the surface is at the field's radius, −1 (creases) to 1 (edges).
    Convexity,
    /// Mean curvature in 1/mesh units (1/r on a sphere of radius r), unsmoothed.
    MeanCurvature,
    /// Gaussian curvature in 1/mesh units² (negative at saddles), unsmoothed.
    GaussianCurvature,
    /// Ambient occlusion: the open share of the hemisphere, 0 enclosed to 1 open.
    Occlusion,
    /// Thickness along the inward normal as a share of the field's distance, 0 to 1.
    Thickness,
    /// How much the surface faces up (+y): the normal's y, −1 facing down to 1 up. Read
    /// from the shaded point's own normal, so it needs no lane.
    Up,
    /// Height within the mesh's bounds, 0 at its lowest point to 1 at its highest.
    Height,
    /// Position along x within the mesh's bounds, 0 at its lowest x to 1 at its highest.
    Width,
    /// Position along z within the mesh's bounds, 0 at its lowest z to 1 at its highest.
    Depth,
    /// Distance along the surface to the nearest sharp edge (its triangles turn by more
    /// than 30°) as a share of the field's distance: 0 on the edge, 1 at the distance.
    SharpEdgeDistance,
    /// Distance along the surface to the nearest UV seam, as a share of the distance.
    SeamDistance,
    /// Distance along the surface to the mesh's boundary, as a share of the distance.
    BoundaryDistance,
}

impl MeshFieldKind {
    /// Every kind, in menu order.
    pub const ALL: [MeshFieldKind; 12] = [
        MeshFieldKind::Convexity,
        MeshFieldKind::MeanCurvature,
        MeshFieldKind::GaussianCurvature,
        MeshFieldKind::Occlusion,
        MeshFieldKind::Thickness,
        MeshFieldKind::Up,
        MeshFieldKind::Width,
        MeshFieldKind::Height,
        MeshFieldKind::Depth,
        MeshFieldKind::SharpEdgeDistance,
        MeshFieldKind::SeamDistance,
        MeshFieldKind::BoundaryDistance,
    ];

    /// The kind as menus and messages name it.
    pub fn name(self) -> &'static str {
        match self {
            MeshFieldKind::Convexity => "convexity",
            MeshFieldKind::MeanCurvature => "mean curvature",
            MeshFieldKind::GaussianCurvature => "Gaussian curvature",
            MeshFieldKind::Occlusion => "ambient occlusion",
            MeshFieldKind::Thickness => "thickness",
            MeshFieldKind::Up => "facing up",
            MeshFieldKind::Height => "height in bounds",
            MeshFieldKind::Width => "x in bounds",
            MeshFieldKind::Depth => "z in bounds",
            MeshFieldKind::SharpEdgeDistance => "distance to sharp edges",
            MeshFieldKind::SeamDistance => "distance to UV seams",
            MeshFieldKind::BoundaryDistance => "distance to the boundary",
        }
    }

    /// The feature a distance kind measures from.
    fn feature(self) -> Option<Feature> {
        match self {
            MeshFieldKind::SharpEdgeDistance => Some(Feature::SharpEdge),
            MeshFieldKind::SeamDistance => Some(Feature::Seam),
            MeshFieldKind::BoundaryDistance => Some(Feature::Boundary),
            _ => None,
        }
    }

    /// Whether the kind has a distance setting (rays' reach, or a feature distance's).
    pub fn has_distance(self) -> bool {
        self.casts_rays() || self.feature().is_some()
    }

    /// The values the kind takes; `None` for the curvatures, which are unbounded.
    pub fn range(self) -> Option<(f64, f64)> {
        match self {
            MeshFieldKind::Convexity | MeshFieldKind::Up => Some((-1.0, 1.0)),
            MeshFieldKind::Occlusion
            | MeshFieldKind::Thickness
            | MeshFieldKind::Height
            | MeshFieldKind::Width
            | MeshFieldKind::Depth
            | MeshFieldKind::SharpEdgeDistance
            | MeshFieldKind::SeamDistance
            | MeshFieldKind::BoundaryDistance => Some((0.0, 1.0)),
            MeshFieldKind::MeanCurvature | MeshFieldKind::GaussianCurvature => None,
        }
    }

    /// The value the kind takes on an unbounded flat plane, which is what flat views
    /// (the flat render, thumbnails, passes over the flat domain) show: nothing bends,
    /// nothing occludes, nothing lies behind within reach, no feature is near, and a
    /// plane has no height in its bounds.
    pub fn on_flat_plane(self) -> f32 {
        match self {
            MeshFieldKind::Convexity
            | MeshFieldKind::MeanCurvature
            | MeshFieldKind::GaussianCurvature
            | MeshFieldKind::Height => 0.0,
            // Across the plane, measured where the view is centred.
            MeshFieldKind::Width | MeshFieldKind::Depth => 0.5,
            MeshFieldKind::Occlusion
            | MeshFieldKind::Thickness
            | MeshFieldKind::Up
            | MeshFieldKind::SharpEdgeDistance
            | MeshFieldKind::SeamDistance
            | MeshFieldKind::BoundaryDistance => 1.0,
        }
    }

    /// Whether the kind is stored per vertex in a lane of `VeneerSurface.fields`
    /// (all but [`MeshFieldKind::Up`], which the shaded point's normal gives).
    pub fn needs_lane(self) -> bool {
        self != MeshFieldKind::Up
    }

    /// Whether the kind casts rays (and so has a sample count and a distance).
    pub fn casts_rays(self) -> bool {
        matches!(self, MeshFieldKind::Occlusion | MeshFieldKind::Thickness)
    }
}

/// A mesh field with its settings: what a Mesh field node asks for, and the unit the
/// renderers compute and cache. Settings the kind does not use are ignored ([`key`]
/// clears them).
///
/// [`key`]: MeshField::key
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct MeshField {
    pub kind: MeshFieldKind,
    /// Convexity's radius, in percent of the mesh's bounding radius.
    #[serde(default = "MeshField::default_radius")]
    pub radius: u32,
    /// Rays per vertex (occlusion and thickness): the accuracy knob.
    #[serde(default = "MeshField::default_samples")]
    pub samples: u32,
    /// How far rays look (occlusion and thickness), or the distance a feature distance
    /// reaches 1 at, in percent of the bounding radius.
    #[serde(default = "MeshField::default_distance")]
    pub distance: u32,
}

/// Each vertex's coordinate `axis` between the mesh's lowest and highest along it, 0 to
/// 1 (0 for a mesh with no extent along it).
fn in_bounds(mesh: &Mesh, axis: usize) -> Vec<f32> {
    let along = || mesh.positions.iter().map(|p| f64::from(p[axis]));
    let (low, high) = along().fold((f64::MAX, f64::MIN), |(lo, hi), c| (lo.min(c), hi.max(c)));
    let span = high - low;
    along()
        .map(|c| match span > 0.0 && span.is_finite() {
            true => ((c - low) / span) as f32,
            false => 0.0,
        })
        .collect()
}

impl std::fmt::Display for MeshField {
    /// The kind and the settings it uses: `convexity (radius 5%)`,
    /// `ambient occlusion (64 rays, 50%)`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.kind.name())?;
        match self.kind {
            MeshFieldKind::Convexity => write!(f, " (radius {}%)", self.radius),
            kind if kind.casts_rays() => {
                write!(f, " ({} rays, {}%)", self.samples, self.distance)
            }
            kind if kind.has_distance() => write!(f, " ({}%)", self.distance),
            _ => Ok(()),
        }
    }
}

/// A mesh field that cannot be computed: settings out of range, or a mesh whose
/// smoothing system cannot be factored.
#[derive(Debug, thiserror::Error)]
pub enum MeshFieldError {
    #[error("{kind}: {setting} {value} is outside {min} to {max}")]
    Setting {
        kind: &'static str,
        setting: &'static str,
        value: u32,
        min: u32,
        max: u32,
    },
    #[error("{kind}: {source}")]
    Heat {
        kind: &'static str,
        source: HeatError,
    },
}

impl MeshField {
    /// Radii accepted, in percent of the bounding radius.
    pub const RADII: RangeInclusive<u32> = 1..=100;
    /// Sample counts accepted.
    pub const SAMPLES: RangeInclusive<u32> = 1..=4096;
    /// Distances accepted, in percent of the bounding radius (400 spans any mesh).
    pub const DISTANCES: RangeInclusive<u32> = 1..=400;

    fn default_radius() -> u32 {
        5
    }

    fn default_samples() -> u32 {
        64
    }

    fn default_distance() -> u32 {
        50
    }

    /// A field of `kind` with the default settings.
    pub fn new(kind: MeshFieldKind) -> MeshField {
        MeshField {
            kind,
            radius: MeshField::default_radius(),
            samples: MeshField::default_samples(),
            distance: MeshField::default_distance(),
        }
    }

    /// The field with the settings its kind ignores set to their defaults, so that two
    /// nodes asking for the same thing share one computed field.
    pub fn key(self) -> MeshField {
        let defaults = MeshField::new(self.kind);
        MeshField {
            radius: match self.kind {
                MeshFieldKind::Convexity => self.radius,
                _ => defaults.radius,
            },
            samples: match self.kind.casts_rays() {
                true => self.samples,
                false => defaults.samples,
            },
            distance: match self.kind.has_distance() {
                true => self.distance,
                false => defaults.distance,
            },
            ..self
        }
    }

    /// Refuses settings outside their limits, naming the limits.
    pub fn validate(&self) -> Result<(), MeshFieldError> {
        let check = |setting, value: u32, range: RangeInclusive<u32>| match range.contains(&value) {
            true => Ok(()),
            false => Err(MeshFieldError::Setting {
                kind: self.kind.name(),
                setting,
                value,
                min: *range.start(),
                max: *range.end(),
            }),
        };
        if self.kind == MeshFieldKind::Convexity {
            check("radius", self.radius, MeshField::RADII)?;
        }
        if self.kind.casts_rays() {
            check("samples", self.samples, MeshField::SAMPLES)?;
        }
        if self.kind.has_distance() {
            check("distance", self.distance, MeshField::DISTANCES)?;
        }
        Ok(())
    }

    /// A failed factorisation, in this field's words.
    fn heat(&self, source: HeatError) -> MeshFieldError {
        MeshFieldError::Heat {
            kind: self.kind.name(),
            source,
        }
    }

    /// How occlusion rays are cast for these settings, stopping at `tolerance` when
    /// given (see [`Sampling::tolerance`]).
    pub fn sampling(&self, tolerance: Option<f32>) -> Sampling {
        Sampling {
            samples: self.samples,
            distance: self.distance as f32 / 100.0,
            tolerance,
        }
    }

    /// The field at every vertex of `mesh` (as loaded), with progress as `(done, total)`.
    pub fn compute(
        &self,
        mesh: &Mesh,
        progress: impl FnMut(usize, usize),
    ) -> Result<Vec<f32>, MeshFieldError> {
        self.validate()?;
        let percent = |value: u32| value as f32 / 100.0;
        match self.kind {
            MeshFieldKind::Occlusion => {
                Ok(occlusion(&Scene::new(mesh), self.sampling(None), progress)
                    .into_iter()
                    .map(|estimate| estimate.open)
                    .collect())
            }
            MeshFieldKind::Thickness => {
                let distance = percent(self.distance);
                let scene = Scene::new(mesh);
                Ok(thickness(&scene, self.samples, distance, progress)
                    .into_iter()
                    .map(|t| t / distance)
                    .collect())
            }
            MeshFieldKind::Up => Ok(mesh.normals.iter().map(|n| n[1]).collect()),
            MeshFieldKind::Width => Ok(in_bounds(mesh, 0)),
            MeshFieldKind::Height => Ok(in_bounds(mesh, 1)),
            MeshFieldKind::Depth => Ok(in_bounds(mesh, 2)),
            kind if kind.feature().is_some() => {
                let reach = f64::from(percent(self.distance)) * mesh.bounding_sphere().1;
                let feature = kind.feature().expect("a feature kind");
                distance_to(mesh, feature, reach, progress).map_err(|source| self.heat(source))
            }
            kind => {
                let (welded, of_vertex) = welded_for_distances(mesh);
                let per_welded = match kind {
                    MeshFieldKind::Convexity => {
                        let radius = f64::from(percent(self.radius)) * mesh.bounding_sphere().1;
                        convexity(&welded, radius).map_err(|source| self.heat(source))?
                    }
                    MeshFieldKind::MeanCurvature => curvatures(&welded).mean,
                    _ => curvatures(&welded).gaussian,
                };
                Ok(of_vertex
                    .iter()
                    .map(|&w| per_welded[w as usize] as f32)
                    .collect())
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::primitive;

    /// What flat views read is what each field computes on a flat plane, at its centre
    /// (the one point of `plane` farther than the distance from its boundary).
    #[test]
    fn flat_views_read_what_a_flat_plane_computes() {
        let plane = primitive("plane:8").unwrap();
        let centre = (plane.positions.iter())
            .position(|p| p[0].abs() < 1e-6 && p[2].abs() < 1e-6)
            .expect("a vertex at the centre");
        for kind in MeshFieldKind::ALL {
            let values = MeshField::new(kind).compute(&plane, |_, _| {}).unwrap();
            let value = values[centre];
            assert!(
                (value - kind.on_flat_plane()).abs() < 1e-3,
                "{}: {value} at the plane's centre, flat views read {}",
                kind.name(),
                kind.on_flat_plane()
            );
        }
    }

    /// A scan's worst: an open sheet, a fin on three triangles of one edge (non-manifold),
    /// a separate closed piece, a triangle with no area, a vertex no triangle uses and one
    /// far away.
    fn dirty() -> Mesh {
        let mut mesh = primitive("plane:4").unwrap();
        let sheet = mesh.positions.len() as u32;
        let fin = [[0.0, 0.5, 0.0], [0.0, -0.5, 0.1], [0.2, 0.4, 0.3]];
        for p in fin {
            mesh.push_vertex(p, [1.0, 0.0, 0.0], [0.0; 2]);
        }
        mesh.indices
            .extend([0, 1, sheet, 1, 0, sheet + 1, 0, 1, sheet + 2]);
        let ball = primitive("sphere:8").unwrap();
        let offset = mesh.positions.len() as u32;
        for ((p, n), uv) in ball.positions.iter().zip(&ball.normals).zip(&ball.uvs) {
            mesh.push_vertex(p.map(|c| c * 0.2 + 3.0), *n, *uv);
        }
        mesh.indices.extend(ball.indices.iter().map(|i| i + offset));
        let flat = mesh.push_vertex([9.0, 9.0, 9.0], [0.0, 1.0, 0.0], [0.0; 2]);
        mesh.indices.extend([flat, flat, 2]);
        mesh.push_vertex([1.0e4, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0; 2]);
        mesh
    }

    #[test]
    fn every_kind_is_finite_on_a_dirty_mesh_and_refuses_settings_out_of_range() {
        let mesh = dirty();
        for kind in MeshFieldKind::ALL {
            let values = MeshField::new(kind).compute(&mesh, |_, _| {}).unwrap();
            assert_eq!(values.len(), mesh.positions.len());
            assert!(values.iter().all(|v| v.is_finite()), "{kind:?}: {values:?}");
        }
        let out_of_range = MeshField {
            radius: 0,
            ..MeshField::new(MeshFieldKind::Convexity)
        };
        let error = out_of_range.compute(&mesh, |_, _| {}).unwrap_err();
        assert_eq!(error.to_string(), "convexity: radius 0 is outside 1 to 100");
    }

    #[test]
    fn facing_up_and_position_in_bounds_run_across_a_sphere() {
        let sphere = primitive("sphere").unwrap();
        let up = MeshField::new(MeshFieldKind::Up)
            .compute(&sphere, |_, _| {})
            .unwrap();
        let in_bounds = |kind| MeshField::new(kind).compute(&sphere, |_, _| {}).unwrap();
        let position = [
            MeshFieldKind::Width,
            MeshFieldKind::Height,
            MeshFieldKind::Depth,
        ]
        .map(in_bounds);
        for (v, p) in sphere.positions.iter().enumerate() {
            assert!((up[v] - p[1]).abs() < 1e-5);
            for axis in 0..3 {
                assert!((position[axis][v] - (p[axis] + 1.0) / 2.0).abs() < 1e-5);
            }
        }
        assert!(!MeshFieldKind::Up.needs_lane() && MeshFieldKind::Height.needs_lane());
    }

    #[test]
    fn fields_attach_in_their_lanes_and_nothing_is_attached_when_no_lane_is_used() {
        let mut mesh = primitive("torus:12").unwrap();
        let lanes: MeshLanes = [
            None,
            Some(MeshField::new(MeshFieldKind::Occlusion)),
            None,
            Some(MeshField::new(MeshFieldKind::Convexity)),
        ];
        mesh.fields = vec![[0.5, 7.0, 0.5, 7.0]; mesh.positions.len()];
        attach_mesh_fields(&mut mesh, &lanes, |_, _| {}).unwrap();
        assert_eq!(mesh.fields.len(), mesh.positions.len());
        // The distance fields' lanes are kept.
        assert!(mesh.fields.iter().all(|f| f[0] == 0.5 && f[2] == 0.5));
        assert!(mesh.fields.iter().any(|f| f[1] < 1.0 && f[3] != 0.0));
        assert!(mesh.fields.iter().all(|f| f[1] <= 1.0 && f[3] != 7.0));
        mesh.fields.clear();
        attach_mesh_fields(&mut mesh, &[None; MESH_LANES], |_, _| {}).unwrap();
        assert!(mesh.fields.is_empty());
    }
}
