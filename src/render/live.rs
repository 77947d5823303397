//! The editor's live preview on the GPU: one material with its parameters in a buffer,
//! drawn on one mesh into an RGBA8 image. Pipelines are kept per code generation, so
//! parameter, camera and time changes only rewrite buffers; drafts (while the user
//! drags) draw at a resolution their own drawing time picks (`draft_scale`) without
//! multisampling, with a pipeline of their own.

use super::draft_scale::DraftScale;
use super::mesh_view::{MeshPipeline, MeshTarget, MeshView};
use super::params::ParamBlock;
use super::readback::read_texture;
use super::{
    EnvironmentMaps, FlatChannels, FlatRenderer, GpuContext, GpuMesh, PassDomain, PassRenderer,
    RenderError,
};
use crate::codegen::passes::Passes;
use crate::codegen::{Compiled, SurfaceUse};
use crate::mesh::Mesh;
use std::sync::Arc;
use std::time::Instant;

/// The output size the preview renders a multi-pass material's passes for, whatever the
/// size of its picture: the preview and the node thumbnails show the same buffers, those
/// of a bake of this size.
pub const PREVIEW_PASS_SIZE: u32 = 512;

/// How finely a live frame is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quality {
    /// While something is being dragged: one sample, at a fraction of the resolution
    /// each way that keeps drafts quick (a half to start with; see `DraftScale`).
    Draft,
    /// At rest: full resolution, 4× multisampled, as `veneer render` draws.
    Full,
}

impl Quality {
    /// Samples a pixel.
    fn samples(self) -> u32 {
        match self {
            Quality::Draft => 1,
            Quality::Full => 4,
        }
    }
}

/// The material a live frame draws; two are the same material when their generations
/// (and so their code) are.
#[derive(Clone, Debug)]
pub struct LiveMaterialCode {
    /// Changes whenever `wgsl` does (a new pipeline is built then).
    pub generation: u64,
    /// The module, with its parameters in a buffer (uniform or storage).
    pub wgsl: Arc<str>,
    /// Its parameter slots.
    pub slots: usize,
    /// What of the surface it uses (height, bump, fields).
    pub uses: SurfaceUse,
    /// Whether the module reads its parameter block (a multi-pass material's slots may
    /// all be its passes').
    pub binds_params: bool,
    /// The passes of a multi-pass material: over the mesh's UV layout when it is drawn
    /// on a mesh; in the flat view, over the unit tile, which it shows with its
    /// neighbours.
    pub passes: Option<Arc<Passes>>,
}

impl LiveMaterialCode {
    /// The code of `compiled` (a material compiled with parameter slots) as generation
    /// `generation`.
    pub fn new(generation: u64, compiled: &Compiled) -> LiveMaterialCode {
        let module = &compiled.module;
        LiveMaterialCode {
            generation,
            wgsl: Arc::from(module.source.as_str()),
            slots: module.params.len(),
            uses: module.uses,
            binds_params: module.binds_params,
            passes: (!compiled.passes.is_empty()).then(|| Arc::new(compiled.passes.clone())),
        }
    }
}

impl PartialEq for LiveMaterialCode {
    fn eq(&self, other: &LiveMaterialCode) -> bool {
        // The generation changes with the code: no need to compare the code itself.
        self.generation == other.generation && self.slots == other.slots
    }
}

/// Draws live frames; keeps the pipelines of the newest material, the uploaded mesh and
/// the targets between frames.
#[derive(Default)]
pub struct LiveRenderer {
    /// The newest material's generation and its pipelines by quality (draft, full),
    /// each built when first needed.
    pipelines: Option<(u64, [Option<MeshPipeline>; 2])>,
    /// The newest multi-pass material's generation and its flat renderer.
    flat: Option<(u64, FlatRenderer)>,
    /// The newest multi-pass material's generation and its passes over the mesh's UV
    /// layout, with the parameter values they read.
    passes: Option<(u64, PassRenderer, Option<Arc<ParamBlock>>)>,
    mesh: Option<(String, GpuMesh)>,
    target: Option<(Quality, MeshTarget)>,
    /// How coarse the next draft is, from the last drafts' drawing times.
    pub draft_scale: DraftScale,
    /// Materials whose (first) pipeline was built, for tests and the status bar.
    pub materials_built: u64,
}

impl LiveRenderer {
    /// Draws `mesh` (uploaded again only when `mesh_key` changes) with `material` and
    /// `params` as `view` sees it, lit by `environment` where the material's shading
    /// asks for one, at `size` pixels (a draft at a fraction of them); returns the
    /// image's size and its RGBA8 rows from the top.
    #[allow(clippy::too_many_arguments)]
    pub fn render(
        &mut self,
        gpu: &GpuContext,
        material: &LiveMaterialCode,
        params: &[[f32; 4]],
        mesh_key: &str,
        mesh: &Mesh,
        view: &MeshView,
        environment: &Arc<EnvironmentMaps>,
        size: (u32, u32),
        quality: Quality,
    ) -> Result<((u32, u32), Vec<u8>), RenderError> {
        let rendered_passes = (material.passes.as_ref()).is_some_and(|p| !p.uploads_only());
        if view.unlit && (rendered_passes || view.repeat_tile) {
            let repeats = if view.repeat_tile { 3 } else { 1 };
            return self.render_tile(gpu, material, params, view.time, size, quality, repeats);
        }
        let (width, height) = self.image_size(size, quality);
        self.prepare(gpu, material, quality)?;
        if let Some((_, built)) = &mut self.pipelines
            && let Some(pipeline) = &mut built[quality as usize]
        {
            pipeline.set_environment(&gpu.device, environment);
        }
        let blends = self.pipeline(quality).is_some_and(MeshPipeline::blends);
        // Buffers over the surface need a layout giving each point its own texels.
        let own_texels = rendered_passes;
        let mesh_key = format!("{mesh_key}{}", if own_texels { "#own-texels" } else { "" });
        if self
            .mesh
            .as_ref()
            .is_none_or(|(key, uploaded)| *key != mesh_key || (blends && !uploaded.sorts()))
        {
            let laid_out;
            let mesh = if own_texels && !mesh.has_own_texels() {
                laid_out = mesh.with_uv_atlas(PREVIEW_PASS_SIZE);
                &laid_out
            } else {
                mesh
            };
            let uploaded = if blends {
                GpuMesh::with_depth_order(&gpu.device, mesh)
            } else {
                GpuMesh::new(&gpu.device, mesh)
            };
            self.mesh = Some((mesh_key, uploaded));
        }
        self.render_passes(gpu, material, params, view, quality)?;
        // The draw alone is timed for the draft scale (not building a pipeline).
        let started = Instant::now();
        let fits = self
            .target
            .as_ref()
            .is_some_and(|(kind, target)| *kind == quality && target.size() == (width, height));
        if !fits {
            let target = MeshTarget::with_samples(&gpu.device, width, height, quality.samples());
            self.target = Some((quality, target));
        }
        let pipeline = self.pipeline(quality).expect("prepared above");
        let (_, gpu_mesh) = self.mesh.as_ref().expect("uploaded above");
        let (_, target) = self.target.as_ref().expect("made above");
        pipeline.write_view(&gpu.queue, view, width as f32 / height as f32);
        pipeline.write_params(&gpu.queue, params);
        pipeline.sort(&gpu.queue, gpu_mesh, view);
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("live preview"),
            });
        pipeline.encode(&mut encoder, target, gpu_mesh, view);
        gpu.queue.submit([encoder.finish()]);
        let pixels = read_texture(gpu, &target.resolved, 4)?;
        gpu.take_errors()?;
        if quality == Quality::Draft {
            self.draft_scale.after_draft(started.elapsed());
        }
        Ok(((width, height), pixels))
    }

    /// Renders a multi-pass material's passes over the UV layout of the uploaded mesh
    /// for [`PREVIEW_PASS_SIZE`] (again only when the mesh, its placement, the time or
    /// the parameter values they read change) and binds their buffers to the pipeline
    /// of `quality`.
    fn render_passes(
        &mut self,
        gpu: &GpuContext,
        material: &LiveMaterialCode,
        params: &[[f32; 4]],
        view: &MeshView,
        quality: Quality,
    ) -> Result<(), RenderError> {
        let Some(passes) = &material.passes else {
            return Ok(());
        };
        if (self.passes.as_ref()).is_none_or(|(generation, ..)| *generation != material.generation)
        {
            let block = ParamBlock::new(gpu, material.slots).map(Arc::new);
            let renderer = PassRenderer::new(gpu, passes, block.as_ref())?;
            self.passes = Some((material.generation, renderer, block));
        }
        let (_, renderer, block) = self.passes.as_ref().expect("made above");
        if let Some(block) = block {
            block.write(gpu, params);
        }
        let (_, mesh) = self.mesh.as_ref().expect("uploaded before the passes");
        let domain = PassDomain::Mesh {
            mesh,
            placement: (view.center, view.size),
        };
        renderer.render(gpu, domain, PREVIEW_PASS_SIZE, view.time)?;
        if let Some((_, built)) = &mut self.pipelines
            && let Some(pipeline) = &mut built[quality as usize]
        {
            pipeline.bind_buffers(|pipeline| renderer.bind_group(gpu, pipeline, renderer.reads()));
        }
        Ok(())
    }

    /// The size of an image of `size` pixels drawn at `quality`.
    fn image_size(&self, size: (u32, u32), quality: Quality) -> (u32, u32) {
        match quality {
            Quality::Draft => self.draft_scale.scaled(size),
            Quality::Full => (size.0.max(1), size.1.max(1)),
        }
    }

    /// Draws a material flat: its albedo over the unit tile. With one repeat, the tile
    /// is centred in the image and the material's neighbours around it (where its
    /// buffers wrap, they repeat it); with `repeats` of them, copies of the tile as
    /// drawn lie side by side, that many across the image's shorter side and centred,
    /// as a bake of the tile repeats (so seams show). A multi-pass material's passes
    /// render for [`PREVIEW_PASS_SIZE`], again only when the material or the parameter
    /// values they read change.
    #[allow(clippy::too_many_arguments)]
    fn render_tile(
        &mut self,
        gpu: &GpuContext,
        material: &LiveMaterialCode,
        params: &[[f32; 4]],
        time: f32,
        size: (u32, u32),
        quality: Quality,
        repeats: u32,
    ) -> Result<((u32, u32), Vec<u8>), RenderError> {
        let (width, height) = self.image_size(size, quality);
        if (self.flat.as_ref()).is_none_or(|(generation, _)| *generation != material.generation) {
            let mut flat = FlatRenderer::with_passes(
                gpu,
                &material.wgsl,
                material.slots,
                material.binds_params,
                material.passes.as_deref(),
            )?;
            flat.set_pass_size(Some(PREVIEW_PASS_SIZE));
            self.flat = Some((material.generation, flat));
            self.materials_built += 1;
        }
        let (_, flat) = self.flat.as_ref().expect("built above");
        flat.write_params(gpu, params);
        let started = Instant::now();
        let side = (width.min(height) / repeats).max(1);
        // Where the tile's top-left corner lies in the image.
        let corner = (
            i64::from(width) / 2 - i64::from(side) * i64::from(repeats) / 2,
            i64::from(height) / 2 - i64::from(side) * i64::from(repeats) / 2,
        );
        let tile = crate::bake::UNIT_TILE;
        let channels = FlatChannels::AlbedoAlpha;
        let rgba = |pixels: &[[f32; 4]]| -> Vec<[u8; 4]> {
            let rgb = super::albedo_to_rgb8(pixels);
            (rgb.chunks_exact(3))
                .map(|pixel| [pixel[0], pixel[1], pixel[2], 255])
                .collect()
        };
        let pixels = if repeats == 1 {
            let origin = (-corner.0, -corner.1);
            let drawn =
                flat.render_region(gpu, tile, side, time, channels, origin, (width, height))?;
            rgba(&drawn)
        } else {
            let drawn =
                flat.render_region(gpu, tile, side, time, channels, (0, 0), (side, side))?;
            let drawn = rgba(&drawn);
            let side = i64::from(side);
            let at = |offset: i64, corner: i64| (offset - corner).rem_euclid(side) as usize;
            (0..i64::from(height))
                .flat_map(|y| (0..i64::from(width)).map(move |x| (x, y)))
                .map(|(x, y)| drawn[at(y, corner.1) * side as usize + at(x, corner.0)])
                .collect()
        };
        gpu.take_errors()?;
        if quality == Quality::Draft {
            self.draft_scale.after_draft(started.elapsed());
        }
        Ok(((width, height), pixels.into_flattened()))
    }

    /// Builds the pipeline `material` needs at `quality` unless it is built already.
    pub fn prepare(
        &mut self,
        gpu: &GpuContext,
        material: &LiveMaterialCode,
        quality: Quality,
    ) -> Result<(), RenderError> {
        if self
            .pipelines
            .as_ref()
            .is_none_or(|(generation, _)| *generation != material.generation)
        {
            self.pipelines = Some((material.generation, [None, None]));
        }
        let (_, built) = self.pipelines.as_mut().expect("set above");
        if built[quality as usize].is_none() {
            let fresh = built.iter().all(Option::is_none);
            let pipeline = MeshPipeline::with_samples(
                &gpu.device,
                &material.wgsl,
                material.slots,
                material.uses,
                quality.samples(),
            )?;
            built[quality as usize] = Some(pipeline);
            if fresh {
                self.materials_built += 1;
            }
        }
        Ok(())
    }

    fn pipeline(&self, quality: Quality) -> Option<&MeshPipeline> {
        self.pipelines.as_ref()?.1[quality as usize].as_ref()
    }
}
