//! The lit mesh render: a material on a mesh, lit as its graph's shading says (the
//! seeds' Blinn-Phong, or metallic-roughness under the key light and an environment).
//! The pieces (uploaded mesh, pipeline, offscreen target) are shared by headless renders
//! and the editor's live preview.

use super::{EnvironmentMaps, GpuMesh, RenderError, ToneMap, shader_source};
use crate::codegen::{AlphaUse, SurfaceUse};
use crate::graph::{Preview, Shading};
use glam::{Mat4, Vec3};
use std::sync::Arc;

/// How the camera looks at the mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// A perspective orbit camera (vertical field of view in degrees).
    Perspective { fov: f32 },
    /// Straight down the y axis at a square of half-width `extent` (the flat 2D view).
    TopDown { extent: f32 },
}

/// The cameras' near and far planes (mesh units from the eye).
const NEAR_PLANE: f32 = 0.05;
const FAR_PLANE: f32 = 200.0;

/// Camera, light and placement of a mesh render.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshView {
    /// Camera orbit angles in degrees, distance from the target, and the target.
    pub yaw: f32,
    pub pitch: f32,
    pub distance: f32,
    pub target: [f32; 3],
    pub projection: Projection,
    /// Direction towards the light (need not be unit).
    pub light: [f32; 3],
    /// Share of the albedo lit regardless of the light.
    pub ambient: f32,
    /// Background colour (linear RGB).
    pub background: [f32; 3],
    /// Where the mesh sits in texture space.
    pub center: [f32; 3],
    pub size: f32,
    pub time: f32,
    /// Show the albedo only, without lighting.
    pub unlit: bool,
    /// With `unlit` (the editor's flat view): show the unit tile as a bake of it
    /// repeats, copies side by side with three across the image's shorter side, so
    /// seams show.
    pub repeat_tile: bool,
    /// How metallic-roughness materials map scene light to the display (Blinn-Phong
    /// materials show the seeds' lighting as it is).
    pub tone_map: ToneMap,
    /// Exposure of metallic-roughness materials in stops (light × 2^exposure).
    pub exposure: f32,
    /// Irradiance of the key light on metallic-roughness materials (0: the environment
    /// alone lights them).
    pub key_light: f32,
    /// How far the environment is turned about +y, in degrees (seen from above,
    /// counter-clockwise).
    pub environment_turn: f32,
    /// What shows behind a metallic-roughness material.
    pub backdrop: Backdrop,
}

/// The key light's irradiance on metallic-roughness materials by default (linear units;
/// a white Lambertian surface facing it reflects 2.5 / π ≈ 0.8).
pub const DEFAULT_KEY_LIGHT: f32 = 2.5;

/// What shows behind a metallic-roughness material (Blinn-Phong materials, and the flat
/// 2D view, always show the background colour).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Backdrop {
    /// The view's flat background colour.
    Colour = 0,
    /// The environment as it is.
    Environment = 1,
    /// The environment blurred (as a GGX lobe of roughness 0.35 reflects it).
    #[default]
    Blurred = 2,
}

impl MeshView {
    /// The default view of a graph's preview settings.
    pub fn for_preview(preview: &Preview) -> MeshView {
        MeshView {
            yaw: 30.0,
            pitch: 25.0,
            distance: 3.6,
            target: [0.0; 3],
            projection: Projection::Perspective { fov: 40.0 },
            light: [-0.4, 0.8, 0.6],
            ambient: 0.25,
            background: [0.12, 0.13, 0.15],
            center: [
                preview.center.0 as f32,
                preview.center.1 as f32,
                preview.center.2 as f32,
            ],
            size: preview.size as f32,
            time: 0.0,
            unlit: false,
            repeat_tile: false,
            tone_map: ToneMap::default(),
            exposure: 0.0,
            key_light: DEFAULT_KEY_LIGHT,
            environment_turn: 0.0,
            backdrop: Backdrop::default(),
        }
    }

    /// The camera position.
    pub fn eye(&self) -> Vec3 {
        let (yaw, pitch) = (self.yaw.to_radians(), self.pitch.to_radians());
        let offset = Vec3::new(
            pitch.cos() * yaw.sin(),
            pitch.sin(),
            pitch.cos() * yaw.cos(),
        ) * self.distance;
        Vec3::from(self.target) + offset
    }

    /// The ray through a point of the image, given in normalised device coordinates
    /// (x right, y up, both in [-1, 1]): its origin and unit direction in mesh space.
    pub fn ray(&self, aspect: f32, ndc: [f32; 2]) -> (Vec3, Vec3) {
        let inverse = self.view_projection(aspect).inverse();
        let near = inverse.project_point3(Vec3::new(ndc[0], ndc[1], 0.0));
        let far = inverse.project_point3(Vec3::new(ndc[0], ndc[1], 1.0));
        (near, (far - near).normalize_or(Vec3::NEG_Z))
    }

    /// How many pixels one mesh unit at `position` spans in an image `image_height`
    /// pixels high (perspective: at the point's depth, never nearer than the near plane).
    pub fn pixels_per_unit(&self, image_height: u32, position: Vec3) -> f32 {
        let half_height = image_height as f32 * 0.5;
        match self.projection {
            Projection::Perspective { fov } => {
                let forward = (Vec3::from(self.target) - self.eye()).normalize_or(Vec3::NEG_Z);
                let depth = (position - self.eye()).dot(forward).max(NEAR_PLANE);
                half_height / ((fov.to_radians() * 0.5).tan() * depth)
            }
            Projection::TopDown { extent } => half_height / extent.max(f32::MIN_POSITIVE),
        }
    }

    fn view_projection(&self, aspect: f32) -> Mat4 {
        match self.projection {
            Projection::Perspective { fov } => {
                let projection = glam::camera::rh::proj::directx::perspective(
                    fov.to_radians(),
                    aspect,
                    NEAR_PLANE,
                    FAR_PLANE,
                );
                projection
                    * glam::camera::rh::view::look_at_mat4(
                        self.eye(),
                        Vec3::from(self.target),
                        Vec3::Y,
                    )
            }
            Projection::TopDown { extent } => {
                let (w, h) = (extent * aspect.max(1.0), extent / aspect.min(1.0));
                let projection = glam::camera::rh::proj::directx::orthographic(
                    -w, w, -h, h, NEAR_PLANE, FAR_PLANE,
                );
                let eye = Vec3::from(self.target) + Vec3::Y * 10.0;
                projection
                    * glam::camera::rh::view::look_at_mat4(
                        eye,
                        Vec3::from(self.target),
                        Vec3::NEG_Z,
                    )
            }
        }
    }

    fn uniform(&self, aspect: f32, crop: Mat4) -> MeshViewUniform {
        let view_projection = crop * self.view_projection(aspect);
        let turn = self.environment_turn.to_radians();
        MeshViewUniform {
            view_projection: view_projection.to_cols_array_2d(),
            inverse_view_projection: view_projection.inverse().to_cols_array_2d(),
            eye: self.eye().extend(1.0).to_array(),
            light_direction: Vec3::from(self.light)
                .normalize_or(Vec3::Y)
                .extend(0.0)
                .to_array(),
            placement: Vec3::from(self.center).extend(self.size).to_array(),
            time: self.time,
            ambient: self.ambient,
            unlit: u32::from(self.unlit),
            tone_map: self.tone_map as u32,
            exposure_scale: self.exposure.exp2(),
            key_light: self.key_light,
            environment_turn: [turn.cos(), turn.sin()],
            backdrop: self.backdrop as u32,
            padding: [0; 3],
        }
    }
}

/// The clip-space transform that shows the pixels `origin .. origin + extent` of a
/// `size`² image on a whole target of `extent` pixels (rows from the top), so a large
/// image renders tile by tile with every pixel centre where the whole image has it.
pub fn tile_crop(size: u32, origin: (u32, u32), extent: (u32, u32)) -> Mat4 {
    let size = size as f32;
    let scale = glam::Vec2::new(size / extent.0 as f32, size / extent.1 as f32);
    // The tile's centre in normalised device coordinates (y up).
    let centre = glam::Vec2::new(
        -1.0 + (2.0 * origin.0 as f32 + extent.0 as f32) / size,
        1.0 - (2.0 * origin.1 as f32 + extent.1 as f32) / size,
    );
    Mat4::from_cols(
        glam::Vec4::new(scale.x, 0.0, 0.0, 0.0),
        glam::Vec4::new(0.0, scale.y, 0.0, 0.0),
        glam::Vec4::Z,
        (-scale * centre).extend(0.0).extend(1.0),
    )
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct MeshViewUniform {
    view_projection: [[f32; 4]; 4],
    inverse_view_projection: [[f32; 4]; 4],
    eye: [f32; 4],
    light_direction: [f32; 4],
    placement: [f32; 4],
    time: f32,
    ambient: f32,
    unlit: u32,
    tone_map: u32,
    exposure_scale: f32,
    key_light: f32,
    environment_turn: [f32; 2],
    backdrop: u32,
    padding: [u32; 3],
}

/// How a material's height shows on the mesh.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Relief {
    /// The vertices move along their normals and the relief shades as bump (the
    /// silhouette changes).
    #[default]
    Displaced,
    /// The relief shades as bump only; the vertices stay (the thesis's bump-mapping
    /// variant of figure 5.10).
    Bump,
}

/// Colour format of offscreen mesh renders.
pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Samples a pixel of headless mesh renders.
pub(super) const SAMPLES: u32 = 4;
const ENTRY_POINTS: &str = concat!(
    include_str!("../../shaders/render_tangent.wgsl"),
    include_str!("../../shaders/render_mesh.wgsl")
);
/// The seeds' lighting.
const BLINN_PHONG: &str = include_str!("../../shaders/render_lit_blinn_phong.wgsl");
/// Seed 003's lighting, as its listings write it.
const THESIS: &str = concat!(
    include_str!("../../shaders/render_lit_thesis_phong.wgsl"),
    include_str!("../../shaders/render_lit_thesis.wgsl")
);
/// Seed 003's C.6.4 lighting and the environment it reflects.
const THESIS_SPHERE_MAP: &str = concat!(
    include_str!("../../shaders/ggx.wgsl"),
    include_str!("../../shaders/tone_map.wgsl"),
    include_str!("../../shaders/render_environment.wgsl"),
    include_str!("../../shaders/render_lit_thesis_phong.wgsl"),
    include_str!("../../shaders/render_lit_thesis_sphere_map.wgsl")
);
/// Metallic-roughness lighting, its environment and the backdrop behind it.
const METALLIC_ROUGHNESS: &str = concat!(
    include_str!("../../shaders/ggx.wgsl"),
    include_str!("../../shaders/tone_map.wgsl"),
    include_str!("../../shaders/render_environment.wgsl"),
    include_str!("../../shaders/render_lit_metallic_roughness.wgsl"),
    include_str!("../../shaders/render_backdrop.wgsl")
);
const DISPLACED_ENTRY_POINT: &str = include_str!("../../shaders/render_mesh_displaced.wgsl");

/// Colour and depth targets of one size and sample count, plus the resolved image.
pub struct MeshTarget {
    /// The multisampled colour target (`None` with one sample: the pass draws straight
    /// into the resolved image).
    multisampled: Option<wgpu::TextureView>,
    depth: wgpu::TextureView,
    /// The resolved image (sampled by the editor, read back by headless renders).
    pub resolved: wgpu::Texture,
    pub resolved_view: wgpu::TextureView,
}

impl MeshTarget {
    /// Targets of `width`×`height` pixels with the headless renders' 4× multisampling.
    pub fn new(device: &wgpu::Device, width: u32, height: u32) -> MeshTarget {
        MeshTarget::with_samples(device, width, height, SAMPLES)
    }

    /// Targets of `width`×`height` pixels and `samples` samples a pixel (1 or 4), for a
    /// pipeline built with the same count.
    pub fn with_samples(
        device: &wgpu::Device,
        width: u32,
        height: u32,
        samples: u32,
    ) -> MeshTarget {
        let texture = |label, format, samples, usage| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width,
                    height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: samples,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let attachment = wgpu::TextureUsages::RENDER_ATTACHMENT;
        let readable =
            attachment | wgpu::TextureUsages::COPY_SRC | wgpu::TextureUsages::TEXTURE_BINDING;
        let resolved = texture("mesh resolved", COLOR_FORMAT, 1, readable);
        MeshTarget {
            multisampled: (samples > 1).then(|| {
                texture("mesh colour", COLOR_FORMAT, samples, attachment)
                    .create_view(&Default::default())
            }),
            depth: texture("mesh depth", DEPTH_FORMAT, samples, attachment)
                .create_view(&Default::default()),
            resolved_view: resolved.create_view(&Default::default()),
            resolved,
        }
    }

    /// Width and height in pixels.
    pub fn size(&self) -> (u32, u32) {
        (self.resolved.width(), self.resolved.height())
    }
}

/// One draw of a mesh pipeline: its pipeline and the bind groups made for its layout.
struct MeshPass {
    pipeline: wgpu::RenderPipeline,
    /// The view uniform, with the environment's maps for metallic-roughness shading
    /// (made by [`MeshPipeline::set_environment`]; until then `None`).
    view_group: Option<wgpu::BindGroup>,
    params_group: Option<wgpu::BindGroup>,
    /// The buffers the material reads at group 2 (uploaded Image files), once bound.
    buffers_group: Option<wgpu::BindGroup>,
    /// Whether it blends, drawing the triangles back to front.
    blended: bool,
}

/// Which fragments a pass draws: alpha in `min..max`; a blended pass writes its alpha
/// for blending and no depth.
struct PassKind {
    min_alpha: f32,
    max_alpha: f32,
    blended: bool,
}

/// Alphas at or above this are opaque in a blended material (within an 8-bit step).
const OPAQUE_ALPHA: f32 = 1.0 - 1.0 / 512.0;
/// An alpha bound no fragment reaches (well within f32, as WGSL literals must be).
const NO_ALPHA_LIMIT: f32 = 3.0e38;
/// Alphas below this add nothing visible to a blended picture.
const INVISIBLE_ALPHA: f32 = 1.0 / 512.0;

impl PassKind {
    /// The passes a material's alpha asks for.
    fn for_alpha(alpha: AlphaUse) -> Vec<PassKind> {
        let opaque = |min_alpha| PassKind {
            min_alpha,
            max_alpha: NO_ALPHA_LIMIT,
            blended: false,
        };
        match alpha {
            AlphaUse::Opaque => vec![opaque(-NO_ALPHA_LIMIT)],
            AlphaUse::Mask(cutoff) => vec![opaque(cutoff)],
            AlphaUse::Blend => vec![
                opaque(OPAQUE_ALPHA),
                PassKind {
                    min_alpha: INVISIBLE_ALPHA,
                    max_alpha: OPAQUE_ALPHA,
                    blended: true,
                },
            ],
        }
    }

    /// The WGSL constants the entry points read for this pass.
    fn constants(&self) -> String {
        format!(
            "const VENEER_MIN_ALPHA: f32 = {:?};\nconst VENEER_MAX_ALPHA: f32 = {:?};\nconst VENEER_BLENDED: bool = {};\n",
            self.min_alpha, self.max_alpha, self.blended
        )
    }
}

/// The render pipeline of one material on meshes, with its view (and parameter) uniforms:
/// one pass for opaque and cut-out materials, two for blended ones (the opaque parts,
/// then the see-through parts back to front over them).
pub struct MeshPipeline {
    passes: Vec<MeshPass>,
    /// Metallic-roughness shading: what draws the backdrop, and its bind group.
    backdrop: Option<(wgpu::RenderPipeline, Option<wgpu::BindGroup>)>,
    /// The environment's bindings the passes read (none unless the shading reads an
    /// environment).
    environment_maps: &'static [u32],
    /// The environment the bind groups hold.
    environment: Option<Arc<EnvironmentMaps>>,
    view: wgpu::Buffer,
    params: Option<wgpu::Buffer>,
}

impl MeshPipeline {
    /// Builds the pipeline for a material module; `param_slots` is the number of slots
    /// of a uniform-mode module (0 when its parameters are baked); `uses` says whether
    /// the material's height moves the vertices, whether it perturbs the normal and what
    /// its alpha does, so that materials without them pay for none.
    pub fn new(
        device: &wgpu::Device,
        material_wgsl: &str,
        param_slots: usize,
        uses: SurfaceUse,
    ) -> Result<MeshPipeline, RenderError> {
        MeshPipeline::with_samples(device, material_wgsl, param_slots, uses, SAMPLES)
    }

    /// [`MeshPipeline::new`] for targets of `samples` samples a pixel (1 or 4; see
    /// [`MeshTarget::with_samples`]). The parameter buffer binds as a uniform block or
    /// as a storage buffer, as the module declares it.
    pub fn with_samples(
        device: &wgpu::Device,
        material_wgsl: &str,
        param_slots: usize,
        uses: SurfaceUse,
        samples: u32,
    ) -> Result<MeshPipeline, RenderError> {
        MeshPipeline::with_relief(
            device,
            material_wgsl,
            param_slots,
            uses,
            samples,
            Relief::Displaced,
        )
    }

    /// [`MeshPipeline::with_samples`] showing the material's height as `relief`.
    pub fn with_relief(
        device: &wgpu::Device,
        material_wgsl: &str,
        param_slots: usize,
        uses: SurfaceUse,
        samples: u32,
        relief: Relief,
    ) -> Result<MeshPipeline, RenderError> {
        let uniform = |label, size: usize| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size as u64,
                usage: wgpu::BufferUsages::UNIFORM
                    | wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let view = uniform("mesh view", std::mem::size_of::<MeshViewUniform>());
        let params = (param_slots > 0).then(|| uniform("material parameters", param_slots * 16));
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let environment_maps = mesh_maps(uses.shading);
        let lit_by_environment = !environment_maps.is_empty();
        let mut modules = Vec::new();
        let passes = PassKind::for_alpha(uses.alpha)
            .iter()
            .map(|kind| {
                let module = mesh_module(device, material_wgsl, uses, relief, kind);
                let pipeline = pass_pipeline(device, &module, uses, samples, relief, kind);
                modules.push(module);
                MeshPass {
                    view_group: (!lit_by_environment)
                        .then(|| view_group(device, &pipeline, &view, None)),
                    params_group: params.as_ref().map(|buffer| {
                        device.create_bind_group(&wgpu::BindGroupDescriptor {
                            label: Some("material parameters"),
                            layout: &pipeline.get_bind_group_layout(1),
                            entries: &[wgpu::BindGroupEntry {
                                binding: 0,
                                resource: buffer.as_entire_binding(),
                            }],
                        })
                    }),
                    buffers_group: None,
                    pipeline,
                    blended: kind.blended,
                }
            })
            .collect();
        let backdrop = (uses.shading == Shading::MetallicRoughness)
            .then(|| (backdrop_pipeline(device, &modules[0], samples), None));
        if let Some(error) = pollster::block_on(scope.pop()) {
            return Err(RenderError::Gpu(format!("mesh render pipeline: {error}")));
        }
        Ok(MeshPipeline {
            passes,
            backdrop,
            environment_maps,
            environment: None,
            view,
            params,
        })
    }

    /// Binds the buffers a material reads at group 2 (its uploaded Image files), from
    /// `group`: their bind group for a pipeline's layout. Only for a material module that
    /// reads buffers.
    pub fn bind_buffers(&mut self, group: impl Fn(&wgpu::RenderPipeline) -> wgpu::BindGroup) {
        for pass in &mut self.passes {
            pass.buffers_group = Some(group(&pass.pipeline));
        }
    }

    /// Whether the pipeline's shading samples an environment: such pipelines
    /// (metallic-roughness, the thesis's sphere map) draw nothing until
    /// [`MeshPipeline::set_environment`] gives them one.
    pub fn needs_environment(&self) -> bool {
        !self.environment_maps.is_empty()
    }

    /// Lights a metallic-roughness pipeline with `environment` (nothing to do when it is
    /// lit by it already, or when its shading is Blinn-Phong).
    pub fn set_environment(&mut self, device: &wgpu::Device, environment: &Arc<EnvironmentMaps>) {
        if !self.needs_environment()
            || self
                .environment
                .as_ref()
                .is_some_and(|lit| Arc::ptr_eq(lit, environment))
        {
            return;
        }
        for pass in &mut self.passes {
            pass.view_group = Some(view_group(
                device,
                &pass.pipeline,
                &self.view,
                Some((environment, self.environment_maps)),
            ));
        }
        if let Some((pipeline, group)) = &mut self.backdrop {
            *group = Some(view_group(
                device,
                pipeline,
                &self.view,
                Some((environment, BACKDROP_MAPS)),
            ));
        }
        self.environment = Some(Arc::clone(environment));
    }

    /// Whether the pipeline blends: meshes it draws need uploading with
    /// [`GpuMesh::with_depth_order`] and sorting for each view ([`MeshPipeline::sort`]).
    pub fn blends(&self) -> bool {
        self.passes.iter().any(|pass| pass.blended)
    }

    /// Sorts `mesh`'s triangles back to front for `view` when the pipeline blends.
    pub fn sort(&self, queue: &wgpu::Queue, mesh: &GpuMesh, view: &MeshView) {
        if self.blends() {
            mesh.sort_back_to_front(queue, view.eye());
        }
    }

    /// Writes the camera, light and time for the next draw into a target of `aspect` (w / h).
    pub fn write_view(&self, queue: &wgpu::Queue, view: &MeshView, aspect: f32) {
        self.write_view_cropped(queue, view, aspect, Mat4::IDENTITY);
    }

    /// [`MeshPipeline::write_view`] for a target that shows part of the image: `crop`
    /// maps that part's clip-space rectangle onto the whole target (see [`tile_crop`]).
    pub fn write_view_cropped(
        &self,
        queue: &wgpu::Queue,
        view: &MeshView,
        aspect: f32,
        crop: Mat4,
    ) {
        queue.write_buffer(
            &self.view,
            0,
            bytemuck::bytes_of(&view.uniform(aspect, crop)),
        );
    }

    /// Writes the parameter values of a uniform-mode material (ignored when baked).
    pub fn write_params(&self, queue: &wgpu::Queue, values: &[[f32; 4]]) {
        if let Some(buffer) = &self.params {
            let fits = (buffer.size() / 16) as usize;
            queue.write_buffer(
                buffer,
                0,
                bytemuck::cast_slice(&values[..values.len().min(fits)]),
            );
        }
    }

    /// Records a pass that clears `target` to `view`'s background, draws its backdrop
    /// (metallic-roughness shading) and draws `mesh` into it.
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        target: &MeshTarget,
        mesh: &GpuMesh,
        view: &MeshView,
    ) {
        self.encode_timed(encoder, target, mesh, view, None);
    }

    /// [`MeshPipeline::encode`] with timestamps written at the pass's beginning and end
    /// (see [`super::PassTimer`]).
    pub fn encode_timed(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        target: &MeshTarget,
        mesh: &GpuMesh,
        view: &MeshView,
        timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) {
        let [r, g, b] = view.background.map(f64::from);
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("mesh"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: target
                    .multisampled
                    .as_ref()
                    .unwrap_or(&target.resolved_view),
                depth_slice: None,
                resolve_target: target.multisampled.as_ref().map(|_| &target.resolved_view),
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color { r, g, b, a: 1.0 }),
                    store: if target.multisampled.is_some() {
                        wgpu::StoreOp::Discard
                    } else {
                        wgpu::StoreOp::Store
                    },
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &target.depth,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes,
            ..Default::default()
        });
        if let Some((pipeline, Some(group))) = &self.backdrop
            && view.backdrop != Backdrop::Colour
            && !view.unlit
        {
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, group, &[]);
            pass.draw(0..3, 0..1);
        }
        for draw in &self.passes {
            let Some(view_group) = &draw.view_group else {
                continue;
            };
            pass.set_pipeline(&draw.pipeline);
            pass.set_bind_group(0, view_group, &[]);
            if let Some(group) = &draw.params_group {
                pass.set_bind_group(1, group, &[]);
            }
            if let Some(group) = &draw.buffers_group {
                pass.set_bind_group(2, group, &[]);
            }
            if draw.blended {
                mesh.draw_back_to_front(&mut pass);
            } else {
                mesh.draw(&mut pass);
            }
        }
    }
}

/// The shader module of one pass of a material: the material, the entry points and the
/// lighting of its shading, specialised by constants for what it uses and what the pass
/// draws.
fn mesh_module(
    device: &wgpu::Device,
    material_wgsl: &str,
    uses: SurfaceUse,
    relief: Relief,
    kind: &PassKind,
) -> wgpu::ShaderModule {
    let displaced = uses.displacement && relief == Relief::Displaced;
    // Height work (vertex displacement, relief shading) only for materials with a
    // height, normal perturbation only for materials with a bump, a height or a tilt.
    let constants = format!(
        "const VENEER_HEIGHT: bool = {};\nconst VENEER_RELIEF: bool = {};\nconst VENEER_NORMAL: bool = {};\n{}",
        uses.displacement,
        uses.perturbs_normal(),
        uses.normal,
        kind.constants()
    );
    let lighting = match uses.shading {
        Shading::BlinnPhong => BLINN_PHONG.to_string(),
        Shading::MetallicRoughness => METALLIC_ROUGHNESS.to_string(),
        Shading::Thesis | Shading::ThesisAbsolute => format!(
            "const VENEER_ABSOLUTE_N_DOT_L: bool = {};\n{THESIS}",
            uses.shading == Shading::ThesisAbsolute
        ),
        Shading::ThesisSphereMap => {
            format!("const VENEER_ABSOLUTE_N_DOT_L: bool = false;\n{THESIS_SPHERE_MAP}")
        }
    };
    let displacement = if displaced { DISPLACED_ENTRY_POINT } else { "" };
    let entry_points = format!("{constants}{ENTRY_POINTS}\n{lighting}\n{displacement}");
    device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("mesh render"),
        source: wgpu::ShaderSource::Wgsl(shader_source(material_wgsl, &entry_points).into()),
    })
}

/// The environment's bindings (render_environment.wgsl) the mesh passes of a shading
/// read: metallic-roughness the prefiltered chain, the irradiance, the BRDF table and the
/// sampler; the thesis's sphere map the sharpest level of the chain and the sampler.
fn mesh_maps(shading: Shading) -> &'static [u32] {
    match shading {
        Shading::MetallicRoughness => &[2, 3, 4, 5],
        Shading::ThesisSphereMap => &[2, 5],
        Shading::BlinnPhong | Shading::Thesis | Shading::ThesisAbsolute => &[],
    }
}
/// The bindings the backdrop reads: the panorama, the prefiltered chain, the sampler.
const BACKDROP_MAPS: &[u32] = &[1, 2, 5];

/// The bind group of a pipeline's view uniform and, for metallic-roughness shading, the
/// environment's maps it reads (`bindings` of render_environment.wgsl's).
fn view_group(
    device: &wgpu::Device,
    pipeline: &wgpu::RenderPipeline,
    view: &wgpu::Buffer,
    environment: Option<(&EnvironmentMaps, &[u32])>,
) -> wgpu::BindGroup {
    let mut entries = vec![wgpu::BindGroupEntry {
        binding: 0,
        resource: view.as_entire_binding(),
    }];
    if let Some((maps, bindings)) = environment {
        let texture = |binding, view| wgpu::BindGroupEntry {
            binding,
            resource: wgpu::BindingResource::TextureView(view),
        };
        let all = [
            texture(1, &maps.source),
            texture(2, &maps.prefiltered),
            texture(3, &maps.irradiance),
            texture(4, &maps.brdf),
            wgpu::BindGroupEntry {
                binding: 5,
                resource: wgpu::BindingResource::Sampler(&maps.sampler),
            },
        ];
        entries.extend(
            all.into_iter()
                .filter(|entry| bindings.contains(&entry.binding)),
        );
    }
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("mesh view"),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &entries,
    })
}

/// The depth state of the mesh targets' pipelines: `compare` against the depth, which
/// the pipeline writes or not.
fn depth_test(write: bool, compare: wgpu::CompareFunction) -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: DEPTH_FORMAT,
        depth_write_enabled: Some(write),
        depth_compare: Some(compare),
        stencil: Default::default(),
        bias: Default::default(),
    }
}

/// The pipeline that draws a metallic-roughness material's backdrop, behind the mesh.
fn backdrop_pipeline(
    device: &wgpu::Device,
    module: &wgpu::ShaderModule,
    samples: u32,
) -> wgpu::RenderPipeline {
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("backdrop"),
        layout: None,
        vertex: wgpu::VertexState {
            module,
            entry_point: Some("veneer_backdrop_vertex"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: Some(depth_test(false, wgpu::CompareFunction::Always)),
        multisample: wgpu::MultisampleState {
            count: samples,
            ..Default::default()
        },
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some("veneer_backdrop_fragment"),
            compilation_options: Default::default(),
            targets: &[Some(COLOR_FORMAT.into())],
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// The pipeline of one pass of a material: `kind` says which fragments it draws and
/// whether it blends; back faces are culled only where the material is opaque.
fn pass_pipeline(
    device: &wgpu::Device,
    module: &wgpu::ShaderModule,
    uses: SurfaceUse,
    samples: u32,
    relief: Relief,
    kind: &PassKind,
) -> wgpu::RenderPipeline {
    let displaced = uses.displacement && relief == Relief::Displaced;
    let blend = kind.blended.then_some(wgpu::BlendState {
        color: wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::SrcAlpha,
            dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
            operation: wgpu::BlendOperation::Add,
        },
        // The image stays opaque: alpha = a + (1 - a) * 1.
        alpha: wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::One,
            dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
            operation: wgpu::BlendOperation::Add,
        },
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("mesh render"),
        layout: None,
        vertex: wgpu::VertexState {
            module,
            entry_point: Some(if displaced {
                "veneer_mesh_vertex_displaced"
            } else {
                "veneer_mesh_vertex"
            }),
            compilation_options: Default::default(),
            buffers: &[Some(GpuMesh::layout())],
        },
        primitive: wgpu::PrimitiveState {
            cull_mode: (uses.alpha == AlphaUse::Opaque).then_some(wgpu::Face::Back),
            ..Default::default()
        },
        depth_stencil: Some(depth_test(!kind.blended, wgpu::CompareFunction::Less)),
        multisample: wgpu::MultisampleState {
            count: samples,
            ..Default::default()
        },
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some("veneer_mesh_fragment"),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::ColorTargetState {
                format: COLOR_FORMAT,
                blend,
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    })
}
