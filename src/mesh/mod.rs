//! Triangle meshes: the procedural primitives the preview and the CLI use.

mod primitives;

pub use primitives::{PRIMITIVES, primitive};

/// An indexed triangle mesh with per-vertex normals and texture coordinates.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    pub positions: Vec<[f32; 3]>,
    pub normals: Vec<[f32; 3]>,
    pub uvs: Vec<[f32; 2]>,
    /// Three vertex indices per triangle, counter-clockwise seen from outside.
    pub indices: Vec<u32>,
}

impl Mesh {
    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// Adds a vertex and returns its index.
    pub fn push_vertex(&mut self, position: [f32; 3], normal: [f32; 3], uv: [f32; 2]) -> u32 {
        self.positions.push(position);
        self.normals.push(normal);
        self.uvs.push(uv);
        (self.positions.len() - 1) as u32
    }

    /// Adds a (u_steps+1)×(v_steps+1) grid of vertices from `vertex(u, v)` with u, v in
    /// [0, 1], and two triangles per cell.
    pub fn push_grid(
        &mut self,
        u_steps: u32,
        v_steps: u32,
        vertex: impl Fn(f32, f32) -> ([f32; 3], [f32; 3]),
    ) {
        let base = self.positions.len() as u32;
        for j in 0..=v_steps {
            for i in 0..=u_steps {
                let (u, v) = (i as f32 / u_steps as f32, j as f32 / v_steps as f32);
                let (position, normal) = vertex(u, v);
                self.push_vertex(position, normal, [u, v]);
            }
        }
        let row = u_steps + 1;
        for j in 0..v_steps {
            for i in 0..u_steps {
                let a = base + j * row + i;
                let (b, c, d) = (a + 1, a + row, a + row + 1);
                self.indices.extend_from_slice(&[a, c, b, b, c, d]);
            }
        }
    }
}
