//! What the atlas needs to know about a mesh's triangles: their unit normals and areas,
//! which are degenerate or slivers, and which share an edge that is no crease (by
//! position, so that vertices a loader split at a normal seam still join their
//! triangles).

use super::super::Mesh;
use glam::DVec3;

/// Twice a triangle's area below this fraction of the squared size of the mesh makes it
/// degenerate: its normal means nothing, so it joins no chart.
const DEGENERATE_AREA: f64 = 1e-12;

/// A triangle smaller than this fraction of the mean triangle is a sliver: its normal
/// says little (marching tetrahedra leave many such) and its distortion shows in no
/// texel, so charts may take it facing further from their axis.
const SLIVER_AREA: f64 = 0.05;

/// Triangles (neither a sliver) whose normals are further apart than this, in degrees,
/// meet at a crease: charts grow across no crease, so that the faces of a box, say,
/// are not folded flat into one chart.
const CREASE_DEGREES: f64 = 60.0;

/// Signed distances within this fraction of the size of the mesh count as touching, not
/// overlapping, when charts are checked for overlaps.
const TOUCH_DISTANCE: f64 = 1e-9;

/// The triangles of a mesh in double precision, with their neighbours.
pub(super) struct Geometry {
    pub positions: Vec<DVec3>,
    pub triangles: Vec<[u32; 3]>,
    /// Unit normal of each triangle (zero for degenerate ones).
    pub normals: Vec<DVec3>,
    /// Twice each triangle's area (zero for degenerate ones).
    pub double_areas: Vec<f64>,
    /// Triangles with a repeated vertex, a coordinate that is not finite or no area.
    pub degenerate: Vec<bool>,
    /// The diagonal of the bounding box of the triangles' vertices.
    pub size: f64,
    /// The mean edge length of the triangles that are not degenerate.
    pub mean_edge: f64,
    /// Twice the mean area of the triangles that are not degenerate.
    pub mean_double_area: f64,
    /// The triangles sharing an edge with triangle `t` are
    /// `neighbour_list[neighbour_start[t]..neighbour_start[t + 1]]`.
    neighbour_start: Vec<usize>,
    neighbour_list: Vec<u32>,
}

impl Geometry {
    pub fn new(mesh: &Mesh) -> Geometry {
        let positions: Vec<DVec3> = (mesh.positions.iter())
            .map(|p| DVec3::from(p.map(f64::from)))
            .collect();
        let triangles: Vec<[u32; 3]> = (mesh.indices.chunks_exact(3))
            .map(|t| [t[0], t[1], t[2]])
            .collect();
        let corners = |t: &[u32; 3]| t.map(|v| positions[v as usize]);
        let finite = |t: &[u32; 3]| corners(t).iter().all(|p| p.is_finite());
        let (min, max) = (triangles.iter().filter(|t| finite(t)))
            .flat_map(corners)
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p), hi.max(p))
            });
        let size = if min.x <= max.x {
            (max - min).length()
        } else {
            0.0
        };
        let (mut normals, mut double_areas, mut degenerate) = (vec![], vec![], vec![]);
        let (mut edge_sum, mut edge_count) = (0.0, 0usize);
        for t in &triangles {
            let [a, b, c] = corners(t);
            let cross = (b - a).cross(c - a);
            let double_area = cross.length();
            let flat = t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || !finite(t);
            if flat || double_area.is_nan() || double_area <= DEGENERATE_AREA * size * size {
                normals.push(DVec3::ZERO);
                double_areas.push(0.0);
                degenerate.push(true);
            } else {
                normals.push(cross / double_area);
                double_areas.push(double_area);
                degenerate.push(false);
                edge_sum += (b - a).length() + (c - b).length() + (a - c).length();
                edge_count += 3;
            }
        }
        let mean_double_area = double_areas.iter().sum::<f64>() / (edge_count / 3).max(1) as f64;
        let mut geometry = Geometry {
            positions,
            triangles,
            normals,
            double_areas,
            degenerate,
            size,
            mean_edge: edge_sum / edge_count.max(1) as f64,
            mean_double_area,
            neighbour_start: Vec::new(),
            neighbour_list: Vec::new(),
        };
        (geometry.neighbour_start, geometry.neighbour_list) = neighbours(mesh, &geometry);
        geometry
    }

    /// Whether triangle `t` is a sliver.
    pub fn is_sliver(&self, t: u32) -> bool {
        self.double_areas[t as usize] < SLIVER_AREA * self.mean_double_area
    }

    /// Whether triangles `a` and `b` (sharing an edge) meet at a crease.
    fn crease(&self, a: u32, b: u32) -> bool {
        let cos = self.normals[a as usize].dot(self.normals[b as usize]);
        !self.is_sliver(a) && !self.is_sliver(b) && cos < CREASE_DEGREES.to_radians().cos()
    }

    /// The triangles sharing an edge with triangle `t` (none for a degenerate one).
    pub fn neighbours(&self, t: u32) -> &[u32] {
        let t = t as usize;
        &self.neighbour_list[self.neighbour_start[t]..self.neighbour_start[t + 1]]
    }

    /// The cell size of the grids that find overlaps in charts: about a triangle wide,
    /// but at least 1/256 of the mesh, so that no triangle covers more than 256² cells.
    pub fn grid_cell(&self) -> f64 {
        self.mean_edge.max(self.size / 256.0).max(f64::MIN_POSITIVE)
    }

    /// How far apart two triangles of a chart may be and still count as touching.
    pub fn touch_distance(&self) -> f64 {
        TOUCH_DISTANCE * self.size
    }
}

/// Neighbours of every triangle that is not degenerate through its edges that are no
/// crease, vertices taken as equal when their positions are bit for bit; all pairs at a
/// non-manifold edge.
fn neighbours(mesh: &Mesh, geometry: &Geometry) -> (Vec<usize>, Vec<u32>) {
    let (triangles, degenerate) = (&geometry.triangles, &geometry.degenerate);
    let mut first_at: std::collections::HashMap<[u32; 3], u32> = Default::default();
    // `+ 0.0` makes -0 and 0 one position.
    let canonical: Vec<u32> = (mesh.positions.iter().enumerate())
        .map(|(v, p)| {
            *first_at
                .entry(p.map(|x| (x + 0.0).to_bits()))
                .or_insert(v as u32)
        })
        .collect();
    let mut edges: Vec<(u32, u32, u32)> = Vec::with_capacity(triangles.len() * 3);
    for (t, corners) in triangles.iter().enumerate() {
        if degenerate[t] {
            continue;
        }
        for k in 0..3 {
            let (a, b) = (
                canonical[corners[k] as usize],
                canonical[corners[(k + 1) % 3] as usize],
            );
            edges.push((a.min(b), a.max(b), t as u32));
        }
    }
    edges.sort_unstable();
    let mut pairs: Vec<(u32, u32)> = Vec::with_capacity(edges.len());
    for run in edges.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
        for x in run {
            pairs.extend(
                (run.iter())
                    .filter(|y| y.2 != x.2 && !geometry.crease(x.2, y.2))
                    .map(|y| (x.2, y.2)),
            );
        }
    }
    pairs.sort_unstable();
    pairs.dedup();
    let mut start = vec![0; triangles.len() + 1];
    for &(t, _) in &pairs {
        start[t as usize + 1] += 1;
    }
    for t in 0..triangles.len() {
        start[t + 1] += start[t];
    }
    (start, pairs.into_iter().map(|(_, n)| n).collect())
}
