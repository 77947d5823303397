//! Buffers over a mesh's UV layout: the texels no triangle covers (between the layout's
//! islands and around them) take the value of the nearest covered texel, so that a
//! blur or a filtered read at an island's border reads the island, not the empty
//! background. The nearest covered texel of every texel is found once per mesh and
//! buffer size, by jump flooding from the covered texels.

use super::{GpuContext, GpuMesh, RenderError};
use std::sync::Mutex;
use wgpu::util::DeviceExt;

/// Each texel's nearest covered texel: its coordinates, or -1 where none is known yet.
const NEAREST_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rg32Sint;

/// The pipelines that find and fill the texels outside a mesh's UV islands.
pub struct Islands {
    module: wgpu::ShaderModule,
    seeds: wgpu::RenderPipeline,
    jump: wgpu::RenderPipeline,
    /// The fill pipeline for each buffer format met so far.
    fills: Mutex<Vec<(wgpu::TextureFormat, wgpu::RenderPipeline)>>,
}

impl Islands {
    /// Builds the pipelines that find the nearest covered texels.
    pub fn new(gpu: &GpuContext) -> Result<Islands, RenderError> {
        let source = concat!(
            include_str!("../../shaders/render_pass_vertex.wgsl"),
            include_str!("../../shaders/render_islands.wgsl")
        );
        let module = gpu.shader("uv islands", source)?;
        let seeds = gpu.checked("uv island seeds pipeline", || {
            super::target_pipeline(
                &gpu.device,
                "uv island seeds",
                &module,
                ("veneer_island_seed_vertex", "veneer_island_seed_fragment"),
                NEAREST_FORMAT,
                &[Some(GpuMesh::layout())],
            )
        })?;
        let jump = gpu.checked("uv island jump pipeline", || {
            super::fullscreen_pipeline(
                &gpu.device,
                "uv island jump",
                &module,
                ("veneer_pass_vertex", "veneer_island_jump_fragment"),
                NEAREST_FORMAT,
            )
        })?;
        Ok(Islands {
            module,
            seeds,
            jump,
            fills: Mutex::new(Vec::new()),
        })
    }

    /// The nearest covered texel of every texel of a `width`×`height` buffer over the UV
    /// layout of `mesh` (every texel -1 when the layout covers none).
    pub fn nearest(
        &self,
        gpu: &GpuContext,
        mesh: &GpuMesh,
        (width, height): (u32, u32),
    ) -> Result<wgpu::Texture, RenderError> {
        let texture = || {
            let usage =
                wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING;
            let label = "nearest uv island texel";
            super::plain_texture(&gpu.device, label, (width, height), NEAREST_FORMAT, usage)
        };
        let mut textures = [texture(), texture()];
        let none = wgpu::Color {
            r: -1.0,
            g: -1.0,
            b: 0.0,
            a: 0.0,
        };
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("uv islands"),
            });
        {
            let target = textures[0].create_view(&Default::default());
            let mut pass = super::tiles::clear_pass(&mut encoder, &target, none, None);
            pass.set_pipeline(&self.seeds);
            mesh.draw(&mut pass);
        }
        // Steps of half the larger side (rounded up to a power of two) down to one, and
        // one more of one texel, which mends most of jump flooding's rare misses.
        let mut steps = Vec::new();
        let mut step = width.max(height).next_power_of_two() / 2;
        while step >= 1 {
            steps.push(step);
            step /= 2;
        }
        steps.push(1);
        let layout = self.jump.get_bind_group_layout(0);
        for step in steps {
            let uniform = gpu
                .device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("uv island step"),
                    contents: bytemuck::cast_slice(&[step as i32, 0, 0, 0]),
                    usage: wgpu::BufferUsages::UNIFORM,
                });
            let read = textures[0].create_view(&Default::default());
            let group = super::uniform_and_texture_group(
                &gpu.device,
                "uv island step",
                &layout,
                &uniform,
                &read,
            );
            let target = textures[1].create_view(&Default::default());
            let mut pass = super::tiles::clear_pass(&mut encoder, &target, none, None);
            pass.set_pipeline(&self.jump);
            pass.set_bind_group(0, &group, &[]);
            pass.draw(0..3, 0..1);
            drop(pass);
            textures.swap(0, 1);
        }
        gpu.queue.submit([encoder.finish()]);
        gpu.take_errors()?;
        let [nearest, _] = textures;
        Ok(nearest)
    }

    /// Writes into `target` the texels of `source` (the same size and format), each
    /// texel no triangle covered taking the value of its nearest covered texel
    /// (`nearest`, from [`Islands::nearest`]).
    pub fn fill(
        &self,
        gpu: &GpuContext,
        nearest: &wgpu::Texture,
        source: &wgpu::Texture,
        target: &wgpu::Texture,
    ) -> Result<(), RenderError> {
        let format = target.format();
        let mut fills = self.fills.lock().expect("island fill pipelines");
        if !fills.iter().any(|(built, _)| *built == format) {
            let pipeline = gpu.checked("uv island fill pipeline", || {
                super::fullscreen_pipeline(
                    &gpu.device,
                    "uv island fill",
                    &self.module,
                    ("veneer_pass_vertex", "veneer_island_fill_fragment"),
                    format,
                )
            })?;
            fills.push((format, pipeline));
        }
        let (_, pipeline) = (fills.iter())
            .find(|(built, _)| *built == format)
            .expect("built above");
        let (nearest, source) = (
            nearest.create_view(&Default::default()),
            source.create_view(&Default::default()),
        );
        let group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("uv island fill"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&nearest),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::TextureView(&source),
                },
            ],
        });
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("uv island fill"),
            });
        {
            let target = target.create_view(&Default::default());
            let mut pass =
                super::tiles::clear_pass(&mut encoder, &target, wgpu::Color::TRANSPARENT, None);
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, &group, &[]);
            pass.draw(0..3, 0..1);
        }
        gpu.queue.submit([encoder.finish()]);
        gpu.take_errors()
    }
}
