//! Rendering a large square image of four f32 per pixel in tiles, so memory on the GPU
//! stays bounded: the shared loop of the flat and UV-layout renders.

use super::readback::Readback;
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

/// Renders a `size`² image tile by tile into one buffer, each tile drawn as `tiles_draw`
/// says, with `progress(tiles done, tiles in all)` after each. Rows run from the top.
pub fn render_tiled<P, D>(
    gpu: &GpuContext,
    size: u32,
    tiles_draw: TileDraw<P, D>,
    progress: impl FnMut(u32, u32),
) -> Result<Vec<[f32; 4]>, RenderError>
where
    P: FnMut((u32, u32), (u32, u32)),
    D: FnMut(&mut wgpu::RenderPass<'_>),
{
    if size == 0 {
        return Err(RenderError::Invalid(
            "image size must be at least 1 pixel".into(),
        ));
    }
    let mut image = image_buffer(size, FLOAT_PIXEL_BYTES)?;
    let rows = tile_size(gpu);
    render_bands(gpu, size, rows, tiles_draw, progress, |first_row, band| {
        let start = first_row as usize * size as usize;
        image[start..start + band.len()].copy_from_slice(&band);
        Ok(band)
    })?;
    Ok(image)
}

/// What a tiled render draws: each tile's pass is cleared to `clear`, then `prepare(first
/// texel, extent)` writes the tile's uniforms and `draw` records its draw calls.
pub struct TileDraw<P, D> {
    pub clear: wgpu::Color,
    pub prepare: P,
    pub draw: D,
}

/// Renders a `size`² image in bands of `band_rows` full-width rows (at most a tile high),
/// each band in tiles: `band(first row, pixels)` receives every band in order, four f32
/// per pixel row by row, and hands back a buffer for a later band (the same one, or any
/// other: its length does not matter). Tile n + 1 renders while tile n is read back, and
/// the two render targets and readback buffers are reused throughout.
pub fn render_bands<P, D>(
    gpu: &GpuContext,
    size: u32,
    band_rows: u32,
    mut tiles_draw: TileDraw<P, D>,
    mut progress: impl FnMut(u32, u32),
    mut band: impl FnMut(u32, Vec<[f32; 4]>) -> Result<Vec<[f32; 4]>, RenderError>,
) -> Result<(), RenderError>
where
    P: FnMut((u32, u32), (u32, u32)),
    D: FnMut(&mut wgpu::RenderPass<'_>),
{
    if size == 0 {
        return Err(RenderError::Invalid(
            "image size must be at least 1 pixel".into(),
        ));
    }
    let width = tile_size(gpu).min(size);
    let height = band_rows.clamp(1, width).min(size);
    let slots: [_; 2] = std::array::from_fn(|_| {
        let texture = target_texture(&gpu.device, (width, height));
        (
            texture.create_view(&Default::default()),
            texture,
            Readback::new(gpu, (width, height), 16),
        )
    });
    let all = size.div_ceil(width) * size.div_ceil(height);
    let mut filling = BandBuffer {
        pixels: Vec::new(),
        first_row: 0,
        size,
    };
    filling.start(0, height);
    let mut pending = None;
    for (index, (origin, extent)) in tile_grid((size, size), (width, height)).enumerate() {
        let (view, texture, readback) = &slots[index % 2];
        (tiles_draw.prepare)(origin, extent);
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("tile"),
            });
        {
            let mut pass = clear_pass(&mut encoder, view, tiles_draw.clear, None);
            pass.set_viewport(0.0, 0.0, extent.0 as f32, extent.1 as f32, 0.0, 1.0);
            (tiles_draw.draw)(&mut pass);
        }
        readback.record_copy(&mut encoder, texture, extent);
        let submission = gpu.queue.submit([encoder.finish()]);
        if let Some((slot, origin, extent, submission)) =
            pending.replace((index % 2, origin, extent, submission))
        {
            filling.read_tile(gpu, &slots[slot].2, submission, origin, extent)?;
            progress(index as u32, all);
            filling.pass_on_if_full(origin, extent, height, &mut band)?;
        }
    }
    if let Some((slot, origin, extent, submission)) = pending {
        filling.read_tile(gpu, &slots[slot].2, submission, origin, extent)?;
        progress(all, all);
        filling.pass_on_if_full(origin, extent, height, &mut band)?;
    }
    Ok(())
}

/// The band of a tiled render being read back into.
struct BandBuffer {
    pixels: Vec<[f32; 4]>,
    first_row: u32,
    size: u32,
}

impl BandBuffer {
    /// Gets ready for the `rows` rows from `first_row` on.
    fn start(&mut self, first_row: u32, rows: u32) {
        self.first_row = first_row;
        let rows = rows.min(self.size - first_row);
        self.pixels
            .resize(rows as usize * self.size as usize, [0.0; 4]);
    }

    /// Copies a finished tile's rows straight from the readback buffer into the band.
    fn read_tile(
        &mut self,
        gpu: &GpuContext,
        readback: &Readback,
        submission: wgpu::SubmissionIndex,
        origin: (u32, u32),
        extent: (u32, u32),
    ) -> Result<(), RenderError> {
        let (size, top) = (self.size as usize, (origin.1 - self.first_row) as usize);
        let pixels = &mut self.pixels;
        readback.read_rows(gpu, submission, extent, |row, bytes| {
            let start = (top + row) * size + origin.0 as usize;
            bytemuck::cast_slice_mut(&mut pixels[start..start + extent.0 as usize])
                .copy_from_slice(bytes);
        })
    }

    /// Hands the band on when the tile at `origin` was its last, and starts the next.
    fn pass_on_if_full(
        &mut self,
        origin: (u32, u32),
        extent: (u32, u32),
        band_rows: u32,
        band: &mut impl FnMut(u32, Vec<[f32; 4]>) -> Result<Vec<[f32; 4]>, RenderError>,
    ) -> Result<(), RenderError> {
        if origin.0 + extent.0 < self.size {
            return Ok(());
        }
        self.pixels = band(self.first_row, std::mem::take(&mut self.pixels))?;
        let next = origin.1 + extent.1;
        if next < self.size {
            self.start(next, band_rows);
        }
        Ok(())
    }
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
    tile_grid((size, size), (tile, tile))
}

/// The tiles of an image of `extent` (width, height) in tiles of at most
/// `width`×`height`, row by row from the top: each tile's first texel and extent.
pub fn tile_grid(
    extent: (u32, u32),
    (width, height): (u32, u32),
) -> impl Iterator<Item = ((u32, u32), (u32, u32))> {
    let (width, height) = (width.max(1), height.max(1));
    (0..extent.1).step_by(height as usize).flat_map(move |y| {
        (0..extent.0)
            .step_by(width as usize)
            .map(move |x| ((x, y), (width.min(extent.0 - x), height.min(extent.1 - y))))
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
    ensure_memory(size, pixels as u64 * bytes_per_pixel)?;
    let mut image = Vec::new();
    image.try_reserve_exact(pixels).map_err(|_| {
        too_large(
            size,
            pixels as u64 * bytes_per_pixel,
            "which the allocator refused",
        )
    })?;
    image.resize(pixels, T::default());
    Ok(image)
}

/// Refuses work on a `size`² image that needs `needed` bytes when the machine has less
/// memory available, saying how much it would need.
pub fn ensure_memory(size: u32, needed: u64) -> Result<(), RenderError> {
    match available_memory() {
        Some(available) if needed > available => Err(too_large(
            size,
            needed,
            &format!(
                "more than the {} this machine has available",
                crate::fsutil::gibibytes(available)
            ),
        )),
        _ => Ok(()),
    }
}

fn too_large(size: u32, needed: u64, why: &str) -> RenderError {
    RenderError::TooLarge {
        size,
        bytes: needed,
        why: why.to_string(),
    }
}

/// Memory the kernel says is available for new allocations (Linux), in bytes.
fn available_memory() -> Option<u64> {
    let meminfo = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = meminfo.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// A render target of `width`×`height` in [`FORMAT`] that can be read back.
pub fn target_texture(device: &wgpu::Device, (width, height): (u32, u32)) -> wgpu::Texture {
    super::plain_texture(
        device,
        "tile",
        (width, height),
        FORMAT,
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
    )
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
