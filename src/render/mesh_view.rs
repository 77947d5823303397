//! The lit mesh render: a material on a mesh with Blinn-Phong lighting, as in the preview.

use super::readback::read_texture;
use super::{GpuContext, RenderError, shader_source};
use crate::graph::Preview;
use crate::mesh::Mesh;
use glam::Vec3;
use wgpu::util::DeviceExt;

/// Camera, light and placement of a mesh render.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshView {
    /// Camera orbit angles in degrees and distance from the origin.
    pub yaw: f32,
    pub pitch: f32,
    pub distance: f32,
    /// Vertical field of view in degrees.
    pub fov: f32,
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
}

impl MeshView {
    /// The default view of a graph's preview settings.
    pub fn for_preview(preview: &Preview) -> MeshView {
        MeshView {
            yaw: 30.0,
            pitch: 25.0,
            distance: 3.6,
            fov: 40.0,
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
        }
    }

    fn eye(&self) -> Vec3 {
        let (yaw, pitch) = (self.yaw.to_radians(), self.pitch.to_radians());
        Vec3::new(
            pitch.cos() * yaw.sin(),
            pitch.sin(),
            pitch.cos() * yaw.cos(),
        ) * self.distance
    }
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct MeshViewUniform {
    view_projection: [[f32; 4]; 4],
    eye: [f32; 4],
    light_direction: [f32; 4],
    placement: [f32; 4],
    time: f32,
    ambient: f32,
    padding: [f32; 2],
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Vertex {
    position: [f32; 3],
    normal: [f32; 3],
    uv: [f32; 2],
}

const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
const SAMPLES: u32 = 4;
const ENTRY_POINTS: &str = include_str!("../../shaders/render_mesh.wgsl");

/// A pipeline that renders one material on meshes.
pub struct MeshRenderer {
    pipeline: wgpu::RenderPipeline,
    uniform: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
}

impl MeshRenderer {
    /// Builds the pipeline for a material module.
    pub fn new(gpu: &GpuContext, material_wgsl: &str) -> Result<MeshRenderer, RenderError> {
        let module = gpu.shader("mesh render", &shader_source(material_wgsl, ENTRY_POINTS))?;
        let uniform = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("mesh view"),
            size: std::mem::size_of::<MeshViewUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let attributes = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x2];
        let pipeline = gpu.checked("mesh render pipeline", || {
            gpu.device
                .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                    label: Some("mesh render"),
                    layout: None,
                    vertex: wgpu::VertexState {
                        module: &module,
                        entry_point: Some("veneer_mesh_vertex"),
                        compilation_options: Default::default(),
                        buffers: &[Some(wgpu::VertexBufferLayout {
                            array_stride: std::mem::size_of::<Vertex>() as u64,
                            step_mode: wgpu::VertexStepMode::Vertex,
                            attributes: &attributes,
                        })],
                    },
                    primitive: wgpu::PrimitiveState {
                        cull_mode: Some(wgpu::Face::Back),
                        ..Default::default()
                    },
                    depth_stencil: Some(wgpu::DepthStencilState {
                        format: DEPTH_FORMAT,
                        depth_write_enabled: Some(true),
                        depth_compare: Some(wgpu::CompareFunction::Less),
                        stencil: Default::default(),
                        bias: Default::default(),
                    }),
                    multisample: wgpu::MultisampleState {
                        count: SAMPLES,
                        ..Default::default()
                    },
                    fragment: Some(wgpu::FragmentState {
                        module: &module,
                        entry_point: Some("veneer_mesh_fragment"),
                        compilation_options: Default::default(),
                        targets: &[Some(COLOR_FORMAT.into())],
                    }),
                    multiview_mask: None,
                    cache: None,
                })
        })?;
        let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("mesh view"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: uniform.as_entire_binding(),
            }],
        });
        Ok(MeshRenderer {
            pipeline,
            uniform,
            bind_group,
        })
    }

    /// Renders `mesh` into a size×size RGBA8 image (rows from the top).
    pub fn render(
        &self,
        gpu: &GpuContext,
        mesh: &Mesh,
        view: &MeshView,
        size: u32,
    ) -> Result<Vec<u8>, RenderError> {
        let limit = gpu.device.limits().max_texture_dimension_2d;
        if size == 0 || size > limit {
            return Err(RenderError(format!(
                "mesh render size {size} is outside 1..={limit} on this adapter"
            )));
        }
        let eye = view.eye();
        let projection =
            glam::camera::rh::proj::directx::perspective(view.fov.to_radians(), 1.0, 0.05, 100.0);
        let uniform = MeshViewUniform {
            view_projection: (projection
                * glam::camera::rh::view::look_at_mat4(eye, Vec3::ZERO, Vec3::Y))
            .to_cols_array_2d(),
            eye: eye.extend(1.0).to_array(),
            light_direction: Vec3::from(view.light)
                .normalize_or(Vec3::Y)
                .extend(0.0)
                .to_array(),
            placement: Vec3::from(view.center).extend(view.size).to_array(),
            time: view.time,
            ambient: view.ambient,
            padding: [0.0; 2],
        };
        gpu.queue
            .write_buffer(&self.uniform, 0, bytemuck::bytes_of(&uniform));
        let vertices: Vec<Vertex> = (0..mesh.positions.len())
            .map(|i| Vertex {
                position: mesh.positions[i],
                normal: mesh.normals[i],
                uv: mesh.uvs[i],
            })
            .collect();
        let vertex_buffer = gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("mesh vertices"),
                contents: bytemuck::cast_slice(&vertices),
                usage: wgpu::BufferUsages::VERTEX,
            });
        let index_buffer = gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("mesh indices"),
                contents: bytemuck::cast_slice(&mesh.indices),
                usage: wgpu::BufferUsages::INDEX,
            });
        let target = |label, format, samples, usage| {
            gpu.device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width: size,
                    height: size,
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
        let multisampled = target("mesh colour", COLOR_FORMAT, SAMPLES, attachment);
        let resolved = target(
            "mesh resolved",
            COLOR_FORMAT,
            1,
            attachment | wgpu::TextureUsages::COPY_SRC,
        );
        let depth = target("mesh depth", DEPTH_FORMAT, SAMPLES, attachment);
        let (multisampled_view, resolved_view, depth_view) = (
            multisampled.create_view(&Default::default()),
            resolved.create_view(&Default::default()),
            depth.create_view(&Default::default()),
        );
        let [r, g, b] = view.background.map(f64::from);
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("mesh"),
            });
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("mesh"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &multisampled_view,
                    depth_slice: None,
                    resolve_target: Some(&resolved_view),
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color { r, g, b, a: 1.0 }),
                        store: wgpu::StoreOp::Discard,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &depth_view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Discard,
                    }),
                    stencil_ops: None,
                }),
                ..Default::default()
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &self.bind_group, &[]);
            pass.set_vertex_buffer(0, vertex_buffer.slice(..));
            pass.set_index_buffer(index_buffer.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..mesh.indices.len() as u32, 0, 0..1);
        }
        gpu.queue.submit([encoder.finish()]);
        read_texture(gpu, &resolved, 4)
    }
}
