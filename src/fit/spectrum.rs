//! The radially averaged power spectrum of an image's luminance: how much of the
//! pattern's variation lies at each spatial frequency, whatever its direction and
//! wherever it lies, so two pictures of one material match without being aligned. The
//! fit compares the logarithms of the two spectra, frequency by frequency; the
//! comparison's derivative by each pixel is one more discrete Fourier transform.

/// A complex number, (real, imaginary).
type Complex = (f64, f64);

/// Added to each band's power before its logarithm, so flat images stay finite.
const FLOOR: f64 = 1e-9;

/// The two-dimensional discrete Fourier transform of `values` (`n`×`n`, rows first),
/// computed as rows then columns with a table of the `n` twiddles.
fn transform(values: &[Complex], n: usize) -> Vec<Complex> {
    let twiddles: Vec<Complex> = (0..n)
        .map(|m| {
            let angle = -std::f64::consts::TAU * m as f64 / n as f64;
            (angle.cos(), angle.sin())
        })
        .collect();
    // One axis: `at(line, position)` read, the result written line by line.
    let pass = |at: &dyn Fn(usize, usize) -> Complex| -> Vec<Complex> {
        let mut out = vec![(0.0, 0.0); n * n];
        for line in 0..n {
            for frequency in 0..n {
                let mut sum = (0.0, 0.0);
                for position in 0..n {
                    let (a, b) = at(line, position);
                    let (c, s) = twiddles[(frequency * position) % n];
                    sum = (sum.0 + a * c - b * s, sum.1 + a * s + b * c);
                }
                out[line * n + frequency] = sum;
            }
        }
        out
    };
    // Along rows (out[y][kx]), then along columns (out[kx][ky], transposed back).
    let rows = pass(&|y, x| values[y * n + x]);
    let columns = pass(&|kx, y| rows[y * n + kx]);
    (0..n * n).map(|k| columns[(k % n) * n + k / n]).collect()
}

/// The band (rounded radius in cycles per image) of frequency `k` of an `n`×`n`
/// transform, where it lies within 1..=n/2.
fn band(k: usize, n: usize) -> Option<usize> {
    let fold = |f: usize| f.min(n - f) as f64;
    let radius = fold(k % n).hypot(fold(k / n)).round() as usize;
    (1..=n / 2).contains(&radius).then_some(radius - 1)
}

/// The logarithm of the mean power in each band of `luminance` (`n`×`n`).
pub struct Spectrum {
    pub log_power: Vec<f64>,
}

/// The transform of `luminance` with its mean taken out, and each band's mean power
/// and size.
fn bands(luminance: &[f64], n: usize) -> (Vec<Complex>, Vec<f64>, Vec<f64>) {
    let mean = luminance.iter().sum::<f64>() / luminance.len() as f64;
    let centred: Vec<Complex> = luminance.iter().map(|&v| (v - mean, 0.0)).collect();
    let transformed = transform(&centred, n);
    let scale = 1.0 / (n * n) as f64;
    let (mut power, mut count) = (vec![0.0; n / 2], vec![0.0f64; n / 2]);
    for (k, &(re, im)) in transformed.iter().enumerate() {
        if let Some(band) = band(k, n) {
            power[band] += (re * re + im * im) * scale * scale;
            count[band] += 1.0;
        }
    }
    for (power, count) in power.iter_mut().zip(&count) {
        *power /= count.max(1.0);
    }
    (transformed, power, count)
}

impl Spectrum {
    /// The spectrum of `luminance`, an `n`×`n` image.
    pub fn of(luminance: &[f64], n: usize) -> Spectrum {
        let (_, power, _) = bands(luminance, n);
        Spectrum {
            log_power: power.iter().map(|p| (p + FLOOR).ln()).collect(),
        }
    }

    /// The mean squared difference between the log spectra of `luminance` (`n`×`n`)
    /// and `self`, and its derivative by each luminance value.
    pub fn distance(&self, luminance: &[f64], n: usize) -> (f64, Vec<f64>) {
        let (transformed, power, count) = bands(luminance, n);
        let bands_compared = power.len().max(1) as f64;
        let scale = 1.0 / (n * n) as f64;
        let mut distance = 0.0;
        // d distance / d power[band], spread over the band's frequencies.
        let mut by_power = vec![0.0; power.len()];
        for (band, (&p, &target)) in power.iter().zip(&self.log_power).enumerate() {
            let gap = (p + FLOOR).ln() - target;
            distance += gap * gap / bands_compared;
            by_power[band] =
                2.0 * gap / bands_compared / (p + FLOOR) / count[band].max(1.0) * scale * scale;
        }
        // |F_k|² = F_k · conj(F_k) with F = W x (W symmetric): the derivative of
        // Σ a_k |F_k|² by x is 2 Re(W (a ⊙ conj F)).
        let weighted: Vec<Complex> = (transformed.iter().enumerate())
            .map(|(k, &(re, im))| match band(k, n) {
                Some(band) => (by_power[band] * re, -by_power[band] * im),
                None => (0.0, 0.0),
            })
            .collect();
        let gradient = transform(&weighted, n)
            .iter()
            .map(|&(re, _)| 2.0 * re)
            .collect();
        (distance, gradient)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Bands along x at `cycles` per image, shifted by `phase`.
    fn stripes(n: usize, cycles: f64, phase: f64) -> Vec<f64> {
        (0..n * n)
            .map(|k| {
                let x = (k % n) as f64 / n as f64;
                0.5 + 0.3 * (std::f64::consts::TAU * cycles * x + phase).sin()
            })
            .collect()
    }

    #[test]
    fn the_spectrum_ignores_where_the_pattern_lies_and_sees_its_frequency() {
        let n = 16;
        let target = Spectrum::of(&stripes(n, 3.0, 0.0), n);
        let shifted = target.distance(&stripes(n, 3.0, 1.3), n).0;
        let other = target.distance(&stripes(n, 5.0, 0.0), n).0;
        assert!(shifted < 1e-12, "{shifted}");
        assert!(other > 1.0, "{other}");
        // A sine at 3 cycles puts its power in the third band alone.
        let peak = (target.log_power.iter().enumerate())
            .max_by(|a, b| a.1.total_cmp(b.1))
            .map(|(band, _)| band);
        assert_eq!(peak, Some(2));
    }

    #[test]
    fn the_derivative_by_a_pixel_is_the_difference_quotient() {
        let n = 12;
        let target = Spectrum::of(&stripes(n, 2.0, 0.4), n);
        let mut image = stripes(n, 3.0, 0.0);
        for (k, v) in image.iter_mut().enumerate() {
            *v += 0.05 * ((k * 7919) % 13) as f64 / 13.0;
        }
        let (_, gradient) = target.distance(&image, n);
        for pixel in [0, 17, 80, 143] {
            let h = 1e-6;
            let mut moved = image.clone();
            moved[pixel] += h;
            let up = target.distance(&moved, n).0;
            moved[pixel] -= 2.0 * h;
            let down = target.distance(&moved, n).0;
            let quotient = (up - down) / (2.0 * h);
            assert!(
                (gradient[pixel] - quotient).abs() <= 1e-5 * quotient.abs().max(1.0),
                "pixel {pixel}: {} vs {quotient}",
                gradient[pixel]
            );
        }
    }
}
