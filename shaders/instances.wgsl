//! Instances placed over a tile (the tile sampler and the splatter): the cells a point
//! must search, each instance's transform and random numbers, the surface its pattern
//! is evaluated at, and how overlapping instances blend. The CPU evaluator's
//! `formulas::instances` is the same arithmetic.

// The instance a local frame is evaluated for (read by the Instance node).
struct veneer_instance {
    cell: vec2f,      // column and row within the tile
    id: f32,          // column + row * columns
    random: f32,      // in [0, 1): stable while the grid grows or the graph changes
    randoms: vec3f,   // three more in [0, 1)
    footprint: f32,   // the pixel's size in local units; 0 when not filtering
}

// One point's view of a grid of instances: the settings every instance shares, the point
// in cell units (wrapped into the tile) and how far an instance can reach.
struct veneer_tile_grid {
    t: vec2f,         // the point, in cells, within [0, counts)
    counts: vec2f,    // columns and rows (whole numbers, at least 1)
    cell: vec2f,      // a cell's size
    offsets: vec2f,   // odd rows move right by offsets.x cells, odd columns up by offsets.y
    jitter: vec2f,    // the most an instance moves from its place, in cells
    rotation: vec2f,  // the base angle and the random span either side, in radians
    scale: vec3f,     // the instance's size in cells (x, y) and how much smaller a random one gets
    reach: vec2f,     // the farthest an instance covers from its centre, in cells (capped)
    corner: vec2f,    // the corner of the tile holding the point, in the point's units
    height: f32,      // the point's y
    seed: u32,
    footprint: f32,   // the pixel's size in cells along its smaller axis
    splat: u32,       // instances per tile (a splatter); 0 for every cell (a tile sampler)
    stride: u32,      // a splatter numbers cell k as (stride * k + shift) % cells: a shuffle
    shift: u32,
}

// The most cells an instance reaches either side of its own along each axis: settings
// asking for more (instances over 16 cells wide) are cut to it, and the check says so.
fn veneer_tile_reach_cap() -> f32 {
    return 8.0;
}

// Whole, positive cell counts from the inputs, at most 4096 per axis.
fn veneer_tile_counts(counts: vec2f) -> vec2f {
    return clamp(floor(counts + 0.5), vec2f(1.0), vec2f(4096.0));
}

// The most instances a splatter places per tile.
fn veneer_splat_limit() -> f32 {
    return 65536.0;
}

// The grid of a splatter of `count` instances: ceil(sqrt(count)) columns and as many
// rows as they need (whole numbers).
fn veneer_splat_counts(count: f32) -> vec2f {
    let n = clamp(floor(count + 0.5), 1.0, veneer_splat_limit());
    let columns = ceil(sqrt(n));
    return vec2f(columns, ceil(n / columns));
}

// The least odd number from 0.618 `cells` up that shares no factor with `cells` (1 if
// none of the first 64 tried does): a stride that visits every cell once, far apart.
fn veneer_splat_stride(cells: u32) -> u32 {
    var stride = max(u32(0.618034 * f32(cells)), 1u) | 1u;
    for (var tried = 0u; tried < 64u; tried++) {
        var a = stride;
        var b = cells;
        while b != 0u {
            let r = a % b;
            a = b;
            b = r;
        }
        if a == 1u {
            return stride;
        }
        stride += 2u;
    }
    return 1u;
}

// The grid as point `p` (its xz) sees it over a tile of `size`: `counts` cells, or for a
// splatter (`splat` above 0) the cells `splat` instances need.
fn veneer_tile_setup(p: vec3f, size: vec2f, counts: vec2f, offsets: vec2f, jitter: f32, rotation: f32, rotation_random: f32, scale: f32, scale_xy: vec2f, scale_random: f32, seed: f32, footprint: f32, splat: f32) -> veneer_tile_grid {
    let tile = select(abs(size), vec2f(1.0), abs(size) < vec2f(1.0e-20));
    let splats = u32(clamp(floor(splat + 0.5), 0.0, veneer_splat_limit()));
    let n = select(veneer_tile_counts(counts), veneer_splat_counts(splat), splats > 0u);
    let limit = vec2f(1.0e30);
    // Wrapped into the tile first: precise at any distance from the origin.
    let q = clamp(p.xz / tile, -limit, limit);
    let t = fract(q) * n;
    let cell = tile / n;
    let moved = clamp(offsets, vec2f(0.0), vec2f(1.0));
    let spread = vec2f(clamp(jitter, 0.0, 1.0));
    let size_cells = abs(vec2f(scale) * scale_xy);
    let turns = radians(vec2f(rotation, clamp(rotation_random, 0.0, 1.0) * 180.0));
    // An instance is its square [-0.5, 0.5]^2 scaled: turned, its corners reach half its
    // diagonal; unturned, half its sides.
    let world = size_cells * cell;
    let turned = turns.y > 0.0 || turns.x != 0.0;
    let half = select(0.5 * world, vec2f(0.5 * length(world)), turned) / cell;
    let reach = min(half, vec2f(veneer_tile_reach_cap()));
    let pixel = footprint / max(min(cell.x, cell.y), 1.0e-30);
    let corner = floor(q) * tile;
    let seed_bits = u32(i32(clamp(floor(seed), -1.0e9, 1.0e9)));
    let cells = u32(n.x * n.y);
    var stride = 1u;
    if splats > 0u {
        stride = veneer_splat_stride(cells);
    }
    let shift = veneer_pcg3d(vec3u(seed_bits, cells, 5u)).x % cells;
    return veneer_tile_grid(t, n, cell, moved, spread, turns, vec3f(size_cells, clamp(scale_random, 0.0, 1.0)), reach, corner, p.y, seed_bits, pixel, splats, stride, shift);
}

// The rows point `grid.t` must search: every row whose instances can reach it (odd
// columns move up by offsets.y).
fn veneer_tile_rows(grid: veneer_tile_grid) -> vec2i {
    let low = grid.t.y - 0.5 - grid.offsets.y - grid.reach.y - grid.jitter.y;
    let high = grid.t.y - 0.5 + grid.reach.y + grid.jitter.y;
    return vec2i(i32(ceil(low)), i32(floor(high)));
}

// The columns of row `row` point `grid.t` must search (odd rows move right by
// offsets.x, so each row has its own).
fn veneer_tile_columns(grid: veneer_tile_grid, row: i32) -> vec2i {
    let moved = select(0.0, grid.offsets.x, (row & 1) == 1);
    let centre = grid.t.x - 0.5 - moved;
    let reach = grid.reach.x + grid.jitter.x;
    return vec2i(i32(ceil(centre - reach)), i32(floor(centre + reach)));
}

// An instance as a point sees it: its identity and random numbers, its centre and the
// point in its frame ([-0.5, 0.5]^2 over its square), and whether the point is inside.
struct veneer_placed {
    instance: veneer_instance,
    centre: vec2f,    // in cells, unwrapped (near the point)
    local: vec2f,
    inside: bool,
    looks: vec4f,     // random numbers for the instance's height, colour, luminance and keeping
}

// Instance (column, row) of `grid` (unwrapped cell coordinates) as point `grid.t` sees it.
fn veneer_tile_place(grid: veneer_tile_grid, column: i32, row: i32) -> veneer_placed {
    let n = vec2i(grid.counts);
    // (Per lane: naga's SPIR-V reader rejects the vector form of its remainder guard.)
    var wrapped = vec2i(column % n.x, row % n.y);
    wrapped = select(wrapped, wrapped + n, wrapped < vec2i(0));
    let cell = bitcast<vec2u>(wrapped);
    let place = veneer_unit_floats(veneer_pcg3d(vec3u(cell, grid.seed * 4u)));
    let looks = veneer_unit_floats(veneer_pcg3d(vec3u(cell, grid.seed * 4u + 1u)));
    let more = veneer_unit_floats(veneer_pcg3d(vec3u(cell, grid.seed * 4u + 2u)));
    let own = veneer_unit_floats(veneer_pcg3d(vec3u(cell, grid.seed * 4u + 3u)));
    let moved = vec2f(select(0.0, grid.offsets.x, (row & 1) == 1), select(0.0, grid.offsets.y, (column & 1) == 1));
    let centre = vec2f(f32(column), f32(row)) + 0.5 + moved + (place.xy * 2.0 - 1.0) * grid.jitter;
    let angle = grid.rotation.x + (place.z * 2.0 - 1.0) * grid.rotation.y;
    let size = grid.scale.xy * (1.0 - grid.scale.z * looks.x);
    // Turned back in world units (cells may not be square), then measured in the
    // instance's size.
    let d = (grid.t - centre) * grid.cell;
    let c = cos(angle);
    let s = sin(angle);
    let turned = vec2f(c * d.x + s * d.y, c * d.y - s * d.x);
    let world = size * grid.cell;
    let safe = select(world, vec2f(1.0e-30), abs(world) < vec2f(1.0e-30));
    let local = turned / safe;
    let inside = max(abs(local.x), abs(local.y)) <= 0.5 && min(world.x, world.y) > 0.0;
    let cells = u32(n.x * n.y);
    let raw = u32(wrapped.x + wrapped.y * n.x);
    let shuffled = ((grid.stride * raw) % cells + grid.shift) % cells;
    let id = f32(select(raw, shuffled, grid.splat > 0u));
    let footprint = grid.footprint / max(min(size.x, size.y), 1.0e-30);
    let instance = veneer_instance(vec2f(wrapped), id, own.x, vec3f(own.yz, more.z), footprint);
    return veneer_placed(instance, centre, local, inside, vec4f(looks.yz, more.xy));
}

// The surface a pattern is evaluated at for `placed`: the point in the instance's frame
// as position (x, 0, y) and as uv (0 to 1 over its square); the rest as shaded.
fn veneer_tile_surface(s: VeneerSurface, placed: veneer_placed) -> VeneerSurface {
    let local = placed.local;
    return VeneerSurface(vec3f(local.x, 0.0, local.y), s.normal, local + 0.5, s.fields, s.time);
}

// The centre of `placed` in the point's coordinates (the grid's `p`, its plane in x
// and z), at the point's height: where a mask is read.
fn veneer_tile_centre(grid: veneer_tile_grid, placed: veneer_placed) -> vec3f {
    let centre = grid.corner + placed.centre * grid.cell;
    return vec3f(centre.x, grid.height, centre.y);
}

// `s` moved to `position`, the rest as shaded.
fn veneer_surface_at(s: VeneerSurface, position: vec3f) -> VeneerSurface {
    return VeneerSurface(position, s.normal, s.uv, s.fields, s.time);
}

// How instances accumulate at a point: the blended value, the coverage, and the instance
// that decided the point (the highest, the lowest, the last drawn).
struct veneer_tile_blend_state {
    value: f32,
    mask: f32,
    decided: f32,     // the deciding instance's own value
    found: bool,
    winner: veneer_placed,
}

// Nothing drawn yet, in blend `mode` (0 max, 1 add, 2 over, 3 min): 1 for min, else 0.
fn veneer_tile_blend_start(mode: u32) -> veneer_tile_blend_state {
    let empty = veneer_placed(veneer_instance(vec2f(0.0), 0.0, 0.0, vec3f(0.0), 0.0), vec2f(0.0), vec2f(0.0), false, vec4f(0.0));
    let value = select(0.0, 1.0, mode == 3u);
    return veneer_tile_blend_state(value, 0.0, value, false, empty);
}

// `state` with an instance of pattern value `pattern` and height `height` drawn over it.
fn veneer_tile_blend(state: veneer_tile_blend_state, placed: veneer_placed, pattern: f32, height: f32, mode: u32) -> veneer_tile_blend_state {
    var next = state;
    let value = veneer_finite_f32(pattern * height);
    let covers = pattern > 0.0;
    next.mask = max(state.mask, clamp(pattern, 0.0, 1.0));
    var decides = false;
    switch mode {
        case 1u: {
            next.value = veneer_finite_f32(state.value + value);
            decides = covers && (!state.found || value > state.decided);
        }
        case 2u: {
            next.value = select(state.value, value, covers);
            decides = covers;
        }
        case 3u: {
            next.value = select(state.value, min(state.value, value), covers);
            decides = covers && (!state.found || value < state.decided);
        }
        default: {
            next.value = max(state.value, value);
            decides = covers && (!state.found || value > state.decided);
        }
    }
    if decides {
        next.decided = value;
        next.found = true;
        next.winner = placed;
    }
    return next;
}

// What a sampler gives at a point: the blended value, the deciding instance's colour,
// the coverage, and the deciding instance's number, random number and local point.
struct veneer_tile_sampled {
    value: f32,
    colour: vec3f,
    mask: f32,
    id: f32,
    random: f32,
    local: vec2f,
}

// The outputs of a sampler that ended in `state`, the deciding instance coloured
// `colour` (black where no instance covers the point).
fn veneer_tile_outputs(state: veneer_tile_blend_state, colour: vec3f) -> veneer_tile_sampled {
    let winner = state.winner;
    return veneer_tile_sampled(state.value, select(vec3f(0.0), colour, state.found), state.mask, winner.instance.id, winner.instance.random, winner.local);
}

// The height of `placed`: `height` less up to `random` of it.
fn veneer_tile_height(placed: veneer_placed, height: f32, random: f32) -> f32 {
    return height * (1.0 - clamp(random, 0.0, 1.0) * placed.looks.x);
}

// Whether `placed` is kept: one of the grid's first `splat` instances (a splatter), and
// its own random number below `density` times the mask at its centre (a mask of 0 keeps
// none, 1 with density 1 keeps all).
fn veneer_tile_keeps(grid: veneer_tile_grid, placed: veneer_placed, density: f32, mask: f32) -> bool {
    let counted = grid.splat == 0u || u32(placed.instance.id) < grid.splat;
    return counted && placed.looks.w < density * mask;
}

// The colour of `placed`: between `low` and `high` at random, darkened by up to
// `luminance_random`.
fn veneer_tile_colour(placed: veneer_placed, low: vec3f, high: vec3f, luminance_random: f32) -> vec3f {
    let tint = veneer_finite_vec3f(mix(low, high, placed.looks.y));
    return tint * (1.0 - clamp(luminance_random, 0.0, 1.0) * placed.looks.z);
}

// The default pattern of an unwired input: a dome, 1 at the centre falling to 0 at the
// circle the square holds.
fn veneer_tile_dome(local: vec2f) -> f32 {
    return max(0.0, 1.0 - 4.0 * dot(local, local));
}

// Three planes' samples blended by the normal: values, colours and masks weighted by the
// normal's components to the fourth, the instance outputs of the plane that weighs most
// (`x` the plane seen along x, and so on).
fn veneer_tile_triplanar(x: veneer_tile_sampled, y: veneer_tile_sampled, z: veneer_tile_sampled, normal: vec3f) -> veneer_tile_sampled {
    let square = normal * normal;
    let power = square * square;
    let total = power.x + power.y + power.z;
    let w = select(vec3f(0.0, 1.0, 0.0), power / max(total, 1.0e-20), total > 1.0e-20);
    var main = z;
    if w.x >= max(w.y, w.z) {
        main = x;
    } else if w.y >= w.z {
        main = y;
    }
    main.value = w.x * x.value + w.y * y.value + w.z * z.value;
    main.colour = w.x * x.colour + w.y * y.colour + w.z * z.colour;
    main.mask = w.x * x.mask + w.y * y.mask + w.z * z.mask;
    return main;
}
