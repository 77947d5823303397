//! Scatter: the tile sampler, which places a pattern once per cell of a grid, each
//! instance moved, turned, scaled and tinted at random, and the Instance node, through
//! which a placed pattern reads the instance it is drawn for.
//!
//! The pattern is any subgraph: the sampler's `pattern` and `pattern_colour` inputs are
//! re-evaluated (see `graph::frames`), in each instance's frame, and its `mask` at each
//! instance's centre.

use super::cpu::{Eval, Instance as CpuInstance, Surface};
use super::emit::{Detail, Emit};
use super::formulas::instances::{self, BlendState, GridSettings, REACH_CAP, TileBlend};
use super::formulas::real::{Real, V3, finite, splat};
use super::interval::{self, Interval, Lanes};
use super::pins::{COLOR, FLOAT, POINT, PinDefault, Signature, VEC2, f, input, output, rgb, v2};
use super::ranges::Ranges;
use super::settings::{Basis, Setting, choice};
use super::{Catalogue, Category, Configure, Definition, Evaluate};
use serde::{Deserialize, Serialize};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather
            [$($units)* (Instance, scatter)]
            [$($configured)* (TileSampler, scatter)]
            $($rest)*);
    };
}
pub(super) use kinds;

/// What a placed pattern reads of the instance it is drawn for: its cell, number and
/// random numbers. At the shaded point (outside any sampler's pattern) every output is 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Instance;

/// The Instance node's outputs, in order, and the `veneer_instance` members they read.
const INSTANCE_OUTPUTS: [(&str, super::value::ValueType, &str); 4] = [
    ("cell", VEC2, "cell"),
    ("id", FLOAT, "id"),
    ("random", FLOAT, "random"),
    ("randoms", super::pins::VEC3, "randoms"),
];

impl Definition for Instance {
    fn title(&self) -> &'static str {
        "Instance"
    }
    fn category(&self) -> Category {
        Category::Input
    }
    fn keywords(&self) -> &'static [&'static str] {
        &[
            "tile sampler",
            "scatter",
            "random",
            "per instance",
            "id",
            "seed",
        ]
    }
    fn signature(&self) -> Signature {
        let outputs = INSTANCE_OUTPUTS.map(|(name, ty, _)| output(name, ty));
        Signature::new(vec![], outputs.to_vec())
    }
    fn reads_surface(&self) -> bool {
        true
    }
    fn basis(&self) -> Option<Basis> {
        None
    }
    fn check(&self) -> Option<String> {
        None
    }
    fn emit(&self, io: &mut Emit) {
        let outputs = match io.instance() {
            Some(instance) => INSTANCE_OUTPUTS
                .map(|(_, _, member)| format!("{instance}.{member}"))
                .to_vec(),
            None => INSTANCE_OUTPUTS
                .map(|(_, ty, _)| super::emit::lanes_literal(ty, [0.0; 3]))
                .to_vec(),
        };
        io.outputs(outputs);
    }
    fn ranges(&self, _: &mut Ranges) -> Vec<Lanes> {
        let cells = Interval::new(0.0, 4095.0);
        vec![
            [cells, cells, Interval::point(0.0)],
            interval::splat(Interval::new(0.0, 4096.0 * 4096.0 - 1.0)),
            interval::splat(Interval::UNIT),
            interval::splat(Interval::UNIT),
        ]
    }
}

impl Evaluate for Instance {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let instance = io.instance().copied().unwrap_or_else(CpuInstance::none);
        let zero = R::c(0.0);
        vec![
            [instance.cell[0], instance.cell[1], zero],
            splat(instance.id),
            splat(instance.random),
            instance.randoms,
        ]
    }
}

plain_catalogue!(Instance);

/// Places a pattern once per cell of a `columns` × `rows` grid over a tile of `size`
/// (in the xz plane, repeating), each instance moved, turned, scaled, tinted and raised
/// at random and kept where the mask at its centre and the density allow; overlapping
/// instances blend by `blend`. An instance is drawn within its own square, never cut
/// by its cell: the search covers every cell whose instances can reach the point.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct TileSampler {
    pub blend: TileBlend,
}

/// What the sampler's unwired `pattern` draws.
const DOME: &str = "a dome";

impl Definition for TileSampler {
    computed_in!(Category::Pattern, unchecked);
    fn title(&self) -> &'static str {
        "Tile sampler"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &[
            "tiler",
            "scatter",
            "instances",
            "grid",
            "pebbles",
            "scales",
            "rivets",
            "bricks",
            "planks",
            "stamp",
        ]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                POINT,
                input("pattern", FLOAT, PinDefault::Builtin(DOME)).re_evaluated(),
                input("pattern_colour", COLOR, rgb(1.0, 1.0, 1.0))
                    .limits(0.0, 1.0)
                    .re_evaluated(),
                input("mask", FLOAT, f(1.0)).limits(0.0, 1.0).re_evaluated(),
                input("size", VEC2, v2(1.0, 1.0)).soft(0.0, 10.0),
                input("columns", FLOAT, f(8.0))
                    .limits(1.0, 4096.0)
                    .soft(1.0, 64.0),
                input("rows", FLOAT, f(8.0))
                    .limits(1.0, 4096.0)
                    .soft(1.0, 64.0),
                input("row_offset", FLOAT, f(0.0)).limits(0.0, 1.0),
                input("column_offset", FLOAT, f(0.0)).limits(0.0, 1.0),
                input("position_random", FLOAT, f(0.0)).limits(0.0, 1.0),
                input("rotation", FLOAT, f(0.0)).soft(-180.0, 180.0),
                input("rotation_random", FLOAT, f(0.0)).limits(0.0, 1.0),
                input("scale", FLOAT, f(1.0)).soft(0.0, 2.0),
                input("scale_xy", VEC2, v2(1.0, 1.0)).soft(0.0, 2.0),
                input("scale_random", FLOAT, f(0.0)).limits(0.0, 1.0),
                input("height", FLOAT, f(1.0)).soft(0.0, 2.0),
                input("height_random", FLOAT, f(0.0)).limits(0.0, 1.0),
                input("colour_low", COLOR, rgb(1.0, 1.0, 1.0)).limits(0.0, 1.0),
                input("colour_high", COLOR, rgb(1.0, 1.0, 1.0)).limits(0.0, 1.0),
                input("luminance_random", FLOAT, f(0.0)).limits(0.0, 1.0),
                input("density", FLOAT, f(1.0)).limits(0.0, 1.0),
                input("seed", FLOAT, f(0.0)).soft(0.0, 100.0),
            ],
            vec![
                output("height", FLOAT),
                output("colour", COLOR),
                output("mask", FLOAT),
                output("id", FLOAT),
                output("random", FLOAT),
                output("local", VEC2),
            ],
        )
    }
    fn emit(&self, io: &mut Emit) {
        emit_sampler(io, self.blend, 0);
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        sampler_ranges(io, self.blend)
    }
}

/// The WGSL of a sampler over a grid with `per_tile` instances per tile (0: one per cell):
/// a loop over the cells that can reach the point, each kept instance's pattern called
/// in its frame and blended, then the deciding instance's colour.
pub(super) fn emit_sampler(io: &mut Emit, blend: TileBlend, per_tile: u32) {
    let name = io.name();
    let mode = format!("{}u", blend.code());
    let footprint = match (io.detail, io.instance()) {
        (Detail::Full, _) => "0.0".to_string(),
        (Detail::Footprint, Some(instance)) => format!("{instance}.footprint"),
        (Detail::Footprint, None) => {
            io.uses("veneer_plane_footprint");
            format!("veneer_plane_footprint({})", io.input("p"))
        }
    };
    let grid = format!("{name}__grid");
    let placed = format!("{name}__placed");
    let setup = format!(
        "veneer_tile_setup({}, {}, vec2f({}, {}), vec2f({}, {}), {}, {}, {}, {}, {}, {}, {}, {footprint}, {per_tile}u)",
        io.input("p"),
        io.input("size"),
        io.input("columns"),
        io.input("rows"),
        io.input("row_offset"),
        io.input("column_offset"),
        io.input("position_random"),
        io.input("rotation"),
        io.input("rotation_random"),
        io.input("scale"),
        io.input("scale_xy"),
        io.input("scale_random"),
        io.input("seed"),
    );
    let mask = match io.local("mask") {
        Some(function) => format!(
            "{function}(veneer_tile_centre_surface(s, {grid}, {placed}), {placed}.instance)"
        ),
        None => io.input("mask").to_string(),
    };
    let pattern = match io.local("pattern") {
        Some(function) => {
            format!("{function}(veneer_tile_surface(s, {placed}), {placed}.instance)")
        }
        None => format!("veneer_tile_dome({placed}.local)"),
    };
    for item in [
        "veneer_tile_setup",
        "veneer_tile_rows",
        "veneer_tile_columns",
        "veneer_tile_place",
        "veneer_tile_keeps",
        "veneer_tile_blend_start",
        "veneer_tile_blend",
        "veneer_tile_height",
        "veneer_tile_colour",
    ] {
        io.uses(item);
    }
    if io.local("mask").is_some() {
        io.uses("veneer_tile_centre_surface");
    }
    if io.local("pattern").is_some() || io.local("pattern_colour").is_some() {
        io.uses("veneer_tile_surface");
    }
    if io.local("pattern").is_none() {
        io.uses("veneer_tile_dome");
    }
    let (density, height, height_random) = (
        io.input("density"),
        io.input("height"),
        io.input("height_random"),
    );
    let state = format!("{name}__state");
    let winner = format!("{state}.winner");
    let tint = match io.local("pattern_colour") {
        Some(function) => {
            format!("{function}(veneer_tile_surface(s, {winner}), {winner}.instance)")
        }
        None => io.input("pattern_colour").to_string(),
    };
    io.uses("veneer_finite_vec3f");
    let colour = format!(
        "veneer_finite_vec3f(veneer_tile_colour({winner}, {}, {}, {}) * {tint})",
        io.input("colour_low"),
        io.input("colour_high"),
        io.input("luminance_random"),
    );
    io.uses("veneer_tile_outputs");
    for line in [
        format!("let {grid} = {setup};"),
        format!("var {state} = veneer_tile_blend_start({mode});"),
        format!("let {name}__rows = veneer_tile_rows({grid});"),
        format!(
            "for (var {name}__row = {name}__rows.x; {name}__row <= {name}__rows.y; {name}__row++) {{"
        ),
        format!("    let {name}__columns = veneer_tile_columns({grid}, {name}__row);"),
        format!(
            "    for (var {name}__column = {name}__columns.x; {name}__column <= {name}__columns.y; {name}__column++) {{"
        ),
        format!("        let {placed} = veneer_tile_place({grid}, {name}__column, {name}__row);"),
        format!(
            "        if {placed}.inside && veneer_tile_keeps({grid}, {placed}, {density}, {mask}) {{"
        ),
        format!(
            "            {state} = veneer_tile_blend({state}, {placed}, {pattern}, veneer_tile_height({placed}, {height}, {height_random}), {mode});"
        ),
        "        }".to_string(),
        "    }".to_string(),
        "}".to_string(),
    ] {
        io.statement(line);
    }
    io.bind(
        "veneer_tile_sampled",
        format!("veneer_tile_outputs({state}, {colour})"),
    );
    io.outputs(
        ["value", "colour", "mask", "id", "random", "local"]
            .map(|member| format!("{name}.{member}"))
            .to_vec(),
    );
}

/// The sampler's outputs at one point on the CPU (the WGSL of [`emit_sampler`]).
pub(super) fn eval_sampler<R: Real>(io: &Eval<R>, blend: TileBlend, per_tile: u32) -> Vec<V3<R>> {
    let two = |pin: &str| {
        let value = io.input(pin);
        [value[0], value[1]]
    };
    let settings = GridSettings {
        size: two("size"),
        counts: [io.float("columns"), io.float("rows")],
        offsets: [io.float("row_offset"), io.float("column_offset")],
        jitter: io.float("position_random"),
        rotation: io.float("rotation"),
        rotation_random: io.float("rotation_random"),
        scale: io.float("scale"),
        scale_xy: two("scale_xy"),
        scale_random: io.float("scale_random"),
        seed: io.float("seed"),
        // The CPU draws every edge in full, as `Detail::Full` does: no footprint.
        footprint: R::c(0.0),
        splat: per_tile,
    };
    let grid = instances::setup(io.input("p"), &settings);
    let local_surface = |placed: &instances::Placed<R>| Surface {
        position: instances::local_position(placed),
        uv: [placed.local[0] + R::c(0.5), placed.local[1] + R::c(0.5)],
        ..*io.surface
    };
    let mut state = BlendState::start(blend);
    instances::search(&grid, |placed| {
        let centre = Surface {
            position: instances::centre_position(&grid, placed),
            ..*io.surface
        };
        let mask = (io.reevaluate("mask", &centre, &placed.instance))
            .map_or(io.float("mask"), |value| value[0]);
        if !instances::keeps(&grid, placed, io.float("density"), mask) {
            return;
        }
        let pattern = match io.reevaluate("pattern", &local_surface(placed), &placed.instance) {
            Some(value) => value[0],
            None => instances::dome(placed.local),
        };
        let height = instances::height(placed, io.float("height"), io.float("height_random"));
        state.blend(placed, pattern, height, blend);
    });
    let zero = R::c(0.0);
    let (colour, id, random, local) = match &state.winner {
        Some(winner) => {
            let tint = io
                .reevaluate("pattern_colour", &local_surface(winner), &winner.instance)
                .unwrap_or(io.input("pattern_colour"));
            let colour = instances::colour(
                winner,
                io.input("colour_low"),
                io.input("colour_high"),
                io.float("luminance_random"),
            );
            (
                [0, 1, 2].map(|k| finite(colour[k] * tint[k])),
                winner.instance.id,
                winner.instance.random,
                winner.local,
            )
        }
        None => ([zero; 3], zero, zero, [zero; 2]),
    };
    vec![
        splat(state.value),
        colour,
        splat(state.mask),
        splat(id),
        splat(random),
        [local[0], local[1], zero],
    ]
}

/// The sampler's output ranges, warning when its instances reach past the cells it
/// searches.
pub(super) fn sampler_ranges(io: &mut Ranges, blend: TileBlend) -> Vec<Lanes> {
    let scale = io.float("scale").magnitude();
    let scale_xy = interval::max_length(&io.input("scale_xy"), 2);
    // Half the diagonal of the largest instance, in cells (square cells).
    let reach = 0.5 * scale * scale_xy;
    if reach > REACH_CAP {
        io.warn(format!(
            "instances up to {:.1} cells across are cut to {} cells (the most the search reaches either side)",
            2.0 * reach,
            2.0 * REACH_CAP
        ));
    }
    let pattern = match io.input("pattern")[0] {
        wired if wired != Interval::point(0.0) => wired,
        _ => Interval::UNIT,
    };
    let height = io.float("height").hull(Interval::point(0.0));
    let value = pattern.mul(height);
    let searched = {
        let side = 2.0 * (reach.min(REACH_CAP) + 1.0) + 1.0;
        side * side
    };
    let result = match blend {
        TileBlend::Max | TileBlend::Over => value.hull(Interval::point(0.0)),
        TileBlend::Add => value.mul(Interval::new(0.0, searched)),
        TileBlend::Min => value.hull(Interval::point(1.0)),
    };
    let colours = [io.input("colour_low"), io.input("colour_high")];
    let tint = io.input("pattern_colour");
    let colour: Lanes = [0, 1, 2].map(|k| {
        colours[0][k]
            .hull(colours[1][k])
            .mul(tint[k])
            .hull(Interval::point(0.0))
    });
    vec![
        interval::splat(result),
        colour,
        interval::splat(Interval::UNIT),
        interval::splat(Interval::new(0.0, 4096.0 * 4096.0 - 1.0)),
        interval::splat(Interval::UNIT),
        interval::splat(Interval::new(-0.5, 0.5)),
    ]
}

impl Evaluate for TileSampler {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        eval_sampler(io, self.blend, 0)
    }
}

impl Configure for TileSampler {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        vec![choice("blend", &mut self.blend, &TileBlend::ALL)]
    }
}

impl Catalogue for TileSampler {
    fn menu() -> Vec<(String, Self)> {
        vec![(
            "Tile sampler".into(),
            TileSampler {
                blend: TileBlend::Max,
            },
        )]
    }
    fn examples() -> Vec<Self> {
        TileBlend::ALL
            .into_iter()
            .map(|blend| TileSampler { blend })
            .collect()
    }
}
