//! Reading meshes from OBJ, STL, PLY and glTF/GLB files. Every loader checks its indices
//! and coordinates, so a broken file is an error naming the file, never a panic.

use super::{FileVertices, Mesh};
use std::path::Path;

/// A mesh file that could not be read.
#[derive(Debug, thiserror::Error)]
#[error("{path}: {message}")]
pub struct MeshError {
    pub path: String,
    pub message: String,
}

/// File extensions [`load`] reads.
pub const EXTENSIONS: [&str; 5] = ["obj", "stl", "ply", "gltf", "glb"];

/// Triangles as positions and indices, before normals and texture coordinates are settled.
pub(super) struct Soup {
    pub positions: Vec<[f32; 3]>,
    pub normals: Option<Vec<[f32; 3]>>,
    pub uvs: Option<Vec<[f32; 2]>>,
    pub indices: Vec<u32>,
    /// Where each vertex came from in the file, when it is not the file's vertex of
    /// the same number.
    pub file_vertices: Option<FileVertices>,
}

/// Reads a mesh file, by extension. Missing normals are computed (area-weighted), missing
/// texture coordinates are zero.
pub fn load(path: &Path) -> Result<Mesh, MeshError> {
    let fail = |message: String| MeshError {
        path: path.display().to_string(),
        message,
    };
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().to_lowercase())
        .unwrap_or_default();
    if !EXTENSIONS.contains(&extension.as_str()) {
        return Err(fail(format!(
            "unknown mesh format '{extension}' (expected one of: {})",
            EXTENSIONS.join(", ")
        )));
    }
    let bytes = std::fs::read(path).map_err(|error| fail(error.to_string()))?;
    from_bytes(&extension, &bytes, path.parent()).map_err(fail)
}

/// Parses the content of a mesh file in the format its lower-case `extension` names.
/// `folder` is where a glTF file's external buffers are read from; without one, only
/// embedded buffers are read.
pub fn from_bytes(extension: &str, bytes: &[u8], folder: Option<&Path>) -> Result<Mesh, String> {
    let soup = match extension {
        "obj" => super::obj::read(bytes),
        "stl" => stl(bytes),
        "ply" => ply(bytes),
        "gltf" | "glb" => gltf(bytes, folder),
        _ => Err(format!(
            "unknown mesh format '{extension}' (expected one of: {})",
            EXTENSIONS.join(", ")
        )),
    }?;
    finish(soup)
}

fn finish(soup: Soup) -> Result<Mesh, String> {
    let count = soup.positions.len();
    if soup.indices.is_empty() {
        return Err("the file has no triangles".into());
    }
    if soup.indices.len() % 3 != 0 {
        return Err(format!(
            "{} indices do not make whole triangles",
            soup.indices.len()
        ));
    }
    if let Some(bad) = soup.indices.iter().find(|&&i| i as usize >= count) {
        return Err(format!(
            "a triangle refers to vertex {bad}, but there are only {count}"
        ));
    }
    if let Some(k) = soup
        .positions
        .iter()
        .position(|p| p.iter().any(|c| !c.is_finite()))
    {
        return Err(format!(
            "vertex {k} has a coordinate that is not a finite number"
        ));
    }
    let normals = match soup.normals {
        Some(normals)
            if normals.len() == count
                && normals.iter().all(|n| n.iter().all(|c| c.is_finite())) =>
        {
            normals
        }
        _ => vertex_normals(&soup.positions, &soup.indices),
    };
    let uvs = soup
        .uvs
        .filter(|uvs| uvs.len() == count)
        .unwrap_or_else(|| vec![[0.0; 2]; count]);
    Ok(Mesh {
        positions: soup.positions,
        normals,
        uvs,
        indices: soup.indices,
        fields: Vec::new(),
        file_vertices: soup.file_vertices,
    })
}

/// Area-weighted vertex normals; +y where a vertex touches only degenerate triangles.
pub fn vertex_normals(positions: &[[f32; 3]], indices: &[u32]) -> Vec<[f32; 3]> {
    let mut sums = vec![glam::Vec3::ZERO; positions.len()];
    for triangle in indices.chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|k| glam::Vec3::from(positions[triangle[k] as usize]));
        let weighted = (b - a).cross(c - a);
        for &index in triangle {
            sums[index as usize] += weighted;
        }
    }
    sums.into_iter()
        .map(|n| n.try_normalize().unwrap_or(glam::Vec3::Y).to_array())
        .collect()
}

fn stl(bytes: &[u8]) -> Result<Soup, String> {
    let mesh = stl_io::read_stl(&mut std::io::Cursor::new(bytes)).map_err(|e| e.to_string())?;
    let indices = mesh
        .faces
        .iter()
        .flat_map(|f| f.vertices)
        .map(|i| u32::try_from(i).unwrap_or(u32::MAX))
        .collect();
    Ok(Soup {
        positions: mesh.vertices.iter().map(|v| v.0).collect(),
        normals: None,
        uvs: None,
        indices,
        file_vertices: None,
    })
}

fn ply(bytes: &[u8]) -> Result<Soup, String> {
    use ply_rs_bw::ply::{DefaultElement, Property};
    let ply = ply_rs_bw::parser::Parser::<DefaultElement>::new()
        .read_ply(&mut &bytes[..])
        .map_err(|e| e.to_string())?;
    let vertices = ply.payload.get("vertex").ok_or("no 'vertex' element")?;
    let scalar =
        |element: &DefaultElement, key: &str| element.get(key).and_then(Property::to_f32_lossy);
    let mut positions = Vec::with_capacity(vertices.len());
    let mut normals = Vec::with_capacity(vertices.len());
    for (k, vertex) in vertices.iter().enumerate() {
        let coordinate =
            |key| scalar(vertex, key).ok_or_else(|| format!("vertex {k} has no '{key}'"));
        positions.push([coordinate("x")?, coordinate("y")?, coordinate("z")?]);
        if let (Some(x), Some(y), Some(z)) = (
            scalar(vertex, "nx"),
            scalar(vertex, "ny"),
            scalar(vertex, "nz"),
        ) {
            normals.push([x, y, z]);
        }
    }
    let faces = ply.payload.get("face").ok_or("no 'face' element")?;
    let mut indices = Vec::new();
    for (k, face) in faces.iter().enumerate() {
        let list = face
            .get("vertex_indices")
            .or_else(|| face.get("vertex_index"))
            .ok_or_else(|| format!("face {k} has no vertex_indices"))?;
        let polygon: Vec<i64> = match list {
            Property::ListChar(v) => v.iter().map(|&i| i64::from(i)).collect(),
            Property::ListUChar(v) => v.iter().map(|&i| i64::from(i)).collect(),
            Property::ListShort(v) => v.iter().map(|&i| i64::from(i)).collect(),
            Property::ListUShort(v) => v.iter().map(|&i| i64::from(i)).collect(),
            Property::ListInt(v) => v.iter().map(|&i| i64::from(i)).collect(),
            Property::ListUInt(v) => v.iter().map(|&i| i64::from(i)).collect(),
            _ => return Err(format!("face {k}: vertex indices are not an integer list")),
        };
        let polygon: Vec<u32> = polygon
            .into_iter()
            .map(|i| u32::try_from(i).unwrap_or(u32::MAX))
            .collect();
        for corner in 1..polygon.len().saturating_sub(1) {
            indices.extend([polygon[0], polygon[corner], polygon[corner + 1]]);
        }
    }
    let normals = (normals.len() == positions.len()).then_some(normals);
    Ok(Soup {
        positions,
        normals,
        uvs: None,
        indices,
        file_vertices: None,
    })
}

fn gltf(bytes: &[u8], folder: Option<&Path>) -> Result<Soup, String> {
    use gltf::Semantic;
    use gltf::accessor::{DataType, Dimensions};
    let gltf::Gltf { document, blob } =
        gltf::Gltf::from_slice_without_validation(bytes).map_err(|e| e.to_string())?;
    position_accessors_exist(document.as_json())?;
    let document = gltf::Document::from_json(document.into_json()).map_err(|e| e.to_string())?;
    let buffers = gltf::import_buffers(&document, folder, blob).map_err(|e| e.to_string())?;
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
    let mut stack: Vec<(gltf::Node, glam::Mat4)> =
        scene.nodes().map(|n| (n, glam::Mat4::IDENTITY)).collect();
    // Nodes form trees; a file whose children loop back is read once per node.
    let mut visited = vec![false; document.nodes().len()];
    while let Some((node, parent)) = stack.pop() {
        if std::mem::replace(&mut visited[node.index()], true) {
            continue;
        }
        let transform = parent * glam::Mat4::from_cols_array_2d(&node.transform().matrix());
        stack.extend(node.children().map(|child| (child, transform)));
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
            let reader =
                primitive.reader(|buffer| buffers.get(buffer.index()).map(|data| &data.0[..]));
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
