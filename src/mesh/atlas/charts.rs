//! Cutting a mesh into charts: regions of adjacent triangles that all face within a cone
//! of one direction, the chart's axis, and that lie side by side without overlapping
//! when projected onto the plane across that axis. A triangle whose normal is within
//! the cone keeps its orientation in that projection and at least `cos(cone)` of its
//! area, so the projection needs no check for flips; overlaps (a surface curling over
//! itself) are refused triangle by triangle as a chart is built.
//!
//! Charts are first grown one after another ([`super::seed`]), then regrown all at once
//! from their centres a few times so that they settle round the directions the surface
//! faces ([`super::settle`]), then merged wherever two neighbours fit one cone
//! ([`super::merge`]), and last their ragged edges are straightened
//! ([`super::smooth`]).

use super::geometry::Geometry;
use super::grid::{TriangleGrid, interiors_overlap};
use glam::{DVec2, DVec3};

/// Half the opening angle of the cone round a chart's axis that its triangles' normals
/// stay in, in degrees: a triangle keeps at least cos 50° ≈ 64% of its area and its
/// shape squeezed by at most that factor in one direction.
pub(super) const CONE_DEGREES: f64 = 50.0;

/// Half the opening angle of the cone for slivers, in degrees: a sliver's normal says
/// little and its distortion shows in no texel, so it may face further from a chart's
/// axis rather than make a chart of its own.
pub(super) const SLIVER_CONE_DEGREES: f64 = 80.0;

/// Steps towards the narrowest cone holding a set of normals.
const CONE_STEPS: usize = 48;

/// The least cosine between a normal and the mean normal of the triangles whose
/// narrowest cone is looked for: central projection needs normals on the mean's side.
/// Triangles with a normal nearly across from their mean (one cone of 50° could still
/// hold them, up to 100° apart) are refused, which leaves two charts apart, no worse.
const FACING_MEAN: f64 = 0.05;

/// A region of the mesh laid flat by projection along its axis.
pub(super) struct Chart {
    pub frame: Frame,
    /// The chart's triangles, in the order they joined it.
    pub triangles: Vec<u32>,
}

/// Right-handed coordinates in the plane across an axis: seen from the side the axis
/// points to, counter-clockwise triangles stay counter-clockwise.
#[derive(Clone, Copy)]
pub(super) struct Frame {
    across: DVec3,
    up: DVec3,
}

impl Chart {
    /// The chart's triangles in its plane.
    pub fn laid_flat(&self, geometry: &Geometry) -> Vec<[DVec2; 3]> {
        (self.triangles.iter())
            .map(|&t| {
                geometry.triangles[t as usize]
                    .map(|v| self.frame.project(geometry.positions[v as usize]))
            })
            .collect()
    }
}

impl Frame {
    /// The frame of the plane across the unit vector `axis`.
    fn across(axis: DVec3) -> Frame {
        let across = axis.any_orthonormal_vector();
        Frame {
            across,
            up: axis.cross(across),
        }
    }

    /// Where `position` lands in the plane.
    pub fn project(&self, position: DVec3) -> DVec2 {
        DVec2::new(position.dot(self.across), position.dot(self.up))
    }
}

/// Cuts the mesh into charts; degenerate triangles join none.
pub(super) fn segment(geometry: &Geometry) -> Vec<Chart> {
    let charts = super::seed::grow_charts(geometry, &mut vec![false; geometry.triangles.len()]);
    let charts = super::settle::settle(geometry, charts);
    let charts = super::merge::merge(geometry, charts);
    super::smooth::smooth(geometry, charts)
}

/// A chart being built round a fixed axis: what it holds, laid out, so that a new
/// triangle can be checked against it.
pub(super) struct ChartBuilder<'a> {
    geometry: &'a Geometry,
    axis: DVec3,
    frame: Frame,
    cos_cone: f64,
    cos_sliver_cone: f64,
    grid: TriangleGrid,
    placed: Vec<[DVec2; 3]>,
    triangles: Vec<u32>,
}

impl<'a> ChartBuilder<'a> {
    /// An empty chart round the unit vector `axis`.
    pub fn new(geometry: &'a Geometry, axis: DVec3) -> ChartBuilder<'a> {
        ChartBuilder {
            geometry,
            axis,
            frame: Frame::across(axis),
            cos_cone: CONE_DEGREES.to_radians().cos(),
            cos_sliver_cone: SLIVER_CONE_DEGREES.to_radians().cos(),
            grid: TriangleGrid::new(geometry.grid_cell()),
            placed: Vec::new(),
            triangles: Vec::new(),
        }
    }

    /// An empty chart round the mean normal of `triangles` (weighted by area), or
    /// `None` when they have no mean direction.
    pub fn round_mean_of(geometry: &'a Geometry, triangles: &[u32]) -> Option<ChartBuilder<'a>> {
        let axis = (triangles.iter())
            .map(|&t| geometry.normals[t as usize] * geometry.double_areas[t as usize])
            .sum::<DVec3>()
            .try_normalize()?;
        Some(ChartBuilder::new(geometry, axis))
    }

    /// The mesh the chart is cut from.
    pub fn geometry(&self) -> &'a Geometry {
        self.geometry
    }

    /// An empty chart round (nearly) the axis of the narrowest cone holding the normals
    /// of `triangles` (slivers aside), found from their mean normal by Bădoiu and
    /// Clarkson's iteration (each step moves towards the farthest normal) over the
    /// corners of their convex hull seen from the mean (the only normals that can be
    /// farthest), or `None` when they have no mean direction or some face away from it.
    pub fn round_narrowest_cone_of(
        geometry: &'a Geometry,
        triangles: &[u32],
    ) -> Option<ChartBuilder<'a>> {
        let mean = ChartBuilder::round_mean_of(geometry, triangles)?;
        let frame = Frame::across(mean.axis);
        let mut corners = Vec::with_capacity(triangles.len());
        for &t in triangles.iter().filter(|&&t| !geometry.is_sliver(t)) {
            let normal = geometry.normals[t as usize];
            let height = normal.dot(mean.axis);
            if height < FACING_MEAN {
                return None;
            }
            // Central projection onto the plane touching the unit sphere at the mean keeps
            // great circles straight, so hulls there are hulls on the sphere.
            corners.push(frame.project(normal) / height);
        }
        let normals: Vec<DVec3> = (super::pack::convex_hull(&corners).into_iter())
            .map(|p| (mean.axis + frame.across * p.x + frame.up * p.y).normalize())
            .collect();
        let farthest = |axis: DVec3| {
            (normals.iter().copied())
                .min_by(|a, b| a.dot(axis).total_cmp(&b.dot(axis)))
                .unwrap_or(axis)
        };
        let (mut axis, mut best) = (mean.axis, mean.axis);
        let mut best_cos = farthest(best).dot(best);
        for step in 1..=CONE_STEPS {
            let far = farthest(axis);
            if far.dot(axis) > best_cos {
                (best, best_cos) = (axis, far.dot(axis));
            }
            axis = (axis + (far - axis) / (step as f64 + 1.0)).normalize_or(axis);
        }
        if farthest(axis).dot(axis) > best_cos {
            best = axis;
        }
        Some(ChartBuilder::new(geometry, best))
    }

    /// How far triangle `t` faces from the axis: 0 along it, 2 against it.
    pub fn deviation(&self, t: u32) -> f64 {
        // `+ 0.0` turns -0 into 0, so that the bits of deviations order like them.
        (1.0 - self.geometry.normals[t as usize].dot(self.axis)).max(0.0) + 0.0
    }

    /// Whether triangle `t` faces within the cone round the axis (the wider sliver cone
    /// for a sliver).
    pub fn faces(&self, t: u32) -> bool {
        let cos_cone = if self.geometry.is_sliver(t) {
            self.cos_sliver_cone
        } else {
            self.cos_cone
        };
        self.geometry.normals[t as usize].dot(self.axis) >= cos_cone
    }

    /// Adds triangle `t` if it faces within the cone and its projection overlaps none
    /// of the chart's; says whether it did.
    pub fn try_add(&mut self, t: u32) -> bool {
        let Some(corners) = self.laid_down(t) else {
            return false;
        };
        self.insert(t, corners);
        true
    }

    /// Adds all of `triangles` if every one faces within the cone and overlaps none of
    /// the chart's or of the others' (the chart is left as it was when not); says
    /// whether it did.
    pub fn try_add_all(&mut self, triangles: &[u32]) -> bool {
        let mut batch = ChartBuilder::new(self.geometry, self.axis);
        for &t in triangles {
            if self.laid_down(t).is_none() || !batch.try_add(t) {
                return false;
            }
        }
        for (t, corners) in batch.triangles.into_iter().zip(batch.placed) {
            self.insert(t, corners);
        }
        true
    }

    /// Where triangle `t` lies in the chart's plane, if it faces within the cone and
    /// overlaps none of the chart's triangles there.
    fn laid_down(&self, t: u32) -> Option<[DVec2; 3]> {
        if !self.faces(t) {
            return None;
        }
        let geometry = self.geometry;
        let corners = (geometry.triangles[t as usize])
            .map(|v| self.frame.project(geometry.positions[v as usize]));
        let touch = geometry.touch_distance();
        let overlaps = (self.grid.near(&corners))
            .any(|other| interiors_overlap(&self.placed[other as usize], &corners, touch));
        (!overlaps).then_some(corners)
    }

    /// Takes triangle `t`, lying at `corners`.
    fn insert(&mut self, t: u32, corners: [DVec2; 3]) {
        self.grid.insert(self.placed.len() as u32, &corners);
        self.placed.push(corners);
        self.triangles.push(t);
    }

    /// The triangles taken so far.
    pub fn triangles(&self) -> &[u32] {
        &self.triangles
    }

    /// Twice the area of the triangles taken so far.
    pub fn double_area(&self) -> f64 {
        (self.triangles.iter())
            .map(|&t| self.geometry.double_areas[t as usize])
            .sum()
    }

    /// Drops the triangles `keep` refuses from the chart (they still count against
    /// overlaps, so what the chart takes from then on stays clear of them).
    pub fn retain(&mut self, keep: impl Fn(u32) -> bool) {
        self.triangles.retain(|&t| keep(t));
    }

    /// The chart built.
    pub fn finish(self) -> Chart {
        Chart {
            frame: self.frame,
            triangles: self.triangles,
        }
    }
}
