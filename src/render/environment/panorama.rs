//! Equirectangular panorama files (Radiance `.hdr`, OpenEXR) read into an
//! [`Environment`]: checked, cleaned of values the GPU's half floats cannot hold, and
//! resampled to a power-of-two size the maps are derived from.

use super::{Environment, EnvironmentError};
use crate::fsutil::{ReadLimit, read_limited};
use std::path::Path;

/// The widest panorama kept (wider files are averaged down to it): 2048 × 1024 texels,
/// 16 MiB on the GPU as half floats, sharper than the preview's field of view can show.
pub const MAX_WIDTH: u32 = 2048;
/// The narrowest panorama accepted: 16 × 8 texels.
pub const MIN_WIDTH: u32 = 16;

/// Panorama files are read up to 1 GiB (a 16k × 8k RGB float EXR is 1.5 GiB
/// uncompressed; HDR files are RLE-compressed and far smaller).
const LIMIT: ReadLimit = ReadLimit {
    what: "environment images",
    bytes: 1 << 30,
};

/// The largest value a half float holds.
const HALF_MAX: f32 = 65504.0;

/// See [`Environment::load`].
pub fn load(path: &Path) -> Result<Environment, EnvironmentError> {
    let error = |message: String| EnvironmentError {
        path: path.display().to_string(),
        message,
    };
    let format = match path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
    {
        Some(e) if e == "hdr" => image::ImageFormat::Hdr,
        Some(e) if e == "exr" => image::ImageFormat::OpenExr,
        _ => {
            return Err(error(
                "not an environment image (expected a .hdr or .exr panorama, or `sky`)".into(),
            ));
        }
    };
    let bytes = read_limited(path, LIMIT).map_err(|e| error(e.to_string()))?;
    // The reader's default limits refuse images that would take over 512 MiB decoded.
    let decoded = image::ImageReader::with_format(std::io::Cursor::new(bytes), format)
        .decode()
        .map_err(|e| error(e.to_string()))?;
    let (width, height) = (decoded.width(), decoded.height());
    if width < MIN_WIDTH || width != 2 * height {
        return Err(error(format!(
            "{width}×{height} is not an equirectangular panorama (twice as wide as high, \
             at least {MIN_WIDTH} wide)"
        )));
    }
    let texels: Vec<[f32; 3]> = decoded
        .into_rgb32f()
        .pixels()
        .map(|pixel| pixel.0.map(clean))
        .collect();
    let name = path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    Ok(resampled(name, width, &texels))
}

/// A radiance the GPU can hold: 0 for NaN and negatives, at most the largest half float.
fn clean(value: f32) -> f32 {
    if value.is_nan() {
        0.0
    } else {
        value.clamp(0.0, HALF_MAX)
    }
}

/// The panorama `texels` (`width` × `width / 2`) averaged down to the largest power of two
/// no wider than it and [`MAX_WIDTH`]: each texel the mean of the source texels whose
/// centres fall inside it.
fn resampled(name: String, width: u32, texels: &[[f32; 3]]) -> Environment {
    let target = (1u32 << width.ilog2()).min(MAX_WIDTH);
    let (source_height, target_height) = (width / 2, target / 2);
    let span = |index: u32, from: u32, to: u32| {
        let start = (u64::from(index) * u64::from(from) / u64::from(to)) as u32;
        let end = (u64::from(index + 1) * u64::from(from) / u64::from(to)) as u32;
        start..end.max(start + 1)
    };
    let mut out = Vec::with_capacity((target * target_height) as usize);
    for row in 0..target_height {
        for column in 0..target {
            let mut sum = [0.0f64; 3];
            let mut count = 0.0;
            for y in span(row, source_height, target_height) {
                for x in span(column, width, target) {
                    let texel = texels[(y * width + x) as usize];
                    for (total, value) in sum.iter_mut().zip(texel) {
                        *total += f64::from(value);
                    }
                    count += 1.0;
                }
            }
            out.push(sum.map(|total| (total / count) as f32));
        }
    }
    Environment {
        name,
        width: target,
        texels: out,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resampling_keeps_the_mean_and_a_power_of_two_width() {
        let width = 48;
        let texels: Vec<[f32; 3]> = (0..width * width / 2)
            .map(|i| [i as f32, 1.0, (i % 7) as f32])
            .collect();
        let mean = |t: &[[f32; 3]]| t.iter().map(|c| f64::from(c[0])).sum::<f64>() / t.len() as f64;
        let environment = resampled("test".into(), width, &texels);
        assert_eq!(environment.size(), (32, 16));
        assert!((mean(environment.texels()) - mean(&texels)).abs() / mean(&texels) < 0.05);
        assert!(environment.texels().iter().all(|c| c[1] == 1.0));
    }

    #[test]
    fn values_the_gpu_cannot_hold_are_cleaned() {
        assert_eq!(clean(f32::NAN), 0.0);
        assert_eq!(clean(-3.0), 0.0);
        assert_eq!(clean(f32::INFINITY), HALF_MAX);
        assert_eq!(clean(1.5e6), HALF_MAX);
        assert_eq!(clean(2.5), 2.5);
    }

    #[test]
    fn files_that_are_not_panoramas_are_refused_with_their_path() {
        let dir = tempfile::tempdir().unwrap();
        let square = dir.path().join("square.hdr");
        let image = image::Rgb32FImage::from_pixel(32, 32, image::Rgb([1.0, 1.0, 1.0]));
        image::DynamicImage::from(image).save(&square).unwrap();
        let message = load(&square).unwrap_err().to_string();
        assert!(
            message.contains("square.hdr") && message.contains("32×32"),
            "{message}"
        );
        let text = dir.path().join("notes.txt");
        std::fs::write(&text, "hello").unwrap();
        assert!(
            load(&text)
                .unwrap_err()
                .to_string()
                .contains(".hdr or .exr")
        );
        let broken = dir.path().join("broken.hdr");
        std::fs::write(&broken, "#?RADIANCE\nnonsense").unwrap();
        assert!(
            load(&broken)
                .unwrap_err()
                .to_string()
                .contains("broken.hdr")
        );
    }

    #[test]
    fn an_hdr_panorama_loads_with_its_values() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("studio.hdr");
        let image = image::Rgb32FImage::from_fn(64, 32, |x, _| {
            image::Rgb([if x < 32 { 4.0 } else { 0.5 }, 1.0, 0.25])
        });
        image::DynamicImage::from(image).save(&path).unwrap();
        let environment = load(&path).unwrap();
        assert_eq!(
            (environment.name.as_str(), environment.size()),
            ("studio.hdr", (64, 32))
        );
        // Radiance's shared exponent keeps about 1% precision.
        let first = environment.texels()[0];
        assert!(
            (first[0] - 4.0).abs() < 0.05 && (first[2] - 0.25).abs() < 0.01,
            "{first:?}"
        );
    }
}
