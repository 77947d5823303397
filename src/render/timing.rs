//! How long the GPU spends in a render pass, from timestamps it writes at the pass's
//! beginning and end, so that timings leave out submission and reading the image back
//! (which dominate on a real GPU). Adapters without timestamp queries get none.

use super::readback::read_buffer;
use super::{GpuContext, RenderError};
use std::time::Duration;

/// Times one render pass drawing at most one tile (`size`² pixels, checked first):
/// `record` records it into the encoder with the timestamp writes it is given. The pass
/// time from timestamps where the device has them ([`PassTimer::supported`]), else the
/// wall time from submitting the pass to its completion.
pub fn time_pass(
    gpu: &GpuContext,
    size: u32,
    record: impl FnOnce(&mut wgpu::CommandEncoder, Option<wgpu::RenderPassTimestampWrites<'_>>),
) -> Result<Duration, RenderError> {
    let limit = super::tile_size(gpu);
    if size == 0 || size > limit {
        return Err(RenderError::Invalid(format!(
            "a timed render is one tile: size {size} is outside 1..={limit}"
        )));
    }
    let timer = PassTimer::new(gpu);
    let mut encoder = gpu
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("timed pass"),
        });
    record(&mut encoder, timer.as_ref().map(PassTimer::writes));
    if let Some(timer) = &timer {
        timer.resolve(&mut encoder);
    }
    let started = std::time::Instant::now();
    gpu.queue.submit([encoder.finish()]);
    match timer {
        Some(timer) => timer.read(gpu),
        None => {
            gpu.device
                .poll(wgpu::PollType::wait_indefinitely())
                .map_err(|error| {
                    RenderError::Gpu(format!("waiting for the GPU failed: {error}"))
                })?;
            Ok(started.elapsed())
        }
    }
}

/// Two timestamp queries around one render pass, and the buffers to read them through.
pub struct PassTimer {
    queries: wgpu::QuerySet,
    resolved: wgpu::Buffer,
    readable: wgpu::Buffer,
}

impl PassTimer {
    /// Whether the device has timestamp queries (else timings fall back to wall time).
    pub fn supported(gpu: &GpuContext) -> bool {
        gpu.device
            .features()
            .contains(wgpu::Features::TIMESTAMP_QUERY)
    }

    /// A timer, when the device has timestamp queries.
    pub fn new(gpu: &GpuContext) -> Option<PassTimer> {
        if !PassTimer::supported(gpu) {
            return None;
        }
        let buffer = |label, usage| {
            gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: 16,
                usage,
                mapped_at_creation: false,
            })
        };
        Some(PassTimer {
            queries: gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("pass timer"),
                ty: wgpu::QueryType::Timestamp,
                count: 2,
            }),
            resolved: buffer(
                "pass timer resolve",
                wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            ),
            readable: buffer(
                "pass timer readback",
                wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            ),
        })
    }

    /// The timestamp writes for the pass to time.
    pub fn writes(&self) -> wgpu::RenderPassTimestampWrites<'_> {
        wgpu::RenderPassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: Some(0),
            end_of_pass_write_index: Some(1),
        }
    }

    /// Records copying the timestamps out, after the pass, into `encoder`.
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.resolve_query_set(&self.queries, 0..2, &self.resolved, 0);
        encoder.copy_buffer_to_buffer(&self.resolved, 0, &self.readable, 0, 16);
    }

    /// The time between the two timestamps, once the submitted work has finished.
    pub fn read(&self, gpu: &GpuContext) -> Result<Duration, RenderError> {
        let ticks = read_buffer(gpu, &self.readable, None, |bytes| {
            let stamp = |k: usize| bytemuck::pod_read_unaligned::<u64>(&bytes[8 * k..8 * k + 8]);
            stamp(1).saturating_sub(stamp(0))
        })?;
        let nanoseconds = ticks as f64 * f64::from(gpu.queue.get_timestamp_period());
        Ok(Duration::from_nanos(nanoseconds as u64))
    }
}
