//! The preview panel: the live material on a mesh (or flat, unlit, from above), drawn
//! through an egui_wgpu paint callback. The pipeline is rebuilt only when the material's
//! code changes; camera, time and parameters are uniforms written every frame.

use crate::graph::Preview;
use crate::render::{GpuMesh, MeshPipeline, MeshTarget, MeshView, Projection};
use eframe::egui_wgpu::{self, wgpu};
use egui::{Sense, Ui};
use std::sync::Arc;

/// What the preview shows and from where; kept by the app between frames.
pub struct PreviewState {
    /// A primitive's name or a mesh file's path.
    pub mesh: String,
    /// The loaded mesh when `mesh` is a file (fitted to the unit sphere).
    pub file: Option<Arc<crate::mesh::Mesh>>,
    /// The mesh with its distance fields solved, and what it was solved for; drawn in
    /// place of the plain mesh when present.
    pub prepared: Option<(String, Arc<crate::mesh::Mesh>)>,
    pub view: MeshView,
    /// Show the albedo flat from above instead of lit on the mesh.
    pub flat: bool,
    pub playing: bool,
}

impl PreviewState {
    /// The default preview of a graph.
    pub fn for_graph(preview: &Preview) -> PreviewState {
        PreviewState {
            file: None,
            prepared: None,
            mesh: preview.mesh.clone(),
            view: MeshView::for_preview(preview),
            flat: false,
            playing: false,
        }
    }

    /// The mesh shown, without distance fields: the primitive named (made anew) or the
    /// loaded file.
    pub fn plain_mesh(&self) -> Option<Arc<crate::mesh::Mesh>> {
        crate::mesh::primitive(&self.mesh)
            .map(Arc::new)
            .or_else(|| self.file.clone())
    }

    /// Takes the placement (centre and size in texture space) of `preview`, keeping the camera.
    pub fn follow(&mut self, preview: &Preview) {
        self.view.center = [
            preview.center.0 as f32,
            preview.center.1 as f32,
            preview.center.2 as f32,
        ];
        self.view.size = preview.size as f32;
    }
}

/// The material the callback draws: its code (uniform mode) and parameter values.
#[derive(Clone)]
pub struct MaterialFrame {
    /// Changes whenever the code does.
    pub generation: u64,
    pub wgsl: Arc<str>,
    pub slots: usize,
    /// What of the surface the material uses (height, bump, fields).
    pub uses: crate::codegen::SurfaceUse,
    pub params: Vec<[f32; 4]>,
}

/// Which preview a callback draws: the big one or the selected node's thumbnail.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Slot {
    Main = 0,
    Thumbnail = 1,
}

/// The GPU objects of both previews, kept in egui_wgpu's callback resources.
pub struct PreviewTargets(pub [PreviewResources; 2]);

impl PreviewTargets {
    /// Both previews' resources for egui's target format.
    pub fn new(device: &wgpu::Device, target_format: wgpu::TextureFormat) -> PreviewTargets {
        PreviewTargets([
            PreviewResources::new(device, target_format),
            PreviewResources::new(device, target_format),
        ])
    }
}

/// GPU objects of one preview that live across frames.
pub struct PreviewResources {
    pipeline: Option<(u64, MeshPipeline)>,
    /// An error from building the newest pipeline; the previous one stays in use.
    pub pipeline_error: Option<String>,
    mesh: Option<(String, GpuMesh)>,
    target: Option<(MeshTarget, wgpu::BindGroup)>,
    blit: wgpu::RenderPipeline,
    sampler: wgpu::Sampler,
    /// How many pipelines have been built (for tests and the status bar).
    pub pipelines_built: u64,
}

impl PreviewResources {
    /// Creates the blit pipeline for egui's target format.
    pub fn new(device: &wgpu::Device, target_format: wgpu::TextureFormat) -> PreviewResources {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("preview blit"),
            source: wgpu::ShaderSource::Wgsl(include_str!("../../shaders/render_blit.wgsl").into()),
        });
        let fragment = if target_format.is_srgb() {
            "veneer_blit_fragment_srgb"
        } else {
            "veneer_blit_fragment"
        };
        let entry_points = ("veneer_blit_vertex", fragment);
        let blit = crate::render::fullscreen_pipeline(
            device,
            "preview blit",
            &module,
            entry_points,
            target_format,
        );
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("preview"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        PreviewResources {
            pipeline: None,
            pipeline_error: None,
            mesh: None,
            target: None,
            blit,
            sampler,
            pipelines_built: 0,
        }
    }

    fn sync(&mut self, device: &wgpu::Device, frame: &PreviewCallback) {
        if let Some(material) = &frame.material {
            let current = self.pipeline.as_ref().map(|(generation, _)| *generation);
            if current != Some(material.generation) {
                match MeshPipeline::new(device, &material.wgsl, material.slots, material.uses) {
                    Ok(pipeline) => {
                        self.pipeline = Some((material.generation, pipeline));
                        self.pipeline_error = None;
                        self.pipelines_built += 1;
                    }
                    Err(error) => self.pipeline_error = Some(error.to_string()),
                }
            }
        }
        let prepared = frame.prepared.as_ref().filter(|_| !frame.flat);
        let mesh_key = match (frame.flat, prepared) {
            (true, _) => "plane",
            (false, Some((key, _))) => key.as_str(),
            (false, None) => frame.mesh.as_str(),
        };
        if self.mesh.as_ref().is_none_or(|(key, _)| key != mesh_key) {
            // Uploaded from where it is: the solved mesh, a primitive, the loaded file
            // or, failing all, the sphere.
            let file = frame.file.as_deref().filter(|_| !frame.flat);
            let generated = match prepared {
                Some(_) => None,
                None => crate::mesh::primitive(mesh_key).or_else(|| {
                    file.is_none()
                        .then(|| crate::mesh::primitive("sphere").expect("sphere exists"))
                }),
            };
            let mesh = prepared
                .map(|(_, mesh)| mesh.as_ref())
                .or(generated.as_ref())
                .or(file)
                .expect("one of them is present");
            self.mesh = Some((mesh_key.to_string(), GpuMesh::new(device, mesh)));
        }
        if self
            .target
            .as_ref()
            .is_none_or(|(target, _)| target.size() != frame.size)
        {
            let target = MeshTarget::new(device, frame.size.0, frame.size.1);
            let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("preview blit"),
                layout: &self.blit.get_bind_group_layout(0),
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: wgpu::BindingResource::TextureView(&target.resolved_view),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::Sampler(&self.sampler),
                    },
                ],
            });
            self.target = Some((target, group));
        }
    }
}

/// One frame of the preview.
pub struct PreviewCallback {
    slot: Slot,
    material: Option<MaterialFrame>,
    mesh: String,
    file: Option<Arc<crate::mesh::Mesh>>,
    prepared: Option<(String, Arc<crate::mesh::Mesh>)>,
    view: MeshView,
    flat: bool,
    size: (u32, u32),
}

impl egui_wgpu::CallbackTrait for PreviewCallback {
    fn prepare(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        _screen: &egui_wgpu::ScreenDescriptor,
        encoder: &mut wgpu::CommandEncoder,
        resources: &mut egui_wgpu::CallbackResources,
    ) -> Vec<wgpu::CommandBuffer> {
        let Some(PreviewTargets(slots)) = resources.get_mut::<PreviewTargets>() else {
            return Vec::new();
        };
        let state = &mut slots[self.slot as usize];
        state.sync(device, self);
        let (Some((_, pipeline)), Some((_, mesh)), Some((target, _))) =
            (&state.pipeline, &state.mesh, &state.target)
        else {
            return Vec::new();
        };
        let aspect = self.size.0 as f32 / self.size.1.max(1) as f32;
        pipeline.write_view(queue, &self.view, aspect);
        if let Some(material) = &self.material {
            pipeline.write_params(queue, &material.params);
        }
        pipeline.encode(encoder, target, mesh, self.view.background);
        Vec::new()
    }

    fn paint(
        &self,
        _info: egui::PaintCallbackInfo,
        pass: &mut wgpu::RenderPass<'static>,
        resources: &egui_wgpu::CallbackResources,
    ) {
        let Some(PreviewTargets(slots)) = resources.get::<PreviewTargets>() else {
            return;
        };
        let state = &slots[self.slot as usize];
        if let (Some(_), Some((_, group))) = (&state.pipeline, &state.target) {
            pass.set_pipeline(&state.blit);
            pass.set_bind_group(0, group, &[]);
            pass.draw(0..3, 0..1);
        }
    }
}

/// Shows the preview in `ui`, filling `size`, with orbit (drag), zoom (scroll) and pan
/// (right drag) on the mesh, or zoom and pan on the flat view.
pub fn show(
    ui: &mut Ui,
    state: &mut PreviewState,
    material: Option<MaterialFrame>,
    size: egui::Vec2,
) -> egui::Response {
    draw(ui, state, material, size, Slot::Main, true)
}

/// Shows a node's thumbnail: the flat view of `state`'s placement, not interactive.
pub fn thumbnail(
    ui: &mut Ui,
    state: &PreviewState,
    material: Option<MaterialFrame>,
    size: egui::Vec2,
) -> egui::Response {
    let mut flat = PreviewState {
        mesh: state.mesh.clone(),
        file: None,
        prepared: None,
        view: state.view.clone(),
        flat: true,
        playing: false,
    };
    flat.view.distance = 3.6;
    flat.view.target = [0.0; 3];
    draw(ui, &mut flat, material, size, Slot::Thumbnail, false)
}

fn draw(
    ui: &mut Ui,
    state: &mut PreviewState,
    material: Option<MaterialFrame>,
    size: egui::Vec2,
    slot: Slot,
    interactive: bool,
) -> egui::Response {
    let sense = if interactive {
        Sense::click_and_drag()
    } else {
        Sense::hover()
    };
    let (rect, response) = ui.allocate_exact_size(size, sense);
    let view = &mut state.view;
    if response.dragged_by(egui::PointerButton::Primary) && !state.flat {
        let delta = response.drag_delta();
        view.yaw -= delta.x * 0.4;
        view.pitch = (view.pitch + delta.y * 0.4).clamp(-89.0, 89.0);
    }
    if response.dragged_by(egui::PointerButton::Secondary)
        || (state.flat && response.dragged_by(egui::PointerButton::Primary))
    {
        let delta = response.drag_delta() / rect.height().max(1.0) * view.distance;
        let yaw = view.yaw.to_radians();
        let (right, up) = if state.flat {
            ([1.0, 0.0, 0.0], [0.0, 0.0, -1.0])
        } else {
            ([yaw.cos(), 0.0, -yaw.sin()], [0.0, 1.0, 0.0])
        };
        for k in 0..3 {
            view.target[k] -= right[k] * delta.x - up[k] * delta.y;
        }
    }
    if response.hovered() {
        let scroll = ui.input(|input| input.smooth_scroll_delta.y);
        view.distance = (view.distance * (-scroll * 0.002).exp()).clamp(0.3, 50.0);
    }
    let mut frame_view = view.clone();
    if state.flat {
        frame_view.projection = Projection::TopDown {
            extent: view.distance / 3.6,
        };
        frame_view.unlit = true;
    }
    let pixels = (rect.size() * ui.ctx().pixels_per_point()).round();
    let callback = PreviewCallback {
        slot,
        material,
        mesh: state.mesh.clone(),
        file: state.file.clone(),
        prepared: state.prepared.clone(),
        view: frame_view,
        flat: state.flat,
        size: (pixels.x.max(1.0) as u32, pixels.y.max(1.0) as u32),
    };
    ui.painter()
        .add(egui_wgpu::Callback::new_paint_callback(rect, callback));
    response
}
