//! Adaptive refinement of a mesh for displacement (the thesis's C.6.2–C.6.3, where the
//! GPU's tessellator subdivides each edge by the displacement along it): wgpu has no
//! tessellation stages, so the mesh is refined on the CPU, edge by edge, where the
//! displaced surface strays from its triangles by more than a tolerance on screen.
//!
//! Every decision belongs to an edge (never to a triangle), so the two triangles that
//! share an edge split it alike and the refined mesh has no cracks. New vertices take
//! their attributes (position, normal, texture coordinates, distance fields) by linear
//! interpolation from the edge's ends, as the thesis's evaluation shader interpolates
//! them from the patch's corners; the displacement then moves them in the vertex stage.

use super::Mesh;
use glam::Vec3;
use rayon::prelude::*;
use rustc_hash::{FxHashMap, FxHashSet};

/// A point of the surface as the material sees it: the interpolated vertex attributes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    pub position: [f32; 3],
    /// Unit normal.
    pub normal: [f32; 3],
    pub uv: [f32; 2],
    pub fields: [f32; 4],
}

/// How far to refine.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Refinement {
    /// The largest distance, in pixels, allowed between the displaced surface and the
    /// displaced triangles drawn for it.
    pub tolerance_px: f32,
    /// The most times an edge of the mesh is halved.
    pub max_levels: u32,
    /// Refinement stops before a level would make more triangles than this.
    pub max_triangles: usize,
}

impl Refinement {
    /// Tolerances below this many pixels are refused: each halving of the tolerance
    /// can double the triangles along every curve, for no visible change.
    pub const MIN_TOLERANCE_PX: f32 = 0.05;
    /// The deepest refinement (each level can quadruple a triangle).
    pub const MAX_LEVELS: u32 = 10;

    /// Checks the settings, saying what is wrong.
    pub fn validate(&self) -> Result<(), String> {
        if !(self.tolerance_px.is_finite() && self.tolerance_px >= Self::MIN_TOLERANCE_PX) {
            return Err(format!(
                "tessellation tolerance {} px must be at least {} px",
                self.tolerance_px,
                Self::MIN_TOLERANCE_PX
            ));
        }
        if self.max_levels > Self::MAX_LEVELS {
            return Err(format!(
                "tessellation levels {} are more than {}",
                self.max_levels,
                Self::MAX_LEVELS
            ));
        }
        Ok(())
    }
}

/// A refined mesh and what refining it did.
#[derive(Clone, Debug)]
pub struct Refined {
    pub mesh: Mesh,
    /// Levels that split at least one edge.
    pub levels: u32,
    /// Whether the triangle limit stopped refinement while edges were still too far off.
    pub limited: bool,
}

/// Where along an edge its straightness is checked (besides its ends): uneven steps
/// (symmetric about the middle), so that a wave whose period divides the edge does not
/// hide between them.
const EDGE_SAMPLES: [f32; 5] = [0.15, 0.32, 0.5, 0.68, 0.85];
/// Where inside a triangle its flatness is checked (barycentric weights): the centre and
/// half-way from it to each corner, for relief that crosses no edge.
const INTERIOR_SAMPLES: [[f32; 3]; 4] = [
    [1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0],
    [2.0 / 3.0, 1.0 / 6.0, 1.0 / 6.0],
    [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0],
    [1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0],
];

/// Refines `mesh` where its displacement needs it. `height` gives the displacement
/// along the normal in mesh units at a surface point; `pixels_per_unit` the size on
/// screen of one mesh unit at a (mesh-space) position. Fields, when the mesh has them,
/// are interpolated with the rest; the result keeps no file-vertex numbering (it is for
/// drawing, not for picking).
pub fn refine_for_displacement(
    mesh: &Mesh,
    refinement: &Refinement,
    height: &(dyn Fn(&SurfacePoint) -> f32 + Sync),
    pixels_per_unit: &(dyn Fn(Vec3) -> f32 + Sync),
) -> Refined {
    let has_fields = mesh.fields.len() == mesh.positions.len();
    let mut out = Mesh {
        positions: mesh.positions.clone(),
        normals: mesh.normals.clone(),
        uvs: mesh.uvs.clone(),
        indices: mesh.indices.clone(),
        fields: if has_fields {
            mesh.fields.clone()
        } else {
            Vec::new()
        },
        file_vertices: None,
    };
    let point = |m: &Mesh, v: u32| SurfacePoint {
        position: m.positions[v as usize],
        normal: m.normals[v as usize],
        uv: m.uvs[v as usize],
        fields: if has_fields {
            m.fields[v as usize]
        } else {
            [0.0; 4]
        },
    };
    let mut heights: Vec<f32> = (0..out.positions.len() as u32)
        .into_par_iter()
        .map(|v| height(&point(&out, v)))
        .collect();
    // Vertices and their heights never change, so an edge found straight and a triangle
    // found flat stay so: each is judged once, not again at every level.
    let mut straight: FxHashSet<(u32, u32)> = FxHashSet::default();
    let mut flat: FxHashSet<[u32; 3]> = FxHashSet::default();
    let mut levels = 0;
    let mut limited = false;
    for _ in 0..refinement.max_levels {
        let edges = unique_edges(&out.indices);
        // Triangles whose inside strays: all their edges are halved.
        let judged: Vec<([u32; 3], bool)> = out
            .indices
            .par_chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .filter(|t| !flat.contains(t))
            .map(|t| {
                let corners = t.map(|v| point(&out, v));
                let corner_heights = t.map(|v| heights[v as usize]);
                let strays = strays_inside(
                    corners,
                    corner_heights,
                    refinement.tolerance_px,
                    height,
                    pixels_per_unit,
                );
                (t, strays)
            })
            .collect();
        let mut bulging: FxHashSet<(u32, u32)> = FxHashSet::default();
        for (t, strays) in judged {
            if strays {
                bulging.extend((0..3).map(|k| edge_key(t[k], t[(k + 1) % 3])));
            } else {
                flat.insert(t);
            }
        }
        // Each edge's verdict and, when split, its midpoint and the midpoint's height.
        let verdicts: Vec<Option<(SurfacePoint, f32)>> = edges
            .par_iter()
            .map(|&(a, b)| {
                let ends = [point(&out, a), point(&out, b)];
                let verdict = if straight.contains(&(a, b)) {
                    None
                } else {
                    let end_heights = [heights[a as usize], heights[b as usize]];
                    split_edge(
                        ends,
                        end_heights,
                        refinement.tolerance_px,
                        height,
                        pixels_per_unit,
                    )
                };
                verdict.or_else(|| {
                    bulging.contains(&(a, b)).then(|| {
                        let mid = interpolate(ends, 0.5);
                        (mid, height(&mid))
                    })
                })
            })
            .collect();
        let splits = verdicts.iter().filter(|v| v.is_some()).count();
        if splits == 0 {
            break;
        }
        // A split edge adds at most two triangles on each side.
        if out.triangle_count() + 2 * splits > refinement.max_triangles {
            limited = true;
            break;
        }
        let mut midpoints: FxHashMap<(u32, u32), u32> = FxHashMap::default();
        for (&edge, verdict) in edges.iter().zip(verdicts) {
            match verdict {
                Some((mid, mid_height)) => {
                    let index = out.push_vertex(mid.position, mid.normal, mid.uv);
                    if has_fields {
                        out.fields.push(mid.fields);
                    }
                    heights.push(mid_height);
                    midpoints.insert(edge, index);
                }
                None => {
                    straight.insert(edge);
                }
            }
        }
        out.indices = split_triangles(&out, &midpoints);
        levels += 1;
    }
    Refined {
        mesh: out,
        levels,
        limited,
    }
}

/// The edges of `indices`' triangles, each once as (smaller index, larger), in the order
/// the triangles first use them (so the refined mesh is the same on every run).
fn unique_edges(indices: &[u32]) -> Vec<(u32, u32)> {
    let mut seen: FxHashSet<(u32, u32)> = FxHashSet::default();
    let mut edges = Vec::with_capacity(indices.len() / 2);
    for t in indices.chunks_exact(3) {
        for k in 0..3 {
            let edge = edge_key(t[k], t[(k + 1) % 3]);
            if seen.insert(edge) {
                edges.push(edge);
            }
        }
    }
    edges
}

fn edge_key(a: u32, b: u32) -> (u32, u32) {
    (a.min(b), a.max(b))
}

/// The point a fraction `t` of the way from `ends[0]` to `ends[1]` (normal renormalised).
/// At `t = 0.5` the result does not depend on the order of the ends, so an edge split
/// from either side lands on the same point.
fn interpolate(ends: [SurfacePoint; 2], t: f32) -> SurfacePoint {
    let [a, b] = ends;
    let mix = |x: f32, y: f32| {
        if t == 0.5 {
            (x + y) * 0.5
        } else {
            x + (y - x) * t
        }
    };
    let normal = Vec3::from([0, 1, 2].map(|k| mix(a.normal[k], b.normal[k])));
    SurfacePoint {
        position: [0, 1, 2].map(|k| mix(a.position[k], b.position[k])),
        normal: normal.normalize_or(Vec3::from(a.normal)).to_array(),
        uv: [0, 1].map(|k| mix(a.uv[k], b.uv[k])),
        fields: [0, 1, 2, 3].map(|k| mix(a.fields[k], b.fields[k])),
    }
}

/// Whether an edge must be halved: the displaced surface along it, sampled at
/// [`EDGE_SAMPLES`], strays from the straight displaced edge by more than `tolerance_px`
/// on screen. Returns the midpoint and its height when it must.
fn split_edge(
    ends: [SurfacePoint; 2],
    end_heights: [f32; 2],
    tolerance_px: f32,
    height: &(dyn Fn(&SurfacePoint) -> f32 + Sync),
    pixels_per_unit: &(dyn Fn(Vec3) -> f32 + Sync),
) -> Option<(SurfacePoint, f32)> {
    let chord = [
        displace(&ends[0], end_heights[0]),
        displace(&ends[1], end_heights[1]),
    ];
    let mid = interpolate(ends, 0.5);
    let scale = pixels_per_unit(Vec3::from(mid.position));
    let mut mid_height = 0.0;
    let mut worst = 0.0f32;
    for t in EDGE_SAMPLES {
        let p = interpolate(ends, t);
        let h = height(&p);
        if t == 0.5 {
            mid_height = h;
        }
        let off = (displace(&p, h) - chord[0].lerp(chord[1], t)).length();
        // A non-finite height never refines (the material's own problem, linted).
        if off.is_finite() {
            worst = worst.max(off);
        }
    }
    (worst * scale > tolerance_px).then_some((mid, mid_height))
}

/// Whether the displaced surface inside a triangle, sampled at [`INTERIOR_SAMPLES`],
/// strays from the displaced triangle by more than `tolerance_px` on screen.
fn strays_inside(
    corners: [SurfacePoint; 3],
    corner_heights: [f32; 3],
    tolerance_px: f32,
    height: &(dyn Fn(&SurfacePoint) -> f32 + Sync),
    pixels_per_unit: &(dyn Fn(Vec3) -> f32 + Sync),
) -> bool {
    let displaced = [0, 1, 2].map(|k| displace(&corners[k], corner_heights[k]));
    let centre = barycentric(corners, INTERIOR_SAMPLES[0]);
    let scale = pixels_per_unit(Vec3::from(centre.position));
    INTERIOR_SAMPLES.iter().any(|&weights| {
        let p = barycentric(corners, weights);
        let flat = (0..3).fold(Vec3::ZERO, |sum, k| sum + displaced[k] * weights[k]);
        let off = (displace(&p, height(&p)) - flat).length();
        off.is_finite() && off * scale > tolerance_px
    })
}

/// The point of a triangle with barycentric `weights` (normal renormalised).
fn barycentric(corners: [SurfacePoint; 3], weights: [f32; 3]) -> SurfacePoint {
    let sum = |read: &dyn Fn(&SurfacePoint, usize) -> f32, i: usize| {
        (0..3)
            .map(|k| read(&corners[k], i) * weights[k])
            .sum::<f32>()
    };
    let normal = Vec3::from([0, 1, 2].map(|i| sum(&|p, i| p.normal[i], i)));
    SurfacePoint {
        position: [0, 1, 2].map(|i| sum(&|p, i| p.position[i], i)),
        normal: normal
            .normalize_or(Vec3::from(corners[0].normal))
            .to_array(),
        uv: [0, 1].map(|i| sum(&|p, i| p.uv[i], i)),
        fields: [0, 1, 2, 3].map(|i| sum(&|p, i| p.fields[i], i)),
    }
}

/// A surface point moved along its normal by `height`.
fn displace(point: &SurfacePoint, height: f32) -> Vec3 {
    Vec3::from(point.position) + Vec3::from(point.normal) * height
}

/// The triangles of `mesh` with every edge in `midpoints` halved: a triangle with one
/// halved edge becomes two, with two three (the quad cut along its shorter diagonal),
/// with three four; winding is kept.
fn split_triangles(mesh: &Mesh, midpoints: &FxHashMap<(u32, u32), u32>) -> Vec<u32> {
    let mut indices = Vec::with_capacity(mesh.indices.len() * 2);
    let length = |a: u32, b: u32| {
        Vec3::from(mesh.positions[a as usize]).distance(Vec3::from(mesh.positions[b as usize]))
    };
    for t in mesh.indices.chunks_exact(3) {
        let corners = [t[0], t[1], t[2]];
        // mids[k]: the midpoint of the edge from corner k to corner k + 1.
        let mids = [0, 1, 2].map(|k| {
            midpoints
                .get(&edge_key(corners[k], corners[(k + 1) % 3]))
                .copied()
        });
        match mids.iter().filter(|m| m.is_some()).count() {
            0 => indices.extend_from_slice(&corners),
            3 => {
                let [m0, m1, m2] = mids.map(Option::unwrap);
                let [v0, v1, v2] = corners;
                indices.extend_from_slice(&[v0, m0, m2, m0, v1, m1, m2, m1, v2, m0, m1, m2]);
            }
            1 => {
                // Rotate so that the halved edge runs from v0 to v1.
                let k = mids.iter().position(Option::is_some).unwrap();
                let [v0, v1, v2] = [0, 1, 2].map(|j| corners[(k + j) % 3]);
                let m = mids[k].unwrap();
                indices.extend_from_slice(&[v0, m, v2, m, v1, v2]);
            }
            _ => {
                // Rotate so that the whole edge runs from v2 to v0 and the halved ones
                // from v0 to v1 (m0) and from v1 to v2 (m1).
                let k = (mids.iter().position(Option::is_none).unwrap() + 1) % 3;
                let [v0, v1, v2] = [0, 1, 2].map(|j| corners[(k + j) % 3]);
                let (m0, m1) = (mids[k].unwrap(), mids[(k + 1) % 3].unwrap());
                indices.extend_from_slice(&[m0, v1, m1]);
                if length(v0, m1) <= length(m0, v2) {
                    indices.extend_from_slice(&[v0, m0, m1, v0, m1, v2]);
                } else {
                    indices.extend_from_slice(&[v0, m0, v2, m0, m1, v2]);
                }
            }
        }
    }
    indices
}

#[cfg(test)]
mod tests {
    use super::*;

    fn refinement(tolerance_px: f32) -> Refinement {
        Refinement {
            tolerance_px,
            max_levels: 8,
            max_triangles: 1_000_000,
        }
    }

    /// A unit square of two triangles in the xz plane, normals up.
    fn square() -> Mesh {
        let mut mesh = Mesh::from_triangles(
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 0.0, 1.0],
                [0.0, 0.0, 1.0],
            ],
            vec![0, 2, 1, 0, 3, 2],
        );
        mesh.normals = vec![[0.0, 1.0, 0.0]; 4];
        mesh
    }

    /// Every edge used by exactly one triangle (the boundary), each as (from, to).
    fn boundary(mesh: &Mesh) -> Vec<(u32, u32)> {
        let mut count: FxHashMap<(u32, u32), u32> = FxHashMap::default();
        for t in mesh.indices.chunks_exact(3) {
            for k in 0..3 {
                *count.entry(edge_key(t[k], t[(k + 1) % 3])).or_default() += 1;
            }
        }
        let mut edges: Vec<_> = count
            .into_iter()
            .filter(|&(_, n)| n == 1)
            .map(|(e, _)| e)
            .collect();
        edges.sort();
        edges
    }

    #[test]
    fn a_flat_displacement_leaves_the_mesh_alone() {
        let mesh = square();
        let refined = refine_for_displacement(&mesh, &refinement(0.5), &|_| 0.3, &|_| 1000.0);
        assert_eq!(refined.levels, 0);
        assert_eq!(refined.mesh.indices, mesh.indices);
    }

    #[test]
    fn a_bump_refines_around_it_and_nowhere_else() {
        let mesh = square();
        // A narrow bump at (0.25, 0.25), 0.05 high.
        let bump = |p: &SurfacePoint| {
            let (dx, dz) = (p.position[0] - 0.25, p.position[2] - 0.25);
            0.05 * (-(dx * dx + dz * dz) / 0.01).exp()
        };
        let refined = refine_for_displacement(&mesh, &refinement(0.5), &bump, &|_| 500.0);
        assert!(refined.levels >= 4, "{} levels", refined.levels);
        let small = |far: bool| {
            refined
                .mesh
                .indices
                .chunks_exact(3)
                .filter(|t| {
                    let c = t.iter().fold(Vec3::ZERO, |s, &v| {
                        s + Vec3::from(refined.mesh.positions[v as usize])
                    }) / 3.0;
                    (c.distance(Vec3::new(0.25, 0.0, 0.25)) > 0.5) == far
                })
                .count()
        };
        // Most triangles near the bump; the far corner keeps big triangles.
        assert!(
            small(false) > 10 * small(true),
            "{} near, {} far",
            small(false),
            small(true)
        );
        // The displaced surface is within tolerance along every edge left.
        for t in refined.mesh.indices.chunks_exact(3) {
            for k in 0..3 {
                let ends = [t[k], t[(k + 1) % 3]].map(|v| SurfacePoint {
                    position: refined.mesh.positions[v as usize],
                    normal: refined.mesh.normals[v as usize],
                    uv: [0.0; 2],
                    fields: [0.0; 4],
                });
                let heights = ends.map(|p| bump(&p));
                assert!(split_edge(ends, heights, 0.5, &bump, &|_| 500.0).is_none());
            }
        }
    }

    #[test]
    fn refined_meshes_have_no_cracks_and_keep_their_winding() {
        let mesh = square();
        let ripple = |p: &SurfacePoint| 0.01 * (p.position[0] * 40.0).sin() * p.position[2];
        let refined = refine_for_displacement(&mesh, &refinement(0.25), &ripple, &|_| 800.0);
        assert!(refined.levels > 2);
        // No T-junctions: the only edges used once are the square's outline, and no
        // vertex lies inside an edge it is not an end of (checked through the outline's
        // length, which T-junctions inside would not change, and through area below).
        let outline: f32 = boundary(&refined.mesh)
            .iter()
            .map(|&(a, b)| {
                Vec3::from(refined.mesh.positions[a as usize])
                    .distance(Vec3::from(refined.mesh.positions[b as usize]))
            })
            .sum();
        assert!((outline - 4.0).abs() < 1e-4, "outline {outline}");
        let mut area = 0.0;
        for t in refined.mesh.indices.chunks_exact(3) {
            let [a, b, c] = [0, 1, 2].map(|k| Vec3::from(refined.mesh.positions[t[k] as usize]));
            let n = (b - a).cross(c - a);
            assert!(n.y > 0.0, "winding flipped");
            area += n.length() * 0.5;
        }
        assert!((area - 1.0).abs() < 1e-4, "area {area}");
        // Every interior edge is shared by exactly two triangles (a crack would leave an
        // edge used once inside the square).
        for (a, b) in boundary(&refined.mesh) {
            let [p, q] = [a, b].map(|v| refined.mesh.positions[v as usize]);
            let on_outline =
                |k: usize| (p[k] == 0.0 && q[k] == 0.0) || (p[k] == 1.0 && q[k] == 1.0);
            assert!(
                on_outline(0) || on_outline(2),
                "inner edge used once: {p:?} {q:?}"
            );
        }
    }

    #[test]
    fn the_triangle_limit_stops_refinement() {
        let mesh = square();
        let noise = |p: &SurfacePoint| 0.05 * (p.position[0] * 300.0).sin();
        let limit = Refinement {
            max_triangles: 100,
            ..refinement(0.1)
        };
        let refined = refine_for_displacement(&mesh, &limit, &noise, &|_| 1000.0);
        assert!(refined.limited);
        assert!(refined.mesh.triangle_count() <= 100);
    }

    #[test]
    fn fields_and_uvs_are_interpolated() {
        let mut mesh = square();
        mesh.uvs = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        mesh.fields = vec![
            [0.0; 4],
            [1.0, 0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0, 0.0],
        ];
        let slope = |p: &SurfacePoint| 0.02 * (p.position[0] * 20.0).sin();
        let refined = refine_for_displacement(&mesh, &refinement(0.5), &slope, &|_| 500.0);
        assert!(refined.levels > 0);
        let m = &refined.mesh;
        assert_eq!(m.fields.len(), m.positions.len());
        for v in 0..m.positions.len() {
            let [x, _, z] = m.positions[v];
            assert!((m.uvs[v][0] - x).abs() < 1e-5 && (m.uvs[v][1] - z).abs() < 1e-5);
            assert!((m.fields[v][0] - (x + z)).abs() < 1e-5);
        }
    }

    #[test]
    fn refusing_bad_settings() {
        assert!(refinement(0.0).validate().is_err());
        assert!(refinement(f32::NAN).validate().is_err());
        assert!(
            Refinement {
                max_levels: 11,
                ..refinement(1.0)
            }
            .validate()
            .is_err()
        );
        assert!(refinement(0.5).validate().is_ok());
    }
}
