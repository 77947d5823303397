//! An automatic UV atlas for meshes without a UV layout (the marching-tetrahedra
//! `genus2`, scans, files saved without texture coordinates), so that materials can be
//! baked onto them. The surface is cut into charts of adjacent triangles that face
//! within a cone of one direction ([`charts`]: grown, settled into compact patches round
//! the directions the surface faces, merged where neighbours fit one cone, their ragged
//! edges straightened). Each chart is projected flat along its direction, which keeps
//! every triangle's orientation, and refuses triangles that would overlap others. The
//! charts, at one scale for the whole mesh (one texel density), are packed into the
//! unit square by their shapes, [`ATLAS_GAP_TEXELS`] texels apart ([`pack`]).
//! Degenerate triangles (no area, a repeated vertex, a coordinate that is not finite)
//! all go to one point of their own.

mod charts;
mod geometry;
mod grid;
mod merge;
mod overlap;
mod pack;
mod seed;
mod settle;
mod smooth;
#[cfg(test)]
mod tests;

use super::{FileVertices, Mesh};
use glam::DVec2;

/// Texels between charts at the texture size an atlas is made for, so that bilinear
/// filtering and the padding grown round baked islands never mix two charts.
pub const ATLAS_GAP_TEXELS: f64 = 4.0;

/// The most cells across the unit square of the grid charts are packed on (fewer for
/// smaller textures: a cell is never smaller than a texel, so that gaps counted in
/// cells hold in texels).
const PACKING_CELLS: u32 = 256;

/// The UV area (in the unit square) below which a mesh counts as having no UV layout.
const NO_LAYOUT_AREA: f64 = 1e-9;

impl Mesh {
    /// Whether the texture coordinates cover some area (loaders give a mesh without
    /// them uv (0, 0) everywhere).
    pub fn has_uv_layout(&self) -> bool {
        self.uv_area() >= NO_LAYOUT_AREA
    }

    /// This mesh when it has a UV layout, else the mesh with an automatic atlas for
    /// textures of `texture_size`² texels ([`Mesh::with_uv_atlas`]).
    pub fn with_uv_layout(self, texture_size: u32) -> Mesh {
        if self.has_uv_layout() {
            self
        } else {
            self.with_uv_atlas(texture_size)
        }
    }

    /// The mesh with new texture coordinates: an atlas of flattened charts packed into
    /// the unit square at one texel density, without flips or overlaps, charts
    /// [`ATLAS_GAP_TEXELS`] texels apart at `texture_size`² (closer only when that many
    /// gaps could not fit). Vertices are split along chart seams, each copy keeping the
    /// position, normal, fields and file vertex of the original; triangles keep their
    /// order and corners; vertices no triangle uses are dropped. The same mesh always
    /// gives the same atlas. Use it after computing distance fields, which need the
    /// connected mesh.
    pub fn with_uv_atlas(&self, texture_size: u32) -> Mesh {
        let geometry = geometry::Geometry::new(self);
        let charts = charts::segment(&geometry);
        let mut chart_of_triangle = vec![charts.len(); geometry.triangles.len()];
        let mut laid_flat: Vec<Vec<[DVec2; 3]>> = Vec::with_capacity(charts.len() + 1);
        for (index, chart) in charts.iter().enumerate() {
            for &t in &chart.triangles {
                chart_of_triangle[t as usize] = index;
            }
            laid_flat.push(chart.laid_flat(&geometry));
        }
        if geometry.degenerate.contains(&true) {
            // The degenerate triangles' point, after the charts.
            laid_flat.push(vec![[DVec2::ZERO; 3]]);
        }
        let texture_size = texture_size.max(1);
        let layout = pack::pack(
            &laid_flat,
            ATLAS_GAP_TEXELS / f64::from(texture_size),
            texture_size.min(PACKING_CELLS),
        );
        let uv = |chart: usize, vertex: u32| -> [f32; 2] {
            let point = match charts.get(chart) {
                Some(chart) => chart.frame.project(geometry.positions[vertex as usize]),
                None => DVec2::ZERO,
            };
            // Charts were laid out with v up: v down (as images count rows) keeps
            // counter-clockwise triangles counter-clockwise on the image.
            let placed = layout.place(chart, point).clamp(DVec2::ZERO, DVec2::ONE);
            [placed.x as f32, (1.0 - placed.y) as f32]
        };
        self.split_by_chart(&chart_of_triangle, uv)
    }

    /// The mesh with one vertex per original vertex and chart of the triangles using
    /// it, numbered in the order the triangles reach them, at `uv(chart, vertex)`.
    fn split_by_chart(
        &self,
        chart_of_triangle: &[usize],
        uv: impl Fn(usize, u32) -> [f32; 2],
    ) -> Mesh {
        let mut split = Mesh {
            indices: Vec::with_capacity(self.indices.len()),
            ..Mesh::default()
        };
        let mut file_vertex_of_copy = Vec::new();
        let mut copies: std::collections::HashMap<(usize, u32), u32> = Default::default();
        for (triangle, &chart) in self.indices.chunks_exact(3).zip(chart_of_triangle) {
            for &vertex in triangle {
                let copy = *copies.entry((chart, vertex)).or_insert_with(|| {
                    let v = vertex as usize;
                    if let Some(field) = self.fields.get(v) {
                        split.fields.push(*field);
                    }
                    file_vertex_of_copy.push(self.file_vertex(vertex));
                    split.push_vertex(self.positions[v], self.normals[v], uv(chart, vertex))
                });
                split.indices.push(copy);
            }
        }
        split.file_vertices = Some(FileVertices {
            of_vertex: file_vertex_of_copy,
            count: self.file_vertex_count(),
        });
        split
    }
}
