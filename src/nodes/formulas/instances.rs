//! Instances placed over a tile (`shaders/instances.wgsl`): the grid a point sees, each
//! instance's transform and random numbers, the search over the cells that can reach the
//! point, and how overlapping instances blend.

use super::noise::{pcg3d, unit_floats};
use super::real::{Real, V3, finite};
use crate::nodes::cpu::Instance;

/// The most cells an instance reaches either side of its own (`veneer_tile_reach_cap`).
pub const REACH_CAP: f64 = 8.0;

/// How overlapping instances combine (the blend `mode` of the WGSL, in this order).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum TileBlend {
    /// The highest instance.
    Max,
    /// The instances' sum.
    Add,
    /// The last instance drawn (in row, then column order) over the others.
    Over,
    /// The lowest instance where any covers the point, 1 elsewhere.
    Min,
}

impl TileBlend {
    /// Every mode, in menu order.
    pub const ALL: [TileBlend; 4] = [
        TileBlend::Max,
        TileBlend::Add,
        TileBlend::Over,
        TileBlend::Min,
    ];

    /// The WGSL's number for the mode.
    pub fn code(self) -> u32 {
        self as u32
    }
}

/// The settings every instance of a grid shares, as the node's inputs give them.
#[derive(Clone, Copy, Debug)]
pub struct GridSettings<R> {
    pub size: [R; 2],
    pub counts: [R; 2],
    pub offsets: [R; 2],
    pub jitter: R,
    pub rotation: R,
    pub rotation_random: R,
    pub scale: R,
    pub scale_xy: [R; 2],
    pub scale_random: R,
    pub seed: R,
    /// The pixel's size in the point's units (0 when not filtering).
    pub footprint: R,
    /// Instances per tile (a splatter), 0 for one per cell.
    pub splat: R,
}

/// One point's view of a grid (`veneer_tile_grid`).
#[derive(Clone, Copy, Debug)]
pub struct Grid<R> {
    pub t: [R; 2],
    pub counts: [R; 2],
    pub cell: [R; 2],
    pub offsets: [R; 2],
    pub jitter: [R; 2],
    pub rotation: [R; 2],
    pub scale: V3<R>,
    pub reach: [R; 2],
    pub corner: [R; 2],
    pub height: R,
    pub seed: u32,
    pub footprint: R,
    pub splat: u32,
    pub stride: u32,
    pub shift: u32,
}

/// The most instances a splatter places per tile (`veneer_splat_limit`).
pub const SPLAT_LIMIT: f64 = 65536.0;

/// The grid of a splatter of `count` instances (`veneer_splat_counts`).
pub fn splat_counts<R: Real>(count: R) -> [R; 2] {
    let n = (count + R::c(0.5))
        .floor()
        .clamp(R::c(1.0), R::c(SPLAT_LIMIT));
    let columns = -(-n.sqrt()).floor();
    [columns, -(-(n / columns)).floor()]
}

/// The shuffling stride of a splatter over `cells` cells (`veneer_splat_stride`).
pub fn splat_stride(cells: u32) -> u32 {
    let mut stride = ((0.618034f32 * cells as f32) as u32).max(1) | 1;
    for _ in 0..64 {
        let (mut a, mut b) = (stride, cells);
        while b != 0 {
            (a, b) = (b, a % b);
        }
        if a == 1 {
            return stride;
        }
        stride += 2;
    }
    1
}

/// Whole, positive cell counts, at most 4096 per axis (`veneer_tile_counts`).
pub fn counts<R: Real>(counts: [R; 2]) -> [R; 2] {
    counts.map(|n| (n + R::c(0.5)).floor().clamp(R::c(1.0), R::c(4096.0)))
}

/// Degrees to radians as WGSL's `radians`.
fn radians<R: Real>(degrees: R) -> R {
    degrees * R::c(std::f64::consts::PI / 180.0)
}

/// The grid as point `p` (its xz) sees it (`veneer_tile_setup`).
pub fn setup<R: Real>(p: V3<R>, settings: &GridSettings<R>) -> Grid<R> {
    let zero = R::c(0.0);
    let tile = settings.size.map(|s| {
        if s.abs() < R::c(1.0e-20) {
            R::c(1.0)
        } else {
            s.abs()
        }
    });
    let splats = (settings.splat + R::c(0.5))
        .floor()
        .to_f64()
        .clamp(0.0, SPLAT_LIMIT) as u32;
    let n = if splats > 0 {
        splat_counts(settings.splat)
    } else {
        counts(settings.counts)
    };
    let limit = R::c(1.0e30);
    let q = [0, 1].map(|k| (p[2 * k] / tile[k]).clamp(-limit, limit));
    let t = [0, 1].map(|k| q[k].fract() * n[k]);
    let cell = [0, 1].map(|k| tile[k] / n[k]);
    let moved = settings.offsets.map(|o| o.clamp(zero, R::c(1.0)));
    let spread = settings.jitter.clamp(zero, R::c(1.0));
    let size_cells = [0, 1].map(|k| (settings.scale * settings.scale_xy[k]).abs());
    let turns = [
        radians(settings.rotation),
        radians(settings.rotation_random.clamp(zero, R::c(1.0)) * R::c(180.0)),
    ];
    let world = [0, 1].map(|k| size_cells[k] * cell[k]);
    let turned = turns[1] > zero || turns[0] != zero;
    let radius = R::c(0.5) * (world[0] * world[0] + world[1] * world[1]).sqrt();
    let half = [0, 1].map(|k| if turned { radius } else { R::c(0.5) * world[k] } / cell[k]);
    let pixel = settings.footprint / cell[0].min(cell[1]).max(R::c(1.0e-30));
    let seed = (settings.seed.floor().to_f64().clamp(-1.0e9, 1.0e9) as i32) as u32;
    let cells = (n[0] * n[1]).to_f64() as u32;
    Grid {
        t,
        counts: n,
        cell,
        offsets: moved,
        jitter: [spread; 2],
        rotation: turns,
        scale: [
            size_cells[0],
            size_cells[1],
            settings.scale_random.clamp(zero, R::c(1.0)),
        ],
        reach: half.map(|h| h.min(R::c(REACH_CAP))),
        corner: [0, 1].map(|k| q[k].floor() * tile[k]),
        height: p[1],
        seed,
        footprint: pixel,
        splat: splats,
        stride: if splats > 0 { splat_stride(cells) } else { 1 },
        shift: pcg3d([seed, cells, 5])[0] % cells,
    }
}

/// The rows the point must search, inclusive (`veneer_tile_rows`).
pub fn rows<R: Real>(grid: &Grid<R>) -> (i32, i32) {
    let low = grid.t[1] - R::c(0.5) - grid.offsets[1] - grid.reach[1] - grid.jitter[1];
    let high = grid.t[1] - R::c(0.5) + grid.reach[1] + grid.jitter[1];
    (ceil(low), low_floor(high))
}

/// The columns of row `row` the point must search, inclusive (`veneer_tile_columns`).
pub fn columns<R: Real>(grid: &Grid<R>, row: i32) -> (i32, i32) {
    let moved = if row & 1 == 1 {
        grid.offsets[0]
    } else {
        R::c(0.0)
    };
    let centre = grid.t[0] - R::c(0.5) - moved;
    let reach = grid.reach[0] + grid.jitter[0];
    (ceil(centre - reach), low_floor(centre + reach))
}

/// `ceil(x)` as an i32, as WGSL's `i32(ceil(x))`.
fn ceil<R: Real>(x: R) -> i32 {
    -low_floor(-x)
}

/// `floor(x)` as an i32, as WGSL's `i32(floor(x))`.
fn low_floor<R: Real>(x: R) -> i32 {
    x.floor().to_f64() as i32
}

/// An instance as a point sees it (`veneer_placed`).
#[derive(Clone, Copy, Debug)]
pub struct Placed<R> {
    pub instance: Instance<R>,
    /// The centre, in cells, unwrapped (near the point).
    pub centre: [R; 2],
    /// The angle it is turned by, in radians.
    pub angle: R,
    /// Its size in cells along its own axes.
    pub size: [R; 2],
    /// The point in its frame: [-0.5, 0.5]² over its square.
    pub local: [R; 2],
    /// Whether the point is inside its square.
    pub inside: bool,
    /// Random numbers for the instance's height, colour, luminance and keeping.
    pub looks: [R; 4],
}

/// Instance (`column`, `row`) of `grid` as the point sees it (`veneer_tile_place`).
pub fn place<R: Real>(grid: &Grid<R>, column: i32, row: i32) -> Placed<R> {
    let n = grid.counts.map(|n| n.to_f64() as i32);
    let wrapped = [column.rem_euclid(n[0]), row.rem_euclid(n[1])];
    let cell = wrapped.map(|c| c as u32);
    let hash = |k: u32| {
        unit_floats::<R>(pcg3d([
            cell[0],
            cell[1],
            grid.seed.wrapping_mul(4).wrapping_add(k),
        ]))
    };
    let (place, looks, more, own) = (hash(0), hash(1), hash(2), hash(3));
    let one = R::c(1.0);
    let two = R::c(2.0);
    let moved = [
        if row & 1 == 1 {
            grid.offsets[0]
        } else {
            R::c(0.0)
        },
        if column & 1 == 1 {
            grid.offsets[1]
        } else {
            R::c(0.0)
        },
    ];
    let centre = [
        R::c(f64::from(column)) + R::c(0.5) + moved[0] + (place[0] * two - one) * grid.jitter[0],
        R::c(f64::from(row)) + R::c(0.5) + moved[1] + (place[1] * two - one) * grid.jitter[1],
    ];
    let angle = grid.rotation[0] + (place[2] * two - one) * grid.rotation[1];
    let size = [0, 1].map(|k| grid.scale[k] * (one - grid.scale[2] * looks[0]));
    let d = [0, 1].map(|k| (grid.t[k] - centre[k]) * grid.cell[k]);
    let (c, s) = (angle.cos(), angle.sin());
    let turned = [c * d[0] + s * d[1], c * d[1] - s * d[0]];
    let world = [0, 1].map(|k| size[k] * grid.cell[k]);
    let safe = world.map(|w| {
        if w.abs() < R::c(1.0e-30) {
            R::c(1.0e-30)
        } else {
            w
        }
    });
    let local = [turned[0] / safe[0], turned[1] / safe[1]];
    let half = R::c(0.5);
    let inside = local.iter().all(|l| l.abs() <= half) && world.iter().all(|w| *w > R::c(0.0));
    let cells = (n[0] * n[1]) as u32;
    let raw = (wrapped[0] + wrapped[1] * n[0]) as u32;
    let shuffled = (grid.stride.wrapping_mul(raw) % cells + grid.shift) % cells;
    let id = R::c(f64::from(if grid.splat > 0 { shuffled } else { raw }));
    let footprint = grid.footprint / size[0].min(size[1]).max(R::c(1.0e-30));
    Placed {
        instance: Instance {
            cell: wrapped.map(|c| R::c(f64::from(c))),
            id,
            random: own[0],
            randoms: [own[1], own[2], more[2]],
            footprint,
        },
        centre,
        angle,
        size,
        local,
        inside,
        looks: [looks[1], looks[2], more[0], more[1]],
    }
}

/// The position a pattern reads for `placed` (`veneer_tile_surface`): (x, 0, y) of the
/// local point; its uv is the local point plus one half.
pub fn local_position<R: Real>(placed: &Placed<R>) -> V3<R> {
    [placed.local[0], R::c(0.0), placed.local[1]]
}

/// The centre of `placed` where a mask reads it (`veneer_tile_centre`).
pub fn centre_position<R: Real>(grid: &Grid<R>, placed: &Placed<R>) -> V3<R> {
    [
        grid.corner[0] + placed.centre[0] * grid.cell[0],
        grid.height,
        grid.corner[1] + placed.centre[1] * grid.cell[1],
    ]
}

/// How instances accumulate at a point (`veneer_tile_blend_state`).
#[derive(Clone, Copy, Debug)]
pub struct BlendState<R> {
    pub value: R,
    pub mask: R,
    pub decided: R,
    pub winner: Option<Placed<R>>,
}

impl<R: Real> BlendState<R> {
    /// Nothing drawn yet (`veneer_tile_blend_start`).
    pub fn start(mode: TileBlend) -> BlendState<R> {
        let value = R::c(if mode == TileBlend::Min { 1.0 } else { 0.0 });
        BlendState {
            value,
            mask: R::c(0.0),
            decided: value,
            winner: None,
        }
    }

    /// With an instance of pattern value `pattern` and height `height` drawn over it
    /// (`veneer_tile_blend`).
    pub fn blend(&mut self, placed: &Placed<R>, pattern: R, height: R, mode: TileBlend) {
        let value = finite(pattern * height);
        let covers = pattern > R::c(0.0);
        self.mask = self.mask.max(pattern.clamp(R::c(0.0), R::c(1.0)));
        let first = self.winner.is_none();
        let decides = match mode {
            TileBlend::Add => {
                self.value = finite(self.value + value);
                covers && (first || value > self.decided)
            }
            TileBlend::Over => {
                if covers {
                    self.value = value;
                }
                covers
            }
            TileBlend::Min => {
                if covers {
                    self.value = self.value.min(value);
                }
                covers && (first || value < self.decided)
            }
            TileBlend::Max => {
                self.value = self.value.max(value);
                covers && (first || value > self.decided)
            }
        };
        if decides {
            self.decided = value;
            self.winner = Some(*placed);
        }
    }
}

/// The height of `placed` (`veneer_tile_height`).
pub fn height<R: Real>(placed: &Placed<R>, height: R, random: R) -> R {
    height * (R::c(1.0) - random.clamp(R::c(0.0), R::c(1.0)) * placed.looks[0])
}

/// Whether `placed` is kept (`veneer_tile_keeps`).
pub fn keeps<R: Real>(grid: &Grid<R>, placed: &Placed<R>, density: R, mask: R) -> bool {
    let counted = grid.splat == 0 || (placed.instance.id.to_f64() as u32) < grid.splat;
    counted && placed.looks[3] < density * mask
}

/// The colour of `placed` (`veneer_tile_colour`).
pub fn colour<R: Real>(placed: &Placed<R>, low: V3<R>, high: V3<R>, luminance_random: R) -> V3<R> {
    let dark = R::c(1.0) - luminance_random.clamp(R::c(0.0), R::c(1.0)) * placed.looks[2];
    [0, 1, 2].map(|k| finite(R::mix(low[k], high[k], placed.looks[1])) * dark)
}

/// The default pattern (`veneer_tile_dome`).
pub fn dome<R: Real>(local: [R; 2]) -> R {
    (R::c(1.0) - R::c(4.0) * (local[0] * local[0] + local[1] * local[1])).max(R::c(0.0))
}

/// Every instance that can reach the point, in the order drawn (rows, then columns):
/// the search the WGSL loops make.
pub fn search<R: Real>(grid: &Grid<R>, mut visit: impl FnMut(&Placed<R>)) {
    let (first_row, last_row) = rows(grid);
    for row in first_row..=last_row {
        let (first, last) = columns(grid, row);
        for column in first..=last {
            let placed = place(grid, column, row);
            if placed.inside {
                visit(&placed);
            }
        }
    }
}
