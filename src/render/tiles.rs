//! Rendering a large square image of four f32 per pixel in tiles, so memory on the GPU
//! stays bounded: the shared loop of the flat and UV-layout renders.

use super::readback::read_texture;
use super::{GpuContext, RenderError};

/// f32 bits in an integer target: renderable on every backend (GL has no float targets).
pub const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Uint;

/// Clear value whose bits read back as NaN in every lane.
pub const NAN_BITS: wgpu::Color = wgpu::Color {
    r: 4294967295.0,
    g: 4294967295.0,
    b: 4294967295.0,
    a: 4294967295.0,
};

/// The largest tile side: at most 2048, within the device's largest texture, and small
/// enough that a tile of four f32 per pixel reads back through one buffer (rows padded to
/// wgpu's 256-byte alignment, which 16-pixel multiples meet).
pub fn tile_size(gpu: &GpuContext) -> u32 {
    let limits = gpu.device.limits();
    let by_buffer = ((limits.max_buffer_size / 16) as f64).sqrt() as u32 / 16 * 16;
    limits
        .max_texture_dimension_2d
        .min(2048)
        .min(by_buffer)
        .max(16)
}

/// Renders a `size`² image tile by tile: `prepare(first texel, tile extent)` writes the
/// tile's uniforms, `draw` records its draw calls into a pass cleared to `clear`, and
/// `progress(tiles done, tiles in all)` follows each tile. Rows run from the top.
pub fn render_tiled(
    gpu: &GpuContext,
    size: u32,
    clear: wgpu::Color,
    mut prepare: impl FnMut((u32, u32), (u32, u32)),
    mut draw: impl FnMut(&mut wgpu::RenderPass<'_>),
    mut progress: impl FnMut(u32, u32),
) -> Result<Vec<[f32; 4]>, RenderError> {
    if size == 0 {
        return Err(RenderError("image size must be at least 1 pixel".into()));
    }
    let mut image = image_buffer(size, FLOAT_PIXEL_BYTES)?;
    let tile = tile_size(gpu);
    let tiles_per_side = size.div_ceil(tile);
    let mut done = 0;
    for (origin, (width, height)) in tiles(size, tile) {
        prepare(origin, (width, height));
        let texture = gpu.device.create_texture(&target_descriptor(width, height));
        let target = texture.create_view(&Default::default());
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("tile"),
            });
        {
            let mut pass = clear_pass(&mut encoder, &target, clear, None);
            draw(&mut pass);
        }
        gpu.queue.submit([encoder.finish()]);
        let pixels: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&read_texture(gpu, &texture, 16)?);
        paste(&mut image, size, origin, width, &pixels);
        done += 1;
        progress(done, tiles_per_side * tiles_per_side);
    }
    Ok(image)
}

/// Copies the rows of a tile `width` pixels wide into a `size`² image at `origin`.
pub fn paste<T: Copy>(image: &mut [T], size: u32, origin: (u32, u32), width: u32, tile: &[T]) {
    for (row, chunk) in tile.chunks(width as usize).enumerate() {
        let start = (origin.1 as usize + row) * size as usize + origin.0 as usize;
        image[start..start + width as usize].copy_from_slice(chunk);
    }
}

/// The tiles of a `size`² image in tiles of at most `tile`², row by row from the top:
/// each tile's first texel and extent.
pub fn tiles(size: u32, tile: u32) -> impl Iterator<Item = ((u32, u32), (u32, u32))> {
    let step = tile.max(1) as usize;
    (0..size).step_by(step).flat_map(move |y| {
        (0..size)
            .step_by(step)
            .map(move |x| ((x, y), (tile.min(size - x), tile.min(size - y))))
    })
}

/// Bytes per pixel a float image costs on its way out: four f32 while rendering, and
/// about as much again while it is converted and encoded.
const FLOAT_PIXEL_BYTES: u64 = 32;

/// The zeroed pixels of a `size`² image that costs `bytes_per_pixel` on its way out, or
/// a clear error when the machine does not have the memory for it (more than is
/// available, or refused by the allocator), so a mistyped size fails at once instead of
/// in the out-of-memory killer.
pub fn image_buffer<T: Copy + Default>(
    size: u32,
    bytes_per_pixel: u64,
) -> Result<Vec<T>, RenderError> {
    let pixels = size as usize * size as usize;
    let needed = pixels as u64 * bytes_per_pixel;
    let refuse = |why: String| {
        RenderError(format!(
            "a {size}×{size} image needs about {} of memory, {why}; ask for a smaller size",
            gibibytes(needed)
        ))
    };
    if let Some(available) = available_memory()
        && needed > available
    {
        return Err(refuse(format!(
            "more than the {} this machine has available",
            gibibytes(available)
        )));
    }
    let mut image = Vec::new();
    image
        .try_reserve_exact(pixels)
        .map_err(|_| refuse("which the allocator refused".into()))?;
    image.resize(pixels, T::default());
    Ok(image)
}

/// Memory the kernel says is available for new allocations (Linux), in bytes.
fn available_memory() -> Option<u64> {
    let meminfo = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = meminfo.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

fn gibibytes(bytes: u64) -> String {
    format!("{:.1} GiB", bytes as f64 / (1u64 << 30) as f64)
}

/// A render target of `width`×`height` in [`FORMAT`] that can be read back.
pub fn target_descriptor(width: u32, height: u32) -> wgpu::TextureDescriptor<'static> {
    wgpu::TextureDescriptor {
        label: Some("tile"),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: FORMAT,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    }
}

/// A render pass into `target`, cleared to `clear` and stored, with `timestamps` written
/// around it when given.
pub fn clear_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    target: &wgpu::TextureView,
    clear: wgpu::Color,
    timestamps: Option<wgpu::RenderPassTimestampWrites<'_>>,
) -> wgpu::RenderPass<'e> {
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("tile"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: target,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(clear),
                store: wgpu::StoreOp::Store,
            },
        })],
        timestamp_writes: timestamps,
        ..Default::default()
    })
}
