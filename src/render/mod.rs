//! wgpu rendering: a headless context on any adapter, the flat albedo render, the
//! lit mesh render, and readback to images.

mod context;
mod draft_scale;
mod environment;
mod flat;
mod gpu_mesh;
mod image;
mod islands;
mod live;
mod mesh_render;
mod mesh_view;
mod params;
mod passes;
mod readback;
mod tessellation;
mod thumbnails;
mod tiles;
mod timing;
mod tone_map;
mod uv_bake;

pub use context::{GpuContext, RenderError};
pub use draft_scale::DraftScale;
pub use environment::{
    Environment, EnvironmentError, EnvironmentMaps, SKY, direction_of, equirect_uv,
};
pub use flat::{FlatChannels, FlatRect, FlatRenderer, albedo_to_rgb8, flat_points, non_finite};
pub use gpu_mesh::GpuMesh;
pub use image::{
    Image, MeshLook, Rendered, View, baked_parameters, mesh_passes, mesh_with_fields, preview_rect,
    render_material, render_material_with, texture_placement,
};
pub use live::{LiveMaterialCode, LiveRenderer, PREVIEW_PASS_SIZE, Quality};
pub use mesh_render::MeshRenderer;
pub use mesh_view::{
    Backdrop, COLOR_FORMAT, DEFAULT_KEY_LIGHT, MeshPipeline, MeshTarget, MeshView, Projection,
    Relief,
};
pub use passes::seams::WrapSeam;
pub use passes::{PassDomain, PassRenderer};
pub use readback::read_texture;
pub use tessellation::{Tessellated, tessellate};
pub use thumbnails::{AtlasLayout, ThumbnailRenderer};
pub use tiles::{ensure_memory, tile_size};
pub use timing::PassTimer;
pub use tone_map::ToneMap;
pub use uv_bake::{TexelFields, UvRenderer};

/// A single-level, single-sample 2D texture of `size` texels.
pub fn plain_texture(
    device: &wgpu::Device,
    label: &str,
    (width, height): (u32, u32),
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    })
}

/// A bind group of `layout` holding `uniform` at binding 0 and `texture` at binding 1.
fn uniform_and_texture_group(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    uniform: &wgpu::Buffer,
    texture: &wgpu::TextureView,
) -> wgpu::BindGroup {
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: uniform.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::TextureView(texture),
            },
        ],
    })
}

/// WGSL of a material module combined with a renderer's entry points.
fn shader_source(material_wgsl: &str, entry_points: &str) -> String {
    // A module written by hand, or exported before modules declared the fields flat
    // views pass, passes 0 in every lane.
    let flat_fields = match material_wgsl.contains("const VENEER_FLAT_FIELDS") {
        true => "",
        false => "const VENEER_FLAT_FIELDS = vec4f(0.0);\n",
    };
    format!("{material_wgsl}\n{flat_fields}{entry_points}")
}

/// A pipeline drawing one full-viewport triangle (no vertex buffers, no depth) with the
/// given entry points of `module` into a single target of `format`.
pub fn fullscreen_pipeline(
    device: &wgpu::Device,
    label: &str,
    module: &wgpu::ShaderModule,
    entry_points: (&str, &str),
    format: wgpu::TextureFormat,
) -> wgpu::RenderPipeline {
    target_pipeline(device, label, module, entry_points, format, &[])
}

/// A pipeline without depth or blending drawing `buffers` (`[Some(GpuMesh::layout())]`
/// for meshes, drawn at their texture coordinates by UV-layout renders) with the given
/// entry points of `module` into a single target of `format`.
pub fn target_pipeline(
    device: &wgpu::Device,
    label: &str,
    module: &wgpu::ShaderModule,
    entry_points: (&str, &str),
    format: wgpu::TextureFormat,
    buffers: &[Option<wgpu::VertexBufferLayout<'_>>],
) -> wgpu::RenderPipeline {
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: None,
        vertex: wgpu::VertexState {
            module,
            entry_point: Some(entry_points.0),
            compilation_options: Default::default(),
            buffers,
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: None,
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some(entry_points.1),
            compilation_options: Default::default(),
            targets: &[Some(format.into())],
        }),
        multiview_mask: None,
        cache: None,
    })
}
