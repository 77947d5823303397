//! UV-layout rendering: a material evaluated over a mesh's texture layout, for baking
//! maps that wrap onto that mesh.

use super::mesh_view::GpuMesh;
use super::readback::read_texture;
use super::{FlatChannels, GpuContext, RenderError, shader_source};

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct UvViewUniform {
    placement: [f32; 4],
    tile: [f32; 4],
    size: f32,
    time: f32,
    channels: u32,
    padding: u32,
}

const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Uint;
const ENTRY_POINTS: &str = include_str!("../../shaders/render_uv.wgsl");

/// A pipeline that renders one material over meshes' UV layouts.
pub struct UvRenderer {
    pipeline: wgpu::RenderPipeline,
    uniform: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
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
            gpu.device
                .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                    label: Some("uv bake"),
                    layout: None,
                    vertex: wgpu::VertexState {
                        module: &module,
                        entry_point: Some("veneer_uv_vertex"),
                        compilation_options: Default::default(),
                        buffers: &[Some(GpuMesh::layout())],
                    },
                    primitive: wgpu::PrimitiveState::default(),
                    depth_stencil: None,
                    multisample: wgpu::MultisampleState::default(),
                    fragment: Some(wgpu::FragmentState {
                        module: &module,
                        entry_point: Some("veneer_uv_fragment"),
                        compilation_options: Default::default(),
                        targets: &[Some(FORMAT.into())],
                    }),
                    multiview_mask: None,
                    cache: None,
                })
        })?;
        let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("uv view"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: uniform.as_entire_binding(),
            }],
        });
        Ok(UvRenderer {
            pipeline,
            uniform,
            bind_group,
        })
    }

    /// Renders `channels` over the UV layout of `mesh` (placed in texture space at
    /// `center` with `size`) into a `texels`² map, in tiles of at most 2048². Texels no
    /// triangle covers are NaN.
    #[allow(clippy::too_many_arguments)]
    pub fn render_channels(
        &self,
        gpu: &GpuContext,
        mesh: &GpuMesh,
        placement: ([f32; 3], f32),
        texels: u32,
        time: f32,
        channels: FlatChannels,
        mut progress: impl FnMut(u32, u32),
    ) -> Result<Vec<[f32; 4]>, RenderError> {
        if texels == 0 {
            return Err(RenderError("map size must be at least 1 texel".into()));
        }
        let tile = gpu.device.limits().max_texture_dimension_2d.min(2048);
        let tiles_per_side = texels.div_ceil(tile);
        let mut image = vec![[f32::NAN; 4]; texels as usize * texels as usize];
        let mut done = 0;
        for tile_y in (0..texels).step_by(tile as usize) {
            for tile_x in (0..texels).step_by(tile as usize) {
                let (width, height) = (tile.min(texels - tile_x), tile.min(texels - tile_y));
                let view = UvViewUniform {
                    placement: [placement.0[0], placement.0[1], placement.0[2], placement.1],
                    tile: [tile_x as f32, tile_y as f32, width as f32, height as f32],
                    size: texels as f32,
                    time,
                    channels: channels as u32,
                    padding: 0,
                };
                let pixels = self.render_tile(gpu, mesh, &view, (width, height))?;
                for (row, chunk) in pixels.chunks(width as usize).enumerate() {
                    let start = (tile_y as usize + row) * texels as usize + tile_x as usize;
                    image[start..start + width as usize].copy_from_slice(chunk);
                }
                done += 1;
                progress(done, tiles_per_side * tiles_per_side);
            }
        }
        Ok(image)
    }

    fn render_tile(
        &self,
        gpu: &GpuContext,
        mesh: &GpuMesh,
        view: &UvViewUniform,
        extent: (u32, u32),
    ) -> Result<Vec<[f32; 4]>, RenderError> {
        gpu.queue
            .write_buffer(&self.uniform, 0, bytemuck::bytes_of(view));
        let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("uv target"),
            size: wgpu::Extent3d {
                width: extent.0,
                height: extent.1,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let target = texture.create_view(&Default::default());
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("uv bake"),
            });
        {
            // All bits set: reads back as NaN, "no triangle here".
            let uncovered = wgpu::Color {
                r: 4294967295.0,
                g: 4294967295.0,
                b: 4294967295.0,
                a: 4294967295.0,
            };
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("uv bake"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &target,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(uncovered),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                ..Default::default()
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &self.bind_group, &[]);
            mesh.draw(&mut pass);
        }
        gpu.queue.submit([encoder.finish()]);
        let bytes = read_texture(gpu, &texture, 16)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }
}
