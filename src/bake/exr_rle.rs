//! OpenEXR's RLE compression of one scan line of 32-bit float channels, byte for byte as
//! the `exr` crate writes it, in one pass over the pixels and a word-at-a-time search
//! for runs. The crate's own path copies each line four times (assembly, a clone kept in
//! case compression loses, little-endian conversion, splitting the bytes) and tests
//! every byte for a run; in an 8192² bake that was a fifth of all the work.
//!
//! The format: the line's little-endian bytes, channel after channel, are split into the
//! bytes at even and at odd places (first half, second half), turned into differences
//! (`d[i] = s[i] − s[i − 1] + 128`, wrapping), then cut into runs of 3 to 128 equal bytes
//! (a count − 1 and the byte) and literal stretches of up to 127 bytes (minus their
//! length, then the bytes). Where that is not shorter than the line, the line is stored
//! as it is.

/// Compresses one scan line: for each of `lanes` (an RGBA lane per file channel, in the
/// file's channel order), that lane of every pixel. The two buffers of `scratch` are
/// reused between calls.
pub fn compress_line(
    pixels: &[[f32; 4]],
    lanes: &[usize],
    scratch: &mut (Vec<u8>, Vec<u8>),
) -> Vec<u8> {
    let samples = pixels.len();
    let length = samples * lanes.len() * 4;
    let (split, differences) = scratch;
    split.clear();
    split.resize(length, 0);
    // Sample m of lane l starts raw byte 4 (l · samples + m): its bytes 0 and 2 go to
    // the first half, 1 and 3 to the second, at twice that sample number.
    let (evens, odds) = split.split_at_mut(length / 2);
    for (l, &lane) in lanes.iter().enumerate() {
        let range = 2 * l * samples..2 * (l + 1) * samples;
        split_lane(pixels, lane, &mut evens[range.clone()], &mut odds[range]);
    }
    differences.clear();
    differences.extend(split.first());
    differences.extend(
        split
            .windows(2)
            .map(|pair| pair[1].wrapping_sub(pair[0]).wrapping_add(128)),
    );
    let packed = pack_runs(differences);
    if packed.len() < length {
        return packed;
    }
    // Stored raw, as the bytes came (little-endian, channel after channel).
    lanes
        .iter()
        .flat_map(|&lane| pixels.iter().flat_map(move |p| p[lane].to_le_bytes()))
        .collect()
}

/// Lane `lane` of `pixels` into `evens` and `odds`: bytes 0 and 2 of each sample to the
/// one, 1 and 3 to the other, four samples (eight bytes each way) at a time.
fn split_lane(pixels: &[[f32; 4]], lane: usize, evens: &mut [u8], odds: &mut [u8]) {
    // Bytes 0 and 2 of a sample, and bytes 1 and 3, as the two bytes of a u16.
    let even = |bits: u32| u64::from((bits & 0xFF) | ((bits >> 8) & 0xFF00));
    let odd = |bits: u32| u64::from(((bits >> 8) & 0xFF) | ((bits >> 16) & 0xFF00));
    let quads = pixels.chunks_exact(4);
    let rest = quads.remainder();
    let targets = evens.chunks_exact_mut(8).zip(odds.chunks_exact_mut(8));
    for (quad, (even_bytes, odd_bytes)) in quads.zip(targets) {
        let bits = [0, 1, 2, 3].map(|i| quad[i][lane].to_bits());
        let (mut e, mut o) = (0u64, 0u64);
        for (i, &b) in bits.iter().enumerate() {
            e |= even(b) << (16 * i);
            o |= odd(b) << (16 * i);
        }
        even_bytes.copy_from_slice(&e.to_le_bytes());
        odd_bytes.copy_from_slice(&o.to_le_bytes());
    }
    let done = pixels.len() - rest.len();
    for (m, pixel) in rest.iter().enumerate() {
        let bits = pixel[lane].to_bits();
        let at = 2 * (done + m);
        evens[at..at + 2].copy_from_slice(&(even(bits) as u16).to_le_bytes());
        odds[at..at + 2].copy_from_slice(&(odd(bits) as u16).to_le_bytes());
    }
}

const MIN_RUN: usize = 3;
const MAX_RUN: usize = 128;
const MAX_LITERAL: usize = 127;

/// The run-length tokens of `data`, as OpenEXR (and the `exr` crate) cut them.
fn pack_runs(data: &[u8]) -> Vec<u8> {
    let mut packed = Vec::with_capacity(data.len() + data.len() / MAX_LITERAL + 2);
    let mut start = 0;
    while start < data.len() {
        let run = run_length(data, start);
        if run >= MIN_RUN {
            packed.extend([(run - 1) as u8, data[start]]);
            start += run;
            continue;
        }
        // A literal stretch: up to where a run of three begins (the bytes just counted
        // belong to it), at most 127 bytes.
        let end = literal_end(data, start + run, start + MAX_LITERAL);
        packed.push((start as isize - end as isize) as u8);
        packed.extend_from_slice(&data[start..end]);
        start = end;
    }
    packed
}

/// How many bytes from `start` repeat `data[start]`, at most 128: eight at a time while
/// eight are there.
fn run_length(data: &[u8], start: usize) -> usize {
    let limit = (start + MAX_RUN).min(data.len());
    let repeated = u64::from_ne_bytes([data[start]; 8]);
    let mut at = start;
    while at + 8 <= limit {
        let word = u64::from_le_bytes(data[at..at + 8].try_into().expect("8 bytes"));
        let differs = word ^ repeated;
        if differs != 0 {
            return at - start + (differs.trailing_zeros() / 8) as usize;
        }
        at += 8;
    }
    at - start
        + data[at..limit]
            .iter()
            .take_while(|&&b| b == data[start])
            .count()
}

/// The first place from `from` (up to `limit`, and the end of `data`) where three equal
/// bytes begin; a run cannot begin in the last two bytes, so a stretch reaching them
/// runs to the end. Eight places are tested at once where eight bytes and two more are
/// there to read.
fn literal_end(data: &[u8], from: usize, limit: usize) -> usize {
    let limit = limit.min(data.len());
    let mut at = from;
    while at + 10 <= data.len() && at < limit {
        let word = |offset: usize| {
            u64::from_le_bytes(
                data[at + offset..at + offset + 8]
                    .try_into()
                    .expect("8 bytes"),
            )
        };
        // A zero byte in `differs` marks a place where the next two bytes repeat it.
        let differs = (word(0) ^ word(1)) | (word(1) ^ word(2));
        let zero_bytes =
            differs.wrapping_sub(0x0101_0101_0101_0101) & !differs & 0x8080_8080_8080_8080;
        if zero_bytes != 0 {
            // The lowest flagged byte is exact (borrows only run upwards).
            let found = at + (zero_bytes.trailing_zeros() / 8) as usize;
            return found.min(limit);
        }
        at += 8;
    }
    while at < limit {
        if at + 2 < data.len() && data[at] == data[at + 1] && data[at + 1] == data[at + 2] {
            return at;
        }
        at += 1;
    }
    limit
}

#[cfg(test)]
mod tests {
    use super::*;
    use exr::block::{BlockIndex, UncompressedBlock, chunk::CompressedBlock};
    use exr::math::Vec2;
    use exr::meta::attribute::{ChannelDescription, LineOrder, SampleType, Text};
    use exr::meta::{BlockDescription, header::Header};

    /// What the `exr` crate writes for the same line.
    fn theirs(pixels: &[[f32; 4]], lanes: &[(&str, usize)]) -> Vec<u8> {
        let width = pixels.len();
        let channels = lanes
            .iter()
            .map(|(name, _)| ChannelDescription::named(*name, SampleType::F32))
            .collect::<Vec<_>>();
        let header = Header::new(Text::from("test"), (width, 1), channels.into()).with_encoding(
            exr::compression::Compression::RLE,
            BlockDescription::ScanLines,
            LineOrder::Increasing,
        );
        let mut data = Vec::new();
        for (_, lane) in lanes {
            pixels
                .iter()
                .for_each(|p| data.extend_from_slice(&p[*lane].to_ne_bytes()));
        }
        let block = UncompressedBlock {
            index: BlockIndex {
                layer: 0,
                pixel_position: Vec2(0, 0),
                pixel_size: Vec2(width, 1),
                level: Vec2(0, 0),
            },
            data,
        };
        match block
            .compress_to_chunk(&[header])
            .expect("compresses")
            .compressed_block
        {
            CompressedBlock::ScanLine(line) => line.compressed_pixels_le,
            _ => unreachable!("scan lines"),
        }
    }

    #[test]
    fn lines_compress_to_the_bytes_the_exr_crate_writes() {
        const LANES: [(&str, usize); 4] = [("A", 3), ("B", 2), ("G", 1), ("R", 0)];
        let lanes = LANES.map(|(_, lane)| lane);
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        let mut noise = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let mut scratch = Default::default();
        for width in [1, 2, 3, 5, 31, 64, 257, 1000] {
            let lines: [Vec<[f32; 4]>; 4] = [
                // Noise, constants, slow ramps, and stretches of repeats among noise.
                (0..width)
                    .map(|_| [0; 4].map(|_| (noise() as u32) as f32 / 4e9))
                    .collect(),
                (0..width).map(|_| [0.25, 0.5, 0.75, 1.0]).collect(),
                (0..width)
                    .map(|x| [x as f32 / 4096.0, 0.5, 1.0 - x as f32 / 8192.0, 1.0])
                    .collect(),
                (0..width)
                    .map(|x| match (x / 7) % 3 {
                        0 => [1.0; 4],
                        _ => [0; 4].map(|_| f32::from_bits(noise() as u32 & 0x3F80_FFFF)),
                    })
                    .collect(),
            ];
            for line in &lines {
                assert_eq!(
                    compress_line(line, &lanes, &mut scratch),
                    theirs(line, &LANES),
                    "width {width}"
                );
            }
        }
    }
}
