//! CPU twins of `shaders/flood_fill.wgsl`: labelling the cells of a mask (its connected
//! regions above 0.5) by their bounding boxes, step by step as the GPU runs it, and what
//! the Flood fill node reads of a cell at a point.
//!
//! A texel's state is the bounding box of its cell as offsets in texels from the texel:
//! `[lo x, hi x, lo y, hi y]`, lows ≤ 0 ≤ highs. A texel outside the mask holds
//! [`OUTSIDE`]. The boxes grow by scans along rows and columns in turn: along an axis,
//! step k merges the boxes of the texels 2ᵏ away on both sides (a segmented scan, 13 steps
//! cover the largest buffer). While a scan has not yet reached the start of its run of
//! inside texels, the low offset is whole; once it has, the low carries −½ (and the high
//! +½ at the run's end), so the flags ride in the offsets' fractions and a state stays
//! four lanes. Each round (a row scan, then a column scan) lets a box turn one more
//! corner of its cell: rectangles need one round, the pixelated cells of a Voronoi
//! diagram three or four, slender slanted or winding cells more.
//! Across the wrap when the buffer wraps; a cell that reaches all the way round an axis
//! spans the whole tile along it.

use super::buffers::{Image, edge_index};
use super::noise::{cell_bits, pcg3d, unit_floats};
use crate::nodes::passes::EdgeMode;

/// Scan steps along an axis: windows of 1, 2, 4, … texels, up to the largest buffer
/// side ([`crate::nodes::passes::MAX_BUFFER_SIZE`], 2¹³).
pub const FILL_STEPS: u32 = 13;

/// The state of a texel outside the mask (a low offset above zero marks it).
const OUTSIDE: [f64; 4] = [1.0; 4];

/// Whether `state` is of a texel outside the mask.
fn is_outside(state: [f64; 4]) -> bool {
    state[0] > 0.5
}

/// The seed state of `texel` (as `veneer_fill_seed`): an empty box inside the mask.
pub fn fill_seed(image: &Image, texel: [i64; 2]) -> [f64; 4] {
    if image.texel(texel[0], texel[1])[0] > 0.5 {
        [0.0; 4]
    } else {
        OUTSIDE
    }
}

/// The state at `texel`, outside beyond an edge that does not wrap (as `veneer_fill_load`).
fn load(image: &Image, texel: [i64; 2]) -> [f64; 4] {
    let size = [i64::from(image.width), i64::from(image.height)];
    let beyond = (0..2).any(|k| texel[k] < 0 || texel[k] >= size[k]);
    if image.edge != EdgeMode::Wrap && beyond {
        OUTSIDE
    } else {
        image.texel(texel[0], texel[1])
    }
}

/// One texel's box along a scan: its extent along the axis, across it, and whether the
/// scan has reached its run's start and end.
#[derive(Clone, Copy)]
struct Run {
    lo: f64,
    hi: f64,
    across: [f64; 2],
    closed: [bool; 2],
}

impl Run {
    /// The run of a state with its lanes ordered along `axis` first (as `veneer_fill_decode`).
    fn decode(state: [f64; 4], axis: usize) -> Run {
        let [a, b, c, d] = if axis == 0 {
            state
        } else {
            [state[2], state[3], state[0], state[1]]
        };
        let (lo, hi) = (a.ceil(), b.floor());
        Run {
            lo,
            hi,
            across: [c.ceil(), d.floor()],
            closed: [a < lo, b > hi],
        }
    }

    /// The state of the run (as `veneer_fill_encode`).
    fn encode(self, axis: usize) -> [f64; 4] {
        let lo = self.lo - if self.closed[0] { 0.5 } else { 0.0 };
        let hi = self.hi + if self.closed[1] { 0.5 } else { 0.0 };
        let [c, d] = self.across;
        if axis == 0 {
            [lo, hi, c, d]
        } else {
            [c, d, lo, hi]
        }
    }

    /// Grows the box by `other`'s, `shift` texels away along the axis.
    fn merge(&mut self, other: Run, shift: f64) {
        self.lo = self.lo.min(other.lo + shift);
        self.hi = self.hi.max(other.hi + shift);
        self.across = [
            self.across[0].min(other.across[0]),
            self.across[1].max(other.across[1]),
        ];
    }
}

/// Scan step `k` along `axis` (0: rows, 1: columns) at `texel` (as `veneer_fill_step`).
/// Step 0 starts the scan: it drops the previous axis' flags and closes the run where a
/// neighbour is outside.
pub fn fill_step(image: &Image, texel: [i64; 2], axis: usize, k: u32) -> [f64; 4] {
    let here = load(image, texel);
    let n = i64::from([image.width, image.height][axis]);
    let s = 1_i64 << k;
    if is_outside(here) || (k > 0 && s >= n) {
        return here;
    }
    let at = |offset: i64| {
        let mut place = texel;
        place[axis] += offset;
        place
    };
    let run_at = |offset: i64| {
        let state = load(image, at(offset));
        let mut run = Run::decode(state, axis);
        if k == 0 {
            run.closed = [-1, 1].map(|side| is_outside(load(image, at(offset + side))));
        }
        (run, is_outside(state))
    };
    let (mut run, _) = run_at(0);
    for (side, sign) in [(0, -1), (1, 1)] {
        if run.closed[side] {
            continue;
        }
        let (other, outside) = run_at(sign * s);
        if outside {
            run.closed[side] = true;
            continue;
        }
        run.merge(other, (sign * s) as f64);
        run.closed[side] |= other.closed[side];
    }
    if run.hi - run.lo + 1.0 >= n as f64 {
        let position = texel[axis] as f64;
        run.lo = -position;
        run.hi = n as f64 - 1.0 - position;
        run.closed = [true, true];
    }
    run.encode(axis)
}

/// What the Flood fill node reads of the cell under a point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FillCell {
    /// A random value in [0, 1) per cell.
    pub value: f64,
    /// A random colour per cell.
    pub colour: [f64; 3],
    /// The point's place in the cell's bounding box, 0 to 1 across it.
    pub uv: [f64; 2],
    /// A ramp from 0 to 1 across the box in a random direction per cell.
    pub gradient: f64,
    /// The box's centre in domain units (beyond 1 for a box across the wrap's seam).
    pub centre: [f64; 2],
}

/// The cell of the labelled `image` under domain coordinate `uv` (as
/// `veneer_flood_fill`), `None` outside the mask. The texel and the fraction within it
/// are found in f32, as the GPU finds them.
pub fn fill_cell(image: &Image, uv: [f64; 2], seed: f64) -> Option<FillCell> {
    let size = [image.width, image.height];
    let place = image.place(uv).map(|p| p + 0.5);
    let base = place.map(f64::floor);
    let texel = base.map(|b| b as i64);
    let state = image.texel(texel[0], texel[1]);
    if is_outside(state) {
        return None;
    }
    let lo = [state[0].ceil(), state[2].ceil()];
    let hi = [state[1].floor(), state[3].floor()];
    let extent = [0, 1].map(|k| hi[k] - lo[k] + 1.0);
    let uv = [0, 1].map(|k| (place[k] - base[k] - lo[k]) / extent[k]);
    let corner = [0, 1].map(|k| {
        let n = i64::from(size[k]);
        let corner = edge_index(texel[k], n, image.edge) + lo[k] as i64;
        if image.edge == EdgeMode::Wrap {
            corner.rem_euclid(n)
        } else {
            corner
        }
    });
    let seed_bits = cell_bits::<f64>([seed; 3]);
    let key = [
        corner[0] as u32,
        corner[1] as u32,
        extent[0] as u32 | ((extent[1] as u32) << 14),
    ];
    let first = pcg3d([0, 1, 2].map(|k| key[k] ^ seed_bits[k]));
    let random = unit_floats::<f64>(first);
    let colour = unit_floats::<f64>(pcg3d(first));
    let angle = std::f64::consts::TAU * random[1];
    let direction = [angle.cos(), angle.sin()];
    let reach = direction[0].abs() + direction[1].abs();
    let gradient = 0.5 + ((uv[0] - 0.5) * direction[0] + (uv[1] - 0.5) * direction[1]) / reach;
    let centre = [0, 1].map(|k| (corner[k] as f64 + 0.5 * extent[k]) / f64::from(size[k]));
    Some(FillCell {
        value: random[0],
        colour,
        uv,
        gradient,
        centre,
    })
}

/// The labelled image of `mask` after every stage of `rounds` rounds (seeds, then row
/// and column scans in turn): the flood fill's buffer.
pub fn label(mask: &Image, rounds: u32) -> Image {
    let mut image = mask.map_texels(fill_seed);
    for _ in 0..rounds {
        for axis in 0..2 {
            for k in 0..FILL_STEPS {
                image = image.map_texels(|image, texel| fill_step(image, texel, axis, k));
            }
        }
    }
    image
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The exact cells of a mask (4-connected, across the wrap when it wraps): a cell
    /// index per texel, `None` outside.
    fn components(mask: &Image) -> Vec<Option<usize>> {
        let (w, h) = (i64::from(mask.width), i64::from(mask.height));
        let inside = |x: i64, y: i64| {
            let wrap = mask.edge == EdgeMode::Wrap;
            if !wrap && (x < 0 || y < 0 || x >= w || y >= h) {
                return None;
            }
            let (x, y) = (x.rem_euclid(w), y.rem_euclid(h));
            (mask.texels[(y * w + x) as usize][0] > 0.5).then_some((x, y))
        };
        let mut cells = vec![None; (w * h) as usize];
        let mut count = 0;
        for start in 0..w * h {
            if cells[start as usize].is_some() || inside(start % w, start / w).is_none() {
                continue;
            }
            let mut stack = vec![(start % w, start / w)];
            cells[start as usize] = Some(count);
            while let Some((x, y)) = stack.pop() {
                for (dx, dy) in [(1, 0), (-1, 0), (0, 1), (0, -1)] {
                    if let Some((nx, ny)) = inside(x + dx, y + dy) {
                        let at = (ny * w + nx) as usize;
                        if cells[at].is_none() {
                            cells[at] = Some(count);
                            stack.push((nx, ny));
                        }
                    }
                }
            }
            count += 1;
        }
        cells
    }

    /// The mask image `n` texels square of `inside(x, y)`.
    fn mask(n: u32, edge: EdgeMode, inside: impl Fn(i64, i64) -> bool) -> Image {
        let texels = (0..i64::from(n * n))
            .map(|k| {
                let on = inside(k % i64::from(n), k / i64::from(n));
                [f32::from(u8::from(on)), 0.0, 0.0, 1.0]
            })
            .collect();
        Image {
            width: n,
            height: n,
            edge,
            texels,
        }
    }

    /// Whether every cell of `mask` reads one value everywhere, and different cells
    /// different values, after `rounds` rounds.
    fn one_value_per_cell(mask: &Image, rounds: u32) -> bool {
        let labelled = label(mask, rounds);
        let cells = components(mask);
        let n = mask.width;
        let mut values: std::collections::HashMap<usize, u64> = Default::default();
        let mut seen: std::collections::HashMap<u64, usize> = Default::default();
        for (at, cell) in cells.iter().enumerate() {
            let uv = [0, 1].map(|k| {
                let i = [at as u32 % n, at as u32 / n][k];
                (f64::from(i) + 0.5) / f64::from(n)
            });
            let read = fill_cell(&labelled, uv, 0.0);
            match (cell, read) {
                (None, None) => {}
                (Some(cell), Some(read)) => {
                    let bits = read.value.to_bits();
                    if *values.entry(*cell).or_insert(bits) != bits
                        || *seen.entry(bits).or_insert(*cell) != *cell
                    {
                        return false;
                    }
                }
                _ => return false,
            }
        }
        true
    }

    #[test]
    fn bricks_across_the_wrap_need_one_round() {
        // Staggered bricks 12 × 6 texels with one-texel mortar, offset so that bricks
        // cross both seams of a 48-texel tile.
        let bricks = mask(48, EdgeMode::Wrap, |x, y| {
            let y = y + 3;
            let x = x + 5 + if (y / 6) % 2 == 1 { 6 } else { 0 };
            x % 12 != 0 && y % 6 != 0
        });
        assert!(one_value_per_cell(&bricks, 1));
    }

    #[test]
    fn voronoi_cells_across_the_wrap_need_three_rounds() {
        // Twelve cells of a wrapped Voronoi diagram, split by lines where the nearest
        // two sites are about equally far. Convex, but their pixelated edges have steps
        // that a second round does not always get round.
        let n = 64;
        let mut state = 7_u32;
        let mut random = || {
            state = state.wrapping_mul(1664525).wrapping_add(1013904223);
            f64::from(state >> 8) / 16777216.0 * f64::from(n)
        };
        let sites: Vec<[f64; 2]> = (0..12).map(|_| [random(), random()]).collect();
        let cells = mask(n, EdgeMode::Wrap, |x, y| {
            let mut d: Vec<f64> = sites
                .iter()
                .map(|s| {
                    let w = |d: f64| d - f64::from(n) * (d / f64::from(n)).round();
                    w(x as f64 + 0.5 - s[0]).hypot(w(y as f64 + 0.5 - s[1]))
                })
                .collect();
            d.sort_by(f64::total_cmp);
            d[1] - d[0] > 1.5
        });
        assert!(!one_value_per_cell(&cells, 2));
        assert!(one_value_per_cell(&cells, 3));
    }

    #[test]
    fn a_winding_cell_needs_a_round_per_corner() {
        // A U-shaped cell: two columns joined at the bottom. Row scans reach across the
        // bottom bar, column scans up the arms: one round leaves the arms' tops apart.
        let u = mask(16, EdgeMode::Clamp, |x, y| {
            (2..14).contains(&y) && (x == 2 || x == 12) || y == 13 && (2..=12).contains(&x)
        });
        assert!(!one_value_per_cell(&u, 1));
        assert!(one_value_per_cell(&u, 2));
    }

    #[test]
    fn a_cell_all_round_the_tile_spans_it_and_the_outside_reads_nothing() {
        let band = mask(16, EdgeMode::Wrap, |_, y| (4..8).contains(&y));
        let labelled = label(&band, 1);
        let cell = fill_cell(&labelled, [0.3, 0.4], 0.0).unwrap();
        assert_eq!(cell.centre, [0.5, 0.375]);
        assert!((cell.uv[0] - 0.3).abs() < 1e-6);
        assert!(fill_cell(&labelled, [0.3, 0.9], 0.0).is_none());
        assert!(one_value_per_cell(&band, 1));
    }
}
