//! The flat render: a material's outputs over a rectangle of the plane y = Y.

use super::readback::read_texture;
use super::{GpuContext, RenderError, shader_source};

/// The part of the plane y = `y` that the image covers: x from `x0` to `x1` left to
/// right, z from `z0` to `z1` top to bottom.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FlatRect {
    pub x0: f64,
    pub z0: f64,
    pub x1: f64,
    pub z1: f64,
    pub y: f64,
}

impl FlatRect {
    /// The surface position sampled at the centre of pixel (i, j) of an n×n image.
    pub fn sample_position(&self, i: u32, j: u32, n: u32) -> [f64; 3] {
        let (u, v) = (
            (f64::from(i) + 0.5) / f64::from(n),
            (f64::from(j) + 0.5) / f64::from(n),
        );
        [
            self.x0 + (self.x1 - self.x0) * u,
            self.y,
            self.z0 + (self.z1 - self.z0) * v,
        ]
    }
}

/// Which material outputs a flat render reads back, as four floats per pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FlatChannels {
    /// (albedo r, g, b, alpha): the `--flat` contract.
    AlbedoAlpha = 0,
    /// (specular r, g, b, shininess).
    SpecularShininess = 1,
    /// (height, bump x, y, z).
    HeightBump = 2,
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct FlatViewUniform {
    rect: [f32; 4],
    pixel_offset: [f32; 2],
    plane_y: f32,
    size: f32,
    time: f32,
    channels: u32,
    padding: [f32; 2],
}

/// f32 bits in an integer target: renderable on every backend (GL has no float targets).
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Uint;
const ENTRY_POINTS: &str = include_str!("../../shaders/render_flat.wgsl");

/// A pipeline that renders one material flat; build once, render many times.
pub struct FlatRenderer {
    pipeline: wgpu::RenderPipeline,
    uniform: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
}

impl FlatRenderer {
    /// Builds the pipeline for a material module (the output of `veneer compile`).
    pub fn new(gpu: &GpuContext, material_wgsl: &str) -> Result<FlatRenderer, RenderError> {
        let module = gpu.shader("flat render", &shader_source(material_wgsl, ENTRY_POINTS))?;
        let uniform = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("flat view"),
            size: std::mem::size_of::<FlatViewUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let entry_points = ("veneer_flat_vertex", "veneer_flat_fragment");
        let pipeline = gpu.checked("flat render pipeline", || {
            super::fullscreen_pipeline(&gpu.device, "flat render", &module, entry_points, FORMAT)
        })?;
        let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("flat view"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: uniform.as_entire_binding(),
            }],
        });
        Ok(FlatRenderer {
            pipeline,
            uniform,
            bind_group,
        })
    }

    /// Renders an n×n image of RGBA (albedo, alpha) in f32, row by row from the top-left,
    /// in tiles no larger than the adapter allows.
    pub fn render(
        &self,
        gpu: &GpuContext,
        rect: FlatRect,
        size: u32,
        time: f32,
    ) -> Result<Vec<[f32; 4]>, RenderError> {
        self.render_channels(gpu, rect, size, time, FlatChannels::AlbedoAlpha, |_, _| {})
    }

    /// Renders an n×n image of `channels` in tiles of at most 2048², calling
    /// `progress(tiles done, tiles in all)` after each.
    pub fn render_channels(
        &self,
        gpu: &GpuContext,
        rect: FlatRect,
        size: u32,
        time: f32,
        channels: FlatChannels,
        mut progress: impl FnMut(u32, u32),
    ) -> Result<Vec<[f32; 4]>, RenderError> {
        if size == 0 {
            return Err(RenderError("image size must be at least 1 pixel".into()));
        }
        let tile = gpu.device.limits().max_texture_dimension_2d.min(2048);
        let tiles_per_side = size.div_ceil(tile);
        let mut image = vec![[0.0f32; 4]; size as usize * size as usize];
        let mut done = 0;
        for tile_y in (0..size).step_by(tile as usize) {
            for tile_x in (0..size).step_by(tile as usize) {
                let (width, height) = (tile.min(size - tile_x), tile.min(size - tile_y));
                let view = FlatViewUniform {
                    rect: [
                        rect.x0 as f32,
                        rect.z0 as f32,
                        rect.x1 as f32,
                        rect.z1 as f32,
                    ],
                    pixel_offset: [tile_x as f32, tile_y as f32],
                    plane_y: rect.y as f32,
                    size: size as f32,
                    time,
                    channels: channels as u32,
                    padding: [0.0; 2],
                };
                let pixels = self.render_tile(gpu, &view, (width, height))?;
                for (row, chunk) in pixels.chunks(width as usize).enumerate() {
                    let start = (tile_y as usize + row) * size as usize + tile_x as usize;
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
        view: &FlatViewUniform,
        extent: (u32, u32),
    ) -> Result<Vec<[f32; 4]>, RenderError> {
        gpu.queue
            .write_buffer(&self.uniform, 0, bytemuck::bytes_of(view));
        let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("flat target"),
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
                label: Some("flat"),
            });
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("flat"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &target,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                ..Default::default()
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &self.bind_group, &[]);
            pass.draw(0..3, 0..1);
        }
        gpu.queue.submit([encoder.finish()]);
        let bytes = read_texture(gpu, &texture, 16)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }
}

/// The contract's 8-bit encoding of the albedo: round(255 · clamp(v, 0, 1)) per channel, RGB.
pub fn albedo_to_rgb8(pixels: &[[f32; 4]]) -> Vec<u8> {
    pixels
        .iter()
        .flat_map(|p| [p[0], p[1], p[2]])
        .map(|v| (255.0 * v.clamp(0.0, 1.0)).round() as u8)
        .collect()
}
