//! The Mesh field node: what the mesh knows about itself at the shaded point (how
//! convex, how occluded, how thick), computed per mesh by [`crate::mesh_fields`] and read
//! from a lane of `VeneerSurface.fields`. The lanes are the module's: every distinct
//! mesh field the material reads gets one of the lanes its distance fields leave free,
//! in the order of their settings.

use super::cpu::Eval;
use super::emit::Emit;
use super::formulas::real::{Real, V3, splat};
use super::interval::{self, Interval, Lanes};
use super::pins::{FLOAT, Signature, output};
use super::ranges::Ranges;
use super::settings::{Basis, Setting, choice};
use super::{Catalogue, Category, Configure, Definition, Evaluate, NodeKind};
use crate::mesh_fields::MeshFieldKind;
pub use crate::mesh_fields::{MESH_LANES, MeshField, MeshLanes};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather
            [$($units)*]
            [$($configured)* (MeshField, mesh_field)]
            $($rest)*);
    };
}
pub(super) use kinds;

/// The mesh fields the nodes `kinds` read, each once (nodes asking for the same field
/// share it), ordered by their settings so the lanes do not depend on where the nodes
/// sit in the graph.
pub fn fields_read<'a>(kinds: impl IntoIterator<Item = &'a NodeKind>) -> Vec<MeshField> {
    let read: std::collections::BTreeSet<MeshField> = kinds
        .into_iter()
        .filter_map(|kind| match kind {
            NodeKind::MeshField(field) if field.kind.needs_lane() => Some(field.key()),
            _ => None,
        })
        .collect();
    read.into_iter().collect()
}

/// The lanes of `VeneerSurface.fields` the fields of `read` go in: the lanes distance
/// fields do not `take`, in order (the check refuses more fields than free lanes).
pub fn lanes(read: &[MeshField], taken: [bool; MESH_LANES]) -> MeshLanes {
    let mut lanes = MeshLanes::default();
    let free = (0..MESH_LANES).filter(|&lane| !taken[lane]);
    for (lane, field) in free.zip(read) {
        lanes[lane] = Some(*field);
    }
    lanes
}

/// What a flat view (no mesh) passes in `VeneerSurface.fields`: each mesh field's value
/// on an unbounded flat plane in its lane, 0 in the others (distance fields read 0 off a
/// mesh).
pub fn flat_fields(lanes: &MeshLanes) -> [f32; MESH_LANES] {
    lanes.map(|lane| lane.map_or(0.0, |field| field.kind.on_flat_plane()))
}

/// The lane holding `field` in `lanes`.
pub fn lane_of(lanes: &MeshLanes, field: &MeshField) -> Option<usize> {
    lanes.iter().position(|lane| *lane == Some(field.key()))
}

impl Definition for MeshField {
    fn title(&self) -> &'static str {
        "Mesh field"
    }
    fn shown_title(&self) -> String {
        let name = self.kind.name();
        name[..1].to_uppercase() + &name[1..]
    }
    fn category(&self) -> Category {
        Category::Input
    }
    fn keywords(&self) -> &'static [&'static str] {
        &[
            "curvature",
            "convexity",
            "cavity",
            "edge wear",
            "ambient occlusion",
            "ao",
            "dirt",
            "thickness",
            "subsurface",
            "seam",
            "border",
            "mesh",
            "position",
            "bounds",
        ]
    }
    fn signature(&self) -> Signature {
        Signature::new(vec![], vec![output("value", FLOAT)])
    }
    fn reads_surface(&self) -> bool {
        true
    }
    fn basis(&self) -> Option<Basis> {
        None
    }
    fn check(&self) -> Option<String> {
        self.validate().err().map(|error| error.to_string())
    }
    fn emit(&self, io: &mut Emit) {
        let value = match (self.kind, lane_of(&io.mesh_lanes(), self)) {
            (MeshFieldKind::Up, _) => "s.normal.y".to_string(),
            (_, Some(lane)) => format!("s.fields.{}", ["x", "y", "z", "w"][lane]),
            (_, None) => "0.0".to_string(),
        };
        io.outputs(vec![value]);
    }
    fn ranges(&self, _: &mut Ranges) -> Vec<Lanes> {
        let (low, high) = self
            .kind
            .range()
            .unwrap_or((f64::NEG_INFINITY, f64::INFINITY));
        vec![interval::splat(Interval::new(low, high))]
    }
}

impl Evaluate for MeshField {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let value = match (self.kind, lane_of(&io.mesh_lanes(), self)) {
            (MeshFieldKind::Up, _) => io.surface.normal[1],
            (_, Some(lane)) => io.surface.fields[lane],
            (_, None) => R::c(0.0),
        };
        vec![splat(value)]
    }
}

impl Configure for MeshField {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        let kind = self.kind;
        let mut settings = vec![choice("kind", &mut self.kind, &MeshFieldKind::ALL)];
        if kind == MeshFieldKind::Convexity {
            settings.push(Setting::Count {
                label: "radius (% of the mesh)",
                value: &mut self.radius,
                range: MeshField::RADII,
            });
        }
        if kind.casts_rays() {
            settings.push(Setting::Count {
                label: "rays per vertex",
                value: &mut self.samples,
                range: MeshField::SAMPLES,
            });
        }
        if kind.has_distance() {
            settings.push(Setting::Count {
                label: "distance (% of the mesh)",
                value: &mut self.distance,
                range: MeshField::DISTANCES,
            });
        }
        settings
    }
}

impl Catalogue for MeshField {
    fn menu() -> Vec<(String, Self)> {
        MeshFieldKind::ALL
            .into_iter()
            .map(|kind| {
                let field = MeshField::new(kind);
                (format!("Mesh field ({})", kind.name()), field)
            })
            .collect()
    }
    fn examples() -> Vec<Self> {
        MeshFieldKind::ALL.map(MeshField::new).to_vec()
    }
}
