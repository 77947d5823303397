//! Mesh fields per texel for material bakes over a UV layout: the ray-cast fields a
//! material reads (ambient occlusion, thickness) are cast from every texel of the
//! layout, as the mesh maps are ([`crate::mesh_fields::Texels`]), instead of being
//! interpolated between the vertices, so a coarse mesh's crevices and thin parts land in
//! the maps texel by texel. A field's rays per vertex become an eighth as many per
//! texel, pooled over ±[`POOLING`] texels: `veneer report` measures that at the error of
//! the vertex count alone ("ambient occlusion per texel").

use super::{UV_PADDING, fill_uncovered};
use crate::mesh::Mesh;
use crate::mesh_fields::{MeshFieldKind, MeshLanes, Sampling, Scene, Texels};
use crate::render::TexelFields;

/// The largest side the texel fields are cast at; a larger bake reads them nearest.
pub const MOST_TEXEL_FIELDS: u32 = 2048;

/// How many texels around each texel its rays are pooled with.
const POOLING: u32 = 3;

/// How many fewer rays a texel casts than the field asks of a vertex.
const RAYS_PER_TEXEL_DIVISOR: u32 = 8;

/// The ray-cast fields among `lanes` cast from every texel of `mesh`'s UV layout (the
/// layout a `size`² bake renders), at no more than [`MOST_TEXEL_FIELDS`] a side, padded
/// as the maps are; `None` when the material reads none. Progress is `(texels done,
/// texels)` over every field cast.
pub fn texel_fields(
    mesh: &Mesh,
    lanes: &MeshLanes,
    size: u32,
    mut progress: impl FnMut(usize, usize),
) -> Option<TexelFields> {
    let cast: Vec<(usize, crate::mesh_fields::MeshField)> = (lanes.iter().enumerate())
        .filter_map(|(lane, field)| field.filter(|f| f.kind.casts_rays()).map(|f| (lane, f)))
        .collect();
    if cast.is_empty() {
        return None;
    }
    let side = size.min(MOST_TEXEL_FIELDS);
    let scene = Scene::new(mesh);
    let texels = Texels::new(mesh, &scene, side);
    let mut values = vec![[0.0f32; 4]; texels.texels.len()];
    let mut held = [false; 4];
    let (count, fields) = (texels.texels.len(), cast.len());
    for (index, (lane, field)) in cast.into_iter().enumerate() {
        let report = |done: usize, _| progress(index * count + done, fields * count);
        let rays = (field.samples / RAYS_PER_TEXEL_DIVISOR).max(1);
        let distance = field.distance as f32 / 100.0;
        let measured = match field.kind {
            MeshFieldKind::Occlusion => {
                let sampling = Sampling {
                    samples: rays,
                    distance,
                    tolerance: None,
                };
                texels.occlusion(&scene, sampling, report)
            }
            _ => texels.thickness(&scene, rays, distance, report),
        };
        for (value, pooled) in values.iter_mut().zip(texels.pooled(&measured, POOLING)) {
            value[lane] = pooled;
        }
        held[lane] = true;
    }
    let mut image = texels.image(&values);
    fill_uncovered(&mut image, side, UV_PADDING);
    Some(TexelFields {
        size: side,
        texels: image,
        lanes: held,
    })
}
