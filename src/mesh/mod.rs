//! Triangle meshes: procedural primitives and mesh files, for the preview and the CLI.

mod analysis;
mod atlas;
mod bvh;
mod file_vertices;
mod gltf_buffers;
mod gltf_scene;
mod implicit;
mod load;
mod obj;
mod pick;
mod primitives;
mod refine;
mod tangents;

pub use analysis::{MeshReport, analyse, vertex_components, weld};
pub use atlas::ATLAS_GAP_TEXELS;
pub use bvh::{Bvh, Hit};
pub use file_vertices::FileVertices;
pub use implicit::{double_torus, polygonize};
pub use load::{EXTENSIONS, MeshError, from_bytes, load, vertex_normals};
pub use pick::pick_vertex;
pub use primitives::{
    DETAIL_COST, MAX_DETAIL, MAX_GENUS2_DETAIL, PRIMITIVES, primitive, shell, sphere, torus,
};
pub use refine::{Refined, Refinement, SurfacePoint, refine_for_displacement};
pub use tangents::{unit_normals, vertex_tangents};

/// The mesh a preview or render shows for `name`: a primitive, or else a mesh file
/// fitted to the unit sphere. A file whose triangles have no area once fitted (all its
/// vertices at one point or on one line) is refused: it would render as nothing.
pub fn preview_mesh(name: &str) -> Result<Mesh, MeshError> {
    if let Some(mesh) = primitive(name) {
        return Ok(mesh);
    }
    let mesh = Mesh::named(name)?.fitted_to_unit_sphere();
    let has_area = mesh
        .indices
        .chunks_exact(3)
        .any(|triangle| analysis::double_area(&mesh.positions, triangle) > 1.0e-12);
    match has_area {
        true => Ok(mesh),
        false => Err(MeshError {
            path: name.to_string(),
            message: "its triangles have no area (all its vertices lie at one point or on \
                      one line): there is nothing to render"
                .into(),
        }),
    }
}

/// Why an existing `path` without an extension is not read as a mesh: it is not a
/// regular file (a device, FIFO or folder, said as such), or its format is unknown.
fn not_a_mesh_file(path: &std::path::Path) -> String {
    match std::fs::metadata(path) {
        Ok(metadata) if !metadata.is_file() => format!(
            "it is {}, not a mesh file",
            crate::fsutil::what_it_is(&metadata)
        ),
        _ => format!(
            "a mesh file's format is taken from its extension ({}), and this name has none",
            load::EXTENSIONS.join(", ")
        ),
    }
}

/// An indexed triangle mesh with per-vertex normals and texture coordinates.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    pub positions: Vec<[f32; 3]>,
    pub normals: Vec<[f32; 3]>,
    pub uvs: Vec<[f32; 2]>,
    /// Three vertex indices per triangle, counter-clockwise seen from outside.
    pub indices: Vec<u32>,
    /// Per-vertex fields for `VeneerSurface.fields`: distance fields normalised to
    /// [0, 1] in their slots, mesh fields in the lanes the compiled material assigns
    /// them ([`crate::codegen::SurfaceUse::mesh_fields`]); empty until computed (the
    /// shader then reads 0).
    pub fields: Vec<[f32; 4]>,
    /// Where each vertex came from in the mesh file, when the loader split or reordered
    /// the file's vertices; `None` when the vertices are the file's, one for one.
    pub file_vertices: Option<FileVertices>,
}

impl Mesh {
    /// A mesh of `positions` and triangle `indices` (not checked), with area-weighted
    /// normals and zero texture coordinates.
    pub fn from_triangles(positions: Vec<[f32; 3]>, indices: Vec<u32>) -> Mesh {
        Mesh {
            normals: vertex_normals(&positions, &indices),
            uvs: vec![[0.0; 2]; positions.len()],
            positions,
            indices,
            ..Mesh::default()
        }
    }

    /// A primitive by name, or else a mesh file.
    pub fn named(name: &str) -> Result<Mesh, MeshError> {
        match primitive(name) {
            Some(mesh) => Ok(mesh),
            None if std::path::Path::new(name).extension().is_some() => {
                load(std::path::Path::new(name))
            }
            None if std::path::Path::new(name).exists() => Err(MeshError {
                path: name.to_string(),
                message: not_a_mesh_file(std::path::Path::new(name)),
            }),
            None => Err(MeshError {
                path: name.to_string(),
                message: format!(
                    "{} (expected one of: {}, with an optional level of detail \
                     1 to {MAX_DETAIL} such as torus:320 (genus2 up to {MAX_GENUS2_DETAIL}; \
                     {DETAIL_COST}), or a mesh file)",
                    match name.split_once(':') {
                        Some((base, _)) if PRIMITIVES.contains(&base) => {
                            "level of detail out of range"
                        }
                        _ => "unknown mesh",
                    },
                    PRIMITIVES.join(", ")
                ),
            }),
        }
    }

    /// The mesh moved and scaled uniformly to fit the unit sphere at the origin, as the
    /// preview expects (the graph's preview placement then applies). Computed in f64, so
    /// that coordinates anywhere in the f32 range (±3.4e38, or subnormal ones like 1e-40)
    /// fit without overflow or underflow.
    pub fn fitted_to_unit_sphere(mut self) -> Mesh {
        let (center, radius) = self.bounding_sphere();
        let scale = if radius > 0.0 { 1.0 / radius } else { 1.0 };
        for p in &mut self.positions {
            *p = ((glam::DVec3::from(p.map(f64::from)) - center) * scale)
                .as_vec3()
                .to_array();
        }
        self
    }

    /// The centre of the bounding box and the distance from it to the farthest vertex:
    /// the sphere [`Mesh::fitted_to_unit_sphere`] maps to the unit one. In f64, so that
    /// coordinates anywhere in the f32 range neither overflow nor underflow.
    pub fn bounding_sphere(&self) -> (glam::DVec3, f64) {
        let point = |p: &[f32; 3]| glam::DVec3::from(p.map(f64::from));
        let (min, max) = self.positions.iter().fold(
            (glam::DVec3::splat(f64::MAX), glam::DVec3::splat(f64::MIN)),
            |(lo, hi), p| (lo.min(point(p)), hi.max(point(p))),
        );
        let center = (min + max) * 0.5;
        let radius = self
            .positions
            .iter()
            .map(|p| (point(p) - center).length())
            .fold(0.0f64, f64::max);
        (center, radius)
    }

    /// The enclosed volume (positive when triangles wind counter-clockwise seen from
    /// outside; meaningful for closed meshes).
    pub fn signed_volume(&self) -> f32 {
        self.indices
            .chunks_exact(3)
            .map(|t| {
                let [a, b, c] = [0, 1, 2].map(|k| glam::Vec3::from(self.positions[t[k] as usize]));
                a.dot(b.cross(c)) / 6.0
            })
            .sum()
    }

    /// The mesh as Wavefront OBJ text (positions, normals, texture coordinates, faces),
    /// which every tool reads.
    pub fn to_obj(&self) -> String {
        use std::fmt::Write;
        let mut obj = String::with_capacity(self.positions.len() * 80 + self.indices.len() * 12);
        for (k, p) in self.positions.iter().enumerate() {
            let n = self.normals.get(k).copied().unwrap_or([0.0, 1.0, 0.0]);
            let t = self.uvs.get(k).copied().unwrap_or([0.0, 0.0]);
            let _ = writeln!(
                obj,
                "v {} {} {}\nvn {} {} {}\nvt {} {}",
                p[0], p[1], p[2], n[0], n[1], n[2], t[0], t[1]
            );
        }
        for t in self.indices.chunks_exact(3) {
            let [a, b, c] = [t[0] + 1, t[1] + 1, t[2] + 1];
            let _ = writeln!(obj, "f {a}/{a}/{a} {b}/{b}/{b} {c}/{c}/{c}");
        }
        obj
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// The area the triangles cover in texture space (overlaps counted twice): 0 for a
    /// mesh without a UV layout, whose loaders give every vertex uv (0, 0).
    pub fn uv_area(&self) -> f64 {
        self.indices
            .chunks_exact(3)
            .map(|t| {
                let [a, b, c] =
                    [0, 1, 2].map(|k| glam::DVec2::from(self.uvs[t[k] as usize].map(f64::from)));
                0.5 * (b - a).perp_dot(c - a).abs()
            })
            .sum()
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
