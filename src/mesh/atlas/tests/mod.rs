//! The atlas checked on the meshes it is for — the marching-tetrahedra `genus2`, a lumpy
//! scan-like OBJ of bare `v` and `f` lines — and on degenerate input: every corner keeps
//! its position, normal, fields and file vertex; texture coordinates are finite and in
//! the unit square; no triangle is mirrored, none overlaps another (checked by sampling,
//! independently of the atlas's own overlap test); charts (found again as the triangles
//! joined by shared texture coordinates) keep the gap; the texel density is one across
//! the mesh and the projection squeezes a triangle by at most cos 50° across; and the
//! same mesh gives the same atlas.

mod checks;
mod meshes;

use super::{ATLAS_GAP_TEXELS, FileVertices, Mesh};
use checks::{checked_atlas, measured_atlas};
use meshes::{lumpy_obj, triangle_soup};

#[test]
fn the_double_torus_unwraps_into_few_charts_packed_apart_at_one_density() {
    let mesh = crate::mesh::primitive("genus2").expect("a primitive");
    assert!(!mesh.has_uv_layout());
    let measured = checked_atlas(&mesh, 1024);
    // Few charts, few of them specks; more than half the square covered; the charts
    // keep most of their triangles' shapes; seams split few vertices.
    assert!(
        measured.charts < 100 && measured.tiny_charts < 10,
        "{measured:?}"
    );
    assert!(measured.coverage > 0.5, "{measured:?}");
    assert!(measured.mean_shape > 0.85, "{measured:?}");
    assert!(measured.vertex_growth < 1.15, "{measured:?}");
    // At the tests' 64² the gaps, 4 of 64 texels, take most of the square.
    let small = checked_atlas(&mesh, 64);
    assert!(small.coverage > 0.05, "{small:?}");
}

#[test]
fn a_lumpy_scan_without_uvs_unwraps() {
    let mesh = lumpy_obj(48);
    assert!(!mesh.has_uv_layout());
    let measured = checked_atlas(&mesh, 1024);
    assert!(
        measured.charts < 100 && measured.tiny_charts < 10,
        "{measured:?}"
    );
    assert!(measured.coverage > 0.5, "{measured:?}");
    assert!(measured.mean_shape > 0.85, "{measured:?}");
}

#[test]
fn a_cube_of_quads_unwraps_into_its_six_faces() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/meshes/cube_quads.ply");
    let cube = crate::mesh::load(std::path::Path::new(path)).expect("the cube loads");
    let measured = checked_atlas(&cube, 256);
    assert_eq!(measured.charts, 6, "{measured:?}");
    // Flat faces keep their shapes exactly.
    assert!(measured.mean_shape > 1.0 - 1e-6, "{measured:?}");
    assert!(measured.coverage > 0.5, "{measured:?}");
}

#[test]
fn more_charts_than_a_small_texture_holds_pack_closer_than_the_gap() {
    // 300 separate triangles and 16² texels: with 4 texels between them they cannot
    // fit, so they are packed in shelves with the gap narrowed, still apart.
    let measured = measured_atlas(&triangle_soup(300), 16);
    assert_eq!(measured.charts, 300);
    assert!(measured.narrowest_gap > 0.0, "{measured:?}");
    assert!(
        measured.narrowest_gap < ATLAS_GAP_TEXELS / 16.0,
        "{measured:?}"
    );
}

#[test]
fn split_vertices_keep_their_fields_and_file_vertices() {
    let mut mesh = crate::mesh::primitive("genus2:12").expect("a primitive");
    let count = mesh.positions.len();
    mesh.fields = (0..count)
        .map(|v| [v as f32, 0.5, 1.0 / (v as f32 + 1.0), 0.25])
        .collect();
    // As if the file listed the vertices backwards, with two more no triangle uses.
    mesh.file_vertices = Some(FileVertices {
        of_vertex: (0..count as u32).rev().map(|v| v + 2).collect(),
        count: count + 2,
    });
    let measured = checked_atlas(&mesh, 512);
    assert!(measured.charts > 1, "{measured:?}");
}

#[test]
fn degenerate_triangles_isolated_vertices_and_non_manifold_edges_unwrap() {
    let positions = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [2.0, 0.0, 0.0],      // collinear with 0 and 1
        [5.0, 5.0, 5.0],      // no triangle uses it
        [0.5, -1.0, 0.5],     // a fin on edge 0–1 ...
        [0.5, -1.0, -0.5],    // ... and another: three triangles on one edge
        [f32::NAN, 0.0, 0.0], // not finite
        [0.0, 1.0, 0.0],      // vertex 2's position again (a split vertex)
        [-1.0, 1.0, 0.0],
    ];
    let indices = vec![
        0, 1, 2, // a plain triangle
        0, 1, 3, // no area
        2, 2, 1, // a repeated vertex
        1, 0, 5, // the fins on edge 0–1
        1, 0, 6, //
        0, 1, 2, // the first triangle again
        2, 1, 0, // and mirrored
        0, 7, 1, // a corner not finite
        0, 8, 9, // beside the first through the split vertex
    ];
    let mesh = Mesh::from_triangles(positions, indices);
    let atlas = mesh.with_uv_atlas(256);
    assert!(atlas.uvs.iter().flatten().all(|x| x.is_finite()));
    checked_atlas(&mesh, 256);
    // Vertex 4 is dropped; the degenerate triangles share one point.
    assert!(
        atlas
            .file_vertices
            .as_ref()
            .unwrap()
            .of_vertex
            .iter()
            .all(|&v| v != 4)
    );
    let spot: Vec<[f32; 2]> = [1, 2, 7]
        .iter()
        .flat_map(|&t| {
            atlas.indices[3 * t..3 * t + 3]
                .iter()
                .map(|&v| atlas.uvs[v as usize])
        })
        .collect();
    assert!(spot.iter().all(|uv| *uv == spot[0]), "{spot:?}");
}

#[test]
fn a_single_triangle_fills_the_square_but_its_margins() {
    let mesh = Mesh::from_triangles(
        vec![[0.0, 0.0, 0.0], [3.0, 0.0, 1.0], [0.0, 2.0, 0.0]],
        vec![0, 1, 2],
    );
    let measured = checked_atlas(&mesh, 128);
    assert_eq!(measured.charts, 1);
    // A right triangle with legs √10 and 2: its longer leg lies along the square's
    // width less the margins of half a gap, give or take a packing cell.
    let width = 1.0 - ATLAS_GAP_TEXELS / 128.0;
    let scale = width / 10f64.sqrt();
    assert!(
        (measured.scale / scale - 1.0).abs() < 2.0 / 128.0,
        "{measured:?}"
    );
    assert!((measured.coverage - 10f64.sqrt() * measured.scale.powi(2)).abs() < 1e-6);
}

#[test]
fn an_empty_mesh_gives_an_empty_atlas() {
    let atlas = Mesh::default().with_uv_atlas(64);
    assert!(atlas.positions.is_empty() && atlas.indices.is_empty());
}

#[test]
fn a_mesh_with_a_uv_layout_keeps_it() {
    let sphere = crate::mesh::primitive("sphere").expect("a primitive");
    assert!(sphere.has_uv_layout());
    assert!(sphere.clone().with_uv_layout(64) == sphere);
    let bare = Mesh::from_triangles(sphere.positions.clone(), sphere.indices.clone());
    assert!(bare.clone().with_uv_layout(64).has_uv_layout());
}
