//! Reading meshes from OBJ, STL, PLY and glTF/GLB files. Every loader checks its indices
//! and coordinates, so a broken file is an error naming the file, never a panic.

use super::{FileVertices, Mesh};
use crate::fsutil::{ReadLimit, read_limited};
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

/// Reads a mesh file, by extension: a regular file of at most [`ReadLimit::MESH`].
/// Missing normals are computed (area-weighted), missing texture coordinates are zero.
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
    let bytes = read_limited(path, ReadLimit::MESH).map_err(|error| fail(error.to_string()))?;
    from_bytes(&extension, &bytes, path.parent()).map_err(fail)
}

/// Parses the content of a mesh file in the format its lower-case `extension` names.
/// `folder` is the glTF file's folder, the only place its external buffers are read
/// from; without one, only embedded buffers are read.
pub fn from_bytes(extension: &str, bytes: &[u8], folder: Option<&Path>) -> Result<Mesh, String> {
    let soup = match extension {
        "obj" => super::obj::read(bytes),
        "stl" => stl(bytes),
        "ply" => ply(bytes),
        "gltf" | "glb" => super::gltf_scene::read(bytes, folder),
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
/// Summed in f64, so that positions anywhere in the f32 range (±3.4e38, or subnormal)
/// give their true directions.
pub fn vertex_normals(positions: &[[f32; 3]], indices: &[u32]) -> Vec<[f32; 3]> {
    let mut sums = vec![glam::DVec3::ZERO; positions.len()];
    for triangle in indices.chunks_exact(3) {
        let [a, b, c] =
            [0, 1, 2].map(|k| glam::DVec3::from(positions[triangle[k] as usize].map(f64::from)));
        let weighted = (b - a).cross(c - a);
        for &index in triangle {
            sums[index as usize] += weighted;
        }
    }
    sums.into_iter()
        .map(|n| {
            n.try_normalize()
                .unwrap_or(glam::DVec3::Y)
                .as_vec3()
                .to_array()
        })
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
        let polygon = polygon
            .into_iter()
            .map(|i| {
                u32::try_from(i).map_err(|_| {
                    format!(
                        "face {k} refers to vertex {i}, but there are only {}",
                        positions.len()
                    )
                })
            })
            .collect::<Result<Vec<u32>, String>>()?;
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
