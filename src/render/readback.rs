//! Copying rendered textures back to the CPU.

use super::{GpuContext, RenderError};

/// A buffer that tiles of up to a fixed size are copied into and read back from, reused
/// from tile to tile so a large render does not allocate (and fault in) a buffer per tile.
pub struct Readback {
    buffer: wgpu::Buffer,
    bytes_per_pixel: u32,
}

impl Readback {
    /// A readback buffer for textures of at most `width`×`height` pixels of
    /// `bytes_per_pixel` bytes.
    pub fn new(gpu: &GpuContext, (width, height): (u32, u32), bytes_per_pixel: u32) -> Readback {
        let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("veneer readback"),
            size: u64::from(padded_row(width, bytes_per_pixel)) * u64::from(height),
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        Readback {
            buffer,
            bytes_per_pixel,
        }
    }

    /// Records a copy of the top-left `extent` of `texture` into the buffer.
    pub fn record_copy(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        texture: &wgpu::Texture,
        (width, height): (u32, u32),
    ) {
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &self.buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded_row(width, self.bytes_per_pixel)),
                    rows_per_image: Some(height),
                },
            },
            wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
        );
    }

    /// Waits for `submission` (which recorded a copy of `extent`) and hands each copied
    /// row, without wgpu's padding, to `row(row index, bytes)`. Work submitted later keeps
    /// running meanwhile.
    pub fn read_rows(
        &self,
        gpu: &GpuContext,
        submission: wgpu::SubmissionIndex,
        (width, height): (u32, u32),
        mut row: impl FnMut(usize, &[u8]),
    ) -> Result<(), RenderError> {
        let padded = padded_row(width, self.bytes_per_pixel) as usize;
        let unpadded = (width * self.bytes_per_pixel) as usize;
        read_buffer(gpu, &self.buffer, Some(submission), |bytes| {
            for (index, bytes) in bytes.chunks(padded).take(height as usize).enumerate() {
                row(index, &bytes[..unpadded]);
            }
        })
    }
}

/// wgpu's row pitch for copies: rows padded to 256 bytes.
fn padded_row(width: u32, bytes_per_pixel: u32) -> u32 {
    (width * bytes_per_pixel).div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT)
        * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT
}

/// Rows of a texture copied to the CPU, without the row padding wgpu requires.
pub fn read_texture(
    gpu: &GpuContext,
    texture: &wgpu::Texture,
    bytes_per_pixel: u32,
) -> Result<Vec<u8>, RenderError> {
    let extent = (texture.width(), texture.height());
    let readback = Readback::new(gpu, extent, bytes_per_pixel);
    let mut encoder = gpu
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("readback"),
        });
    readback.record_copy(&mut encoder, texture, extent);
    let submission = gpu.queue.submit([encoder.finish()]);
    let mut pixels = Vec::with_capacity((extent.0 * bytes_per_pixel * extent.1) as usize);
    readback.read_rows(gpu, submission, extent, |_, row| {
        pixels.extend_from_slice(row)
    })?;
    Ok(pixels)
}

/// `read` applied to the content of a `MAP_READ` buffer once the GPU has finished
/// `submission` (`None`: all work submitted before; waits for it).
pub fn read_buffer<T>(
    gpu: &GpuContext,
    buffer: &wgpu::Buffer,
    submission: Option<wgpu::SubmissionIndex>,
    read: impl FnOnce(&[u8]) -> T,
) -> Result<T, RenderError> {
    let (sender, receiver) = std::sync::mpsc::channel();
    buffer
        .slice(..)
        .map_async(wgpu::MapMode::Read, move |result| {
            let _ = sender.send(result);
        });
    gpu.device
        .poll(wgpu::PollType::Wait {
            submission_index: submission,
            timeout: None,
        })
        .map_err(|error| RenderError::Gpu(format!("waiting for the GPU failed: {error}")))?;
    gpu.take_errors()?;
    receiver
        .recv()
        .map_err(|_| RenderError::Gpu("the GPU dropped the readback".into()))?
        .map_err(|error| RenderError::Gpu(format!("cannot map the readback buffer: {error}")))?;
    let value = read(
        &buffer
            .get_mapped_range(..)
            .map_err(|error| RenderError::Gpu(format!("cannot read back: {error}")))?,
    );
    buffer.unmap();
    Ok(value)
}
