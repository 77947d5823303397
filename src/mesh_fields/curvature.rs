//! Discrete curvatures of a welded mesh (Meyer, Desbrun, Schröder & Barr 2003): the mean
//! curvature from the cotangent Laplacian of the positions over each vertex's mixed
//! Voronoi area, the Gaussian curvature from the angle defect over the same area, and a
//! convexity smoothed over a geodesic neighbourhood by implicit heat diffusion.

use crate::geodesic::{HeatError, NO_TWIN, Triangulation, diffuse, split};
use crate::mesh::Mesh;
use glam::DVec3;
use std::f64::consts::{PI, TAU};

/// Per-vertex curvatures of a welded mesh, in the mesh's units.
#[derive(Clone, Debug)]
pub struct Curvatures {
    /// Mean curvature (1/length), positive where the surface is convex (bulges towards
    /// its normal): `1/r` on a sphere of radius `r`. 0 on vertices with no area.
    pub mean: Vec<f64>,
    /// Gaussian curvature (1/length²): `1/r²` on a sphere, negative at saddles.
    pub gaussian: Vec<f64>,
}

impl Curvatures {
    /// The principal curvatures `(k₁, k₂)`, `k₁ ≥ k₂`, of vertex `v` from its mean and
    /// Gaussian curvature (equal where rounding makes `H² < K`).
    pub fn principal(&self, v: usize) -> (f64, f64) {
        let (h, k) = (self.mean[v], self.gaussian[v]);
        let spread = (h * h - k).max(0.0).sqrt();
        (h + spread, h - spread)
    }
}

/// The parts of the cotangent formulas at every vertex.
struct CotanParts {
    /// Σ (cot α + cot β)(xᵢ − xⱼ) over the vertex's edges.
    laplace: Vec<DVec3>,
    /// Area-weighted normal (unnormalised).
    normal: Vec<DVec3>,
    /// Mixed Voronoi area.
    area: Vec<f64>,
    /// Sum of the corner angles.
    angles: Vec<f64>,
    /// Whether a triangle at the vertex has an angle outside [`TRUSTED_ANGLES`], where
    /// the cotangent formula breaks down.
    poorly_shaped: Vec<bool>,
}

/// The corner angles (radians, 5° to 110°) of the triangles the cotangent formula
/// trusts: past them the cotangent of a nearly flat or nearly closed corner, times the
/// edge across it, throws the mean curvature off by orders of magnitude.
const TRUSTED_ANGLES: std::ops::RangeInclusive<f64> = (5.0 * PI / 180.0)..=(110.0 * PI / 180.0);

/// [`CotanParts`] of every vertex of `mesh` (Meyer et al. 2003).
fn cotan_parts(mesh: &Mesh) -> CotanParts {
    let n = mesh.positions.len();
    let position = |i: u32| DVec3::from(mesh.positions[i as usize].map(f64::from));
    let mut parts = CotanParts {
        laplace: vec![DVec3::ZERO; n],
        normal: vec![DVec3::ZERO; n],
        area: vec![0.0; n],
        angles: vec![0.0; n],
        poorly_shaped: vec![false; n],
    };
    for triangle in mesh.indices.chunks_exact(3) {
        let corners = [0, 1, 2].map(|k| position(triangle[k]));
        let doubled = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
        let twice_area = doubled.length();
        if twice_area <= 0.0 || !twice_area.is_finite() {
            continue;
        }
        // Angle and cotangent at each corner, from the two edges leaving it.
        let mut angle = [0.0; 3];
        let mut cotan = [0.0; 3];
        for k in 0..3 {
            let (a, b) = (
                corners[(k + 1) % 3] - corners[k],
                corners[(k + 2) % 3] - corners[k],
            );
            let (cos, sin) = (a.dot(b), a.cross(b).length());
            angle[k] = sin.atan2(cos);
            cotan[k] = cos / sin;
        }
        let obtuse = (0..3).find(|&k| angle[k] > PI / 2.0);
        let poor = angle.iter().any(|a| !TRUSTED_ANGLES.contains(a));
        for k in 0..3 {
            let (i, j, l) = (k, (k + 1) % 3, (k + 2) % 3);
            let v = triangle[i] as usize;
            let (to_j, to_l) = (corners[i] - corners[j], corners[i] - corners[l]);
            // Edge (i, j) is across corner l; edge (i, l) across corner j.
            parts.laplace[v] += cotan[l] * to_j + cotan[j] * to_l;
            parts.normal[v] += doubled;
            parts.angles[v] += angle[i];
            parts.poorly_shaped[v] |= poor;
            parts.area[v] += match obtuse {
                None => (to_j.length_squared() * cotan[l] + to_l.length_squared() * cotan[j]) / 8.0,
                Some(o) if o == i => twice_area / 4.0,
                Some(_) => twice_area / 8.0,
            };
        }
    }
    parts
}

/// The curvatures of every vertex of `mesh` (welded: its triangles share vertices).
/// Triangles with no area add nothing. On a boundary the discrete curvatures measure the
/// boundary's turn rather than the surface's bend, so there the mean curvature is taken
/// along the normal only and the Gaussian curvature is 0: a flat sheet reads 0 to its
/// edges and corners. Accurate on good triangles (within 1% on a sphere); a scan's or a
/// marching-cubes mesh's slivers make these pointwise values noisy, which is why
/// [`convexity`] smooths a sturdier measure instead.
pub fn curvatures(mesh: &Mesh) -> Curvatures {
    let boundary = Triangulation::from_mesh(mesh).boundary_vertices();
    curvatures_from(&cotan_parts(mesh), &boundary)
}

/// [`curvatures`] from the cotangent formulas' parts and the boundary vertices.
fn curvatures_from(parts: &CotanParts, boundary: &[bool]) -> Curvatures {
    let n = parts.area.len();
    let mut mean = vec![0.0; n];
    let mut gaussian = vec![0.0; n];
    for v in 0..n {
        let area = parts.area[v];
        if area <= 0.0 || area.is_nan() {
            continue;
        }
        let unit = parts.normal[v].normalize_or_zero();
        mean[v] = finite_or_zero(0.25 * parts.laplace[v].dot(unit) / area);
        if !boundary[v] {
            gaussian[v] = finite_or_zero((TAU - parts.angles[v]) / area);
        }
    }
    Curvatures { mean, gaussian }
}

/// An edge shared by two triangles, and how they fold across it.
pub(super) struct Fold {
    pub tail: u32,
    pub head: u32,
    pub length: f64,
    /// The angle the second triangle's normal turns from the first's about the edge,
    /// positive where they fold away from their normals (a convex edge); 0 where either
    /// triangle has no area.
    pub turn: f64,
}

/// Every edge of `triangulation` (made from `mesh`) shared by exactly two consistently
/// oriented triangles, each once, with its fold.
pub(super) fn folds<'a>(
    mesh: &'a Mesh,
    triangulation: &'a Triangulation,
) -> impl Iterator<Item = Fold> + 'a {
    let position = |i: u32| DVec3::from(mesh.positions[i as usize].map(f64::from));
    let normal = move |f: usize| {
        let [a, b, c] = triangulation.faces[f].map(position);
        (b - a).cross(c - a).normalize_or_zero()
    };
    (triangulation.twins.iter().enumerate())
        .filter(|&(h, &twin)| twin != NO_TWIN && (twin as usize) > h)
        .map(move |(h, &twin)| {
            let (f, k) = split(h as u32);
            let (tail, head) = (
                triangulation.faces[f][k],
                triangulation.faces[f][(k + 1) % 3],
            );
            let edge = position(head) - position(tail);
            let (first, second) = (normal(f), normal(split(twin).0));
            let turn = first
                .cross(second)
                .dot(edge.normalize_or_zero())
                .atan2(first.dot(second));
            Fold {
                tail,
                head,
                length: edge.length(),
                turn: finite_or_zero(turn),
            }
        })
}

/// The mean curvature of each vertex in the form smoothing wants it: a density (the
/// cotangent formula's, [`curvatures`]) where the triangles at the vertex are well
/// shaped, else an amount integrated over the vertex's share of the surface from the
/// dihedral angles of its edges (a quarter of each edge's length times the angle its two
/// triangles turn by, [`Fold::turn`]). The dihedral measure depends on lengths and
/// angles only, each bounded, so slivers and needles cannot blow it up as they do the
/// cotangent formula, nor does it divide by their tiny areas. Boundary and non-manifold
/// edges add nothing to it.
pub fn sturdy_mean_curvature(mesh: &Mesh) -> Vec<MeanCurvature> {
    let parts = cotan_parts(mesh);
    let triangulation = Triangulation::from_mesh(mesh);
    let mean = curvatures_from(&parts, &triangulation.boundary_vertices()).mean;
    let poor = |v: u32| parts.poorly_shaped[v as usize];
    let mut dihedral = vec![0.0; mesh.positions.len()];
    for fold in folds(mesh, &triangulation).filter(|fold| poor(fold.tail) || poor(fold.head)) {
        let share = finite_or_zero(0.25 * fold.length * fold.turn);
        dihedral[fold.tail as usize] += share;
        dihedral[fold.head as usize] += share;
    }
    (0..mesh.positions.len())
        .map(|v| match parts.poorly_shaped[v] {
            true => MeanCurvature::Integrated(dihedral[v]),
            false => MeanCurvature::Density(mean[v]),
        })
        .collect()
}

/// A vertex's mean curvature as [`sturdy_mean_curvature`] gives it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MeanCurvature {
    /// Per unit area.
    Density(f64),
    /// Over the vertex's share of the surface.
    Integrated(f64),
}

impl MeanCurvature {
    /// The amount at a vertex whose share of the surface is `area`.
    fn amount(self, area: f64) -> f64 {
        match self {
            MeanCurvature::Density(density) => density * area,
            MeanCurvature::Integrated(amount) => amount,
        }
    }
}

/// `value`, or 0 when it is not finite.
fn finite_or_zero(value: f64) -> f64 {
    if value.is_finite() { value } else { 0.0 }
}

/// How convex the surface is around each vertex at the scale `radius` (mesh units):
/// the mean curvature ([`sturdy_mean_curvature`]) smoothed
/// by a Gaussian of the geodesic distance whose standard deviation is half the radius
/// (heat diffusion for time `radius²/8` over the intrinsic Delaunay triangulation, so
/// poor triangles cannot make it unstable), times the radius, clamped to [−1, 1]. Surfaces bent more tightly than the radius read ±1 (convex
/// edges +1, creases −1); a sphere of radius `R` reads `radius / R`; a radius of 0 reads
/// 0 everywhere.
pub fn convexity(mesh: &Mesh, radius: f64) -> Result<Vec<f64>, HeatError> {
    if !(radius > 0.0) {
        return Ok(vec![0.0; mesh.positions.len()]);
    }
    let mut triangulation = Triangulation::from_mesh(mesh);
    triangulation.mollify(1.0e-5);
    triangulation.flip_to_delaunay();
    let mean = sturdy_mean_curvature(mesh);
    let smoothed = diffuse(&triangulation, radius * radius / 8.0, |v, area| {
        mean[v].amount(area)
    })?;
    Ok(smoothed
        .iter()
        .map(|&h| finite_or_zero(h * radius).clamp(-1.0, 1.0))
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geodesic::welded_for_distances;
    use crate::mesh::primitive;

    #[test]
    fn a_spheres_mean_curvature_is_one_over_its_radius_at_every_vertex() {
        let (mut sphere, _) = welded_for_distances(&primitive("sphere:64").unwrap());
        let radius = 2.5f32;
        for p in &mut sphere.positions {
            *p = p.map(|c| c * radius);
        }
        let curvatures = curvatures(&sphere);
        let expected = 1.0 / f64::from(radius);
        for (v, &h) in curvatures.mean.iter().enumerate() {
            assert!(
                (h - expected).abs() <= 0.01 * expected,
                "vertex {v}: {h} against {expected}"
            );
        }
        let total: f64 = curvatures.gaussian.iter().sum();
        assert!(total > 0.0);
    }

    #[test]
    fn a_torus_principal_curvatures_are_the_analytic_ones() {
        let (torus, _) = welded_for_distances(&crate::mesh::torus(0.7, 0.3, 256, 128));
        let curvatures = curvatures(&torus);
        let mut worst: f64 = 0.0;
        for (v, p) in torus.positions.iter().enumerate() {
            let [x, y, z] = p.map(f64::from);
            // Distance from the axis, and the cosine of the angle round the tube.
            let from_axis = (x * x + z * z).sqrt();
            let cos = (from_axis - 0.7) / 0.3;
            let (tube, around) = (1.0 / 0.3, cos / (0.7 + 0.3 * cos));
            let (k1, k2) = curvatures.principal(v);
            let _ = y;
            worst = worst
                .max((k1 - tube).abs() / tube)
                .max((k2 - around).abs() / tube.max(around.abs()));
        }
        assert!(worst <= 0.02, "worst relative error {worst}");
    }

    #[test]
    fn a_flat_sheet_has_no_curvature_up_to_its_edges() {
        let plane = primitive("plane").unwrap();
        let (plane, _) = welded_for_distances(&plane);
        let curvatures = curvatures(&plane);
        assert!(curvatures.mean.iter().all(|h| h.abs() < 1e-9));
        assert!(curvatures.gaussian.iter().all(|k| k.abs() < 1e-6));
    }

    #[test]
    fn convexity_reads_the_radius_over_the_spheres_and_saturates_on_edges() {
        let (sphere, _) = welded_for_distances(&primitive("sphere:32").unwrap());
        let convex = convexity(&sphere, 0.2).unwrap();
        let mean = convex.iter().sum::<f64>() / convex.len() as f64;
        assert!((mean - 0.2).abs() < 0.002, "mean {mean}");

        let worst = convex.iter().map(|c| (c - 0.2).abs()).fold(0.0, f64::max);
        assert!(worst < 0.01, "worst {worst}");
        let (cube, _) = welded_for_distances(&primitive("cube").unwrap());
        let convex = convexity(&cube, 0.3).unwrap();
        let corner = cube
            .positions
            .iter()
            .position(|p| p.iter().all(|c| c.abs() > 0.69))
            .unwrap();
        assert!(convex[corner] > 0.5, "corner {}", convex[corner]);
        assert!(convex.iter().all(|c| *c >= -1e-9 && c.is_finite()));
    }
}
