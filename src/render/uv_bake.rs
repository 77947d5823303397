//! UV-layout rendering: a material evaluated over a mesh's texture layout, for baking
//! maps that wrap onto that mesh.

use super::GpuMesh;
use super::tiles::{FORMAT, NAN_BITS, TileDraw, render_tiled};
use super::{FlatChannels, GpuContext, RenderError, shader_source};

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct UvViewUniform {
    placement: [f32; 4],
    tile: [f32; 4],
    size: f32,
    time: f32,
    channels: u32,
    /// Bit k: lane k of the fields comes from the texel fields.
    texel_lanes: u32,
}

const ENTRY_POINTS: &str = concat!(
    include_str!("../../shaders/render_tangent.wgsl"),
    include_str!("../../shaders/render_channels.wgsl"),
    include_str!("../../shaders/render_uv.wgsl")
);

/// Mesh fields per texel of a UV layout, which a UV render reads in place of the
/// vertices' interpolated values in some lanes.
pub struct TexelFields {
    /// The width and height of `texels`; a render of another size reads them nearest.
    pub size: u32,
    /// Every texel's four lanes, rows from the top; every texel a triangle may cover
    /// holds a finite value.
    pub texels: Vec<[f32; 4]>,
    /// Which lanes the texels hold.
    pub lanes: [bool; 4],
}

/// A pipeline that renders one material over meshes' UV layouts.
pub struct UvRenderer {
    pipeline: wgpu::RenderPipeline,
    uniform: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    /// The lanes the bound texel fields hold, as bits.
    texel_lanes: u32,
    /// The files the material reads at group 2 (see [`UvRenderer::bind_uploads`]).
    buffers: Option<wgpu::BindGroup>,
}

impl UvRenderer {
    /// Builds the pipeline for a material module with baked parameters.
    pub fn new(gpu: &GpuContext, material_wgsl: &str) -> Result<UvRenderer, RenderError> {
        let module = gpu.shader("uv bake", &shader_source(material_wgsl, ENTRY_POINTS))?;
        let uniform = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("uv view"),
            size: std::mem::size_of::<UvViewUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let pipeline = gpu.checked("uv bake pipeline", || {
            super::target_pipeline(
                &gpu.device,
                "uv bake",
                &module,
                ("veneer_uv_vertex", "veneer_uv_fragment"),
                FORMAT,
                &[Some(GpuMesh::layout())],
            )
        })?;
        let none = TexelFields {
            size: 1,
            texels: vec![[0.0; 4]],
            lanes: [false; 4],
        };
        let bind_group = view_group(gpu, &pipeline, &uniform, &none);
        Ok(UvRenderer {
            pipeline,
            uniform,
            bind_group,
            texel_lanes: 0,
            buffers: None,
        })
    }

    /// Reads the lanes of `fields` from its texels from now on.
    pub fn set_texel_fields(&mut self, gpu: &GpuContext, fields: &TexelFields) {
        self.bind_group = view_group(gpu, &self.pipeline, &self.uniform, fields);
        self.texel_lanes = (fields.lanes.iter().enumerate())
            .filter(|(_, on)| **on)
            .fold(0, |bits, (lane, _)| bits | 1 << lane);
    }

    /// Binds the buffers a multi-pass material reads, as `passes` last rendered them
    /// (over the mesh's UV layout: see [`super::mesh_passes`]).
    pub fn bind_passes(&mut self, gpu: &GpuContext, passes: &super::PassRenderer) {
        self.buffers = Some(passes.bind_group(gpu, &self.pipeline, passes.reads()));
    }

    /// Renders `channels` over the UV layout of `mesh` (placed in texture space at
    /// `placement`: centre and size) into a `texels`² map, in tiles of at most 2048².
    /// Texels no triangle covers are NaN.
    #[allow(clippy::too_many_arguments)]
    pub fn render_channels(
        &self,
        gpu: &GpuContext,
        mesh: &GpuMesh,
        placement: ([f32; 3], f32),
        texels: u32,
        time: f32,
        channels: FlatChannels,
        progress: impl FnMut(u32, u32),
    ) -> Result<Vec<[f32; 4]>, RenderError> {
        let prepare = |offset: (u32, u32), extent: (u32, u32)| {
            let view = UvViewUniform {
                placement: [placement.0[0], placement.0[1], placement.0[2], placement.1],
                tile: [
                    offset.0 as f32,
                    offset.1 as f32,
                    extent.0 as f32,
                    extent.1 as f32,
                ],
                size: texels as f32,
                time,
                channels: channels as u32,
                texel_lanes: self.texel_lanes,
            };
            gpu.queue
                .write_buffer(&self.uniform, 0, bytemuck::bytes_of(&view));
        };
        let draw = |pass: &mut wgpu::RenderPass<'_>| {
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &self.bind_group, &[]);
            if let Some(buffers) = &self.buffers {
                pass.set_bind_group(2, buffers, &[]);
            }
            mesh.draw(pass);
        };
        let tiles_draw = TileDraw {
            // NaN bits: "no triangle here".
            clear: NAN_BITS,
            prepare,
            draw,
        };
        render_tiled(gpu, texels, tiles_draw, progress)
    }
}

/// The view's bind group: the uniform and `fields` uploaded as a float texture.
fn view_group(
    gpu: &GpuContext,
    pipeline: &wgpu::RenderPipeline,
    uniform: &wgpu::Buffer,
    fields: &TexelFields,
) -> wgpu::BindGroup {
    let texture = super::plain_texture(
        &gpu.device,
        "texel fields",
        (fields.size, fields.size),
        wgpu::TextureFormat::Rgba32Float,
        wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
    );
    gpu.queue.write_texture(
        texture.as_image_copy(),
        bytemuck::cast_slice(&fields.texels),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(fields.size * 16),
            rows_per_image: Some(fields.size),
        },
        texture.size(),
    );
    let view = texture.create_view(&Default::default());
    let layout = pipeline.get_bind_group_layout(0);
    super::uniform_and_texture_group(&gpu.device, "uv view", &layout, uniform, &view)
}
