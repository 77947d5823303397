//! Distance to a mesh's features — its sharp edges, its UV seams, its boundary — along
//! the surface (the heat method, on the welded mesh, from every vertex on the feature),
//! as a share of a reach: 0 on the feature, 1 at the reach and beyond (and where no
//! feature is reachable, or the mesh has none).

use super::curvature::folds;
use crate::geodesic::{HeatError, Method, Triangulation, fields};
use crate::mesh::Mesh;

/// The turn between its two triangles' normals past which an edge is sharp (30°).
const SHARP_TURN: f64 = std::f64::consts::FRAC_PI_6;

/// UVs closer than this are the same (a seam splits a vertex into copies whose UVs
/// differ).
const SAME_UV: f32 = 1.0e-6;

/// What the distance is measured from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Feature {
    /// Edges whose two triangles turn by more than 30°.
    SharpEdge,
    /// Vertices the UV layout splits (copies with different UVs).
    Seam,
    /// Edges with one triangle (or three and more).
    Boundary,
}

/// The welded vertices on `feature`: `welded` is `mesh` welded, `of_vertex` the welded
/// vertex of each of `mesh`'s.
fn sources(mesh: &Mesh, welded: &Mesh, of_vertex: &[u32], feature: Feature) -> Vec<u32> {
    let triangulation = Triangulation::from_mesh(welded);
    let mut on = vec![false; welded.positions.len()];
    match feature {
        Feature::Boundary => on = triangulation.boundary_vertices(),
        Feature::SharpEdge => {
            for fold in folds(welded, &triangulation) {
                if fold.turn.abs() > SHARP_TURN {
                    on[fold.tail as usize] = true;
                    on[fold.head as usize] = true;
                }
            }
        }
        Feature::Seam => {
            let mut first_uv: Vec<Option<[f32; 2]>> = vec![None; welded.positions.len()];
            for (vertex, &target) in of_vertex.iter().enumerate() {
                let uv = mesh.uvs.get(vertex).copied().unwrap_or([0.0; 2]);
                match first_uv[target as usize] {
                    None => first_uv[target as usize] = Some(uv),
                    Some(seen) if (0..2).any(|k| (seen[k] - uv[k]).abs() > SAME_UV) => {
                        on[target as usize] = true;
                    }
                    Some(_) => {}
                }
            }
        }
    }
    (0..on.len() as u32).filter(|&v| on[v as usize]).collect()
}

/// The distance from every vertex of `mesh` (as loaded) to `feature`, divided by `reach`
/// (mesh units) and capped at 1.
pub fn distance_to(
    mesh: &Mesh,
    feature: Feature,
    reach: f64,
    progress: impl FnMut(usize, usize),
) -> Result<Vec<f32>, HeatError> {
    let (welded, of_vertex) = crate::geodesic::welded_for_distances(mesh);
    let sources = sources(mesh, &welded, &of_vertex, feature);
    if sources.is_empty() || reach <= 0.0 || reach.is_nan() {
        return Ok(vec![1.0; mesh.positions.len()]);
    }
    let solved = fields(
        &welded,
        &[sources],
        Method::Heat(Default::default()),
        progress,
    )?;
    let distances = &solved.fields[0];
    Ok(of_vertex
        .iter()
        .map(|&w| match distances[w as usize] {
            d if d.is_finite() => (d / reach).clamp(0.0, 1.0) as f32,
            _ => 1.0,
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::primitive;

    #[test]
    fn a_cubes_faces_grow_away_from_its_edges_and_a_plane_from_its_border() {
        let cube = primitive("cube").unwrap();
        let edges = distance_to(&cube, Feature::SharpEdge, 0.7, |_, _| {}).unwrap();
        // The cube runs from −0.7 to 0.7: a face's centre is 0.7 from its edges.
        for (v, p) in cube.positions.iter().enumerate() {
            let on_edge = p.iter().filter(|c| c.abs() > 0.699).count() >= 2;
            let centre = p.iter().filter(|c| c.abs() < 1e-6).count() == 2;
            if on_edge {
                assert!(edges[v] < 0.01, "edge vertex {v}: {}", edges[v]);
            }
            if centre {
                assert!((edges[v] - 1.0).abs() < 0.05, "centre {v}: {}", edges[v]);
            }
        }
        let plane = primitive("plane").unwrap();
        let border = distance_to(&plane, Feature::Boundary, 10.0, |_, _| {}).unwrap();
        let middle = plane
            .positions
            .iter()
            .position(|p| p[0].abs() < 1e-6 && p[2].abs() < 1e-6)
            .unwrap();
        assert!(border.iter().copied().fold(0.0, f32::max) == border[middle]);
        assert!(border.iter().any(|&d| d == 0.0));
    }

    #[test]
    fn seams_are_where_copies_of_a_vertex_disagree_on_uv_and_none_reads_one() {
        let sphere = primitive("sphere").unwrap();
        let seams = distance_to(&sphere, Feature::Seam, 0.5, |_, _| {}).unwrap();
        // The seam runs down u = 0 (x > 0, z = 0); the far side is 1 away at least.
        for (v, p) in sphere.positions.iter().enumerate() {
            if sphere.uvs[v][0] == 0.0 && sphere.uvs[v][1] > 0.1 && sphere.uvs[v][1] < 0.9 {
                assert!(seams[v] < 0.01, "{v}: {}", seams[v]);
            }
            if p[0] < -0.9 {
                assert_eq!(seams[v], 1.0);
            }
        }
        let torus = primitive("torus").unwrap();
        let welded = crate::geodesic::welded_for_distances(&torus).0;
        let none = distance_to(&welded, Feature::Seam, 0.5, |_, _| {}).unwrap();
        assert!(none.iter().all(|&d| d == 1.0));
    }
}
