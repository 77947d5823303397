//! White noise, value-gradient noise and Gabor noise, formula for formula as in
//! shaders/white.wgsl, value_gradient.wgsl and gabor.wgsl (seed 003 §3.2).

// The node kinds that use these arrive through the node registry.

use super::noise::{cell_bits, gradient, lattice_domain, lattice_pcg, pcg3d, unit_floats, value};
use super::real::{Real, V3, add, dot, map, safe_normalize, scale, splat, sub};
use std::f64::consts::{PI, TAU};

/// `veneer_white_noise`: the PCG hash of the cell floor(p), in [0, 1).
pub fn white_noise<R: Real>(p: V3<R>) -> R {
    lattice_pcg(map(lattice_domain(p), R::floor))
}

/// `veneer_white_noise_color`: the three PCG lanes of the cell floor(p), each in [0, 1).
pub fn white_noise_color<R: Real>(p: V3<R>) -> V3<R> {
    unit_floats(pcg3d(cell_bits(map(lattice_domain(p), R::floor))))
}

/// `veneer_noise_value_gradient`: the mean of PCG value noise and gradient noise, in [0, 1].
pub fn value_gradient<R: Real>(p: V3<R>) -> R {
    R::c(0.5) * (value(p, lattice_pcg, None) + gradient(p, None))
}

/// `veneer_gabor_kernel`: the Hann-windowed unit Gaussian times the sine of a plane wave.
/// (The WGSL's 3.14159265 and 6.28318531 are pi and tau rounded to the same f32.)
pub fn gabor_kernel<R: Real>(x: V3<R>, frequency: R, direction: V3<R>) -> R {
    let r2 = dot(x, x, 3);
    let envelope = (R::c(-PI) * r2).exp() * (R::c(0.5) + R::c(0.5) * (R::c(PI) * r2).cos());
    let phase = (frequency * dot(x, direction, 3) + R::c(0.5)).fract() - R::c(0.5);
    envelope * (R::c(TAU) * phase).sin()
}

/// `veneer_gabor_direction`: a random unit vector from `u`, blended towards `dir`.
pub fn gabor_direction<R: Real>(dir: V3<R>, anisotropy: R, u: [R; 2]) -> V3<R> {
    let (zero, one) = (R::c(0.0), R::c(1.0));
    let z = R::c(2.0) * u[0] - one;
    let longitude = R::c(TAU) * (u[1] - R::c(0.5));
    let s = (one - z * z).max(zero).sqrt();
    let random = [s * longitude.cos(), s * longitude.sin(), z];
    if dir == splat(zero) {
        return safe_normalize(random, 3);
    }
    let turned = if dot(random, dir, 3) < zero {
        scale(random, -one)
    } else {
        random
    };
    let a = anisotropy.clamp(zero, one);
    safe_normalize(add(scale(turned, one - a), scale(dir, a)), 3)
}

/// `veneer_gabor_cell`: the kernels of the eight impulses of `cell` at offset `x` from
/// the cell's lowest corner.
pub fn gabor_cell<R: Real>(cell: V3<R>, x: V3<R>, frequency: R, anisotropy: R, dir: V3<R>) -> R {
    let base = pcg3d(cell_bits(cell));
    let mut sum = R::c(0.0);
    for i in 0..8u32 {
        let h = pcg3d(base.map(|b| b.wrapping_add(i)));
        let offset = sub(x, unit_floats(h));
        if dot(offset, offset, 3) < R::c(1.0) {
            let u = unit_floats::<R>(pcg3d(h));
            let direction = gabor_direction(dir, anisotropy, [u[0], u[1]]);
            let k = gabor_kernel(offset, frequency, direction);
            sum = sum + if u[2] < R::c(0.5) { k } else { -k };
        }
    }
    sum
}

/// `veneer_gabor_sum`: the kernel sum over the 27 cells around `p` (zero mean, standard
/// deviation about 1.0146 from a cycle per unit up).
pub fn gabor_sum<R: Real>(point: V3<R>, frequency: R, anisotropy: R, dir: V3<R>) -> R {
    let p = lattice_domain(point);
    let cell = map(p, R::floor);
    let f = sub(p, cell);
    let mut sum = R::c(0.0);
    for z in -1..=1 {
        for y in -1..=1 {
            for x in -1..=1 {
                let o = [x, y, z].map(|k| R::c(f64::from(k)));
                sum = sum + gabor_cell(add(cell, o), sub(f, o), frequency, anisotropy, dir);
            }
        }
    }
    sum
}

/// `veneer_gabor`: Gabor noise in [0, 1], 0.5 + 0.5 clamp(sum / (3 sigma), -1, 1).
pub fn gabor<R: Real>(p: V3<R>, frequency: R, anisotropy: R, orientation: V3<R>) -> R {
    let n = gabor_sum(p, frequency, anisotropy, safe_normalize(orientation, 3));
    R::c(0.5) + R::c(0.5) * (n * R::c(0.3285345)).clamp(R::c(-1.0), R::c(1.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points along a skew line through `origin`, `step` apart.
    fn line(origin: [f64; 3], step: f64, count: usize) -> impl Iterator<Item = [f64; 3]> {
        (0..count).map(move |k| {
            let t = k as f64 * step;
            [origin[0] + t, origin[1] + 0.37 * t, origin[2] - 0.71 * t]
        })
    }

    /// Points spread over a cube of side `size` at `centre` (a fixed low-discrepancy set).
    fn cloud(centre: f64, size: f64, count: usize) -> impl Iterator<Item = [f64; 3]> {
        let g = [0.8191725134, 0.6710436067, 0.5497004779];
        (0..count).map(move |k| g.map(|a| centre + size * ((k as f64 + 0.5) * a).fract()))
    }

    const FAR: [f64; 7] = [0.0, 1.0, -17.5, 1.0e5, -1.0e7, 4.0e20, -3.0e38];

    #[test]
    fn white_noise_is_constant_per_cell_in_range_and_the_same_in_f32_and_f64() {
        for p in cloud(0.0, 40.0, 3000) {
            let v = white_noise::<f64>(p);
            assert!((0.0..1.0).contains(&v));
            let inside = p.map(|x| x.floor() + 0.999);
            assert_eq!(white_noise::<f64>(inside), v, "{p:?}");
            let narrow = white_noise::<f32>(p.map(|x| x as f32));
            let wide = white_noise::<f64>(p.map(|x| f64::from(x as f32)));
            assert_eq!(f64::from(narrow), wide);
            let color = white_noise_color::<f64>(p);
            assert_eq!(color[0], v);
            assert!(color.iter().all(|c| (0.0..1.0).contains(c)));
        }
        for x in FAR {
            for p in [[x, 0.0, 0.0], [x, -x, 0.5 * x]] {
                assert!((0.0..1.0).contains(&white_noise::<f32>(p.map(|v| v as f32))));
            }
        }
    }

    #[test]
    fn white_noise_is_uncorrelated_between_neighbouring_cells() {
        let (mut sum, mut product, mut count) = (0.0, 0.0, 0.0);
        for k in 0..20000 {
            let p = [k as f64, (k / 7) as f64, 3.0];
            let (a, b) = (
                white_noise::<f64>(p),
                white_noise::<f64>([p[0] + 1.0, p[1], p[2]]),
            );
            sum += a;
            product += (a - 0.5) * (b - 0.5);
            count += 1.0;
        }
        assert!((sum / count - 0.5).abs() < 0.01);
        // Correlation of neighbours (variance 1/12).
        assert!((product / count * 12.0).abs() < 0.03);
    }

    #[test]
    fn value_gradient_noise_stays_in_range_and_is_continuous() {
        let mut previous = value_gradient::<f64>([-3.0, 0.3, 0.7]);
        for p in line([-3.0, 0.3, 0.7], 0.003, 4000) {
            let v = value_gradient::<f64>(p);
            assert!((0.0..=1.0).contains(&v), "{p:?}: {v}");
            assert!((v - previous).abs() < 0.05, "jump at {p:?}");
            previous = v;
            let narrow = value_gradient::<f32>(p.map(|x| x as f32));
            assert!((f64::from(narrow) - v).abs() < 1.0e-5);
        }
        for x in FAR {
            for p in [[x, 0.0, 0.0], [x, -x, 0.5 * x]] {
                let v = value_gradient::<f32>(p.map(|v| v as f32));
                assert!((0.0..=1.0).contains(&v), "{p:?}: {v}");
            }
        }
    }

    #[test]
    fn gabor_noise_stays_in_range_and_finite_for_any_finite_input() {
        let frequencies = [0.0, 2.0, -3.5, 1.0e-30, 1.0e30, 3.0e38];
        let anisotropies = [0.0, 0.5, 1.0, -4.0, 1.0e30];
        let orientations = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0e-30, 0.0, 0.0],
            [3.0e38, -3.0e38, 1.0],
        ];
        for x in FAR {
            for p in [[x, 0.0, 0.0], [x, -x, 0.5 * x], [0.3, x, 0.7]] {
                for frequency in frequencies {
                    for anisotropy in anisotropies {
                        for orientation in orientations {
                            let narrow = gabor::<f32>(
                                p.map(|v| v as f32),
                                frequency as f32,
                                anisotropy as f32,
                                orientation.map(|v| v as f32),
                            );
                            let wide = gabor::<f64>(p, frequency, anisotropy, orientation);
                            assert!((0.0..=1.0).contains(&narrow), "{p:?} {frequency}");
                            assert!((0.0..=1.0).contains(&wide), "{p:?} {frequency}");
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn gabor_noise_is_continuous_and_agrees_in_f32_and_f64() {
        let at = |p: [f64; 3]| gabor::<f64>(p, 2.0, 0.3, [0.0, 0.0, 0.0]);
        let mut previous = at([-3.0, 0.3, 0.7]);
        for p in line([-3.0, 0.3, 0.7], 0.002, 3000) {
            let v = at(p);
            assert!(
                (v - previous).abs() < 0.03,
                "jump at {p:?}: {previous} -> {v}"
            );
            previous = v;
            let narrow = gabor::<f32>(p.map(|x| x as f32), 2.0, 0.3, [0.0; 3]);
            let wide = gabor::<f64>(p.map(|x| f64::from(x as f32)), 2.0, 0.3, [0.0; 3]);
            assert!((f64::from(narrow) - wide).abs() < 1.0e-5, "{p:?}");
        }
    }

    #[test]
    fn gabor_sum_has_zero_mean_and_the_documented_deviation() {
        let dirs = [[0.0, 0.0, 0.0], [0.6, 0.0, 0.8]];
        for (dir, anisotropy) in [(dirs[0], 0.0), (dirs[1], 1.0), (dirs[1], 0.5)] {
            let (mut sum, mut squares, mut count) = (0.0, 0.0, 0.0);
            for p in cloud(0.0, 60.0, 40000) {
                let n = gabor_sum::<f64>(p, 3.0, anisotropy, dir);
                sum += n;
                squares += n * n;
                count += 1.0;
            }
            let mean = sum / count;
            let deviation = (squares / count - mean * mean).sqrt();
            assert!(mean.abs() < 0.05, "mean {mean}");
            assert!(
                (deviation / 1.0146 - 1.0).abs() < 0.06,
                "{dir:?} {anisotropy}: deviation {deviation}"
            );
        }
    }

    /// Mean squared change of the noise over a small step along `step`.
    fn roughness(anisotropy: f64, orientation: [f64; 3], step: [f64; 3]) -> f64 {
        let points: Vec<[f64; 3]> = cloud(5.0, 30.0, 6000).collect();
        let total: f64 = points
            .iter()
            .map(|&p| {
                let here = gabor::<f64>(p, 3.0, anisotropy, orientation);
                let there = gabor::<f64>(add(p, step), 3.0, anisotropy, orientation);
                (there - here) * (there - here)
            })
            .sum();
        total / points.len() as f64
    }

    #[test]
    fn anisotropic_gabor_noise_varies_along_its_orientation() {
        let h = 0.01;
        let (x, y, z) = ([h, 0.0, 0.0], [0.0, h, 0.0], [0.0, 0.0, h]);
        let along = roughness(1.0, [2.0, 0.0, 0.0], x);
        let across = roughness(1.0, [2.0, 0.0, 0.0], y);
        assert!(along > 10.0 * across, "along {along}, across {across}");
        let across = roughness(1.0, [2.0, 0.0, 0.0], z);
        assert!(along > 10.0 * across, "along {along}, across {across}");
        // Isotropic: the same roughness in every direction, whatever `orientation` says.
        for orientation in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]] {
            let (rx, ry) = (
                roughness(0.0, orientation, x),
                roughness(0.0, orientation, y),
            );
            assert!((rx / ry - 1.0).abs() < 0.2, "{orientation:?}: {rx} vs {ry}");
        }
        let half = roughness(0.5, [1.0, 0.0, 0.0], x) / roughness(0.5, [1.0, 0.0, 0.0], y);
        assert!(
            half > 1.5 && half < along / across,
            "anisotropy 0.5: ratio {half}"
        );
    }

    #[test]
    fn gabor_directions_are_unit_vectors() {
        for k in 0..2000 {
            let u = [(k as f64 * 0.618034).fract(), (k as f64 * 0.754878).fract()];
            for (dir, a) in [
                ([0.0; 3], 0.7),
                ([0.0, 1.0, 0.0], 0.0),
                ([0.0, 0.0, -1.0], 0.5),
            ] {
                let d = gabor_direction::<f64>(dir, a, u);
                assert!((dot(d, d, 3) - 1.0).abs() < 1.0e-12, "{dir:?} {a} {u:?}");
            }
            let d = gabor_direction::<f64>([0.0, 0.0, -1.0], 1.0, u);
            assert_eq!(d, [0.0, 0.0, -1.0]);
        }
    }
}
