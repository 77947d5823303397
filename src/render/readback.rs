//! Copying a rendered texture back to the CPU.

use super::{GpuContext, RenderError};

/// Rows of a texture copied to the CPU, without the row padding wgpu requires.
pub fn read_texture(
    gpu: &GpuContext,
    texture: &wgpu::Texture,
    bytes_per_pixel: u32,
) -> Result<Vec<u8>, RenderError> {
    let (width, height) = (texture.width(), texture.height());
    let unpadded = width * bytes_per_pixel;
    let padded =
        unpadded.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("veneer readback"),
        size: u64::from(padded) * u64::from(height),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = gpu
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("readback"),
        });
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(height),
            },
        },
        wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
    );
    gpu.queue.submit([encoder.finish()]);
    read_buffer(gpu, &buffer, |bytes| {
        let mut pixels = Vec::with_capacity((unpadded * height) as usize);
        for row in bytes.chunks(padded as usize) {
            pixels.extend_from_slice(&row[..unpadded as usize]);
        }
        pixels
    })
}

/// `read` applied to the content of a `MAP_READ` buffer once the GPU has finished the
/// work submitted before (waits for it).
pub fn read_buffer<T>(
    gpu: &GpuContext,
    buffer: &wgpu::Buffer,
    read: impl FnOnce(&[u8]) -> T,
) -> Result<T, RenderError> {
    let (sender, receiver) = std::sync::mpsc::channel();
    buffer
        .slice(..)
        .map_async(wgpu::MapMode::Read, move |result| {
            let _ = sender.send(result);
        });
    gpu.device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|error| RenderError(format!("waiting for the GPU failed: {error}")))?;
    gpu.take_errors()?;
    receiver
        .recv()
        .map_err(|_| RenderError("the GPU dropped the readback".into()))?
        .map_err(|error| RenderError(format!("cannot map the readback buffer: {error}")))?;
    let value = read(
        &buffer
            .get_mapped_range(..)
            .map_err(|error| RenderError(format!("cannot read back: {error}")))?,
    );
    buffer.unmap();
    Ok(value)
}
