//! The glTF/GLB loader: the triangles of the default scene (or the first), with node
//! transforms applied. Buffers come from [`super::gltf_buffers`], which keeps them inside
//! the file's folder; images are not read.

use super::gltf_buffers;
use super::load::Soup;
use std::path::Path;

/// The triangles of a glTF or GLB file; `folder` is the file's folder (see
/// [`gltf_buffers::import`]).
pub(super) fn read(bytes: &[u8], folder: Option<&Path>) -> Result<Soup, String> {
    use gltf::Semantic;
    use gltf::accessor::{DataType, Dimensions};
    glb_length_fits(bytes)?;
    let gltf::Gltf { document, blob } =
        gltf::Gltf::from_slice_without_validation(bytes).map_err(|e| e.to_string())?;
    position_accessors_exist(document.as_json())?;
    let document = gltf::Document::from_json(document.into_json()).map_err(|e| e.to_string())?;
    let buffers = gltf_buffers::import(&document, folder, blob)?;
    let mut soup = Soup {
        positions: vec![],
        normals: Some(vec![]),
        uvs: Some(vec![]),
        indices: vec![],
        file_vertices: None,
    };
    let scene = document
        .default_scene()
        .or_else(|| document.scenes().next())
        .ok_or("the file has no scene")?;
    // Depth first, in the order the file lists nodes, which numbers the vertices (see
    // `FileVertices`): the stack holds them reversed.
    let mut stack: Vec<(gltf::Node, glam::Mat4)> =
        scene.nodes().map(|n| (n, glam::Mat4::IDENTITY)).collect();
    stack.reverse();
    // Nodes form trees; a file whose children loop back is read once per node.
    let mut visited = vec![false; document.nodes().len()];
    while let Some((node, parent)) = stack.pop() {
        if std::mem::replace(&mut visited[node.index()], true) {
            continue;
        }
        let transform = parent * glam::Mat4::from_cols_array_2d(&node.transform().matrix());
        let siblings = stack.len();
        stack.extend(node.children().map(|child| (child, transform)));
        stack[siblings..].reverse();
        let Some(mesh) = node.mesh() else { continue };
        let normal_matrix = glam::Mat3::from_mat4(transform).inverse().transpose();
        for primitive in mesh
            .primitives()
            .filter(|p| p.mode() == gltf::mesh::Mode::Triangles)
        {
            // The glTF crate trusts each accessor's type (and reaches `unreachable!` on
            // float indices; found by fuzzing): only the types the format allows are read.
            let typed = |semantic, types: &[DataType], dimensions| {
                primitive.get(&semantic).is_none_or(|accessor| {
                    types.contains(&accessor.data_type()) && accessor.dimensions() == dimensions
                })
            };
            let integers = [DataType::U8, DataType::U16, DataType::U32];
            let indices_typed = primitive.indices().is_none_or(|accessor| {
                integers.contains(&accessor.data_type())
                    && accessor.dimensions() == Dimensions::Scalar
            });
            if !typed(Semantic::Positions, &[DataType::F32], Dimensions::Vec3) || !indices_typed {
                return Err(format!(
                    "mesh {}, primitive {}: positions must be float VEC3 and indices unsigned integer SCALAR",
                    mesh.index(),
                    primitive.index()
                ));
            }
            let normals_typed = typed(Semantic::Normals, &[DataType::F32], Dimensions::Vec3);
            let uvs_typed = typed(
                Semantic::TexCoords(0),
                &[DataType::U8, DataType::U16, DataType::F32],
                Dimensions::Vec2,
            );
            let accessors = [
                Semantic::Positions,
                Semantic::Normals,
                Semantic::TexCoords(0),
            ]
            .into_iter()
            .filter_map(|semantic| primitive.get(&semantic).map(|a| (semantic.to_string(), a)))
            .chain(primitive.indices().map(|a| ("indices".to_string(), a)));
            for (what, accessor) in accessors {
                accessor_in_bounds(&accessor, &buffers).map_err(|problem| {
                    format!(
                        "mesh {}, primitive {}: the {what} accessor ({}) {problem}",
                        mesh.index(),
                        primitive.index(),
                        accessor.index()
                    )
                })?;
            }
            let reader = primitive.reader(|buffer| buffers.get(buffer.index()).map(Vec::as_slice));
            let Some(positions) = reader.read_positions() else {
                continue;
            };
            let base = soup.positions.len() as u32;
            let positions: Vec<[f32; 3]> = positions
                .map(|p| transform.transform_point3(p.into()).to_array())
                .collect();
            let count = positions.len() as u32;
            match reader.read_indices() {
                Some(indices) => soup
                    .indices
                    .extend(indices.into_u32().map(|i| base.saturating_add(i))),
                None => soup
                    .indices
                    .extend((0..count).map(|i| base.saturating_add(i))),
            }
            match (
                &mut soup.normals,
                normals_typed.then(|| reader.read_normals()).flatten(),
            ) {
                (Some(normals), Some(read)) => normals.extend(read.map(|n| {
                    (normal_matrix * glam::Vec3::from(n))
                        .normalize_or(glam::Vec3::Y)
                        .to_array()
                })),
                (normals, _) => *normals = None,
            }
            match (
                &mut soup.uvs,
                uvs_typed.then(|| reader.read_tex_coords(0)).flatten(),
            ) {
                (Some(uvs), Some(read)) => uvs.extend(read.into_f32()),
                (uvs, _) => *uvs = None,
            }
            soup.positions.extend(positions);
        }
    }
    Ok(soup)
}

/// Checks that every primitive's POSITION accessor exists, before the glTF crate's own
/// validation, which looks that accessor up without checking (and panics; found by
/// fuzzing, gltf-json 1.4.1).
fn position_accessors_exist(json: &gltf::json::Root) -> Result<(), String> {
    for (m, mesh) in json.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            let position = gltf::json::validation::Checked::Valid(gltf::Semantic::Positions);
            if let Some(accessor) = primitive.attributes.get(&position)
                && accessor.value() >= json.accessors.len()
            {
                return Err(format!(
                    "mesh {m}, primitive {p}: POSITION refers to accessor {}, but there are only {}",
                    accessor.value(),
                    json.accessors.len()
                ));
            }
        }
    }
    Ok(())
}

/// Checks that `accessor`'s elements lie inside its buffer view and the view inside its
/// buffer: the glTF crate reads an accessor that does not as absent, which would make a
/// file with a bad offset a mesh without triangles, or its indices a plain list.
fn accessor_in_bounds(accessor: &gltf::Accessor, buffers: &[Vec<u8>]) -> Result<(), String> {
    let Some(view) = accessor.view() else {
        return Ok(());
    };
    let buffer = buffers.get(view.buffer().index()).map_or(0, Vec::len) as u64;
    let view_end = (view.offset() as u64).checked_add(view.length() as u64);
    if view_end.is_none_or(|end| end > buffer) {
        return Err(format!(
            "uses buffer view {} at bytes {}..+{}, past the end of buffer {} ({buffer} bytes)",
            view.index(),
            view.offset(),
            view.length(),
            view.buffer().index()
        ));
    }
    let count = accessor.count() as u64;
    if count == 0 {
        return Ok(());
    }
    let size = accessor.size() as u64;
    let stride = view.stride().map_or(size, |stride| stride as u64);
    let end = (count - 1)
        .checked_mul(stride)
        .and_then(|last| last.checked_add(accessor.offset() as u64))
        .and_then(|last| last.checked_add(size));
    match end {
        Some(end) if end <= view.length() as u64 => Ok(()),
        _ => Err(format!(
            "reads {count} elements from byte offset {}, past the end of buffer view {} \
             ({} bytes)",
            accessor.offset(),
            view.index(),
            view.length()
        )),
    }
}

/// Refuses a GLB whose header gives a total length shorter than the header itself,
/// which the `gltf` crate subtracts from without a check (found by fuzzing: it panics
/// where overflow checks are on, and reads a wrapped length where they are off).
fn glb_length_fits(bytes: &[u8]) -> Result<(), String> {
    const HEADER: usize = 12;
    match bytes {
        [b'g', b'l', b'T', b'F', _, _, _, _, a, b, c, d, ..] => {
            let length = u32::from_le_bytes([*a, *b, *c, *d]) as usize;
            if length < HEADER {
                Err(format!(
                    "the GLB header gives a length of {length} bytes, less than the header's own {HEADER}"
                ))
            } else {
                Ok(())
            }
        }
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_glb_length_shorter_than_its_header_is_refused_before_the_gltf_crate_reads_it() {
        let bytes = std::fs::read(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/tests/fuzz/mesh_load/glb_length_below_header.glb"
        ))
        .expect("the fuzz finding");
        let Err(error) = super::read(&bytes, None) else {
            panic!("a GLB shorter than its header loaded")
        };
        assert!(error.contains("less than the header's own 12"), "{error}");
    }
}
