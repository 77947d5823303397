//! Writing baked maps as their rows are converted: EXR as RLE-compressed scan-line
//! blocks, compressed on every core and written while the next band renders; PNG as
//! 8- or 16-bit samples encoded at the end, byte for byte as before (the png crate's
//! streaming writer compresses differently).

use super::Format;
use super::exr_rle::compress_line;
use exr::block::chunk::{Chunk, CompressedBlock, CompressedScanLineBlock};
use exr::block::writer::ChunksWriter;
use exr::meta::BlockDescription;
use exr::meta::attribute::{ChannelDescription, LineOrder, SampleType, Text};
use exr::meta::header::Header;
use rayon::prelude::*;
use std::io::{self, Seek, Write};

/// Where converted rows go: `emit(pixels)` takes whole rows of RGBA, in order.
pub type Emit<'e> = dyn FnMut(&[[f32; 4]]) -> io::Result<()> + 'e;

/// Writes a `size`² map in `format` to `file`: `produce` calls its argument with every
/// row of the map, top to bottom, in batches of whole rows. Fails, naming what is
/// missing, when `produce` gives fewer rows.
pub fn encode<W: Write + Seek + Send>(
    file: &mut W,
    size: u32,
    format: Format,
    produce: impl FnOnce(&mut Emit<'_>) -> io::Result<()>,
) -> io::Result<()> {
    let mut rows = 0usize;
    let width = size as usize;
    let counted = move |emit: &mut Emit<'_>| {
        produce(&mut |pixels: &[[f32; 4]]| {
            rows += pixels.len() / width;
            emit(pixels)
        })?;
        match rows == width {
            true => Ok(()),
            false => Err(io::Error::other(format!(
                "the bake stopped after {rows} of {size} rows"
            ))),
        }
    };
    match format {
        Format::Png8 => png_rows(file, size, png::BitDepth::Eight, counted),
        Format::Png16 => png_rows(file, size, png::BitDepth::Sixteen, counted),
        Format::Exr => exr_rows(file, size, counted),
    }
}

/// RGB PNG rows, each channel round(max · clamp(v, 0, 1)), encoded as `image`'s
/// `PngEncoder` encodes (fast compression, adaptive filter, the whole image at once), so
/// the file is byte for byte the same. The rows are held as the 8- or 16-bit samples the
/// encoder takes (3 or 6 bytes per pixel), not as floats.
fn png_rows<W: Write>(
    file: &mut W,
    size: u32,
    depth: png::BitDepth,
    produce: impl FnOnce(&mut Emit<'_>) -> io::Result<()>,
) -> io::Result<()> {
    let sixteen = depth == png::BitDepth::Sixteen;
    let bytes = size as usize * size as usize * if sixteen { 6 } else { 3 };
    let mut samples = Vec::new();
    samples
        .try_reserve_exact(bytes)
        .map_err(|_| io::Error::other(format!("cannot hold the {bytes} bytes of the image")))?;
    produce(&mut |pixels: &[[f32; 4]]| {
        for value in pixels.iter().flat_map(|p| [p[0], p[1], p[2]]) {
            let value = value.clamp(0.0, 1.0);
            match sixteen {
                true => samples.extend(((65535.0 * value).round() as u16).to_be_bytes()),
                false => samples.push((255.0 * value).round() as u8),
            }
        }
        Ok(())
    })?;
    let mut encoder = png::Encoder::new(file, size, size);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(depth);
    encoder.set_compression(png::Compression::Fast);
    encoder.set_filter(png::Filter::Adaptive);
    let mut writer = encoder.write_header().map_err(io::Error::other)?;
    writer
        .write_image_data(&samples)
        .map_err(io::Error::other)?;
    writer.finish().map_err(io::Error::other)
}

/// 32-bit float RGBA EXR rows as RLE-compressed scan lines (one line a block, compressed
/// by [`compress_line`], the same bytes as the `exr` crate's), on every core, then
/// written in order by a thread of their own while the next rows compress (the file's
/// writes wait on the disk, not the processor).
fn exr_rows<W: Write + Seek + Send>(
    file: &mut W,
    size: u32,
    produce: impl FnOnce(&mut Emit<'_>) -> io::Result<()>,
) -> io::Result<()> {
    let width = size as usize;
    // Channels in the file's (alphabetical) order, as lanes of an RGBA pixel.
    const LANES: [(&str, usize); 4] = [("A", 3), ("B", 2), ("G", 1), ("R", 0)];
    let channels = LANES
        .iter()
        .map(|(name, _)| ChannelDescription::named(*name, SampleType::F32))
        .collect::<Vec<_>>();
    let header = Header::new(Text::from("veneer bake"), (width, width), channels.into())
        .with_encoding(
            exr::compression::Compression::RLE,
            BlockDescription::ScanLines,
            LineOrder::Increasing,
        );
    let mut next_line = 0usize;
    exr::block::writer::write_chunks_with(file, vec![header].into(), true, |_, writer| {
        std::thread::scope(|scope| {
            let (batches, to_write) = std::sync::mpsc::sync_channel::<Vec<Chunk>>(1);
            let file_writer = scope.spawn(move || -> exr::error::UnitResult {
                for (index, chunk) in to_write.into_iter().flatten().enumerate() {
                    writer.write_chunk(index, chunk)?;
                }
                Ok(())
            });
            let produced = produce(&mut |pixels: &[[f32; 4]]| -> io::Result<()> {
                let first = next_line;
                let lanes = LANES.map(|(_, lane)| lane);
                let chunks = pixels
                    .par_chunks(width)
                    .enumerate()
                    .map_init(Default::default, |scratch, (index, line)| Chunk {
                        layer_index: 0,
                        compressed_block: CompressedBlock::ScanLine(CompressedScanLineBlock {
                            y_coordinate: (first + index) as i32,
                            compressed_pixels_le: compress_line(line, &lanes, scratch),
                        }),
                    })
                    .collect::<Vec<_>>();
                next_line += chunks.len();
                batches
                    .send(chunks)
                    .map_err(|_| io::Error::other("the EXR file writer stopped"))
            });
            drop(batches);
            let written = file_writer
                .join()
                .map_err(|_| io::Error::other("the EXR file writer panicked"))?;
            // A failed write explains why the rows could not be sent.
            written?;
            produced.map_err(exr::error::Error::from)
        })
    })
    .map_err(|error| match error {
        exr::error::Error::Io(error) => error,
        other => io::Error::other(other),
    })
}
