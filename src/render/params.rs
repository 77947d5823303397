//! The parameter values of a material compiled with slots (the editor's): one buffer of
//! `vec4f` slots at group 1, binding 0, read by the material's module and by every pass
//! that uses a slot (a multi-pass material's modules share one numbering).

use super::GpuContext;
use std::sync::Mutex;

/// A buffer of parameter slots and the values last written to it.
pub struct ParamBlock {
    buffer: wgpu::Buffer,
    written: Mutex<Vec<[f32; 4]>>,
}

impl ParamBlock {
    /// A block of `slots` slots (`None` when there are none), usable as a uniform or a
    /// storage buffer.
    pub fn new(gpu: &GpuContext, slots: usize) -> Option<ParamBlock> {
        (slots > 0).then(|| ParamBlock {
            buffer: gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("material parameters"),
                size: slots as u64 * 16,
                usage: wgpu::BufferUsages::UNIFORM
                    | wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            written: Mutex::new(Vec::new()),
        })
    }

    /// Writes `values` (as many as fit), unless they are those last written.
    pub fn write(&self, gpu: &GpuContext, values: &[[f32; 4]]) {
        let fits = &values[..values.len().min((self.buffer.size() / 16) as usize)];
        let mut written = self.written.lock().expect("parameter values");
        if written.as_slice() != fits {
            gpu.queue
                .write_buffer(&self.buffer, 0, bytemuck::cast_slice(fits));
            *written = fits.to_vec();
        }
    }

    /// The values last written.
    pub fn values(&self) -> Vec<[f32; 4]> {
        self.written.lock().expect("parameter values").clone()
    }

    /// The bind group of the block for group 1 of `pipeline`.
    pub fn bind_group(&self, gpu: &GpuContext, pipeline: &wgpu::RenderPipeline) -> wgpu::BindGroup {
        gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("material parameters"),
            layout: &pipeline.get_bind_group_layout(1),
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: self.buffer.as_entire_binding(),
            }],
        })
    }
}
