//! The flat render: a material's outputs over a rectangle of the plane y = Y.

use super::params::ParamBlock;
use super::passes::PassRenderer;
use super::tiles::{FORMAT, TileDraw, clear_pass, render_bands, render_tiled};
use super::timing::time_pass;
use super::{GpuContext, RenderError, shader_source};
use crate::codegen::Compiled;
use crate::codegen::passes::Passes;
use std::sync::{Arc, Mutex};

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
    /// Refuses a rectangle the GPU cannot sample: the shader works in f32, where a
    /// coordinate or a span beyond its range becomes infinite and the image uniform.
    pub fn validate(&self) -> Result<(), String> {
        let fits = |v: f64| v.is_finite() && v.abs() <= f64::from(f32::MAX);
        let values = [self.x0, self.z0, self.x1, self.z1, self.y];
        if !values.into_iter().all(fits) {
            return Err(
                "the rectangle must be finite numbers within the f32 range (±3.4e38)".into(),
            );
        }
        if !(fits(self.x1 - self.x0) && fits(self.z1 - self.z0)) {
            return Err("the rectangle's width or depth overflows f32".into());
        }
        Ok(())
    }

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
    /// (height, bump x, y, z plus the tangent-space normal's tilt).
    HeightBump = 2,
    /// (metallic, roughness, occlusion, shininess).
    MetallicRoughness = 3,
    /// (emission × emission strength, 0).
    Emission = 4,
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
    /// 1 when the surface uv is the pixel's place in the rectangle (the domain
    /// coordinate of a multi-pass material), 0 for the contract's uv 0.
    domain_uv: u32,
    padding: f32,
}

const ENTRY_POINTS: &str = concat!(
    include_str!("../../shaders/render_tangent.wgsl"),
    include_str!("../../shaders/render_channels.wgsl"),
    include_str!("../../shaders/render_flat.wgsl")
);

/// A pipeline that renders one material flat; build once, render many times.
pub struct FlatRenderer {
    pipeline: wgpu::RenderPipeline,
    uniform: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    /// The passes of a multi-pass material, rendered before the material.
    passes: Option<PassRenderer>,
    /// The parameter values of a material compiled with slots, and their bind group at
    /// group 1 of the material's pipeline (when its module reads them).
    params: Option<(Arc<ParamBlock>, Option<wgpu::BindGroup>)>,
    /// The material's buffers, bound at group 2 (multi-pass materials).
    buffers: Mutex<Option<wgpu::BindGroup>>,
    /// The output size the passes render for, whatever the image's (`None`: the image's).
    pass_size: Option<u32>,
}

impl FlatRenderer {
    /// Builds the pipelines of a compiled material and of its passes, if it has any.
    pub fn for_compiled(
        gpu: &GpuContext,
        compiled: &Compiled,
    ) -> Result<FlatRenderer, RenderError> {
        let module = &compiled.module;
        let passes = (!compiled.passes.is_empty()).then_some(&compiled.passes);
        FlatRenderer::with_passes(
            gpu,
            &module.source,
            module.params.len(),
            module.binds_params,
            passes,
        )
    }

    /// Builds the pipelines of a material module with `slots` parameter slots (read by
    /// the module itself when `binds_params`; set with [`FlatRenderer::write_params`])
    /// and of its passes.
    pub fn with_passes(
        gpu: &GpuContext,
        material_wgsl: &str,
        slots: usize,
        binds_params: bool,
        passes: Option<&Passes>,
    ) -> Result<FlatRenderer, RenderError> {
        let mut renderer = FlatRenderer::new(gpu, material_wgsl)?;
        let block = ParamBlock::new(gpu, slots).map(Arc::new);
        if let Some(passes) = passes {
            renderer.passes = Some(PassRenderer::new(gpu, passes, block.as_ref())?);
        }
        renderer.params = block.map(|block| {
            let group = binds_params.then(|| block.bind_group(gpu, &renderer.pipeline));
            (block, group)
        });
        Ok(renderer)
    }

    /// Sets the values of the parameter slots (a material compiled with slots); the
    /// passes that read a changed slot render again at the next render.
    pub fn write_params(&self, gpu: &GpuContext, values: &[[f32; 4]]) {
        if let Some((block, _)) = &self.params {
            block.write(gpu, values);
        }
    }

    /// Renders the passes for an output of `size` pixels whatever the size of the
    /// image asked for (`None`: the image's), so that pictures of any size show the
    /// same buffers.
    pub fn set_pass_size(&mut self, size: Option<u32>) {
        self.pass_size = size;
    }

    /// The bytes of textures the passes hold at once for an output of `size` pixels (0
    /// for a single-pass material).
    pub fn pass_bytes(&self, size: u32) -> u64 {
        let size = self.pass_size.unwrap_or(size);
        self.passes
            .as_ref()
            .map_or(0, |passes| passes.buffer_bytes(size))
    }

    /// The seams of the wrapped surface passes last rendered over `rect` at `time` (by
    /// a render of `rect`; see [`PassRenderer::wrap_seams`]): none for a single-pass
    /// material.
    pub fn wrap_seams(
        &self,
        gpu: &GpuContext,
        rect: FlatRect,
        time: f32,
    ) -> Result<Vec<super::WrapSeam>, RenderError> {
        match &self.passes {
            Some(passes) => passes.wrap_seams(gpu, rect, time),
            None => Ok(Vec::new()),
        }
    }

    /// How many passes have rendered so far (0 for a single-pass material).
    pub fn passes_rendered(&self) -> u64 {
        self.passes
            .as_ref()
            .map_or(0, PassRenderer::passes_rendered)
    }

    /// Renders the passes for an output of size² pixels over `rect` (when the material
    /// has passes and they are not rendered for these already) and binds their buffers.
    fn prepare(
        &self,
        gpu: &GpuContext,
        rect: FlatRect,
        size: u32,
        time: f32,
    ) -> Result<(), RenderError> {
        rect.validate().map_err(RenderError::Invalid)?;
        let Some(passes) = &self.passes else {
            return Ok(());
        };
        passes.render(
            gpu,
            super::PassDomain::Flat(rect),
            self.pass_size.unwrap_or(size),
            time,
        )?;
        let reads = passes.reads();
        let group = (!reads.is_empty()).then(|| passes.bind_group(gpu, &self.pipeline, reads));
        *self.buffers.lock().expect("flat buffers") = group;
        Ok(())
    }

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
            passes: None,
            params: None,
            buffers: Mutex::new(None),
            pass_size: None,
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
        progress: impl FnMut(u32, u32),
    ) -> Result<Vec<[f32; 4]>, RenderError> {
        self.prepare(gpu, rect, size, time)?;
        let draw = self.tile_draw(gpu, rect, size, time, channels);
        render_tiled(gpu, size, draw, progress)
    }

    /// How each tile of a size×size render of `channels` over `rect` is drawn.
    fn tile_draw<'a>(
        &'a self,
        gpu: &'a GpuContext,
        rect: FlatRect,
        size: u32,
        time: f32,
        channels: FlatChannels,
    ) -> TileDraw<impl FnMut((u32, u32), (u32, u32)) + 'a, impl FnMut(&mut wgpu::RenderPass<'_>) + 'a>
    {
        TileDraw {
            clear: wgpu::Color::TRANSPARENT,
            prepare: move |offset: (u32, u32), _| {
                let offset = [offset.0 as f32, offset.1 as f32];
                self.write_view(gpu, rect, size, time, channels, offset)
            },
            draw: |pass: &mut wgpu::RenderPass<'_>| self.draw(pass),
        }
    }

    /// Renders an n×n image of `channels` in bands of `band_rows` full-width rows, handing
    /// each band to `band(first row, pixels)` in order, which returns a buffer to fill
    /// later (see [`render_bands`]): the whole image is never held at once.
    #[allow(clippy::too_many_arguments)]
    pub fn render_channel_bands(
        &self,
        gpu: &GpuContext,
        rect: FlatRect,
        size: u32,
        time: f32,
        channels: FlatChannels,
        band_rows: u32,
        progress: impl FnMut(u32, u32),
        band: impl FnMut(u32, Vec<[f32; 4]>) -> Result<Vec<[f32; 4]>, RenderError>,
    ) -> Result<(), RenderError> {
        self.prepare(gpu, rect, size, time)?;
        let draw = self.tile_draw(gpu, rect, size, time, channels);
        render_bands(gpu, size, band_rows, draw, progress, band)
    }

    /// The time the GPU takes to shade a size×size image (at most one tile), without
    /// reading it back: the pass time from timestamp queries where the device has them,
    /// else the wall time from submitting the pass to its completion.
    pub fn shading_time(
        &self,
        gpu: &GpuContext,
        rect: FlatRect,
        size: u32,
        time: f32,
    ) -> Result<std::time::Duration, RenderError> {
        self.prepare(gpu, rect, size, time)?;
        time_pass(gpu, size, |encoder, writes| {
            self.write_view(gpu, rect, size, time, FlatChannels::AlbedoAlpha, [0.0; 2]);
            let target = super::tiles::target_texture(&gpu.device, (size, size))
                .create_view(&Default::default());
            let mut pass = clear_pass(encoder, &target, wgpu::Color::TRANSPARENT, writes);
            self.draw(&mut pass);
        })
    }

    /// Renders the `extent` pixels from `origin` of the size×size pixel grid over `rect`,
    /// which may reach past the image's edges (pixel (-1, j) lies one pixel spacing left
    /// of the image, as if the grid went on): four f32 per pixel of `channels`, row by
    /// row, in pieces no larger than a tile. A tile check renders the rows and columns
    /// just beyond a bake's edges this way.
    #[allow(clippy::too_many_arguments)]
    pub fn render_region(
        &self,
        gpu: &GpuContext,
        rect: FlatRect,
        size: u32,
        time: f32,
        channels: FlatChannels,
        origin: (i64, i64),
        extent: (u32, u32),
    ) -> Result<Vec<[f32; 4]>, RenderError> {
        self.prepare(gpu, rect, size, time)?;
        let mut pixels = vec![[0.0f32; 4]; extent.0 as usize * extent.1 as usize];
        let tile = super::tile_size(gpu);
        for (at, part) in super::tiles::tile_grid(extent, (tile, tile)) {
            let offset = [
                (origin.0 + i64::from(at.0)) as f32,
                (origin.1 + i64::from(at.1)) as f32,
            ];
            self.write_view(gpu, rect, size, time, channels, offset);
            let texture = super::tiles::target_texture(&gpu.device, part);
            let mut encoder = gpu
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("region"),
                });
            {
                let view = texture.create_view(&Default::default());
                let mut pass = clear_pass(&mut encoder, &view, wgpu::Color::TRANSPARENT, None);
                self.draw(&mut pass);
            }
            gpu.queue.submit([encoder.finish()]);
            let bytes = super::readback::read_texture(gpu, &texture, 16)?;
            let rows: &[[f32; 4]] = bytemuck::cast_slice(&bytes);
            super::tiles::paste(&mut pixels, extent.0, at, part.0, rows);
        }
        Ok(pixels)
    }

    fn write_view(
        &self,
        gpu: &GpuContext,
        rect: FlatRect,
        size: u32,
        time: f32,
        channels: FlatChannels,
        offset: [f32; 2],
    ) {
        let view = FlatViewUniform {
            rect: [
                rect.x0 as f32,
                rect.z0 as f32,
                rect.x1 as f32,
                rect.z1 as f32,
            ],
            pixel_offset: offset,
            plane_y: rect.y as f32,
            size: size as f32,
            time,
            channels: channels as u32,
            domain_uv: u32::from(self.passes.is_some()),
            padding: 0.0,
        };
        gpu.queue
            .write_buffer(&self.uniform, 0, bytemuck::bytes_of(&view));
    }

    fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.bind_group, &[]);
        if let Some((_, Some(params))) = &self.params {
            pass.set_bind_group(1, params, &[]);
        }
        if let Some(buffers) = self.buffers.lock().expect("flat buffers").as_ref() {
            pass.set_bind_group(2, buffers, &[]);
        }
        pass.draw(0..3, 0..1);
    }
}

/// Why `pixels` (whole rows of a `width`-wide image of `what`, a map's name, the first of
/// them image row `first_row`) must not be written, if a sample is NaN or infinite: every
/// node's output is finite, so this is a bug, and the writers refuse it loudly rather
/// than store an infinity or a black pixel.
pub fn non_finite(
    what: &str,
    pixels: &[[f32; 4]],
    width: usize,
    first_row: usize,
) -> Option<String> {
    let index = pixels
        .iter()
        .position(|p| !p.iter().all(|v| v.is_finite()))?;
    let (x, y) = (index % width.max(1), first_row + index / width.max(1));
    Some(format!(
        "the {what} map holds a non-finite value {:?} at pixel ({x}, {y}); nothing was written",
        pixels[index]
    ))
}

/// The contract's 8-bit encoding of the albedo: round(255 · clamp(v, 0, 1)) per channel, RGB.
pub fn albedo_to_rgb8(pixels: &[[f32; 4]]) -> Vec<u8> {
    pixels
        .iter()
        .flat_map(|p| [p[0], p[1], p[2]])
        .map(|v| (255.0 * v.clamp(0.0, 1.0)).round() as u8)
        .collect()
}

/// The flat render's sample positions over `rect` at size×size, rows from the top,
/// computed in f32 as `shaders/render_flat.wgsl` computes them (so the CPU evaluator can
/// see exactly the GPU's points).
pub fn flat_points(rect: FlatRect, size: u32) -> Vec<[f64; 3]> {
    let mut points = Vec::with_capacity((size * size) as usize);
    for j in 0..size {
        for i in 0..size {
            let t = [
                (i as f32 + 0.5) / size as f32,
                (j as f32 + 0.5) / size as f32,
            ];
            let x = rect.x0 as f32 + (rect.x1 as f32 - rect.x0 as f32) * t[0];
            let z = rect.z0 as f32 + (rect.z1 as f32 - rect.z0 as f32) * t[1];
            points.push([f64::from(x), rect.y, f64::from(z)]);
        }
    }
    points
}
