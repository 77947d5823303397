//! What the tile sampler and the splatter share: the WGSL loop over the instances that
//! can reach a point and its CPU twin, laid out on a grid of cells or as a number of
//! instances per tile, projected on the xz plane or on three planes blended by the
//! normal (triplanar, for meshes), and the outputs' ranges.

use super::cpu::{Eval, Surface};
use super::emit::{Detail, Emit};
use super::formulas::instances::{self, BlendState, GridSettings, Placed, REACH_CAP, TileBlend};
use super::formulas::real::{Real, V3, finite, splat};
use super::interval::{self, Interval, Lanes};
use super::ranges::Ranges;
use serde::{Deserialize, Serialize};

/// How a sampler lays its instances out.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Layout {
    /// One per cell of `columns` × `rows`, odd rows and columns offset (a tile sampler).
    Grid,
    /// `count` per tile, one per cell of the grid that holds them, the cells left over
    /// chosen at random (a splatter).
    Splat,
}

/// Which planes a sampler places its instances on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum Projection {
    /// The xz plane (flat views, and meshes seen from above).
    Planar,
    /// The three axis planes, blended by the normal: seamless over any mesh.
    Triplanar,
}

impl Projection {
    /// Every projection, in menu order.
    pub const ALL: [Projection; 2] = [Projection::Planar, Projection::Triplanar];
}

/// The planes of a triplanar sampler: the swizzle that puts each plane's coordinates
/// into a point's x and z (its y the height along the plane's normal), named for the
/// normal's axis.
const PLANES: [(&str, [usize; 3]); 3] = [("x", [2, 0, 1]), ("y", [0, 1, 2]), ("z", [0, 2, 1])];

/// The lanes that undo `swizzle`: lane k of the original point is lane `inverse[k]` of
/// the swizzled one (a mask reads the instance's centre where the shaded point lives).
fn inverse(swizzle: [usize; 3]) -> [usize; 3] {
    [0, 1, 2].map(|k| swizzle.iter().position(|&lane| lane == k).unwrap_or(k))
}

/// The identity swizzle (a planar sampler).
const PLANAR: [usize; 3] = [0, 1, 2];

/// Writes a sampler node's WGSL: a loop over the instances reaching the point (three,
/// blended by the normal, when triplanar), each kept instance's pattern called in its
/// frame and blended, then the deciding instance's colour; bound to the node's name as
/// a `veneer_tile_sampled`.
pub fn emit(io: &mut Emit, blend: TileBlend, layout: Layout, projection: Projection) {
    let name = io.name();
    let p = io.input("p").to_string();
    let sampled = match projection {
        Projection::Planar => emit_plane(io, blend, layout, (&p, PLANAR), name),
        Projection::Triplanar => {
            let mut planes = Vec::new();
            for (axis, swizzle) in PLANES {
                let [a, b, c] = swizzle;
                let swizzled = format!("vec3f(({p})[{a}], ({p})[{b}], ({p})[{c}])");
                let prefix = format!("{name}__{axis}");
                let sampled = emit_plane(io, blend, layout, (&swizzled, swizzle), &prefix);
                io.statement(format!("let {prefix} = {sampled};"));
                planes.push(prefix);
            }
            io.uses("veneer_tile_triplanar");
            format!("veneer_tile_triplanar({}, s.normal)", planes.join(", "))
        }
    };
    io.bind("veneer_tile_sampled", sampled);
    io.outputs(
        ["value", "colour", "mask", "id", "random", "local"]
            .map(|member| format!("{name}.{member}"))
            .to_vec(),
    );
}

/// The statements of one plane's loop at point `p` (`swizzle` of the sampler's point;
/// its names prefixed with `prefix`), and the expression of its `veneer_tile_sampled`.
fn emit_plane(
    io: &mut Emit,
    blend: TileBlend,
    layout: Layout,
    (p, swizzle): (&str, [usize; 3]),
    prefix: &str,
) -> String {
    let mode = format!("{}u", blend.code());
    let footprint = match (io.detail, io.instance()) {
        (Detail::Full, _) => "0.0".to_string(),
        (Detail::Footprint, Some(instance)) => format!("{instance}.footprint"),
        (Detail::Footprint, None) => {
            io.uses("veneer_plane_footprint");
            format!("veneer_plane_footprint({p})")
        }
    };
    let (counts, offsets, count) = match layout {
        Layout::Grid => (
            format!("vec2f({}, {})", io.input("columns"), io.input("rows")),
            format!(
                "vec2f({}, {})",
                io.input("row_offset"),
                io.input("column_offset")
            ),
            "0.0".to_string(),
        ),
        Layout::Splat => (
            "vec2f(1.0)".to_string(),
            "vec2f(0.0)".to_string(),
            io.input("count").to_string(),
        ),
    };
    let grid = format!("{prefix}__grid");
    let placed = format!("{prefix}__placed");
    let state = format!("{prefix}__state");
    let (row, column) = (format!("{prefix}__row"), format!("{prefix}__column"));
    let setup = format!(
        "veneer_tile_setup({p}, {}, {counts}, {offsets}, {}, {}, {}, {}, {}, {}, {}, {footprint}, {count})",
        io.input("size"),
        io.input("position_random"),
        io.input("rotation"),
        io.input("rotation_random"),
        io.input("scale"),
        io.input("scale_xy"),
        io.input("scale_random"),
        io.input("seed"),
    );
    let local =
        |function: &str, frame: &str, of: &str| format!("{function}({frame}, {of}.instance)");
    let mask = match io.local("mask") {
        Some(function) => {
            let lanes = inverse(swizzle).map(|k| ["x", "y", "z"][k]).concat();
            let centre = format!("veneer_tile_centre({grid}, {placed}).{lanes}");
            local(
                function,
                &format!("veneer_surface_at(s, {centre})"),
                &placed,
            )
        }
        None => io.input("mask").to_string(),
    };
    let pattern = match io.local("pattern") {
        Some(function) => local(
            function,
            &format!("veneer_tile_surface(s, {placed})"),
            &placed,
        ),
        None => format!("veneer_tile_dome({placed}.local)"),
    };
    let winner = format!("{state}.winner");
    let tint = match io.local("pattern_colour") {
        Some(function) => local(
            function,
            &format!("veneer_tile_surface(s, {winner})"),
            &winner,
        ),
        None => io.input("pattern_colour").to_string(),
    };
    let colour = format!(
        "veneer_finite_vec3f(veneer_tile_colour({winner}, {}, {}, {}) * {tint})",
        io.input("colour_low"),
        io.input("colour_high"),
        io.input("luminance_random"),
    );
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
        "veneer_tile_outputs",
        "veneer_finite_vec3f",
    ] {
        io.uses(item);
    }
    if io.local("mask").is_some() {
        io.uses("veneer_tile_centre");
        io.uses("veneer_surface_at");
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
    for line in [
        format!("let {grid} = {setup};"),
        format!("var {state} = veneer_tile_blend_start({mode});"),
        format!("let {prefix}__rows = veneer_tile_rows({grid});"),
        format!("for (var {row} = {prefix}__rows.x; {row} <= {prefix}__rows.y; {row}++) {{"),
        format!("    let {prefix}__columns = veneer_tile_columns({grid}, {row});"),
        format!(
            "    for (var {column} = {prefix}__columns.x; {column} <= {prefix}__columns.y; {column}++) {{"
        ),
        format!("        let {placed} = veneer_tile_place({grid}, {column}, {row});"),
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
    format!("veneer_tile_outputs({state}, {colour})")
}

/// What a sampler gives at a point (`veneer_tile_sampled`).
#[derive(Clone, Copy, Debug)]
struct Sampled<R> {
    value: R,
    colour: V3<R>,
    mask: R,
    id: R,
    random: R,
    local: [R; 2],
}

/// A sampler node's outputs at one point on the CPU (the WGSL of [`emit`]).
pub fn eval<R: Real>(
    io: &Eval<R>,
    blend: TileBlend,
    layout: Layout,
    projection: Projection,
) -> Vec<V3<R>> {
    let p = io.input("p");
    let sampled = match projection {
        Projection::Planar => eval_plane(io, blend, layout, p, PLANAR),
        Projection::Triplanar => {
            let planes = PLANES
                .map(|(_, swizzle)| eval_plane(io, blend, layout, swizzle.map(|k| p[k]), swizzle));
            triplanar(&planes, io.surface.normal)
        }
    };
    let zero = R::c(0.0);
    vec![
        splat(sampled.value),
        sampled.colour,
        splat(sampled.mask),
        splat(sampled.id),
        splat(sampled.random),
        [sampled.local[0], sampled.local[1], zero],
    ]
}

/// The three planes' samples blended by the normal (`veneer_tile_triplanar`): values,
/// colours and masks weighted by the normal's components to the fourth, the instance
/// outputs of the plane that weighs most.
fn triplanar<R: Real>(planes: &[Sampled<R>; 3], normal: V3<R>) -> Sampled<R> {
    let power = normal.map(|n| {
        let square = n * n;
        square * square
    });
    let total = power[0] + power[1] + power[2];
    let weights = if total > R::c(1.0e-20) {
        power.map(|w| w / total)
    } else {
        [R::c(0.0), R::c(1.0), R::c(0.0)]
    };
    let mix = |lane: &dyn Fn(&Sampled<R>) -> R| {
        (0..3).fold(R::c(0.0), |sum, k| sum + weights[k] * lane(&planes[k]))
    };
    let main = if weights[0] >= weights[1].max(weights[2]) {
        0
    } else if weights[1] >= weights[2] {
        1
    } else {
        2
    };
    Sampled {
        value: mix(&|s| s.value),
        colour: [0, 1, 2].map(|c| mix(&|s| s.colour[c])),
        mask: mix(&|s| s.mask),
        ..planes[main]
    }
}

/// One plane's sample of a sampler at `p` (its xz; `swizzle` of the sampler's point)
/// on the CPU.
fn eval_plane<R: Real>(
    io: &Eval<R>,
    blend: TileBlend,
    layout: Layout,
    p: V3<R>,
    swizzle: [usize; 3],
) -> Sampled<R> {
    let unswizzle = inverse(swizzle);
    let zero = R::c(0.0);
    let (counts, offsets, count) = match layout {
        Layout::Grid => (
            [io.float("columns"), io.float("rows")],
            [io.float("row_offset"), io.float("column_offset")],
            zero,
        ),
        Layout::Splat => ([R::c(1.0); 2], [zero; 2], io.float("count")),
    };
    let settings = GridSettings {
        size: io.pair("size"),
        counts,
        offsets,
        jitter: io.float("position_random"),
        rotation: io.float("rotation"),
        rotation_random: io.float("rotation_random"),
        scale: io.float("scale"),
        scale_xy: io.pair("scale_xy"),
        scale_random: io.float("scale_random"),
        seed: io.float("seed"),
        // The CPU draws every edge in full, as `Detail::Full` does: no footprint.
        footprint: zero,
        splat: count,
    };
    let grid = instances::setup(p, &settings);
    let local_surface = |placed: &Placed<R>| Surface {
        position: instances::local_position(placed),
        uv: [placed.local[0] + R::c(0.5), placed.local[1] + R::c(0.5)],
        ..*io.surface
    };
    let mut state = BlendState::start(blend);
    instances::search(&grid, |placed| {
        let centre = instances::centre_position(&grid, placed);
        let centre = Surface {
            position: unswizzle.map(|k| centre[k]),
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
    match &state.winner {
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
            Sampled {
                value: state.value,
                colour: [0, 1, 2].map(|k| finite(colour[k] * tint[k])),
                mask: state.mask,
                id: winner.instance.id,
                random: winner.instance.random,
                local: winner.local,
            }
        }
        None => Sampled {
            value: state.value,
            colour: [zero; 3],
            mask: state.mask,
            id: zero,
            random: zero,
            local: [zero; 2],
        },
    }
}

/// How many cells a sampler searches per point at most, across and down, and how far its
/// largest instance reaches from its centre, from its constant settings; a sentence for
/// `veneer check`.
pub fn search_report(layout: Layout, constant: &dyn Fn(&str) -> Option<[f64; 3]>) -> String {
    let float = |pin: &str| constant(pin).map(|value| value[0]);
    let pair = |pin: &str| constant(pin).map(|value| [value[0], value[1]]);
    let (counts, offsets, splat) = match layout {
        Layout::Grid => (
            float("columns").zip(float("rows")).map(|(c, r)| [c, r]),
            float("row_offset")
                .zip(float("column_offset"))
                .map(|(r, c)| [r, c]),
            Some(0.0),
        ),
        Layout::Splat => (Some([1.0; 2]), Some([0.0; 2]), float("count")),
    };
    let settings = (|| {
        Some(GridSettings {
            size: pair("size")?,
            counts: counts?,
            offsets: offsets?,
            jitter: float("position_random")?,
            rotation: float("rotation")?,
            rotation_random: float("rotation_random")?,
            scale: float("scale")?,
            scale_xy: pair("scale_xy")?,
            scale_random: float("scale_random")?,
            seed: 0.0,
            footprint: 0.0,
            splat: splat?,
        })
    })();
    let Some(settings) = settings else {
        let most = 2 * REACH_CAP as u32 + 3;
        return format!(
            "its placement is wired, so the cells it searches per point follow the wired values (at most about {most} × {most})"
        );
    };
    let grid = instances::setup([0.0; 3], &settings);
    let across = (2.0 * (grid.reach[0] + grid.jitter[0])).floor() as u32 + 1;
    let down = (2.0 * (grid.reach[1] + grid.jitter[1]) + grid.offsets[1]).floor() as u32 + 1;
    format!(
        "searches at most {across} × {down} cells per point ({} × {} cells per tile; its largest instance reaches {:.2} × {:.2} cells from its centre{})",
        grid.counts[0],
        grid.counts[1],
        grid.reach[0],
        grid.reach[1],
        if grid.reach.iter().any(|r| *r >= REACH_CAP) {
            ", cut at the cap"
        } else {
            ""
        }
    )
}

/// A sampler's output ranges, warning when its instances reach past the cells it
/// searches.
pub fn ranges(io: &mut Ranges, blend: TileBlend) -> Vec<Lanes> {
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
