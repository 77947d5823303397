//! The headless lit mesh render (`veneer render`, snapshots, exports): one baked
//! material on a mesh, in tiles when the image is larger than a tile, so any size the
//! machine has memory for renders within the device's texture and buffer limits.

use super::mesh_view::{MeshPipeline, MeshTarget, MeshView, Relief, SAMPLES, tile_crop};
use super::readback::read_texture;
use super::tiles::{image_buffer, paste, tile_size, tiles};
use super::timing::time_pass;
use super::{Environment, EnvironmentMaps, GpuContext, GpuMesh, RenderError};
use crate::codegen::SurfaceUse;
use crate::mesh::Mesh;
use std::sync::Arc;

/// Bytes per pixel of a mesh image on its way out: RGBA8, and as much again encoding it.
const PIXEL_BYTES: u64 = 8;

/// A headless renderer of one (baked) material on meshes.
pub struct MeshRenderer {
    pipeline: MeshPipeline,
}

impl MeshRenderer {
    /// Builds the pipeline for a material module with baked parameters, using what
    /// `uses` says of its height and bump.
    pub fn new(
        gpu: &GpuContext,
        material_wgsl: &str,
        uses: SurfaceUse,
    ) -> Result<MeshRenderer, RenderError> {
        MeshRenderer::with_relief(gpu, material_wgsl, uses, Relief::Displaced)
    }

    /// [`MeshRenderer::new`] showing the material's height as `relief`; a
    /// metallic-roughness material is lit by the procedural sky.
    pub fn with_relief(
        gpu: &GpuContext,
        material_wgsl: &str,
        uses: SurfaceUse,
        relief: Relief,
    ) -> Result<MeshRenderer, RenderError> {
        MeshRenderer::lit(gpu, material_wgsl, uses, relief, None)
    }

    /// [`MeshRenderer::with_relief`] lighting a metallic-roughness material with
    /// `environment` (`None`: the procedural sky, whose maps the context keeps), its maps
    /// derived on the GPU first; Blinn-Phong materials need none and derive none.
    pub fn lit(
        gpu: &GpuContext,
        material_wgsl: &str,
        uses: SurfaceUse,
        relief: Relief,
        environment: Option<&Environment>,
    ) -> Result<MeshRenderer, RenderError> {
        let mut pipeline =
            MeshPipeline::with_relief(&gpu.device, material_wgsl, 0, uses, SAMPLES, relief)?;
        if pipeline.needs_environment() {
            let maps = match environment {
                Some(environment) => Arc::new(EnvironmentMaps::new(gpu, environment)?),
                None => gpu.sky()?,
            };
            pipeline.set_environment(&gpu.device, &maps);
        }
        Ok(MeshRenderer { pipeline })
    }

    /// Binds the buffers a multi-pass material reads, as `passes` last rendered them.
    pub fn bind_passes(&mut self, gpu: &GpuContext, passes: &super::PassRenderer) {
        self.pipeline
            .bind_buffers(|pipeline| passes.bind_group(gpu, pipeline, passes.reads()));
    }

    /// Renders `mesh` into a size×size RGBA8 image (rows from the top), tile by tile
    /// past the device's tile size.
    pub fn render(
        &self,
        gpu: &GpuContext,
        mesh: &Mesh,
        view: &MeshView,
        size: u32,
    ) -> Result<Vec<[u8; 4]>, RenderError> {
        self.render_in_tiles(gpu, mesh, view, size, tile_size(gpu))
    }

    /// [`MeshRenderer::render`] in tiles of at most `tile`² pixels (any tiling gives the
    /// same image, up to rounding at triangle edges).
    pub fn render_in_tiles(
        &self,
        gpu: &GpuContext,
        mesh: &Mesh,
        view: &MeshView,
        size: u32,
        tile: u32,
    ) -> Result<Vec<[u8; 4]>, RenderError> {
        if size == 0 || tile == 0 {
            return Err(RenderError::Invalid(
                "image and tile sizes must be at least 1 pixel".into(),
            ));
        }
        let mut image = image_buffer::<[u8; 4]>(size, PIXEL_BYTES)?;
        let tile = tile.min(tile_size(gpu));
        let mesh = if self.pipeline.blends() {
            GpuMesh::with_depth_order(&gpu.device, mesh)
        } else {
            GpuMesh::new(&gpu.device, mesh)
        };
        self.pipeline.sort(&gpu.queue, &mesh, view);
        for (origin, extent) in tiles(size, tile) {
            let target = MeshTarget::new(&gpu.device, extent.0, extent.1);
            let crop = tile_crop(size, origin, extent);
            self.pipeline
                .write_view_cropped(&gpu.queue, view, 1.0, crop);
            let mut encoder = gpu
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("mesh"),
                });
            self.pipeline.encode(&mut encoder, &target, &mesh, view);
            gpu.queue.submit([encoder.finish()]);
            let pixels: Vec<[u8; 4]> =
                bytemuck::pod_collect_to_vec(&read_texture(gpu, &target.resolved, 4)?);
            paste(&mut image, size, origin, extent.0, &pixels);
        }
        Ok(image)
    }

    /// The time the GPU takes to draw one size×size frame of an uploaded `mesh` (at most
    /// one tile), without reading it back (see [`time_pass`]).
    pub fn frame_time(
        &self,
        gpu: &GpuContext,
        mesh: &GpuMesh,
        view: &MeshView,
        size: u32,
    ) -> Result<std::time::Duration, RenderError> {
        time_pass(gpu, size, |encoder, writes| {
            let target = MeshTarget::new(&gpu.device, size, size);
            self.pipeline.write_view(&gpu.queue, view, 1.0);
            self.pipeline
                .encode_timed(encoder, &target, mesh, view, writes);
        })
    }
}
