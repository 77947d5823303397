//! The node thumbnails' atlas: one uniform-mode material module, compiled into one
//! pipeline, drawn into square tiles of one texture. Each tile has its own copy of the
//! parameter block (the editor's atlas graph uses it to pick which node the tile shows),
//! so a parameter edit rewrites buffers and never rebuilds the pipeline, and only the
//! tiles asked for are drawn (viewport and scissor per tile); the others keep their pixels.
//! A module that reads buffers has its passes rendered first, over the rectangle the
//! tiles sample at the preview's pass size, and again only where a parameter they read
//! changed (see [`PassRenderer`]); every tile reads the same buffers.

use super::params::ParamBlock;
use super::readback::Readback;
use super::{FlatRect, GpuContext, PassDomain, PassRenderer, RenderError, shader_source};
use crate::codegen::passes::Passes;
use std::sync::Arc;

/// The atlas texture's format: 8-bit RGBA, written without colour-space conversion.
const ATLAS_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// How tiles sit in the atlas: `columns` per row, each `tile` pixels square, `rows` rows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AtlasLayout {
    pub columns: u32,
    pub rows: u32,
    pub tile: u32,
}

impl AtlasLayout {
    /// A layout for `count` tiles of `tile` pixels, at most `columns` to a row.
    pub fn for_tiles(count: usize, columns: u32, tile: u32) -> AtlasLayout {
        let count = count.max(1) as u32;
        AtlasLayout {
            columns: columns.min(count),
            rows: count.div_ceil(columns),
            tile,
        }
    }

    /// The atlas size in pixels (width, height).
    pub fn size(&self) -> (u32, u32) {
        (self.columns * self.tile, self.rows * self.tile)
    }

    /// The top-left pixel of tile `index`.
    pub fn origin(&self, index: usize) -> (u32, u32) {
        let index = index as u32;
        (
            (index % self.columns) * self.tile,
            (index / self.columns) * self.tile,
        )
    }
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct ThumbnailView {
    rect: [f32; 4],
    plane_y: f32,
    time: f32,
    tile: f32,
    padding: f32,
}

const ENTRY_POINTS: &str = include_str!("../../shaders/render_thumbnails.wgsl");

/// One material's thumbnail pipeline and its atlas; build once per module, then draw
/// tiles as often as their parameters change.
pub struct ThumbnailRenderer {
    pipeline: wgpu::RenderPipeline,
    view_buffer: wgpu::Buffer,
    view_group: wgpu::BindGroup,
    /// Parameter slots of the module (one `vec4f` each).
    slots: usize,
    atlas: Option<(AtlasLayout, wgpu::Texture, Readback)>,
    /// The module's passes and the parameter block they read, when it reads buffers.
    passes: Option<(PassRenderer, Option<Arc<ParamBlock>>)>,
}

impl ThumbnailRenderer {
    /// Builds the pipeline for a uniform-mode material module with `slots` parameters,
    /// and those of its `passes` when it reads buffers.
    pub fn new(
        gpu: &GpuContext,
        material_wgsl: &str,
        slots: usize,
        passes: Option<&Passes>,
    ) -> Result<ThumbnailRenderer, RenderError> {
        let source = shader_source(material_wgsl, ENTRY_POINTS);
        let module = gpu.shader("node thumbnails", &source)?;
        let entry_points = ("veneer_thumbnail_vertex", "veneer_thumbnail_fragment");
        let pipeline = gpu.checked("node thumbnail pipeline", || {
            super::fullscreen_pipeline(
                &gpu.device,
                "node thumbnails",
                &module,
                entry_points,
                ATLAS_FORMAT,
            )
        })?;
        let view_buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("thumbnail view"),
            size: std::mem::size_of::<ThumbnailView>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let view_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("thumbnail view"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: view_buffer.as_entire_binding(),
            }],
        });
        let passes = match passes {
            Some(passes) => {
                let block = ParamBlock::new(gpu, slots).map(Arc::new);
                Some((PassRenderer::new(gpu, passes, block.as_ref())?, block))
            }
            None => None,
        };
        Ok(ThumbnailRenderer {
            pipeline,
            view_buffer,
            view_group,
            slots,
            atlas: None,
            passes,
        })
    }

    /// Draws `tiles` (tile index and that tile's parameter values, `slots` of them) into
    /// the atlas of `layout`, sampling `rect` at `time`, and returns the whole atlas as
    /// RGBA8 rows from the top-left. Tiles not drawn keep what they last showed (an
    /// atlas of a new layout starts black). The passes, if any, render first with the
    /// values `shared` (what every tile's values hold in the slots the passes read).
    pub fn render(
        &mut self,
        gpu: &GpuContext,
        layout: AtlasLayout,
        (rect, time): (FlatRect, f32),
        shared: &[[f32; 4]],
        tiles: &[(usize, Vec<[f32; 4]>)],
    ) -> Result<Vec<u8>, RenderError> {
        let buffers = match &self.passes {
            Some((passes, block)) => {
                if let Some(block) = block {
                    block.write(gpu, shared);
                }
                passes.render(gpu, PassDomain::Flat(rect), super::PREVIEW_PASS_SIZE, time)?;
                let reads = passes.reads();
                (!reads.is_empty()).then(|| passes.bind_group(gpu, &self.pipeline, reads))
            }
            None => None,
        };
        let size = layout.size();
        if self.atlas.as_ref().is_none_or(|(old, ..)| *old != layout) {
            let texture = super::plain_texture(
                &gpu.device,
                "thumbnail atlas",
                size,
                ATLAS_FORMAT,
                wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            );
            self.atlas = Some((layout, texture, Readback::new(gpu, size, 4)));
        }
        let (_, texture, readback) = self.atlas.as_ref().expect("made above");
        let view = ThumbnailView {
            rect: [rect.x0, rect.z0, rect.x1, rect.z1].map(|v| v as f32),
            plane_y: rect.y as f32,
            time,
            tile: layout.tile as f32,
            padding: 0.0,
        };
        gpu.queue
            .write_buffer(&self.view_buffer, 0, bytemuck::bytes_of(&view));
        // One buffer holds every drawn tile's parameter block, each at an offset the
        // device accepts for a uniform binding.
        let block = (self.slots.max(1) * 16) as u64;
        let alignment = u64::from(gpu.device.limits().min_uniform_buffer_offset_alignment);
        let stride = block.div_ceil(alignment) * alignment;
        let params = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("thumbnail parameters"),
            size: stride * tiles.len().max(1) as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut groups = Vec::with_capacity(tiles.len());
        for (k, (_, values)) in tiles.iter().enumerate() {
            let mut bytes: Vec<u8> = bytemuck::cast_slice(values).to_vec();
            bytes.resize(block as usize, 0);
            gpu.queue.write_buffer(&params, k as u64 * stride, &bytes);
            groups.push(gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("thumbnail parameters"),
                layout: &self.pipeline.get_bind_group_layout(1),
                entries: &[wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: &params,
                        offset: k as u64 * stride,
                        size: wgpu::BufferSize::new(block),
                    }),
                }],
            }));
        }
        let target = texture.create_view(&Default::default());
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("node thumbnails"),
            });
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("node thumbnails"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &target,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Load,
                        store: wgpu::StoreOp::Store,
                    },
                })],
                ..Default::default()
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &self.view_group, &[]);
            if let Some(buffers) = &buffers {
                pass.set_bind_group(2, buffers, &[]);
            }
            for ((index, _), group) in tiles.iter().zip(&groups) {
                let (x, y) = layout.origin(*index);
                let tile = layout.tile;
                pass.set_viewport(x as f32, y as f32, tile as f32, tile as f32, 0.0, 1.0);
                pass.set_scissor_rect(x, y, tile, tile);
                pass.set_bind_group(1, group, &[]);
                pass.draw(0..3, 0..1);
            }
        }
        readback.record_copy(&mut encoder, texture, size);
        let submission = gpu.queue.submit([encoder.finish()]);
        let mut pixels = Vec::with_capacity((size.0 * size.1 * 4) as usize);
        readback.read_rows(gpu, submission, size, |_, row| {
            pixels.extend_from_slice(row)
        })?;
        Ok(pixels)
    }
}
