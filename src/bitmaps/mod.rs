//! Bitmaps read from files for Image nodes: PNG, JPEG, OpenEXR and Radiance HDR,
//! decoded into linear RGBA floats (8- and 16-bit files from sRGB unless told they are
//! linear data), checked against the limits, and kept in a small cache so that the
//! editor's checks and renders after each edit do not decode the same file again.

mod edges;
mod path;

pub use path::{relative_to, resolve};

use crate::fsutil::{ReadLimit, read_limited};
use crate::nodes::passes::MAX_BUFFER_SIZE;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::SystemTime;

/// How the numbers of an image file become linear values.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum ColourSpace {
    /// As the graph's other colours are. A Blinn-Phong graph's colours are the numbers
    /// a display shows (the seeds' convention), so an 8- or 16-bit file's numbers are
    /// read as they are; a metallic-roughness graph's are linear light, so they are
    /// decoded from sRGB. Float files (EXR, HDR) hold linear light: read as they are.
    #[default]
    Auto,
    /// The colour lanes decoded from sRGB to linear light (alpha is always as it is).
    Srgb,
    /// The numbers as they are: heights, masks, normal maps and other data.
    Linear,
}

impl ColourSpace {
    /// Every choice, in menu order.
    pub const ALL: [ColourSpace; 3] = [ColourSpace::Auto, ColourSpace::Srgb, ColourSpace::Linear];
}

/// A decoded image: linear RGBA, rows from the top.
#[derive(Debug, PartialEq)]
pub struct Bitmap {
    pub width: u32,
    pub height: u32,
    pub texels: Vec<[f32; 4]>,
    /// Whether the colour lanes were decoded from sRGB.
    pub from_srgb: bool,
    /// The least and the greatest value of each lane (for the lint's ranges).
    pub lanes: [[f32; 2]; 4],
}

/// The largest magnitude a texel lane keeps (a half float's largest value): a float
/// file's infinities and huge values are clamped to it, its NaNs read as 0.
pub const MAX_TEXEL_VALUE: f32 = 65504.0;

/// Image files are read up to 1 GiB.
const LIMIT: ReadLimit = ReadLimit {
    what: "images",
    bytes: 1 << 30,
};

/// Decoded bitmaps kept at most, and their bytes together at most.
const CACHE_ENTRIES: usize = 16;
const CACHE_BYTES: usize = 2 << 30;

/// What a cached bitmap was decoded from: the file (by its resolved path, length and
/// modification time, so an edited file is decoded again), the colour space asked and
/// whether the graph's colours are linear.
type CacheKey = (PathBuf, u64, Option<SystemTime>, ColourSpace, bool);

/// Recently decoded bitmaps, most recent last.
static CACHE: Mutex<Vec<(CacheKey, Arc<Bitmap>)>> = Mutex::new(Vec::new());

/// The bitmap of file `written` (a path relative to `folder`, the graph's), decoded in
/// `space` for a graph whose colours are linear light (`linear_graph`, metallic-
/// roughness) or display values (Blinn-Phong); or a message saying why it cannot be
/// used, naming the file.
pub fn load(
    folder: &Path,
    written: &str,
    space: ColourSpace,
    linear_graph: bool,
) -> Result<Arc<Bitmap>, String> {
    let fail = |why: String| format!("image '{written}' {why}");
    let path = resolve(folder, written).map_err(fail)?;
    let metadata = std::fs::metadata(&path).map_err(|e| fail(format!("cannot be read: {e}")))?;
    let key = (
        path,
        metadata.len(),
        metadata.modified().ok(),
        space,
        linear_graph,
    );
    let mut cache = CACHE
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner());
    if let Some(at) = cache.iter().position(|(seen, _)| *seen == key) {
        let entry = cache.remove(at);
        let bitmap = entry.1.clone();
        cache.push(entry);
        return Ok(bitmap);
    }
    drop(cache);
    let bitmap = Arc::new(decode(&key.0, space, linear_graph).map_err(fail)?);
    let mut cache = CACHE
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner());
    cache.push((key, bitmap.clone()));
    let bytes = |cache: &[(CacheKey, Arc<Bitmap>)]| -> usize {
        (cache.iter())
            .map(|(_, bitmap)| bitmap.texels.len() * 16)
            .sum()
    };
    while cache.len() > 1 && (cache.len() > CACHE_ENTRIES || bytes(&cache) > CACHE_BYTES) {
        cache.remove(0);
    }
    Ok(bitmap)
}

/// Reads and decodes `path`: at most [`LIMIT`] bytes and [`MAX_BUFFER_SIZE`] texels a
/// side, checked before the pixels are decoded.
fn decode(path: &Path, space: ColourSpace, linear_graph: bool) -> Result<Bitmap, String> {
    let bytes = read_limited(path, LIMIT).map_err(|e| format!("cannot be read: {e}"))?;
    let undecodable = |e: image::ImageError| format!("does not decode: {e}");
    let reader = image::ImageReader::new(std::io::Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| format!("cannot be read: {e}"))?;
    match reader.format() {
        Some(
            image::ImageFormat::Png
            | image::ImageFormat::Jpeg
            | image::ImageFormat::OpenExr
            | image::ImageFormat::Hdr,
        ) => {}
        _ => return Err("is not a PNG, JPEG, OpenEXR or Radiance HDR file".to_string()),
    }
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_BUFFER_SIZE);
    limits.max_image_height = Some(MAX_BUFFER_SIZE);
    limits.max_alloc = Some(2 << 30);
    let mut reader = reader;
    reader.limits(limits);
    let decoded = reader.decode().map_err(|e| match e {
        image::ImageError::Limits(_) => format!(
            "is larger than Veneer reads: images are at most {MAX_BUFFER_SIZE} texels a side"
        ),
        e => undecodable(e),
    })?;
    let float = matches!(
        decoded,
        image::DynamicImage::ImageRgb32F(_) | image::DynamicImage::ImageRgba32F(_)
    );
    let from_srgb = match space {
        ColourSpace::Auto => !float && linear_graph,
        ColourSpace::Srgb => true,
        ColourSpace::Linear => false,
    };
    let (width, height) = (decoded.width(), decoded.height());
    let texels: Vec<[f32; 4]> = decoded
        .into_rgba32f()
        .pixels()
        .map(|pixel| {
            let [r, g, b, a] = pixel.0.map(clean);
            let colour = [r, g, b].map(|lane| {
                if from_srgb {
                    srgb_to_linear(lane)
                } else {
                    lane
                }
            });
            [colour[0], colour[1], colour[2], a]
        })
        .collect();
    let mut lanes = [[f32::INFINITY, f32::NEG_INFINITY]; 4];
    for texel in &texels {
        for (span, &value) in lanes.iter_mut().zip(texel) {
            *span = [span[0].min(value), span[1].max(value)];
        }
    }
    Ok(Bitmap {
        width,
        height,
        texels,
        from_srgb,
        lanes,
    })
}

/// A lane the GPU and the CPU hold alike: NaN as 0, at most [`MAX_TEXEL_VALUE`] either way.
fn clean(value: f32) -> f32 {
    if value.is_nan() {
        0.0
    } else {
        value.clamp(-MAX_TEXEL_VALUE, MAX_TEXEL_VALUE)
    }
}

/// The sRGB encoding of a linear value (0..1; the inverse of [`srgb_to_linear`]).
pub fn linear_to_srgb(linear: f32) -> f32 {
    if linear <= 0.003_130_8 {
        linear * 12.92
    } else {
        1.055 * linear.powf(1.0 / 2.4) - 0.055
    }
}

/// An sRGB-encoded value (0..1) as linear light (IEC 61966-2-1).
pub fn srgb_to_linear(encoded: f32) -> f32 {
    if encoded <= 0.04045 {
        encoded / 12.92
    } else {
        ((encoded + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn folder(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("veneer-bitmaps-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn png_decodes_from_srgb_and_linear_as_asked() {
        let dir = folder("png");
        let image = image::RgbaImage::from_fn(3, 2, |x, y| {
            image::Rgba([(x * 100) as u8, (y * 255) as u8, 188, 128])
        });
        image.save(dir.join("a.png")).unwrap();
        let srgb = load(&dir, "a.png", ColourSpace::Auto, true).unwrap();
        assert_eq!((srgb.width, srgb.height), (3, 2));
        assert!(srgb.from_srgb);
        let texel = srgb.texels[3 + 2];
        assert!((texel[0] - srgb_to_linear(200.0 / 255.0)).abs() < 1e-6);
        assert_eq!(texel[1], 1.0);
        assert!((texel[2] - 0.5029).abs() < 1e-3, "{texel:?}");
        assert!(
            (texel[3] - 128.0 / 255.0).abs() < 1e-6,
            "alpha stays linear"
        );
        let linear = load(&dir, "a.png", ColourSpace::Linear, true).unwrap();
        assert!((linear.texels[5][2] - 188.0 / 255.0).abs() < 1e-6);
        // A Blinn-Phong graph's colours are display values: Auto reads them as they are.
        let display = load(&dir, "a.png", ColourSpace::Auto, false).unwrap();
        assert_eq!(display.texels, linear.texels);
        assert!(
            load(&dir, "a.png", ColourSpace::Srgb, false)
                .unwrap()
                .from_srgb
        );
        // The same file and space come from the cache.
        assert!(Arc::ptr_eq(
            &srgb,
            &load(&dir, "a.png", ColourSpace::Auto, true).unwrap()
        ));
    }

    #[test]
    fn float_files_are_linear_and_cleaned() {
        let dir = folder("exr");
        let image = image::Rgba32FImage::from_fn(2, 2, |x, _| {
            image::Rgba([f32::NAN, 1.0e9, -2.5 * x as f32, 1.0])
        });
        image.save(dir.join("h.exr")).unwrap();
        let bitmap = load(&dir, "h.exr", ColourSpace::Auto, true).unwrap();
        assert!(!bitmap.from_srgb);
        assert_eq!(bitmap.texels[1], [0.0, MAX_TEXEL_VALUE, -2.5, 1.0]);
    }

    #[test]
    fn broken_strange_and_huge_files_are_refused_naming_the_file() {
        let dir = folder("bad");
        std::fs::write(dir.join("broken.png"), b"\x89PNG\r\n\x1a\nnot really").unwrap();
        let error = load(&dir, "broken.png", ColourSpace::Auto, true).unwrap_err();
        assert!(
            error.starts_with("image 'broken.png' does not decode"),
            "{error}"
        );
        std::fs::write(dir.join("notes.png"), b"hello").unwrap();
        let error = load(&dir, "notes.png", ColourSpace::Auto, true).unwrap_err();
        assert!(error.contains("is not a PNG, JPEG"), "{error}");
        let wide = image::GrayImage::new(MAX_BUFFER_SIZE + 1, 1);
        wide.save(dir.join("wide.png")).unwrap();
        let error = load(&dir, "wide.png", ColourSpace::Auto, true).unwrap_err();
        assert!(error.contains("at most 8192 texels a side"), "{error}");
        let error = load(&dir, "gone.png", ColourSpace::Auto, true).unwrap_err();
        assert!(
            error.starts_with("image 'gone.png' cannot be read"),
            "{error}"
        );
    }

    #[test]
    fn a_fifo_is_refused_at_once() {
        let dir = folder("fifo");
        let fifo = dir.join("pipe.png");
        let name = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
        // SAFETY: a NUL-terminated path.
        assert_eq!(unsafe { libc::mkfifo(name.as_ptr(), 0o600) }, 0);
        let error = load(&dir, "pipe.png", ColourSpace::Auto, true).unwrap_err();
        assert!(error.contains("a FIFO"), "{error}");
    }
}
