//! wgpu rendering: a headless context on any adapter, the flat albedo render, the
//! lit mesh render, and readback to images.

mod context;
mod flat;
mod image;
mod mesh_view;
mod readback;

pub use context::{GpuContext, RenderError};
pub use flat::{FlatRect, FlatRenderer, albedo_to_rgb8};
pub use image::{Image, View, preview_rect, render_graph};
pub use mesh_view::{
    COLOR_FORMAT, GpuMesh, MeshPipeline, MeshRenderer, MeshTarget, MeshView, Projection,
};

/// WGSL of a material module combined with a renderer's entry points.
fn shader_source(material_wgsl: &str, entry_points: &str) -> String {
    format!("{material_wgsl}\n{entry_points}")
}
