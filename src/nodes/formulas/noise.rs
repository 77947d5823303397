//! Hashes and lattice noises, formula for formula as in shaders/hash.wgsl, value.wgsl,
//! gradient.wgsl, simplex.wgsl and worley.wgsl.

use super::real::{Real, V3, add, dot, length, map, splat, sub, zip};
use crate::nodes::settings::{Basis, Metric};

/// The sine hash of a lattice cell (`veneer_lattice_sine`).
pub fn lattice_sine<R: Real>(cell: V3<R>) -> R {
    let h = dot(cell, [R::c(127.1), R::c(311.7), R::c(74.7)], 3);
    (h.sin() * R::c(43758.5453)).fract()
}

/// `p` within the lattice's range, ±2147483520 per axis (`veneer_lattice_domain`): every
/// lattice noise samples its point through this, so any coordinate gives a finite value.
pub fn lattice_domain<R: Real>(p: V3<R>) -> V3<R> {
    let limit = R::c(2147483520.0);
    map(p, |x| x.clamp(-limit, limit))
}

/// How a lattice noise repeats: `None` never (every cell hashes to its own values),
/// `Some(n)` every `n` cells along x, y and z (the cells hashed are wrapped).
pub type Period = Option<i32>;

/// `p` within the lattice's range and moved by whole periods into [0, period) per axis,
/// up to rounding (`veneer_lattice_periodic`).
pub fn lattice_periodic<R: Real>(point: V3<R>, period: i32) -> V3<R> {
    let span = R::c(f64::from(period));
    map(lattice_domain(point), |x| x - span * (x / span).floor())
}

/// A lattice cell wrapped into [0, period) per axis (`veneer_wrap_cell`).
pub fn wrap_cell<R: Real>(cell: V3<R>, period: i32) -> V3<R> {
    let span = R::c(f64::from(period));
    map(cell, |c| c - span * (c / span).floor())
}

/// A simplex-lattice (skewed) cell wrapped so that a shift of space by `period` along any
/// axis leaves it unchanged (`veneer_wrap_simplex_cell`; `period` a multiple of 3).
pub fn wrap_simplex_cell<R: Real>(cell: V3<R>, period: i32) -> V3<R> {
    let span = R::c(f64::from(period));
    let sum = cell[0] + cell[1] + cell[2];
    let turns = map(cell, |c| {
        ((R::c(6.0) * c - sum) / (R::c(6.0) * span)).floor()
    });
    let all_turns = turns[0] + turns[1] + turns[2];
    std::array::from_fn(|k| cell[k] - span * turns[k] - span / R::c(3.0) * all_turns)
}

/// The lattice step a periodic `basis` takes: a period must be a multiple of it (3 for
/// simplex noise, whose skewed lattice repeats along the axes only every 3 cells).
pub fn period_step(basis: Basis) -> i32 {
    if basis == Basis::Simplex { 3 } else { 1 }
}

/// How many cells an octave at `frequency` spans over a noise repeating every `period`
/// cells (`veneer_octave_period`): the nearest multiple of `step` (ties to even, as
/// WGSL rounds), at least one step and at most 2^24 cells.
pub fn octave_period<R: Real>(period: i32, frequency: R, step: i32) -> i32 {
    let steps = (R::c(f64::from(period)) * frequency.abs() / R::c(f64::from(step)))
        .to_f64()
        .round_ties_even();
    step * steps.clamp(1.0, 16777216.0 / f64::from(step)) as i32
}

/// The point a noise of `period` samples: within the lattice's range, and near the
/// origin when periodic.
fn domain<R: Real>(point: V3<R>, period: Period) -> V3<R> {
    match period {
        None => lattice_domain(point),
        Some(n) => lattice_periodic(point, n),
    }
}

/// The cell a noise of `period` hashes for `cell`.
fn wrap<R: Real>(cell: V3<R>, period: Period) -> V3<R> {
    match period {
        None => cell,
        Some(n) => wrap_cell(cell, n),
    }
}

/// Integer coordinates of a lattice cell, clamped to the i32 range (`veneer_cell_bits`).
pub fn cell_bits<R: Real>(cell: V3<R>) -> [u32; 3] {
    let limit = 2147483520.0;
    cell.map(|c| (c.to_f64().clamp(-limit, limit) as i32) as u32)
}

/// PCG3D (`veneer_pcg3d`).
pub fn pcg3d(seed: [u32; 3]) -> [u32; 3] {
    let mut v = seed.map(|x| x.wrapping_mul(1664525).wrapping_add(1013904223));
    let mix = |v: &mut [u32; 3]| {
        v[0] = v[0].wrapping_add(v[1].wrapping_mul(v[2]));
        v[1] = v[1].wrapping_add(v[2].wrapping_mul(v[0]));
        v[2] = v[2].wrapping_add(v[0].wrapping_mul(v[1]));
    };
    mix(&mut v);
    v = v.map(|x| x ^ (x >> 16));
    mix(&mut v);
    v
}

/// Top 24 bits of each lane in [0, 1) (`veneer_unit_floats`).
pub fn unit_floats<R: Real>(bits: [u32; 3]) -> V3<R> {
    bits.map(|b| R::c(f64::from(b >> 8) / 16777216.0))
}

/// The PCG hash of a lattice cell (`veneer_lattice_pcg`).
pub fn lattice_pcg<R: Real>(cell: V3<R>) -> R {
    unit_floats::<R>(pcg3d(cell_bits(cell)))[0]
}

const CORNERS: [[f64; 3]; 8] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [1.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
    [1.0, 1.0, 1.0],
];

/// Trilinear blend of eight corner values (in `CORNERS` order) with weights `u`.
fn trilinear<R: Real>(n: [R; 8], u: V3<R>) -> R {
    let nx00 = R::mix(n[0], n[1], u[0]);
    let nx10 = R::mix(n[2], n[3], u[0]);
    let nx01 = R::mix(n[4], n[5], u[0]);
    let nx11 = R::mix(n[6], n[7], u[0]);
    R::mix(R::mix(nx00, nx10, u[1]), R::mix(nx01, nx11, u[1]), u[2])
}

fn corner<R: Real>(k: usize) -> V3<R> {
    CORNERS[k].map(R::c)
}

/// Value noise in [0, 1] (`veneer_noise_value_sine` / `_pcg`, and their `_periodic`
/// variants).
pub fn value<R: Real>(point: V3<R>, lattice: fn(V3<R>) -> R, period: Period) -> R {
    let p = domain(point, period);
    let i = map(p, R::floor);
    let f = map(p, R::fract);
    let u = map(f, |f| f * f * (R::c(3.0) - R::c(2.0) * f));
    trilinear(
        std::array::from_fn(|k| lattice(wrap(add(i, corner(k)), period))),
        u,
    )
}

/// Hashed edge gradient of `cell` dotted with `d` (`veneer_gradient_dot`).
pub fn gradient_dot<R: Real>(cell: V3<R>, d: V3<R>) -> R {
    let h = pcg3d(cell_bits(cell))[0] & 15;
    let u = if h < 8 { d[0] } else { d[1] };
    let v = if h < 4 {
        d[1]
    } else if h == 12 || h == 14 {
        d[0]
    } else {
        d[2]
    };
    (if h & 1 == 0 { u } else { -u }) + (if h & 2 == 0 { v } else { -v })
}

/// Gradient noise in [0, 1] (`veneer_noise_gradient`, `veneer_noise_gradient_periodic`).
pub fn gradient<R: Real>(point: V3<R>, period: Period) -> R {
    let p = domain(point, period);
    let i = map(p, R::floor);
    let f = sub(p, i);
    let u = map(f, |f| {
        f * f * f * (f * (f * R::c(6.0) - R::c(15.0)) + R::c(10.0))
    });
    let n = trilinear(
        std::array::from_fn(|k| gradient_dot(wrap(add(i, corner(k)), period), sub(f, corner(k)))),
        u,
    );
    R::c(0.5) + R::c(0.5) * n.clamp(R::c(-1.0), R::c(1.0))
}

fn simplex_corner<R: Real>(cell: V3<R>, d: V3<R>) -> R {
    let falloff = (R::c(0.6) - dot(d, d, 3)).max(R::c(0.0));
    let f2 = falloff * falloff;
    f2 * f2 * gradient_dot(cell, d)
}

/// Simplex noise in [0, 1] (`veneer_noise_simplex`, `veneer_noise_simplex_periodic`).
pub fn simplex<R: Real>(point: V3<R>, period: Period) -> R {
    let p = domain(point, period);
    let skew = (p[0] + p[1] + p[2]) * R::c(1.0 / 3.0);
    let i = map(add(p, splat(skew)), R::floor);
    let unskew = (i[0] + i[1] + i[2]) * R::c(1.0 / 6.0);
    let x0 = sub(p, sub(i, splat(unskew)));
    let g = zip([x0[1], x0[2], x0[0]], x0, R::step);
    let l = map(g, |g| R::c(1.0) - g);
    let l_zxy = [l[2], l[0], l[1]];
    let i1 = zip(g, l_zxy, R::min);
    let i2 = zip(g, l_zxy, R::max);
    let x1 = add(sub(x0, i1), splat(R::c(1.0 / 6.0)));
    let x2 = add(sub(x0, i2), splat(R::c(2.0 / 6.0)));
    let x3 = add(sub(x0, splat(R::c(1.0))), splat(R::c(0.5)));
    let cell = |c: V3<R>| match period {
        None => c,
        Some(n) => wrap_simplex_cell(c, n),
    };
    let n = simplex_corner(cell(i), x0)
        + simplex_corner(cell(add(i, i1)), x1)
        + simplex_corner(cell(add(i, i2)), x2)
        + simplex_corner(cell(add(i, splat(R::c(1.0)))), x3);
    R::c(0.5) + R::c(0.5) * (R::c(32.0) * n).clamp(R::c(-1.0), R::c(1.0))
}

/// A basis in its natural range [0, 1] (`veneer_noise_<basis>`).
pub fn basis<R: Real>(basis: Basis, p: V3<R>) -> R {
    repeating(basis, p, None)
}

/// A basis in its natural range [0, 1], repeating every `period` cells
/// (`veneer_noise_<basis>_periodic`; `veneer_noise_<basis>` when `None`).
pub fn repeating<R: Real>(basis: Basis, p: V3<R>, period: Period) -> R {
    match basis {
        Basis::ValueSine => value(p, lattice_sine, period),
        Basis::ValuePcg => value(p, lattice_pcg, period),
        Basis::Gradient => gradient(p, period),
        Basis::Simplex => simplex(p, period),
    }
}

/// A basis in [-1, 1] (`veneer_noise_<basis>_signed`).
pub fn signed<R: Real>(b: Basis, p: V3<R>) -> R {
    signed_repeating(b, p, None)
}

/// A basis in [-1, 1], repeating every `period` cells (`veneer_noise_<basis>_signed_periodic`).
pub fn signed_repeating<R: Real>(b: Basis, p: V3<R>, period: Period) -> R {
    R::c(2.0) * repeating(b, p, period) - R::c(1.0)
}

fn metric<R: Real>(d: V3<R>, metric: Metric) -> R {
    let a = map(d, R::abs);
    match metric {
        Metric::Euclidean => length(d, 3),
        Metric::Manhattan => a[0] + a[1] + a[2],
        Metric::Chebyshev => a[0].max(a[1].max(a[2])),
    }
}

/// The three smallest feature distances F1, F2, F3 (`veneer_worley`), `jitter` clamped to
/// [-1, 1].
/// With a `period`, the point is moved by whole periods near the origin and the cells
/// whose feature points are hashed are wrapped (`veneer_worley_periodic`).
pub fn worley<R: Real>(point: V3<R>, jitter: R, m: Metric, period: Period) -> V3<R> {
    let jitter = jitter.clamp(R::c(-1.0), R::c(1.0));
    nearest_features(domain(point, period), m, |c| {
        let r = unit_floats::<R>(pcg3d(cell_bits(wrap(c, period))));
        add(
            add(c, splat(R::c(0.5))),
            map(r, |r| jitter * (r - R::c(0.5))),
        )
    })
}

/// F1, F2, F3 over the GeoTextures thesis's feature points (`veneer_worley_simplex`,
/// seed 003's `gpuCellNoise3D`): each cell's corner moved along (1, 1, 1) by signed
/// simplex noise at the corner times `spread` (the thesis's `noiseScale`), unclamped.
pub fn worley_simplex<R: Real>(point: V3<R>, spread: R, m: Metric) -> V3<R> {
    nearest_features(domain(point, None), m, |c| {
        add(c, splat(spread * signed(Basis::Simplex, c)))
    })
}

/// The three smallest distances under metric `m` from `p` to the feature points
/// `feature(cell)` of the 27 cells around it, visited z, y, x from −1 to 1.
fn nearest_features<R: Real>(p: V3<R>, m: Metric, feature: impl Fn(V3<R>) -> V3<R>) -> V3<R> {
    let cell = map(p, R::floor);
    let mut f = splat(R::c(1.0e9));
    for z in -1..=1 {
        for y in -1..=1 {
            for x in -1..=1 {
                let c = add(cell, [R::c(x as f64), R::c(y as f64), R::c(z as f64)]);
                let d = metric(sub(p, feature(c)), m);
                if d < f[0] {
                    f = [d, f[0], f[1]];
                } else if d < f[1] {
                    f = [f[0], d, f[1]];
                } else if d < f[2] {
                    f[2] = d;
                }
            }
        }
    }
    f
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pcg3d_is_pinned() {
        // Values computed independently from the published PCG3D recurrence; changing the
        // hash would change every PCG material.
        assert_eq!(pcg3d([0, 0, 0]), [2611992518, 2833812075, 1058359340]);
        assert_eq!(pcg3d([1, 2, 3]), [4204755366, 1223881804, 1500469937]);
    }

    #[test]
    fn pcg_lattice_is_the_same_in_f32_and_f64_at_any_coordinate() {
        for cell in [
            [0.0, 0.0, 0.0],
            [-1.0, 5.0, 9.0],
            [1.0e7, -3.0e9, 4.0e20],
            [-1.0e38, 1.0e38, 0.0],
        ] {
            let narrow = lattice_pcg::<f32>(cell.map(|c| c as f32));
            let wide = lattice_pcg::<f64>(cell.map(|c: f64| f64::from(c as f32)));
            assert_eq!(f64::from(narrow), wide, "{cell:?}");
            assert!((0.0..1.0).contains(&wide));
        }
    }

    #[test]
    fn every_basis_stays_in_its_range_and_is_continuous() {
        for b in Basis::ALL {
            let at = |t: f64| basis::<f64>(b, [t - 3.0, 0.3 + 0.5 * t, 0.7 - t]);
            let mut previous = at(0.0);
            for k in 1..4000 {
                let value = at(k as f64 * 0.003);
                assert!((0.0..=1.0).contains(&value), "{b:?} at step {k}: {value}");
                assert!((value - previous).abs() < 0.05, "{b:?} jumps at step {k}");
                previous = value;
            }
        }
    }

    /// Points spread over a few periods, some negative, some on cell corners.
    fn points() -> impl Iterator<Item = [f64; 3]> {
        (0..200)
            .map(|k| {
                let t = f64::from(k);
                [
                    (t * 0.37).sin() * 7.0,
                    (t * 0.91).cos() * 5.0 - 1.0,
                    t * 0.113 - 9.0,
                ]
            })
            .chain([[0.0; 3], [3.0, -6.0, 12.0]])
    }

    #[test]
    fn periodic_noises_repeat_along_every_axis_and_differ_from_cell_to_cell() {
        for basis in Basis::ALL {
            for period in [3, 6, 12] {
                for p in points() {
                    let here = repeating::<f64>(basis, p, Some(period));
                    for axis in 0..3 {
                        let mut moved = p;
                        moved[axis] += f64::from(period) * [1.0, -2.0, 3.0][axis];
                        let there = repeating::<f64>(basis, moved, Some(period));
                        assert!(
                            (here - there).abs() < 1e-9,
                            "{basis:?} period {period} at {p:?} axis {axis}: {here} vs {there}"
                        );
                    }
                }
                // Not a constant: the noise still varies within the period.
                let values: Vec<f64> = points()
                    .map(|p| repeating(basis, p, Some(period)))
                    .collect();
                let spread = values.iter().cloned().fold(f64::MIN, f64::max)
                    - values.iter().cloned().fold(f64::MAX, f64::min);
                assert!(spread > 0.3, "{basis:?} period {period}: spread {spread}");
            }
        }
        for period in [1, 4, 7] {
            for p in points() {
                let here = worley::<f64>(p, 1.0, Metric::Euclidean, Some(period));
                let moved = [
                    p[0] - f64::from(period),
                    p[1] + f64::from(2 * period),
                    p[2] + f64::from(period),
                ];
                let there = worley::<f64>(moved, 1.0, Metric::Euclidean, Some(period));
                assert!(
                    (0..3).all(|k| (here[k] - there[k]).abs() < 1e-9),
                    "worley period {period} at {p:?}"
                );
            }
        }
    }

    #[test]
    fn a_periodic_noise_is_the_infinite_one_within_its_first_period() {
        // Inside [0, period) the wrap changes no cell that a point's corners reach
        // except across the far faces, so away from them the two agree exactly.
        for basis in [Basis::ValuePcg, Basis::Gradient] {
            for p in points().map(|p| p.map(|x| x.rem_euclid(6.0).min(4.9))) {
                assert_eq!(
                    repeating::<f64>(basis, p, Some(6)),
                    repeating::<f64>(basis, p, None)
                );
            }
        }
    }

    #[test]
    fn octave_periods_are_whole_multiples_of_the_step() {
        assert_eq!(octave_period::<f32>(4, 1.0, 1), 4);
        assert_eq!(octave_period::<f32>(4, 2.0, 1), 8);
        assert_eq!(octave_period::<f32>(3, 2.1, 3), 6);
        assert_eq!(
            octave_period::<f32>(1, 2.5, 1),
            2,
            "ties go to even, as WGSL rounds"
        );
        assert_eq!(octave_period::<f32>(5, 0.0, 1), 1, "at least one step");
        assert_eq!(
            octave_period::<f32>(9, 3.0e38, 3),
            16777215,
            "at most 2^24 cells"
        );
    }

    #[test]
    fn worley_distances_are_sorted_and_f1_is_zero_at_a_feature_point() {
        let f = worley::<f64>([0.3, 1.7, -2.2], 1.0, Metric::Euclidean, None);
        assert!(f[0] <= f[1] && f[1] <= f[2]);
        let cell = [4.0, -2.0, 7.0];
        let r = unit_floats::<f64>(pcg3d(cell_bits(cell)));
        let feature = [0, 1, 2].map(|k| cell[k] + 0.5 + 0.8 * (r[k] - 0.5));
        assert!(worley::<f64>(feature, 0.8, Metric::Chebyshev, None)[0] < 1e-12);
    }
}

#[cfg(test)]
mod sine_hash_precision {
    use super::*;

    /// Share of x-neighbouring lattice cells near magnitude `m` whose f32 sine hashes are
    /// equal: 0 for a working hash, growing once f32 can no longer tell the cells apart.
    pub fn repeats(m: f64) -> f64 {
        let pairs = 4000;
        let equal = (0..pairs)
            .filter(|k| {
                let k = *k as f64;
                let cell = [
                    (m + k).floor(),
                    (0.7 * m).floor() + (k / 7.0).floor(),
                    (0.3 * m).floor(),
                ];
                let next = [cell[0] + 1.0, cell[1], cell[2]];
                lattice_sine::<f32>(cell.map(|c| c as f32))
                    == lattice_sine::<f32>(next.map(|c| c as f32))
            })
            .count();
        equal as f64 / f64::from(pairs)
    }

    #[test]
    #[ignore = "prints the measurement behind SINE_HASH_SAFE_COORDINATE"]
    fn measure() {
        for m in [1.0e2, 1.0e4, 1.0e5, 1.0e6, 2.0e6, 4.0e6, 8.0e6, 1.6e7] {
            println!(
                "|p| ~ {m:e}: {:.2}% of neighbouring cells repeat",
                100.0 * repeats(m)
            );
        }
    }
}
