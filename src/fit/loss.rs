//! How far a rendered image is from a photo that is not aligned with it: statistics
//! compared across scales, not pixels. At each level of a pyramid (the image, then
//! halved by 2×2 averages), the sliced Wasserstein distance — the mean, over fixed
//! directions, of the squared differences between the sorted projections — between the
//! colours of the two images, between their local patches (the 3×3 luminance
//! neighbourhood of each pixel, on random directions) and between their oriented
//! gradients (the luminance's derivative in eight directions, so the distribution of
//! edge strengths per orientation); and, on one level, the radially averaged power
//! spectra ([`super::spectrum`]). Where the target was rendered over the same square
//! (`--aligned`), the mean squared difference per pixel is added at every level. Each
//! part's derivative by every pixel comes with it, for the fit to pass back through the
//! graph.

use super::Draws;
use super::image::Image;
use super::spectrum::Spectrum;

/// Levels of the pyramid compared (fewer where the image is too small).
const LEVELS: usize = 3;
/// The smallest side a level may have.
const SMALLEST: u32 = 8;
/// Random directions in colour space.
const COLOUR_DIRECTIONS: usize = 8;
/// Random directions in patch space.
const PATCH_DIRECTIONS: usize = 16;
/// Values per patch: a 3×3 neighbourhood.
const PATCH: usize = 9;
/// Orientations of the gradient statistics, evenly spread over a half turn.
const ORIENTATIONS: usize = 8;
/// The largest side the power spectrum is taken at (the finest level no larger).
const SPECTRUM_SIDE: u32 = 128;
/// The spectrum part's weight: its log-power differences are larger than the other
/// parts' differences of values in [0, 1].
const SPECTRUM_WEIGHT: f64 = 0.01;

/// The parts of a loss.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct LossParts {
    /// Sliced Wasserstein distance of colours, averaged over the levels.
    pub colour: f64,
    /// Sliced Wasserstein distance of 3×3 luminance patches, averaged over the levels.
    pub patches: f64,
    /// Sliced Wasserstein distance of the luminance's derivatives in eight orientations,
    /// averaged over the levels.
    pub gradients: f64,
    /// Mean squared difference of the log power spectra, per band, weighted.
    pub spectrum: f64,
    /// Mean squared difference per pixel and channel, averaged over the levels, where
    /// the target is aligned.
    pub aligned: Option<f64>,
}

impl LossParts {
    /// The sum of the parts.
    pub fn total(&self) -> f64 {
        self.colour + self.patches + self.gradients + self.spectrum + self.aligned.unwrap_or(0.0)
    }
}

/// The statistics of a target image at one size.
pub struct Target {
    size: u32,
    /// Per level, per direction, the sorted projections of the colours, of the patches
    /// and of the patches on the gradients' orientations.
    colours: Vec<Vec<Vec<f64>>>,
    patches: Vec<Vec<Vec<f64>>>,
    gradients: Vec<Vec<Vec<f64>>>,
    /// The power spectrum, of the level [`spectrum_level`] picks.
    spectrum: Spectrum,
    /// Each level's pixels themselves, for the aligned part.
    aligned: Option<Vec<Vec<[f64; 3]>>>,
}

/// The directions a loss projects on (fixed by a seed, so losses compare).
pub struct Loss {
    colour_directions: Vec<[f64; 3]>,
    patch_directions: Vec<[f64; PATCH]>,
    /// The central difference along each orientation, as a direction in patch space.
    orientations: Vec<[f64; PATCH]>,
}

/// The patch-space direction whose projection is the central difference of luminance
/// along the angle `angle` (x to the right, y down).
fn orientation(angle: f64) -> [f64; PATCH] {
    let mut direction = [0.0; PATCH];
    // Patch lane j holds the pixel (j % 3 - 1, j / 3 - 1) away.
    (direction[5], direction[3]) = (angle.cos() / 2.0, -angle.cos() / 2.0);
    (direction[7], direction[1]) = (angle.sin() / 2.0, -angle.sin() / 2.0);
    direction
}

/// The level the spectrum is taken at: the finest no larger than [`SPECTRUM_SIDE`].
fn spectrum_level(levels: &[Image]) -> usize {
    (levels.iter())
        .position(|level| level.size <= SPECTRUM_SIDE)
        .unwrap_or(levels.len() - 1)
}

/// A unit vector of `N` lanes drawn from `draws`.
fn direction<const N: usize>(draws: &mut Draws) -> [f64; N] {
    loop {
        let v: [f64; N] = std::array::from_fn(|_| 2.0 * draws.uniform() - 1.0);
        let length = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if length > 0.1 {
            return v.map(|x| x / length);
        }
    }
}

/// The pyramid of `image`: the image, then each level halved by 2×2 averages.
fn pyramid(image: &Image) -> Vec<Image> {
    let mut levels = vec![image.clone()];
    while levels.len() < LEVELS {
        let last = levels.last().expect("one level");
        let half = last.size / 2;
        if half < SMALLEST {
            break;
        }
        let mut pixels = Vec::with_capacity((half * half) as usize);
        for y in 0..half {
            for x in 0..half {
                let at = |dx: u32, dy: u32| {
                    last.pixels[((2 * y + dy) * last.size + 2 * x + dx) as usize]
                };
                let block = [at(0, 0), at(1, 0), at(0, 1), at(1, 1)];
                pixels.push(std::array::from_fn(|c| {
                    block.iter().map(|p| p[c]).sum::<f64>() / 4.0
                }));
            }
        }
        levels.push(Image { size: half, pixels });
    }
    levels
}

/// The luminance (the channels' mean) of each pixel.
fn luminance(image: &Image) -> Vec<f64> {
    image
        .pixels
        .iter()
        .map(|p| (p[0] + p[1] + p[2]) / 3.0)
        .collect()
}

/// The pixel `(x + dx, y + dy)` of an image of side `n`, wrapping around its edges.
fn neighbour(n: u32, x: u32, y: u32, dx: i64, dy: i64) -> usize {
    let n = i64::from(n);
    let wrap = |v: i64| v.rem_euclid(n);
    (wrap(i64::from(y) + dy) * n + wrap(i64::from(x) + dx)) as usize
}

/// The 3×3 patch around each pixel of `lum`, an image of side `n`'s luminance
/// (wrapping: textures repeat).
fn patches(lum: &[f64], n: u32) -> Vec<[f64; PATCH]> {
    (0..n * n)
        .map(|k| {
            let (x, y) = (k % n, k / n);
            std::array::from_fn(|j| {
                let (dx, dy) = (j as i64 % 3 - 1, j as i64 / 3 - 1);
                lum[neighbour(n, x, y, dx, dy)]
            })
        })
        .collect()
}

/// Projections of `features` on `direction`.
fn project<const N: usize>(features: &[[f64; N]], direction: &[f64; N]) -> Vec<f64> {
    (features.iter())
        .map(|f| f.iter().zip(direction).map(|(a, b)| a * b).sum())
        .collect()
}

/// `values` sorted.
fn sorted(mut values: Vec<f64>) -> Vec<f64> {
    values.sort_by(f64::total_cmp);
    values
}

/// The sliced Wasserstein distance between `features` and the target's sorted
/// projections on `directions`, and its derivative by each feature.
fn sliced<const N: usize>(
    features: &[[f64; N]],
    directions: &[[f64; N]],
    target: &[Vec<f64>],
) -> (f64, Vec<[f64; N]>) {
    let count = features.len() as f64;
    let scale = 1.0 / (count * directions.len() as f64);
    let mut distance = 0.0;
    let mut gradient = vec![[0.0; N]; features.len()];
    for (direction, target) in directions.iter().zip(target) {
        let projections = project(features, direction);
        let mut order: Vec<usize> = (0..features.len()).collect();
        order.sort_by(|&a, &b| projections[a].total_cmp(&projections[b]));
        for (rank, &index) in order.iter().enumerate() {
            let gap = projections[index] - target[rank];
            distance += gap * gap * scale;
            for (g, d) in gradient[index].iter_mut().zip(direction) {
                *g += 2.0 * gap * scale * d;
            }
        }
    }
    (distance, gradient)
}

impl Loss {
    /// The loss whose directions `seed` draws.
    pub fn new(seed: u64) -> Loss {
        let mut draws = Draws::new(seed);
        Loss {
            colour_directions: (0..COLOUR_DIRECTIONS)
                .map(|_| direction(&mut draws))
                .collect(),
            patch_directions: (0..PATCH_DIRECTIONS)
                .map(|_| direction(&mut draws))
                .collect(),
            orientations: (0..ORIENTATIONS)
                .map(|k| orientation(std::f64::consts::PI * k as f64 / ORIENTATIONS as f64))
                .collect(),
        }
    }

    /// The statistics of `image` (and, where `aligned`, its pixels).
    pub fn target(&self, image: &Image, aligned: bool) -> Target {
        let levels = pyramid(image);
        let colours = (levels.iter())
            .map(|level| {
                (self.colour_directions.iter())
                    .map(|d| sorted(project(&level.pixels, d)))
                    .collect()
            })
            .collect();
        let lums: Vec<Vec<f64>> = levels.iter().map(luminance).collect();
        let features: Vec<Vec<[f64; PATCH]>> = (levels.iter().zip(&lums))
            .map(|(level, lum)| patches(lum, level.size))
            .collect();
        let sorted_on = |directions: &[[f64; PATCH]]| -> Vec<Vec<Vec<f64>>> {
            (features.iter())
                .map(|features| {
                    (directions.iter())
                        .map(|d| sorted(project(features, d)))
                        .collect()
                })
                .collect()
        };
        let spectral = spectrum_level(&levels);
        Target {
            size: image.size,
            colours,
            patches: sorted_on(&self.patch_directions),
            gradients: sorted_on(&self.orientations),
            spectrum: Spectrum::of(&lums[spectral], levels[spectral].size as usize),
            aligned: aligned.then(|| levels.iter().map(|l| l.pixels.clone()).collect()),
        }
    }

    /// The loss of `image` against `target` (of the same size), and its derivative by
    /// each pixel's channels.
    pub fn evaluate(&self, image: &Image, target: &Target) -> (LossParts, Vec<[f64; 3]>) {
        assert_eq!(
            image.size, target.size,
            "the target is made at the image's size"
        );
        let levels = pyramid(image);
        let count = levels.len() as f64;
        let spectral = spectrum_level(&levels);
        let mut parts = LossParts {
            colour: 0.0,
            patches: 0.0,
            gradients: 0.0,
            spectrum: 0.0,
            aligned: target.aligned.as_ref().map(|_| 0.0),
        };
        // The derivative by each level's pixels, passed down level by level.
        let mut carried: Vec<[f64; 3]> = Vec::new();
        for (k, level) in levels.iter().enumerate().rev() {
            let n = level.size;
            let (distance, mut gradient) =
                sliced(&level.pixels, &self.colour_directions, &target.colours[k]);
            parts.colour += distance / count;
            // The derivative by each luminance value, from the patches, the gradients
            // and the spectrum.
            let mut by_luminance = vec![0.0; level.pixels.len()];
            let lum = luminance(level);
            let features = patches(&lum, n);
            for (directions, sorted, part) in [
                (
                    &self.patch_directions,
                    &target.patches[k],
                    &mut parts.patches,
                ),
                (
                    &self.orientations,
                    &target.gradients[k],
                    &mut parts.gradients,
                ),
            ] {
                let (distance, by_patch) = sliced(&features, directions, sorted);
                *part += distance / count;
                for (p, patch) in by_patch.iter().enumerate() {
                    let (x, y) = (p as u32 % n, p as u32 / n);
                    for (j, g) in patch.iter().enumerate() {
                        by_luminance[neighbour(n, x, y, j as i64 % 3 - 1, j as i64 / 3 - 1)] += g;
                    }
                }
            }
            if k == spectral {
                let (distance, by_value) = (target.spectrum).distance(&lum, n as usize);
                parts.spectrum = SPECTRUM_WEIGHT * distance;
                for (total, g) in by_luminance.iter_mut().zip(by_value) {
                    *total += SPECTRUM_WEIGHT * g * count;
                }
            }
            for (pixel, g) in gradient.iter_mut().zip(&by_luminance) {
                *pixel = pixel.map(|lane| (lane + g / 3.0) / count);
            }
            if let (Some(pixels), Some(aligned)) = (&target.aligned, &mut parts.aligned) {
                let scale = 1.0 / (3.0 * level.pixels.len() as f64 * count);
                for ((mine, theirs), g) in level.pixels.iter().zip(&pixels[k]).zip(&mut gradient) {
                    for c in 0..3 {
                        let gap = mine[c] - theirs[c];
                        *aligned += gap * gap * scale;
                        g[c] += 2.0 * gap * scale;
                    }
                }
            }
            // What the coarser level passed down: each of its pixels averaged four (an
            // odd side's last row and column averaged into none).
            if !carried.is_empty() {
                let half = n / 2;
                for (p, g) in gradient.iter_mut().enumerate() {
                    let (x, y) = (p as u32 % n / 2, p as u32 / n / 2);
                    if x >= half || y >= half {
                        continue;
                    }
                    let parent = carried[(y * half + x) as usize];
                    for c in 0..3 {
                        g[c] += parent[c] / 4.0;
                    }
                }
            }
            carried = gradient;
        }
        (parts, carried)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn noise_image(size: u32, seed: u64, brightness: f64) -> Image {
        let mut draws = Draws::new(seed);
        Image {
            size,
            pixels: (0..size * size)
                .map(|_| [0; 3].map(|_| brightness * draws.uniform()))
                .collect(),
        }
    }

    #[test]
    fn an_image_is_at_no_distance_from_itself_and_a_shuffled_copy_is_close() {
        let loss = Loss::new(1);
        let image = noise_image(32, 3, 1.0);
        let target = loss.target(&image, false);
        let (parts, _) = loss.evaluate(&image, &target);
        assert!(parts.total() < 1e-20, "{parts:?}");
        // The same statistics elsewhere: another draw of the same noise.
        let other = noise_image(32, 4, 1.0);
        let darker = noise_image(32, 4, 0.5);
        let near = loss.evaluate(&other, &target).0.total();
        let far = loss.evaluate(&darker, &target).0.total();
        assert!(near * 5.0 < far, "{near} vs {far}");
    }

    #[test]
    fn the_derivative_by_a_pixel_is_the_difference_quotient() {
        let loss = Loss::new(2);
        let target = loss.target(&noise_image(16, 5, 1.0), true);
        let image = noise_image(16, 6, 0.8);
        let (_, gradient) = loss.evaluate(&image, &target);
        for (pixel, channel) in [(0, 0), (37, 1), (200, 2), (255, 0)] {
            let h = 1e-6;
            let mut moved = image.clone();
            moved.pixels[pixel][channel] += h;
            let up = loss.evaluate(&moved, &target).0.total();
            moved.pixels[pixel][channel] -= 2.0 * h;
            let down = loss.evaluate(&moved, &target).0.total();
            let quotient = (up - down) / (2.0 * h);
            let got = gradient[pixel][channel];
            assert!(
                (got - quotient).abs() <= 1e-6 * quotient.abs().max(1e-3),
                "pixel {pixel}.{channel}: {got} vs {quotient}"
            );
        }
    }
}
