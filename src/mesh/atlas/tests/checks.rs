//! Checking an atlas against its mesh, and measuring it.

use super::super::ATLAS_GAP_TEXELS;
use super::super::charts::CONE_DEGREES;
use super::super::grid::{TriangleGrid, bounds};
use crate::mesh::Mesh;
use glam::{DVec2, DVec3};

/// What an atlas measured like.
#[derive(Debug)]
pub struct Measured {
    /// Charts, counted as the triangles joined by shared texture coordinates.
    pub charts: usize,
    /// Charts of fewer than 4 triangles.
    pub tiny_charts: usize,
    /// The least distance between two charts in the unit square.
    pub narrowest_gap: f64,
    /// The area the triangles cover in the unit square.
    pub coverage: f64,
    /// UV units per mesh unit (the median of the triangles' largest stretch).
    pub scale: f64,
    /// Mean over the area of the ratio of a triangle's squeezed direction to its
    /// stretched one: 1 where its shape is kept, the share of its area kept.
    pub mean_shape: f64,
    /// Vertices after the split over vertices before.
    pub vertex_growth: f64,
}

/// Makes the atlas of `mesh` for `size`² texels, checks it, measures it and checks that
/// its charts are [`ATLAS_GAP_TEXELS`] texels apart.
pub fn checked_atlas(mesh: &Mesh, size: u32) -> Measured {
    let measured = measured_atlas(mesh, size);
    let gap = ATLAS_GAP_TEXELS / f64::from(size);
    assert!(
        measured.narrowest_gap >= gap * (1.0 - 1e-4),
        "charts {} apart, not {gap}",
        measured.narrowest_gap
    );
    measured
}

/// Makes the atlas of `mesh` for `size`² texels, checks all but the gap, and measures
/// it.
pub fn measured_atlas(mesh: &Mesh, size: u32) -> Measured {
    let atlas = mesh.with_uv_atlas(size);
    // Debug text, as NaN normals of degenerate input compare unequal to themselves.
    let again = mesh.with_uv_atlas(size);
    assert!(
        format!("{atlas:?}") == format!("{again:?}"),
        "the same mesh, another atlas"
    );
    keeps_corners(mesh, &atlas);
    let degenerate = degenerate_triangles(mesh);
    for uv in &atlas.uvs {
        assert!(uv.iter().all(|x| (0.0..=1.0).contains(x)), "{uv:?}");
    }
    let corners = uv_corners(&atlas);
    for (t, c) in corners.iter().enumerate() {
        let doubled = (c[1] - c[0]).perp_dot(c[2] - c[0]);
        let perimeter: f64 = (0..3).map(|k| (c[(k + 1) % 3] - c[k]).length()).sum();
        // Counter-clockwise seen from outside is clockwise with v up (v counts down the
        // image); f32 rounding of the coordinates may tip slivers over.
        let rounding = perimeter * 2f64.powi(-22);
        assert!(
            degenerate[t] || doubled < rounding,
            "triangle {t} mirrored or flat: {c:?}"
        );
    }
    no_overlaps(&corners, &degenerate, 2048);
    let charts = charts_by_shared_uvs(&atlas);
    let mut measured = measure(mesh, &corners, &degenerate, &charts, &atlas);
    // Looked for up to a little past the gap asked for.
    let reach = 1.01 * ATLAS_GAP_TEXELS / f64::from(size);
    measured.narrowest_gap = narrowest_gap(&atlas, &charts, reach);
    eprintln!("{measured:?}");
    measured
}

/// Every corner of every triangle keeps its position, normal, fields and file vertex.
fn keeps_corners(mesh: &Mesh, atlas: &Mesh) {
    assert_eq!(mesh.indices.len(), atlas.indices.len());
    assert_eq!(atlas.file_vertex_count(), mesh.file_vertex_count());
    assert_eq!(atlas.positions.len(), atlas.uvs.len());
    assert_eq!(atlas.positions.len(), atlas.normals.len());
    assert_eq!(
        atlas.fields.len(),
        if mesh.fields.is_empty() {
            0
        } else {
            atlas.positions.len()
        }
    );
    let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    for (&before, &after) in mesh.indices.iter().zip(&atlas.indices) {
        let (b, a) = (before as usize, after as usize);
        assert_eq!(bits(&mesh.positions[b]), bits(&atlas.positions[a]));
        assert_eq!(bits(&mesh.normals[b]), bits(&atlas.normals[a]));
        if !mesh.fields.is_empty() {
            assert_eq!(bits(&mesh.fields[b]), bits(&atlas.fields[a]));
        }
        assert_eq!(mesh.file_vertex(before), atlas.file_vertex(after));
    }
}

/// Triangles with a repeated vertex, a coordinate that is not finite or (next to)
/// no area: 2·area ≤ 10⁻¹² of the squared diagonal of the mesh's box.
fn degenerate_triangles(mesh: &Mesh) -> Vec<bool> {
    let points: Vec<DVec3> = (mesh.positions.iter())
        .map(|p| DVec3::from(p.map(f64::from)))
        .filter(|p| p.is_finite())
        .collect();
    let min = points.iter().fold(DVec3::INFINITY, |m, &p| m.min(p));
    let max = points.iter().fold(DVec3::NEG_INFINITY, |m, &p| m.max(p));
    let diagonal = (max - min).length();
    (mesh.indices.chunks_exact(3))
        .map(|t| {
            let [a, b, c] =
                [0, 1, 2].map(|k| DVec3::from(mesh.positions[t[k] as usize].map(f64::from)));
            let doubled = (b - a).cross(c - a).length();
            t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || !(doubled > 1e-12 * diagonal * diagonal)
        })
        .collect()
}

fn uv_corners(mesh: &Mesh) -> Vec<[DVec2; 3]> {
    (mesh.indices.chunks_exact(3))
        .map(|t| [0, 1, 2].map(|k| DVec2::from(mesh.uvs[t[k] as usize].map(f64::from))))
        .collect()
}

/// Samples a `samples`² grid over the unit square: no sample lies inside two triangles
/// (farther than a millionth of a texel from their edges).
fn no_overlaps(corners: &[[DVec2; 3]], degenerate: &[bool], samples: usize) {
    let mut owner = vec![u32::MAX; samples * samples];
    let margin = 1e-6 / samples as f64;
    for (t, c) in corners.iter().enumerate().filter(|(t, _)| !degenerate[*t]) {
        let (min, max) = bounds(c);
        let [i0, j0] = (min * samples as f64)
            .floor()
            .as_ivec2()
            .max(glam::IVec2::ZERO)
            .to_array();
        let [i1, j1] = (max * samples as f64)
            .ceil()
            .as_ivec2()
            .min(glam::IVec2::splat(samples as i32 - 1))
            .to_array();
        for j in j0..=j1 {
            for i in i0..=i1 {
                let p = (DVec2::new(i as f64, j as f64) + 0.5) / samples as f64;
                // Clockwise triangles: the inside is right of every edge.
                let inside = (0..3).all(|k| {
                    let edge = c[(k + 1) % 3] - c[k];
                    -edge.perp_dot(p - c[k]) > margin * edge.length()
                });
                if inside {
                    let cell = &mut owner[j as usize * samples + i as usize];
                    assert!(
                        *cell == u32::MAX,
                        "triangles {} and {t} overlap at {p}",
                        *cell
                    );
                    *cell = t as u32;
                }
            }
        }
    }
}

/// The chart of each triangle: triangles sharing a texture coordinate (bit for bit)
/// are in one chart.
fn charts_by_shared_uvs(mesh: &Mesh) -> Vec<usize> {
    let mut first_at: std::collections::HashMap<[u32; 2], u32> = Default::default();
    let points: Vec<u32> = (mesh.uvs.iter().enumerate())
        .map(|(v, uv)| *first_at.entry(uv.map(f32::to_bits)).or_insert(v as u32))
        .collect();
    let triangles =
        (mesh.indices.chunks_exact(3)).map(|t| [0, 1, 2].map(|k| points[t[k] as usize]));
    let roots = crate::mesh::vertex_components(mesh.uvs.len(), triangles);
    (mesh.indices.chunks_exact(3))
        .map(|t| roots[points[t[0] as usize] as usize])
        .collect()
}

/// The least distance between two charts, or `reach` when none are closer: between
/// their outlines, the edges that one triangle of a chart has (and those of triangles
/// with no area in the square). That overlapping charts are kept apart is for
/// [`no_overlaps`] to check.
fn narrowest_gap(mesh: &Mesh, charts: &[usize], reach: f64) -> f64 {
    let corners = uv_corners(mesh);
    let point = |v: u32| mesh.uvs[v as usize].map(f32::to_bits);
    let mut uses: std::collections::HashMap<([u32; 2], [u32; 2]), usize> = Default::default();
    for triangle in mesh.indices.chunks_exact(3) {
        for k in 0..3 {
            let (a, b) = (point(triangle[k]), point(triangle[(k + 1) % 3]));
            *uses.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    let mut outline: Vec<(DVec2, DVec2, usize)> = Vec::new();
    for (t, triangle) in mesh.indices.chunks_exact(3).enumerate() {
        let c = corners[t];
        let flat = (c[1] - c[0]).perp_dot(c[2] - c[0]) == 0.0;
        for k in 0..3 {
            let (a, b) = (point(triangle[k]), point(triangle[(k + 1) % 3]));
            if flat || uses[&(a.min(b), a.max(b))] == 1 {
                outline.push((c[k], c[(k + 1) % 3], charts[t]));
            }
        }
    }
    let mut grid = TriangleGrid::new(reach);
    for (index, &(a, b, _)) in outline.iter().enumerate() {
        grid.insert(index as u32, &[a, b, b]);
    }
    let mut narrowest = reach;
    for &(a, b, chart) in &outline {
        let (min, max) = (a.min(b), a.max(b));
        for other in grid.near_box(min - reach, max + reach) {
            let (c, d, other_chart) = outline[other as usize];
            if other_chart != chart {
                narrowest = narrowest.min(segment_distance((a, b), (c, d)));
            }
        }
    }
    narrowest
}

/// The distance between segments a–b and c–d.
fn segment_distance((a, b): (DVec2, DVec2), (c, d): (DVec2, DVec2)) -> f64 {
    let side = |p: DVec2, q: DVec2, r: DVec2| (q - p).perp_dot(r - p);
    let crossing = side(a, b, c) * side(a, b, d) < 0.0 && side(c, d, a) * side(c, d, b) < 0.0;
    if crossing {
        return 0.0;
    }
    let to_segment = |p: DVec2, (s, e): (DVec2, DVec2)| {
        let along = (e - s).length_squared();
        let k = if along > 0.0 {
            ((p - s).dot(e - s) / along).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (s + k * (e - s) - p).length()
    };
    [
        to_segment(a, (c, d)),
        to_segment(b, (c, d)),
        to_segment(c, (a, b)),
        to_segment(d, (a, b)),
    ]
    .into_iter()
    .fold(f64::INFINITY, f64::min)
}

/// How each triangle was stretched from 3D into the unit square (its Jacobian's
/// singular values), checking that the projection never stretches past the common
/// scale and squeezes by at most cos CONE_DEGREES.
fn measure(
    mesh: &Mesh,
    corners: &[[DVec2; 3]],
    degenerate: &[bool],
    charts: &[usize],
    atlas: &Mesh,
) -> Measured {
    let mut stretches = Vec::new();
    for (t, triangle) in mesh
        .indices
        .chunks_exact(3)
        .enumerate()
        .filter(|(t, _)| !degenerate[*t])
    {
        let [a, b, c] =
            [0, 1, 2].map(|k| DVec3::from(mesh.positions[triangle[k] as usize].map(f64::from)));
        let (e1, e2) = (b - a, c - a);
        let x = e1.normalize();
        let y = e1.cross(e2).cross(e1).normalize();
        let flat =
            glam::DMat2::from_cols(DVec2::new(e1.dot(x), 0.0), DVec2::new(e2.dot(x), e2.dot(y)));
        let uv = corners[t];
        let mapped = glam::DMat2::from_cols(uv[1] - uv[0], uv[2] - uv[0]);
        let jacobian = mapped * flat.inverse();
        // Singular values of a 2×2 matrix from its Frobenius norm and determinant.
        let (frobenius, det) = (
            jacobian.col(0).length_squared() + jacobian.col(1).length_squared(),
            jacobian.determinant().abs(),
        );
        let root = (frobenius * frobenius - 4.0 * det * det).max(0.0).sqrt();
        let largest = ((frobenius + root) / 2.0).sqrt();
        let smallest = det / largest;
        stretches.push((0.5 * e1.cross(e2).length(), largest, smallest));
    }
    let mut largest: Vec<f64> = stretches.iter().map(|s| s.1).collect();
    largest.sort_by(f64::total_cmp);
    let scale = largest.get(largest.len() / 2).copied().unwrap_or(0.0);
    let area: f64 = stretches.iter().map(|s| s.0).sum();
    let weighted = |f: &dyn Fn(&(f64, f64, f64)) -> f64| {
        stretches.iter().map(|s| s.0 * f(s)).sum::<f64>() / area
    };
    // f32 texture coordinates blur the smallest triangles; over the area the stretch
    // is the scale and the squeeze within the cone.
    let off_scale = weighted(&|s| (s.1 / scale - 1.0).abs());
    assert!(
        off_scale < 1e-4,
        "the stretch strays from the common scale by {off_scale} on average"
    );
    let cos_cone = CONE_DEGREES.to_radians().cos();
    let squeezed = weighted(&|s| {
        if s.2 / s.1 < cos_cone - 1e-3 {
            1.0
        } else {
            0.0
        }
    });
    assert!(
        squeezed < 1e-4,
        "{squeezed} of the area squeezed past cos {CONE_DEGREES}°"
    );
    let mut triangles_of_chart: std::collections::BTreeMap<usize, usize> = Default::default();
    for &chart in charts {
        *triangles_of_chart.entry(chart).or_default() += 1;
    }
    Measured {
        charts: triangles_of_chart.len(),
        tiny_charts: triangles_of_chart.values().filter(|&&n| n < 4).count(),
        coverage: atlas.uv_area(),
        scale,
        mean_shape: weighted(&|s| s.2 / s.1),
        narrowest_gap: f64::INFINITY,
        vertex_growth: atlas.positions.len() as f64 / mesh.positions.len().max(1) as f64,
    }
}
