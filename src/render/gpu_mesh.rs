//! Meshes uploaded to the GPU. A mesh whose vertex or index data would pass the
//! device's largest buffer (256 MiB by default: about 5.6 million vertices) is uploaded
//! in parts, each with its own compact vertex buffer, and drawn part by part.

use crate::mesh::Mesh;
use wgpu::util::DeviceExt;

#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
struct Vertex {
    position: [f32; 3],
    normal: [f32; 3],
    uv: [f32; 2],
    fields: [f32; 4],
}

const VERTEX_BYTES: u64 = std::mem::size_of::<Vertex>() as u64;
const INDEX_BYTES: u64 = std::mem::size_of::<u32>() as u64;

/// One drawable part of a mesh: its vertices and triangles, indexed within the part.
struct Part {
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    index_count: u32,
    /// What drawing the part's triangles back to front needs, when asked for.
    depth_order: Option<DepthOrder>,
}

/// A part's triangles, their centres, and the index buffer they are sorted into for
/// each view (blended surfaces are drawn back to front).
struct DepthOrder {
    triangles: Vec<[u32; 3]>,
    centres: Vec<glam::Vec3>,
    sorted: wgpu::Buffer,
}

/// A mesh uploaded to the GPU.
pub struct GpuMesh {
    parts: Vec<Part>,
    /// Tells this upload from every other (what was rendered over its UV layout is kept
    /// for as long as the id is the same).
    id: u64,
}

impl GpuMesh {
    const ATTRIBUTES: [wgpu::VertexAttribute; 4] = wgpu::vertex_attr_array![
        0 => Float32x3, 1 => Float32x3, 2 => Float32x2, 3 => Float32x4
    ];

    /// The vertex layout of every mesh pipeline: position (location 0), normal (1), uv
    /// (2), distance fields (3).
    pub fn layout() -> wgpu::VertexBufferLayout<'static> {
        wgpu::VertexBufferLayout {
            array_stride: VERTEX_BYTES,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &Self::ATTRIBUTES,
        }
    }

    /// Binds the buffers and draws every triangle.
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        for part in &self.parts {
            pass.set_vertex_buffer(0, part.vertices.slice(..));
            pass.set_index_buffer(part.indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..part.index_count, 0, 0..1);
        }
    }

    /// Draws every triangle in the order the last [`GpuMesh::sort_back_to_front`] put
    /// them (within each part; in the mesh's order for a mesh uploaded without a depth
    /// order).
    pub fn draw_back_to_front(&self, pass: &mut wgpu::RenderPass<'_>) {
        for part in &self.parts {
            let indices = part
                .depth_order
                .as_ref()
                .map_or(&part.indices, |order| &order.sorted);
            pass.set_vertex_buffer(0, part.vertices.slice(..));
            pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..part.index_count, 0, 0..1);
        }
    }

    /// Whether the mesh was uploaded with what sorting its triangles needs.
    pub fn sorts(&self) -> bool {
        self.parts.iter().all(|part| part.depth_order.is_some())
    }

    /// Sorts the triangles of each part by the distance of their centres from `eye`,
    /// farthest first, for [`GpuMesh::draw_back_to_front`] (ties in triangle order, so
    /// the same view draws the same picture).
    pub fn sort_back_to_front(&self, queue: &wgpu::Queue, eye: glam::Vec3) {
        use rayon::prelude::*;
        for part in &self.parts {
            let Some(order) = &part.depth_order else {
                continue;
            };
            let mut keys: Vec<(u32, u32)> = order
                .centres
                .par_iter()
                .enumerate()
                // Distances are positive: their bits order as they do; farthest first.
                .map(|(k, c)| (u32::MAX - c.distance_squared(eye).to_bits(), k as u32))
                .collect();
            keys.par_sort_unstable();
            let indices: Vec<u32> = keys
                .iter()
                .flat_map(|&(_, k)| order.triangles[k as usize])
                .collect();
            queue.write_buffer(&order.sorted, 0, bytemuck::cast_slice(&indices));
        }
    }

    /// Uploads `mesh`, in as many parts as the device's buffer size limit asks for.
    pub fn new(device: &wgpu::Device, mesh: &Mesh) -> GpuMesh {
        GpuMesh::upload(device, mesh, false)
    }

    /// [`GpuMesh::new`] keeping what drawing the triangles back to front needs (for
    /// blended surfaces; see [`GpuMesh::sort_back_to_front`]).
    pub fn with_depth_order(device: &wgpu::Device, mesh: &Mesh) -> GpuMesh {
        GpuMesh::upload(device, mesh, true)
    }

    fn upload(device: &wgpu::Device, mesh: &Mesh, depth_order: bool) -> GpuMesh {
        let limit = device.limits().max_buffer_size;
        let max_vertices = usize::try_from(limit / VERTEX_BYTES).unwrap_or(usize::MAX);
        // Whole triangles per part.
        let max_indices = usize::try_from(limit / INDEX_BYTES / 3 * 3).unwrap_or(usize::MAX);
        let buffer = |label, contents: &[u8], usage| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage,
            })
        };
        let parts = split(mesh, max_vertices, max_indices)
            .into_iter()
            .map(|(vertices, indices)| Part {
                vertices: buffer(
                    "mesh vertices",
                    bytemuck::cast_slice(&vertices),
                    wgpu::BufferUsages::VERTEX,
                ),
                indices: buffer(
                    "mesh indices",
                    bytemuck::cast_slice(&indices),
                    wgpu::BufferUsages::INDEX,
                ),
                index_count: indices.len() as u32,
                depth_order: depth_order.then(|| {
                    let triangles: Vec<[u32; 3]> = indices
                        .chunks_exact(3)
                        .map(|t| [t[0], t[1], t[2]])
                        .collect();
                    let centres = triangles
                        .iter()
                        .map(|t| {
                            t.iter().fold(glam::Vec3::ZERO, |sum, &v| {
                                sum + glam::Vec3::from(vertices[v as usize].position)
                            }) / 3.0
                        })
                        .collect();
                    DepthOrder {
                        triangles,
                        centres,
                        sorted: buffer(
                            "mesh indices, back to front",
                            bytemuck::cast_slice(&indices),
                            wgpu::BufferUsages::INDEX | wgpu::BufferUsages::COPY_DST,
                        ),
                    }
                }),
            })
            .collect();
        static UPLOADS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
        GpuMesh {
            parts,
            id: UPLOADS.fetch_add(1, std::sync::atomic::Ordering::Relaxed),
        }
    }

    /// A number no other upload in this process has.
    pub fn id(&self) -> u64 {
        self.id
    }
}

/// The vertex of `mesh` at `index` as the shaders read it.
fn vertex(mesh: &Mesh, index: usize) -> Vertex {
    Vertex {
        position: mesh.positions[index],
        normal: mesh.normals[index],
        uv: mesh.uvs[index],
        fields: mesh.fields.get(index).copied().unwrap_or([0.0; 4]),
    }
}

/// The mesh as parts of at most `max_vertices` vertices and `max_indices` indices
/// (a multiple of 3, at least 3), triangles in their original order; one part, the
/// mesh's own vertices, when it fits.
fn split(mesh: &Mesh, max_vertices: usize, max_indices: usize) -> Vec<(Vec<Vertex>, Vec<u32>)> {
    let all_vertices = || (0..mesh.positions.len()).map(|i| vertex(mesh, i)).collect();
    if mesh.positions.len() <= max_vertices && mesh.indices.len() <= max_indices {
        return vec![(all_vertices(), mesh.indices.clone())];
    }
    let mut parts = Vec::new();
    // Where each mesh vertex sits in the current part (u32::MAX: not in it).
    let mut local = vec![u32::MAX; mesh.positions.len()];
    let (mut vertices, mut indices): (Vec<Vertex>, Vec<u32>) = (Vec::new(), Vec::new());
    let mut members: Vec<u32> = Vec::new();
    for triangle in mesh.indices.chunks_exact(3) {
        let new = triangle
            .iter()
            .filter(|&&v| local[v as usize] == u32::MAX)
            .count();
        if vertices.len() + new > max_vertices || indices.len() + 3 > max_indices {
            for &v in &members {
                local[v as usize] = u32::MAX;
            }
            members.clear();
            parts.push((std::mem::take(&mut vertices), std::mem::take(&mut indices)));
        }
        for &v in triangle {
            if local[v as usize] == u32::MAX {
                local[v as usize] = vertices.len() as u32;
                vertices.push(vertex(mesh, v as usize));
                members.push(v);
            }
            indices.push(local[v as usize]);
        }
    }
    if !indices.is_empty() {
        parts.push((vertices, indices));
    }
    parts
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The triangles of parts as vertex triples, for comparing with the mesh's own.
    fn triangles(parts: &[(Vec<Vertex>, Vec<u32>)]) -> Vec<[Vertex; 3]> {
        parts
            .iter()
            .flat_map(|(vertices, indices)| {
                indices
                    .chunks_exact(3)
                    .map(|t| [0, 1, 2].map(|k| vertices[t[k] as usize]))
            })
            .collect()
    }

    #[test]
    fn split_parts_keep_every_triangle_in_order_within_the_limits() {
        let mesh = crate::mesh::primitive("torus:12").expect("a primitive");
        let whole = split(&mesh, usize::MAX, usize::MAX);
        assert_eq!(whole.len(), 1);
        for (max_vertices, max_indices) in [(50, usize::MAX), (usize::MAX, 99), (3, 3), (40, 60)] {
            let parts = split(&mesh, max_vertices, max_indices);
            assert!(parts.len() > 1, "{max_vertices}, {max_indices}");
            assert!(
                parts
                    .iter()
                    .all(|(v, i)| v.len() <= max_vertices && i.len() <= max_indices)
            );
            assert_eq!(triangles(&parts), triangles(&whole));
        }
    }
}
