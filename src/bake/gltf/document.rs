//! The glTF 2.0 document of a baked material: one mesh, one node, one material with its
//! textures, as a binary `.glb` (everything in one file) or a `.gltf` with its buffer and
//! PNGs beside it. Keys are written sorted (serde_json's map), so the same bake gives
//! the same bytes.

use super::super::model::{MeshData, Texture};
use serde_json::{Value, json};

/// The material's glTF description: its `materials[0]` object, which refers to textures
/// by their index in `textures`.
pub struct MaterialData {
    pub json: Value,
    /// Extensions the material uses (`extensionsUsed`).
    pub extensions: Vec<&'static str>,
    pub textures: Vec<Texture>,
}

/// The files of one document: (file name, bytes), the document first.
pub type Files = Vec<(String, Vec<u8>)>;

/// How a document is packaged.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Packaging {
    /// One `.glb` file.
    Binary,
    /// A `.gltf` file, its buffer as `<stem>.bin` and each texture as a PNG.
    Separate,
}

/// The binary buffer under construction: views appended 4-byte aligned.
#[derive(Default)]
struct Buffer {
    bytes: Vec<u8>,
    views: Vec<Value>,
}

impl Buffer {
    /// Appends `data` as a buffer view (with `target` for vertex and index data) and
    /// returns its index.
    fn view(&mut self, data: &[u8], target: Option<u32>) -> usize {
        while !self.bytes.len().is_multiple_of(4) {
            self.bytes.push(0);
        }
        let mut view =
            json!({ "buffer": 0, "byteOffset": self.bytes.len(), "byteLength": data.len() });
        if let Some(target) = target {
            view["target"] = json!(target);
        }
        self.bytes.extend_from_slice(data);
        self.views.push(view);
        self.views.len() - 1
    }
}

const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;

/// Writes the document for `mesh` and `material`, its files named from `stem`.
pub fn document(
    stem: &str,
    mesh: &MeshData,
    material: &MaterialData,
    packaging: Packaging,
) -> Files {
    let mut buffer = Buffer::default();
    let mut accessors = Vec::new();
    let mut accessor =
        |buffer: &mut Buffer, bytes: &[u8], target, kind: &str, count: usize, component| {
            let view = buffer.view(bytes, Some(target));
            accessors.push(
            json!({ "bufferView": view, "componentType": component, "count": count, "type": kind }),
        );
            accessors.len() - 1
        };
    let indices = accessor(
        &mut buffer,
        bytemuck::cast_slice(&mesh.indices),
        ELEMENT_ARRAY_BUFFER,
        "SCALAR",
        mesh.indices.len(),
        UNSIGNED_INT,
    );
    let count = mesh.positions.len();
    let position = accessor(
        &mut buffer,
        bytemuck::cast_slice(&mesh.positions),
        ARRAY_BUFFER,
        "VEC3",
        count,
        FLOAT,
    );
    let normal = accessor(
        &mut buffer,
        bytemuck::cast_slice(&mesh.normals),
        ARRAY_BUFFER,
        "VEC3",
        count,
        FLOAT,
    );
    let uv = accessor(
        &mut buffer,
        bytemuck::cast_slice(&mesh.uvs),
        ARRAY_BUFFER,
        "VEC2",
        count,
        FLOAT,
    );
    let tangent = (mesh.tangents.as_ref()).map(|tangents| {
        accessor(
            &mut buffer,
            bytemuck::cast_slice(tangents),
            ARRAY_BUFFER,
            "VEC4",
            count,
            FLOAT,
        )
    });
    // POSITION must give its bounds.
    let (min, max) = bounds(&mesh.positions);
    accessors[position]["min"] = json!(min);
    accessors[position]["max"] = json!(max);
    let mut attributes = json!({ "POSITION": position, "NORMAL": normal, "TEXCOORD_0": uv });
    if let Some(tangent) = tangent {
        attributes["TANGENT"] = json!(tangent);
    }
    let images: Vec<Value> = (material.textures.iter())
        .map(|texture| match packaging {
            Packaging::Binary => {
                json!({ "bufferView": buffer.view(&texture.png, None), "mimeType": "image/png" })
            }
            Packaging::Separate => json!({ "uri": uri(&texture.file_name) }),
        })
        .collect();
    let textures: Vec<Value> = (0..images.len())
        .map(|image| json!({ "sampler": 0, "source": image }))
        .collect();
    let bin_name = buffer_name(stem);
    let mut root = json!({
        "asset": { "version": "2.0", "generator": concat!("Veneer ", env!("CARGO_PKG_VERSION")) },
        "scene": 0,
        "scenes": [{ "nodes": [0] }],
        "nodes": [{ "mesh": 0, "name": stem }],
        "meshes": [{ "name": stem, "primitives": [{ "attributes": attributes, "indices": indices, "material": 0, "mode": 4 }] }],
        "materials": [material.json.clone()],
        "accessors": accessors,
        "bufferViews": buffer.views,
        "buffers": [{ "byteLength": buffer.bytes.len() }],
        // Linear filtering with mipmaps, repeating: what baked tiles expect.
        "samplers": [{ "magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497 }],
    });
    if !images.is_empty() {
        root["images"] = json!(images);
        root["textures"] = json!(textures);
    }
    if !material.extensions.is_empty() {
        root["extensionsUsed"] = json!(material.extensions);
    }
    match packaging {
        Packaging::Binary => {
            let json = serde_json::to_vec(&root).expect("a JSON value serialises");
            vec![(format!("{stem}.glb"), glb(json, buffer.bytes))]
        }
        Packaging::Separate => {
            root["buffers"][0]["uri"] = json!(uri(&bin_name));
            let json = serde_json::to_vec_pretty(&root).expect("a JSON value serialises");
            let mut files = vec![(format!("{stem}.gltf"), json), (bin_name, buffer.bytes)];
            files.extend((material.textures.iter()).map(|t| (t.file_name.clone(), t.png.clone())));
            files
        }
    }
}

/// The file name of the buffer beside a `.gltf`.
pub fn buffer_name(stem: &str) -> String {
    format!("{stem}.bin")
}

/// A file name as a relative URI (spaces and other reserved characters escaped).
fn uri(file_name: &str) -> String {
    urlencoding::encode(file_name).into_owned()
}

/// The componentwise bounds of `points`.
fn bounds(points: &[[f32; 3]]) -> ([f32; 3], [f32; 3]) {
    let mut min = [f32::INFINITY; 3];
    let mut max = [f32::NEG_INFINITY; 3];
    for p in points {
        for k in 0..3 {
            min[k] = min[k].min(p[k]);
            max[k] = max[k].max(p[k]);
        }
    }
    (min, max)
}

/// A GLB container: the 12-byte header, the JSON chunk padded with spaces and the binary
/// chunk padded with zeros, each to 4 bytes.
fn glb(mut json: Vec<u8>, mut bin: Vec<u8>) -> Vec<u8> {
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    for (kind, chunk) in [(b"JSON", &json), (b"BIN\0", &bin)] {
        out.extend_from_slice(&(chunk.len() as u32).to_le_bytes());
        out.extend_from_slice(kind);
        out.extend_from_slice(chunk);
    }
    out
}
