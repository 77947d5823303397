//! Comparing a render with its golden image: per-channel differences, PSNR, SSIM and a
//! heat map of where they differ.

use crate::render::Image;
use serde::{Deserialize, Serialize};
use std::fmt;

/// When a render counts as matching its golden.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Tolerance {
    /// Largest per-channel difference (0–255) a pixel may have and still match.
    pub channel: u8,
    /// Share of pixels (0–1) allowed to differ by more than `channel`.
    pub share: f64,
    /// When set, the mean SSIM of the luminance must be at least this.
    pub ssim: Option<f64>,
}

impl Tolerance {
    /// Same adapter, same driver: renders are bit-identical, this absorbs driver updates.
    pub const SAME_ADAPTER: Tolerance = Tolerance {
        channel: 2,
        share: 0.001,
        ssim: None,
    };
    /// Another adapter: covers the measured spread between Vulkan/lavapipe and GL/llvmpipe
    /// on the PCG-hashed presets (at most 5/255 on 0.003% of pixels, SSIM 1.0000; see
    /// README, "Snapshot-test your materials"), and fails sine-hashed graphs, whose bits
    /// differ between adapters (the marble preset: 16% of pixels, SSIM 0.81).
    pub const CROSS_ADAPTER: Tolerance = Tolerance {
        channel: 8,
        share: 0.005,
        ssim: Some(0.98),
    };

    /// Parses `channel=N,share=S[,ssim=M]` (any subset; the rest from `base`).
    pub fn parse(spec: &str, base: Tolerance) -> Result<Tolerance, String> {
        let mut tolerance = base;
        for part in spec.split(',').map(str::trim).filter(|p| !p.is_empty()) {
            let (key, value) = part
                .split_once('=')
                .ok_or_else(|| format!("'{part}' is not key=value"))?;
            let number = |range: std::ops::RangeInclusive<f64>| -> Result<f64, String> {
                let x: f64 = value
                    .parse()
                    .map_err(|_| format!("'{value}' is not a number"))?;
                if range.contains(&x) {
                    Ok(x)
                } else {
                    Err(format!("{key}={value} is outside {range:?}"))
                }
            };
            match key {
                "channel" => tolerance.channel = number(0.0..=255.0)? as u8,
                "share" => tolerance.share = number(0.0..=1.0)?,
                "ssim" => tolerance.ssim = Some(number(-1.0..=1.0)?),
                _ => {
                    return Err(format!(
                        "unknown tolerance key '{key}' (expected channel, share or ssim)"
                    ));
                }
            }
        }
        Ok(tolerance)
    }
}

impl fmt::Display for Tolerance {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "channel={},share={}", self.channel, self.share)?;
        match self.ssim {
            Some(ssim) => write!(f, ",ssim={ssim}"),
            None => Ok(()),
        }
    }
}

/// How a render differs from its golden.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Comparison {
    /// Largest per-channel difference.
    pub max: u8,
    /// Mean per-channel difference (0–255).
    pub mean: f64,
    /// Share of pixels with some channel differing by more than the tolerance.
    pub share_outside: f64,
    /// Peak signal-to-noise ratio in dB (infinite when identical).
    pub psnr: f64,
    /// Mean SSIM of the luminance, when the tolerance asks for it.
    pub ssim: Option<f64>,
    /// The tolerance the share and SSIM were measured for.
    pub tolerance: Tolerance,
}

impl Comparison {
    /// Whether the difference is within the tolerance it was measured for.
    pub fn passes(&self) -> bool {
        let tolerance = &self.tolerance;
        self.share_outside <= tolerance.share
            && tolerance
                .ssim
                .is_none_or(|min| self.ssim.is_some_and(|s| s >= min))
    }
}

impl fmt::Display for Comparison {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "max {}/255, mean {:.3}/255, {:.3}% of pixels outside tolerance, PSNR {:.1} dB",
            self.max,
            self.mean,
            100.0 * self.share_outside,
            self.psnr
        )?;
        match self.ssim {
            Some(ssim) => write!(f, ", SSIM {ssim:.4}"),
            None => Ok(()),
        }
    }
}

/// Compares two images of the same size and channel count.
pub fn compare(
    actual: &Image,
    golden: &Image,
    tolerance: &Tolerance,
) -> Result<Comparison, String> {
    if (actual.width, actual.height, actual.channels)
        != (golden.width, golden.height, golden.channels)
    {
        return Err(format!(
            "the render is {}×{} with {} channels, the golden {}×{} with {}",
            actual.width,
            actual.height,
            actual.channels,
            golden.width,
            golden.height,
            golden.channels
        ));
    }
    let channels = actual.channels;
    let (mut max, mut sum, mut squares, mut outside) = (0u8, 0u64, 0u64, 0usize);
    for (a, b) in actual
        .pixels
        .chunks(channels)
        .zip(golden.pixels.chunks(channels))
    {
        let mut worst = 0u8;
        for (x, y) in a.iter().zip(b) {
            let d = x.abs_diff(*y);
            worst = worst.max(d);
            sum += u64::from(d);
            squares += u64::from(d) * u64::from(d);
        }
        max = max.max(worst);
        outside += usize::from(worst > tolerance.channel);
    }
    let samples = actual.pixels.len().max(1) as f64;
    let mse = squares as f64 / samples;
    let psnr = if mse == 0.0 {
        f64::INFINITY
    } else {
        10.0 * (255.0f64 * 255.0 / mse).log10()
    };
    let pixels = (actual.width as usize * actual.height as usize).max(1) as f64;
    Ok(Comparison {
        max,
        mean: sum as f64 / samples,
        share_outside: outside as f64 / pixels,
        psnr,
        ssim: tolerance.ssim.map(|_| ssim(actual, golden)),
        tolerance: *tolerance,
    })
}

fn luminance(image: &Image) -> Vec<f64> {
    image
        .pixels
        .chunks(image.channels)
        .map(|p| 0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2]))
        .collect()
}

/// Mean structural similarity (Wang et al. 2004) of the luminance over 8×8 windows
/// with a stride of 4: 1 for identical images, lower as structure differs.
pub fn ssim(a: &Image, b: &Image) -> f64 {
    const WINDOW: usize = 8;
    let (width, height) = (a.width as usize, a.height as usize);
    let (la, lb) = (luminance(a), luminance(b));
    let (c1, c2) = ((0.01f64 * 255.0).powi(2), (0.03f64 * 255.0).powi(2));
    let (mut total, mut windows) = (0.0, 0usize);
    for y in (0..height.saturating_sub(WINDOW - 1)).step_by(4) {
        for x in (0..width.saturating_sub(WINDOW - 1)).step_by(4) {
            let at = |l: &[f64], i: usize, j: usize| l[(y + j) * width + x + i];
            let n = (WINDOW * WINDOW) as f64;
            let (mut ma, mut mb) = (0.0, 0.0);
            for j in 0..WINDOW {
                for i in 0..WINDOW {
                    ma += at(&la, i, j);
                    mb += at(&lb, i, j);
                }
            }
            let (ma, mb) = (ma / n, mb / n);
            let (mut va, mut vb, mut cov) = (0.0, 0.0, 0.0);
            for j in 0..WINDOW {
                for i in 0..WINDOW {
                    let (da, db) = (at(&la, i, j) - ma, at(&lb, i, j) - mb);
                    va += da * da;
                    vb += db * db;
                    cov += da * db;
                }
            }
            let (va, vb, cov) = (va / (n - 1.0), vb / (n - 1.0), cov / (n - 1.0));
            total += ((2.0 * ma * mb + c1) * (2.0 * cov + c2))
                / ((ma * ma + mb * mb + c1) * (va + vb + c2));
            windows += 1;
        }
    }
    if windows == 0 {
        1.0
    } else {
        total / windows as f64
    }
}

/// An RGB heat map of where two images differ: black where equal, through red and
/// yellow to white at a difference of 64/255 or more.
pub fn heat_map(actual: &Image, golden: &Image) -> Image {
    let channels = actual.channels;
    let pixels = actual
        .pixels
        .chunks(channels)
        .zip(golden.pixels.chunks(channels))
        .flat_map(|(a, b)| {
            let d = a
                .iter()
                .zip(b)
                .map(|(x, y)| x.abs_diff(*y))
                .max()
                .unwrap_or(0);
            let t = (f64::from(d) / 64.0).min(1.0);
            [
                (3.0 * t).min(1.0),
                (3.0 * t - 1.0).clamp(0.0, 1.0),
                (3.0 * t - 2.0).clamp(0.0, 1.0),
            ]
            .map(|c| (c * 255.0).round() as u8)
        })
        .collect();
    Image {
        width: actual.width,
        height: actual.height,
        channels: 3,
        pixels,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gradient(offset: u8) -> Image {
        let pixels = (0..32 * 32)
            .flat_map(|i| {
                [
                    (i % 32 * 8) as u8,
                    (i / 32 * 8) as u8,
                    100u8.saturating_add(offset),
                ]
            })
            .collect();
        Image {
            width: 32,
            height: 32,
            channels: 3,
            pixels,
        }
    }

    #[test]
    fn identical_images_match_with_infinite_psnr() {
        let tolerance = Tolerance {
            ssim: Some(0.99),
            ..Tolerance::SAME_ADAPTER
        };
        let comparison = compare(&gradient(0), &gradient(0), &tolerance).unwrap();
        assert_eq!((comparison.max, comparison.share_outside), (0, 0.0));
        assert!(comparison.psnr.is_infinite() && comparison.ssim == Some(1.0));
        assert!(comparison.passes());
    }

    #[test]
    fn a_uniform_shift_is_measured_exactly() {
        let comparison = compare(&gradient(5), &gradient(0), &Tolerance::SAME_ADAPTER).unwrap();
        assert_eq!(comparison.max, 5);
        assert!((comparison.mean - 5.0 / 3.0).abs() < 1e-12);
        assert_eq!(comparison.share_outside, 1.0);
        assert!((comparison.psnr - 10.0 * (255.0f64 * 255.0 / (25.0 / 3.0)).log10()).abs() < 1e-9);
        assert!(!comparison.passes());
        let looser = Tolerance {
            channel: 5,
            ..Tolerance::SAME_ADAPTER
        };
        assert!(
            compare(&gradient(5), &gradient(0), &looser)
                .unwrap()
                .passes()
        );
    }

    #[test]
    fn tolerance_specs_parse_and_reject_nonsense() {
        let parsed =
            Tolerance::parse("channel=4, share=0.02,ssim=0.9", Tolerance::SAME_ADAPTER).unwrap();
        assert_eq!(
            parsed,
            Tolerance {
                channel: 4,
                share: 0.02,
                ssim: Some(0.9)
            }
        );
        assert!(Tolerance::parse("share=2", Tolerance::SAME_ADAPTER).is_err());
        assert!(Tolerance::parse("gamma=1", Tolerance::SAME_ADAPTER).is_err());
        assert_eq!(
            Tolerance::parse(&parsed.to_string(), Tolerance::SAME_ADAPTER).unwrap(),
            parsed
        );
    }
}
