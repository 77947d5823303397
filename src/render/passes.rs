//! The GPU side of a multi-pass material: a pipeline per pass, and the buffers they
//! render, in order, for one domain (a rectangle of the plane, or a mesh's UV layout),
//! output size and time. The buffers are kept while the output size is: a pass renders
//! again only when it evaluates the domain and the domain or time changed, a parameter
//! slot it reads changes, or a buffer it reads rendered again (files are uploaded once).
//! A buffer read only by the stage after it (the inside of a jump flood's chain of steps) lives in one of two
//! scratch textures that the chain's steps take turns with.

pub mod seams;

use super::islands::Islands;
use super::params::ParamBlock;
use super::{FlatRect, GpuContext, GpuMesh, RenderError, shader_source};
use crate::codegen::passes::{PassKind, Passes, STAGE_ENTRY_POINTS, SURFACE_ENTRY_POINTS};
use crate::nodes::passes::BufferFormat;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

/// The entry points a surface pass is rendered with over a mesh's UV layout.
const MESH_SURFACE_ENTRY_POINTS: &str = include_str!("../../shaders/render_pass_mesh.wgsl");

/// Where a material's surface passes evaluate the graph.
#[derive(Clone, Copy)]
pub enum PassDomain<'m> {
    /// A rectangle of the plane y = `rect.y` (flat views, plane and tile bakes): a
    /// texel's place in the rectangle is its domain coordinate.
    Flat(FlatRect),
    /// A mesh's UV layout, its points placed in texture space at `placement` (centre and
    /// size, as mesh views place them): the mesh's uv is the domain coordinate. Texels
    /// no triangle covers take the value of the nearest covered texel.
    Mesh {
        mesh: &'m GpuMesh,
        placement: ([f32; 3], f32),
    },
}

impl PassDomain<'_> {
    /// What the buffers rendered over this domain depend on.
    fn key(&self) -> DomainKey {
        match self {
            PassDomain::Flat(rect) => DomainKey::Flat(
                [rect.x0, rect.z0, rect.x1, rect.z1, rect.y].map(|v| (v as f32).to_bits()),
            ),
            PassDomain::Mesh { mesh, placement } => DomainKey::Mesh(
                mesh.id(),
                [placement.0[0], placement.0[1], placement.0[2], placement.1].map(f32::to_bits),
            ),
        }
    }
}

/// A domain as the kept buffers remember it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum DomainKey {
    Flat([u32; 5]),
    Mesh(u64, [u32; 4]),
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct PassMeshViewUniform {
    placement: [f32; 4],
    time: f32,
    padding: [f32; 3],
}

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

/// The most bytes of textures a material's passes may hold at once.
pub const MAX_PASS_BYTES: u64 = 4 << 30;

/// The buffers as last rendered: for what domain, time and output size, and with which
/// values of its parameter slots each pass.
struct Rendered {
    domain: DomainKey,
    time: u32,
    size: u32,
    /// One texture per storage slot (see [`PassRenderer::storage`]), for `size`.
    textures: Vec<wgpu::Texture>,
    values: Vec<Vec<[f32; 4]>>,
    /// Over a mesh: the nearest covered texel of each buffer size met so far.
    nearest: Vec<((u32, u32), wgpu::Texture)>,
}

/// A material's passes, built once, each rendered again only when what it reads changes.
pub struct PassRenderer {
    passes: Passes,
    /// The pipeline of each pass (none for an uploaded bitmap).
    pipelines: Vec<Option<wgpu::RenderPipeline>>,
    /// The pipeline of each surface pass over a mesh's UV layout, built when first
    /// needed, and what fills the texels between the layout's islands.
    mesh_pipelines: Vec<OnceLock<wgpu::RenderPipeline>>,
    islands: OnceLock<Islands>,
    /// The parameter values the passes that read them bind at group 1.
    block: Option<Arc<ParamBlock>>,
    view: wgpu::Buffer,
    mesh_view: wgpu::Buffer,
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
                let info = gpu.adapter.get_info();
                // wgpu finds float render targets on desktop GL only by extension names
                // that Mesa's core profiles leave out (gfx-rs/wgpu#2838).
                let mesa_gl =
                    info.backend == wgpu::Backend::Gl && info.driver_info.contains("Mesa");
                let workaround = if mesa_gl {
                    "; on Mesa's OpenGL, MESA_EXTENSION_OVERRIDE=+GL_ARB_color_buffer_float \
                     lets wgpu see the float render targets the driver has"
                } else {
                    ""
                };
                return Err(RenderError::Gpu(format!(
                    "pass '{}': this adapter, {}, cannot render into {format:?} textures, \
                     which the material's passes need; use a Vulkan, Metal or DirectX 12 \
                     adapter (without a GPU on Linux: Mesa's lavapipe, package \
                     mesa-vulkan-drivers){workaround}",
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
        let uniform = |label, size| {
            gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let (storage, slot_specs) = storage(passes);
        Ok(PassRenderer {
            storage,
            slot_specs,
            passes: passes.clone(),
            pipelines,
            mesh_pipelines: passes.passes.iter().map(|_| OnceLock::new()).collect(),
            islands: OnceLock::new(),
            block: params.cloned(),
            view: uniform("pass view", std::mem::size_of::<PassViewUniform>() as u64),
            mesh_view: uniform(
                "pass mesh view",
                std::mem::size_of::<PassMeshViewUniform>() as u64,
            ),
            rendered: Mutex::new(None),
            renders: AtomicU64::new(0),
        })
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

    /// Renders the passes for an output of size² pixels over `domain` at `time` and the
    /// parameter values last written: every pass when the domain changed, otherwise
    /// only those whose slots changed and those reading a buffer rendered again.
    pub fn render(
        &self,
        gpu: &GpuContext,
        domain: PassDomain<'_>,
        size: u32,
        time: f32,
    ) -> Result<(), RenderError> {
        let (key, time_bits) = (domain.key(), time.to_bits());
        let values = self
            .block
            .as_ref()
            .map(|block| block.values())
            .unwrap_or_default();
        let mut rendered = self.rendered.lock().expect("pass buffers");
        // The textures are kept while the output size is: a new domain or time renders
        // the passes that evaluate the domain again (and those reading them), never the
        // uploads.
        let mut state = match rendered.take() {
            Some(state) if state.size == size => state,
            _ => Rendered {
                domain: key,
                time: time_bits,
                size,
                textures: self.textures(gpu, size)?,
                values: Vec::new(),
                nearest: Vec::new(),
            },
        };
        if state.domain != key {
            state.nearest.clear();
        }
        let moved = (state.domain, state.time) != (key, time_bits);
        (state.domain, state.time) = (key, time_bits);
        let fresh = state.values.is_empty();
        let mut again = vec![false; self.passes.passes.len()];
        for (index, pass) in self.passes.passes.iter().enumerate() {
            let own = values.get(pass.slots.clone()).unwrap_or_default();
            let reads = pass.reads();
            let evaluates_domain = matches!(pass.kind, PassKind::Surface { .. });
            again[index] = fresh
                || (moved && evaluates_domain)
                || state.values[index] != own
                || reads.iter().any(|&read| again[read]);
            if !again[index] {
                continue;
            }
            self.draw(gpu, index, domain, time, &mut state)?;
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
        for (slot, &index) in self.slot_specs.iter().enumerate() {
            let pass = &self.passes.passes[index];
            let (width, height) = pass.extent(size);
            if width.max(height) > limit {
                return Err(RenderError::Invalid(format!(
                    "the buffer of pass '{}' would be {width}×{height} texels, past this adapter's largest texture ({limit}²)",
                    pass.label
                )));
            }
            // A slot only ever uploaded into (bitmaps) is no render target: adapters that
            // cannot render into float textures (GL) can still hold a float bitmap.
            let drawn = (self.storage.iter().zip(&self.passes.passes))
                .any(|(&held, pass)| held == slot && !matches!(pass.kind, PassKind::Bitmap { .. }));
            let target = if drawn {
                wgpu::TextureUsages::RENDER_ATTACHMENT
            } else {
                wgpu::TextureUsages::empty()
            };
            textures.push(super::plain_texture(
                &gpu.device,
                &pass.label,
                (width, height),
                texture_format(pass.spec.format),
                target
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC
                    | wgpu::TextureUsages::COPY_DST,
            ));
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

    /// Renders pass `index` into its texture over `domain`, reading the textures before
    /// it.
    fn draw(
        &self,
        gpu: &GpuContext,
        index: usize,
        domain: PassDomain<'_>,
        time: f32,
        state: &mut Rendered,
    ) -> Result<(), RenderError> {
        let pass = &self.passes.passes[index];
        let Rendered {
            textures, nearest, ..
        } = state;
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
        // A surface pass over a mesh draws the mesh's triangles into a scratch texture,
        // which the island fill then copies into the buffer.
        let over_mesh = match (&pass.kind, domain) {
            (PassKind::Surface { .. }, PassDomain::Mesh { mesh, .. }) => Some(mesh),
            _ => None,
        };
        let pipeline = match over_mesh {
            Some(_) => self.mesh_pipeline(gpu, index)?,
            None => (self.pipelines[index].as_ref()).expect("a rendered pass has a pipeline"),
        };
        let groups = self.bind_groups(gpu, index, pipeline, (domain, time), texture, textures);
        let scratch = over_mesh.map(|_| {
            super::plain_texture(
                &gpu.device,
                &pass.label,
                (texture.width(), texture.height()),
                texture.format(),
                wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            )
        });
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some(&pass.label),
            });
        {
            let target = (scratch.as_ref().unwrap_or(texture)).create_view(&Default::default());
            let mut render =
                super::tiles::clear_pass(&mut encoder, &target, wgpu::Color::TRANSPARENT, None);
            render.set_pipeline(pipeline);
            for (index, group) in &groups {
                render.set_bind_group(*index, group, &[]);
            }
            match over_mesh {
                Some(mesh) => mesh.draw(&mut render),
                None => render.draw(0..3, 0..1),
            }
        }
        // One submission per pass: the view uniform is rewritten for the next.
        gpu.queue.submit([encoder.finish()]);
        if let (Some(mesh), Some(scratch)) = (over_mesh, &scratch) {
            let islands = built(&self.islands, || Islands::new(gpu))?;
            let extent = (texture.width(), texture.height());
            let at = match nearest.iter().position(|(size, _)| *size == extent) {
                Some(at) => at,
                None => {
                    nearest.push((extent, islands.nearest(gpu, mesh, extent)?));
                    nearest.len() - 1
                }
            };
            islands.fill(gpu, &nearest[at].1, scratch, texture)?;
        }
        self.renders.fetch_add(1, Ordering::Relaxed);
        gpu.take_errors()
    }

    /// The bind groups pass `index` draws with through `pipeline`: the view of `domain`
    /// at a time over a buffer the size of `target` (a surface pass; written into the
    /// view uniform, so the draw is submitted before the next view is written), the
    /// parameter block, and the buffers it reads among `textures`.
    fn bind_groups(
        &self,
        gpu: &GpuContext,
        index: usize,
        pipeline: &wgpu::RenderPipeline,
        (domain, time): (PassDomain<'_>, f32),
        target: &wgpu::Texture,
        textures: &[wgpu::Texture],
    ) -> Vec<(u32, wgpu::BindGroup)> {
        let pass = &self.passes.passes[index];
        let mut groups = Vec::new();
        if let PassKind::Surface { .. } = pass.kind {
            let view = self.write_view(gpu, domain, target, time);
            groups.push((
                0,
                gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("pass view"),
                    layout: &pipeline.get_bind_group_layout(0),
                    entries: &[wgpu::BindGroupEntry {
                        binding: 0,
                        resource: view.as_entire_binding(),
                    }],
                }),
            ));
        }
        if let Some(block) = (self.block.as_ref())
            .filter(|_| pass.module().is_some_and(|module| module.binds_params))
        {
            groups.push((1, block.bind_group(gpu, pipeline)));
        }
        let reads = pass.reads();
        if !reads.is_empty() {
            groups.push((
                2,
                bind_buffers(gpu, pipeline, &self.textures_of(textures, &reads)),
            ));
        }
        groups
    }

    /// Writes the view of a surface pass over `domain` into `target` at `time`; returns
    /// the uniform buffer holding it.
    fn write_view(
        &self,
        gpu: &GpuContext,
        domain: PassDomain<'_>,
        target: &wgpu::Texture,
        time: f32,
    ) -> &wgpu::Buffer {
        match domain {
            PassDomain::Flat(rect) => {
                let view = PassViewUniform {
                    rect: [rect.x0, rect.z0, rect.x1, rect.z1].map(|v| v as f32),
                    size: [target.width() as f32, target.height() as f32],
                    plane_y: rect.y as f32,
                    time,
                };
                gpu.queue
                    .write_buffer(&self.view, 0, bytemuck::bytes_of(&view));
                &self.view
            }
            PassDomain::Mesh { placement, .. } => {
                let view = PassMeshViewUniform {
                    placement: [placement.0[0], placement.0[1], placement.0[2], placement.1],
                    time,
                    padding: [0.0; 3],
                };
                gpu.queue
                    .write_buffer(&self.mesh_view, 0, bytemuck::bytes_of(&view));
                &self.mesh_view
            }
        }
    }

    /// The pipeline of surface pass `index` over a mesh's UV layout, built when first
    /// asked for.
    fn mesh_pipeline(
        &self,
        gpu: &GpuContext,
        index: usize,
    ) -> Result<&wgpu::RenderPipeline, RenderError> {
        built(&self.mesh_pipelines[index], || {
            let pass = &self.passes.passes[index];
            let module = pass.module().expect("a surface pass has a module");
            let source = shader_source(&module.source, MESH_SURFACE_ENTRY_POINTS);
            let module = gpu.shader(&pass.label, &source)?;
            gpu.checked(&format!("mesh pipeline of pass '{}'", pass.label), || {
                super::target_pipeline(
                    &gpu.device,
                    &pass.label,
                    &module,
                    ("veneer_pass_mesh_vertex", "veneer_pass_mesh_fragment"),
                    texture_format(pass.spec.format),
                    &[Some(GpuMesh::layout())],
                )
            })
        })
    }
}

/// What `cell` holds, built by `build` when it holds nothing yet.
fn built<T>(
    cell: &OnceLock<T>,
    build: impl FnOnce() -> Result<T, RenderError>,
) -> Result<&T, RenderError> {
    if let Some(value) = cell.get() {
        return Ok(value);
    }
    let value = build()?;
    Ok(cell.get_or_init(|| value))
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
