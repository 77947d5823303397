//! The GPU side of a multi-pass material over a flat domain: a pipeline per pass, and
//! the buffers they render, in order, for one rectangle, output size and time. The
//! buffers are kept: a pass renders again only when the domain changes, a parameter
//! slot it reads changes, or a buffer it reads rendered again. A buffer read only by the
//! stage after it (the inside of a jump flood's chain of steps) lives in one of two
//! scratch textures that the chain's steps take turns with.

use super::params::ParamBlock;
use super::{FlatRect, GpuContext, RenderError, shader_source};
use crate::codegen::passes::{PassKind, Passes, STAGE_ENTRY_POINTS, SURFACE_ENTRY_POINTS};
use crate::nodes::passes::BufferFormat;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct PassViewUniform {
    rect: [f32; 4],
    size: [f32; 2],
    plane_y: f32,
    time: f32,
}

/// The texture format a buffer of `format` renders into.
fn texture_format(format: BufferFormat) -> wgpu::TextureFormat {
    match format {
        BufferFormat::Unorm8 => wgpu::TextureFormat::Rgba8Unorm,
        BufferFormat::Float16 => wgpu::TextureFormat::Rgba16Float,
        BufferFormat::Float32 => wgpu::TextureFormat::Rgba32Float,
    }
}

/// What the buffers were last rendered for: rectangle, output size and time.
type RenderedFor = ([u32; 5], u32, u32);

/// The most bytes of textures a material's passes may hold at once.
pub const MAX_PASS_BYTES: u64 = 4 << 30;

/// The buffers as last rendered: for what domain, and with which values of its
/// parameter slots each pass.
struct Rendered {
    domain: RenderedFor,
    /// One texture per storage slot (see [`PassRenderer::storage`]).
    textures: Vec<wgpu::Texture>,
    values: Vec<Vec<[f32; 4]>>,
}

/// A material's passes, built once, each rendered again only when what it reads changes.
pub struct PassRenderer {
    passes: Passes,
    /// The pipeline of each pass (none for an uploaded bitmap).
    pipelines: Vec<Option<wgpu::RenderPipeline>>,
    /// The parameter values, and their bind group at group 1 of each pass that reads them.
    block: Option<Arc<ParamBlock>>,
    params: Vec<Option<wgpu::BindGroup>>,
    view: wgpu::Buffer,
    /// The texture each pass renders into: its own, or a scratch texture shared by the
    /// buffers only the next stage reads.
    storage: Vec<usize>,
    /// The pass whose buffer settings each texture takes.
    slot_specs: Vec<usize>,
    rendered: Mutex<Option<Rendered>>,
    /// Passes rendered so far (for tests and reports).
    renders: AtomicU64,
}

impl PassRenderer {
    /// Builds a pipeline per pass of `passes`, those that read parameter slots reading
    /// them from `params`.
    pub fn new(
        gpu: &GpuContext,
        passes: &Passes,
        params: Option<&Arc<ParamBlock>>,
    ) -> Result<PassRenderer, RenderError> {
        let mut pipelines = Vec::with_capacity(passes.passes.len());
        for pass in &passes.passes {
            let entry_points = match pass.kind {
                PassKind::Surface { .. } => SURFACE_ENTRY_POINTS,
                PassKind::Stage { .. } => STAGE_ENTRY_POINTS,
                PassKind::Bitmap { .. } => {
                    // Uploaded, not rendered.
                    pipelines.push(None);
                    continue;
                }
            };
            let module = pass.module().expect("a rendered pass has a module");
            let source = shader_source(&module.source, entry_points);
            let module = gpu.shader(&pass.label, &source)?;
            let format = texture_format(pass.spec.format);
            let usages = gpu
                .adapter
                .get_texture_format_features(format)
                .allowed_usages;
            if !usages.contains(wgpu::TextureUsages::RENDER_ATTACHMENT) {
                return Err(RenderError::Gpu(format!(
                    "pass '{}': this adapter, {}, cannot render into {format:?} textures, \
                     which the material's passes need; use a Vulkan, Metal or DirectX 12 \
                     adapter (without a GPU on Linux: Mesa's lavapipe, package \
                     mesa-vulkan-drivers)",
                    pass.label,
                    gpu.adapter_description()
                )));
            }
            pipelines.push(Some(gpu.checked(
                &format!("pipeline of pass '{}'", pass.label),
                || {
                    super::fullscreen_pipeline(
                        &gpu.device,
                        &pass.label,
                        &module,
                        ("veneer_pass_vertex", "veneer_pass_fragment"),
                        format,
                    )
                },
            )?));
        }
        let groups = (passes.passes.iter().zip(&pipelines))
            .map(|(pass, pipeline)| {
                let block = params.filter(|_| pass.module().is_some_and(|m| m.binds_params))?;
                Some(block.bind_group(gpu, pipeline.as_ref()?))
            })
            .collect();
        let view = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("pass view"),
            size: std::mem::size_of::<PassViewUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let (storage, slot_specs) = storage(passes);
        Ok(PassRenderer {
            storage,
            slot_specs,
            passes: passes.clone(),
            pipelines,
            block: params.cloned(),
            params: groups,
            view,
            rendered: Mutex::new(None),
            renders: AtomicU64::new(0),
        })
    }

    /// The passes of a material that only uploads files ([`Passes::uploads_only`]),
    /// uploaded: ready to bind wherever the material is drawn, on a mesh too.
    pub fn uploaded(gpu: &GpuContext, passes: &Passes) -> Result<PassRenderer, RenderError> {
        let renderer = PassRenderer::new(gpu, passes, None)?;
        // Uploads take their files' sizes whatever the domain and output.
        renderer.render(gpu, crate::bake::UNIT_TILE, 1, 0.0)?;
        Ok(renderer)
    }

    /// The buffers' texture bytes for an output of `size` pixels: what the passes hold
    /// on the GPU at once (scratch textures counted once).
    pub fn buffer_bytes(&self, size: u32) -> u64 {
        (self.slot_specs.iter())
            .map(|&pass| {
                let pass = &self.passes.passes[pass];
                let (width, height) = pass.extent(size);
                u64::from(width) * u64::from(height) * pass.spec.format.texel_bytes()
            })
            .sum()
    }

    /// How many passes have rendered so far: a parameter edit renders again only the
    /// passes that read the slots it changed and those downstream of them.
    pub fn passes_rendered(&self) -> u64 {
        self.renders.load(Ordering::Relaxed)
    }

    /// The buffers the material's module reads, binding `k` holding entry `k`.
    pub fn reads(&self) -> &[usize] {
        &self.passes.reads
    }

    /// The bind group of `reads` (buffers of the last render) for group 2 of `pipeline`.
    pub fn bind_group(
        &self,
        gpu: &GpuContext,
        pipeline: &wgpu::RenderPipeline,
        reads: &[usize],
    ) -> wgpu::BindGroup {
        let rendered = self.rendered.lock().expect("pass buffers");
        let rendered = rendered.as_ref().expect("the passes rendered first");
        bind_buffers(gpu, pipeline, &self.textures_of(&rendered.textures, reads))
    }

    /// Renders the passes for an output of size² pixels over `rect` at `time` and the
    /// parameter values last written: every pass when the domain changed, otherwise
    /// only those whose slots changed and those reading a buffer rendered again.
    pub fn render(
        &self,
        gpu: &GpuContext,
        rect: FlatRect,
        size: u32,
        time: f32,
    ) -> Result<(), RenderError> {
        let domain: RenderedFor = (
            [rect.x0, rect.z0, rect.x1, rect.z1, rect.y].map(|v| (v as f32).to_bits()),
            size,
            time.to_bits(),
        );
        let values = self
            .block
            .as_ref()
            .map(|block| block.values())
            .unwrap_or_default();
        let mut rendered = self.rendered.lock().expect("pass buffers");
        let mut state = match rendered.take() {
            Some(state) if state.domain == domain => state,
            _ => Rendered {
                domain,
                textures: self.textures(gpu, size)?,
                values: Vec::new(),
            },
        };
        let fresh_domain = state.values.is_empty();
        let mut again = vec![false; self.passes.passes.len()];
        for (index, pass) in self.passes.passes.iter().enumerate() {
            let own = values.get(pass.slots.clone()).unwrap_or_default();
            let reads = pass.reads();
            again[index] =
                fresh_domain || state.values[index] != own || reads.iter().any(|&read| again[read]);
            if !again[index] {
                continue;
            }
            self.draw(gpu, index, rect, time, &state.textures)?;
            match state.values.get_mut(index) {
                Some(seen) => *seen = own.to_vec(),
                None => state.values.push(own.to_vec()),
            }
        }
        *rendered = Some(state);
        Ok(())
    }

    /// One texture per storage slot, for an output of `size` pixels.
    fn textures(&self, gpu: &GpuContext, size: u32) -> Result<Vec<wgpu::Texture>, RenderError> {
        let bytes = self.buffer_bytes(size);
        if bytes > MAX_PASS_BYTES {
            return Err(RenderError::TooLarge {
                size,
                bytes,
                why: format!(
                    "its {} passes' buffers would take more than the {} a material's passes may hold",
                    self.passes.passes.len(),
                    crate::fsutil::gibibytes(MAX_PASS_BYTES)
                ),
            });
        }
        let limit = gpu.device.limits().max_texture_dimension_2d;
        let mut textures = Vec::with_capacity(self.slot_specs.len());
        for &index in &self.slot_specs {
            let pass = &self.passes.passes[index];
            let (width, height) = pass.extent(size);
            if width.max(height) > limit {
                return Err(RenderError::Invalid(format!(
                    "the buffer of pass '{}' would be {width}×{height} texels, past this adapter's largest texture ({limit}²)",
                    pass.label
                )));
            }
            textures.push(gpu.device.create_texture(&wgpu::TextureDescriptor {
                label: Some(&pass.label),
                size: wgpu::Extent3d {
                    width,
                    height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: texture_format(pass.spec.format),
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC
                    | wgpu::TextureUsages::COPY_DST,
                view_formats: &[],
            }));
        }
        Ok(textures)
    }

    /// The textures holding the buffers of passes `reads`, in order.
    fn textures_of<'t>(
        &self,
        textures: &'t [wgpu::Texture],
        reads: &[usize],
    ) -> Vec<&'t wgpu::Texture> {
        reads
            .iter()
            .map(|&pass| &textures[self.storage[pass]])
            .collect()
    }

    /// Renders pass `index` into its texture, reading the textures before it.
    fn draw(
        &self,
        gpu: &GpuContext,
        index: usize,
        rect: FlatRect,
        time: f32,
        textures: &[wgpu::Texture],
    ) -> Result<(), RenderError> {
        let pass = &self.passes.passes[index];
        let texture = &textures[self.storage[index]];
        if let PassKind::Bitmap { bitmap, .. } = &pass.kind {
            gpu.queue.write_texture(
                texture.as_image_copy(),
                bytemuck::cast_slice(&bitmap.texels),
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(bitmap.width * 16),
                    rows_per_image: Some(bitmap.height),
                },
                texture.size(),
            );
            self.renders.fetch_add(1, Ordering::Relaxed);
            return gpu.take_errors();
        }
        let pipeline = self.pipelines[index]
            .as_ref()
            .expect("a rendered pass has a pipeline");
        if let PassKind::Stage { source, stage, .. } = &pass.kind
            && texture.width() <= stage.unchanged_up_to
        {
            // The stage would leave every texel as it is: copy its source.
            let source = &textures[self.storage[*source]];
            let mut encoder = gpu
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some(&pass.label),
                });
            encoder.copy_texture_to_texture(
                source.as_image_copy(),
                texture.as_image_copy(),
                texture.size(),
            );
            gpu.queue.submit([encoder.finish()]);
            self.renders.fetch_add(1, Ordering::Relaxed);
            return gpu.take_errors();
        }
        let mut groups = Vec::new();
        if let PassKind::Surface { .. } = pass.kind {
            let view = PassViewUniform {
                rect: [rect.x0, rect.z0, rect.x1, rect.z1].map(|v| v as f32),
                size: [texture.width() as f32, texture.height() as f32],
                plane_y: rect.y as f32,
                time,
            };
            gpu.queue
                .write_buffer(&self.view, 0, bytemuck::bytes_of(&view));
            groups.push((
                0,
                gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("pass view"),
                    layout: &pipeline.get_bind_group_layout(0),
                    entries: &[wgpu::BindGroupEntry {
                        binding: 0,
                        resource: self.view.as_entire_binding(),
                    }],
                }),
            ));
        }
        if let Some(params) = &self.params[index] {
            groups.push((1, params.clone()));
        }
        let reads = pass.reads();
        if !reads.is_empty() {
            groups.push((
                2,
                bind_buffers(gpu, pipeline, &self.textures_of(textures, &reads)),
            ));
        }
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some(&pass.label),
            });
        {
            let target = texture.create_view(&Default::default());
            let mut render =
                super::tiles::clear_pass(&mut encoder, &target, wgpu::Color::TRANSPARENT, None);
            render.set_pipeline(pipeline);
            for (index, group) in &groups {
                render.set_bind_group(*index, group, &[]);
            }
            render.draw(0..3, 0..1);
        }
        // One submission per pass: the view uniform is rewritten for the next.
        gpu.queue.submit([encoder.finish()]);
        self.renders.fetch_add(1, Ordering::Relaxed);
        gpu.take_errors()
    }
}

/// A bind group of `textures[k]` at binding k of group 2 of `pipeline`.
fn bind_buffers(
    gpu: &GpuContext,
    pipeline: &wgpu::RenderPipeline,
    textures: &[&wgpu::Texture],
) -> wgpu::BindGroup {
    let views: Vec<wgpu::TextureView> = (textures.iter())
        .map(|texture| texture.create_view(&Default::default()))
        .collect();
    let entries: Vec<wgpu::BindGroupEntry> = views
        .iter()
        .enumerate()
        .map(|(binding, view)| wgpu::BindGroupEntry {
            binding: binding as u32,
            resource: wgpu::BindingResource::TextureView(view),
        })
        .collect();
    gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("pass buffers"),
        layout: &pipeline.get_bind_group_layout(2),
        entries: &entries,
    })
}

/// The texture each pass renders into, and for each texture the pass whose settings it
/// takes. A buffer read by nothing but the stage right after it is scratch: such
/// buffers of the same settings take turns with two textures (a chain's step k writes
/// one while reading the other); every other buffer has a texture of its own.
fn storage(passes: &Passes) -> (Vec<usize>, Vec<usize>) {
    let count = passes.passes.len();
    let mut readers = vec![0usize; count];
    for read in passes
        .passes
        .iter()
        .flat_map(|pass| pass.reads())
        .chain(passes.reads.iter().copied())
    {
        readers[read] += 1;
    }
    let scratch = |index: usize| {
        readers[index] == 1
            && (passes.passes.get(index + 1)).is_some_and(|next| {
                matches!(next.kind, PassKind::Stage { .. }) && next.reads() == [index]
            })
    };
    let mut storage = Vec::with_capacity(count);
    let mut slot_specs: Vec<usize> = Vec::new();
    // Per buffer settings: the two scratch textures and whose turn it is.
    let mut turns: Vec<(crate::nodes::passes::BufferSpec, [usize; 2], usize)> = Vec::new();
    for (index, pass) in passes.passes.iter().enumerate() {
        if !scratch(index) {
            storage.push(slot_specs.len());
            slot_specs.push(index);
            continue;
        }
        let at = match turns.iter().position(|(spec, _, _)| *spec == pass.spec) {
            Some(at) => at,
            None => {
                let pair = [slot_specs.len(), slot_specs.len() + 1];
                slot_specs.extend([index, index]);
                turns.push((pass.spec, pair, 0));
                turns.len() - 1
            }
        };
        let (_, pair, turn) = &mut turns[at];
        storage.push(pair[*turn]);
        *turn = 1 - *turn;
    }
    (storage, slot_specs)
}
