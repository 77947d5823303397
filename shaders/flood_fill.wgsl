//! Flood fill: the cells of a mask (its 4-connected regions above 0.5) labelled by their
//! bounding boxes. A texel's state is its cell's box as offsets in texels from the
//! texel, (lo x, hi x, lo y, hi y), lows <= 0 <= highs; a texel outside the mask holds
//! vec4f(1.0). Boxes grow by segmented scans along rows and columns in turn (step k
//! merges the boxes 2^k texels away on both sides); once a scan has reached the start
//! of its run of inside texels the low offset carries -0.5, and the high +0.5 at its
//! end. Across the wrap when the buffer wraps (edge 0).

// The seed state of `texel`: an empty box inside the mask (first lane above 0.5).
fn veneer_fill_seed(t: texture_2d<f32>, edge: u32, texel: vec2i) -> vec4f {
    if veneer_buffer_texel(t, edge, texel).x > 0.5 {
        return vec4f(0.0);
    }
    return vec4f(1.0);
}

// The state at `texel`, outside beyond an edge that does not wrap.
fn veneer_fill_load(t: texture_2d<f32>, edge: u32, texel: vec2i) -> vec4f {
    let size = vec2i(textureDimensions(t));
    if edge != 0u && (any(texel < vec2i(0)) || any(texel >= size)) {
        return vec4f(1.0);
    }
    return veneer_buffer_texel(t, edge, texel);
}

// A texel's box along a scan: its extent along the axis, across it, and whether the
// scan has reached its run's start (closed.x) and end (closed.y).
struct veneer_fill_run {
    lo: f32,
    hi: f32,
    across: vec2f,
    closed: vec2<bool>,
}

// The run of a state, its lanes taken along `axis` (0: x, 1: y) first.
fn veneer_fill_decode(state: vec4f, axis: u32) -> veneer_fill_run {
    let s = select(state, state.zwxy, axis == 1u);
    let lo = ceil(s.x);
    let hi = floor(s.y);
    return veneer_fill_run(lo, hi, vec2f(ceil(s.z), floor(s.w)), vec2<bool>((s.x < lo), (s.y > hi)));
}

// The state of a run along `axis`.
fn veneer_fill_encode(run: veneer_fill_run, axis: u32) -> vec4f {
    let lo = run.lo - select(0.0, 0.5, run.closed.x);
    let hi = run.hi + select(0.0, 0.5, run.closed.y);
    let s = vec4f(lo, hi, run.across);
    return select(s, s.zwxy, axis == 1u);
}

// The run `offset` texels from `texel` along `axis`. On step 0 its flags come from its
// neighbours: the run is closed where one is outside.
fn veneer_fill_run_at(t: texture_2d<f32>, edge: u32, texel: vec2i, axis: u32, k: u32, offset: i32) -> veneer_fill_run {
    let direction = select(vec2i(1, 0), vec2i(0, 1), axis == 1u);
    let place = texel + direction * offset;
    var run = veneer_fill_decode(veneer_fill_load(t, edge, place), axis);
    if k == 0u {
        run.closed = vec2<bool>(
            veneer_fill_load(t, edge, place - direction).x > 0.5,
            veneer_fill_load(t, edge, place + direction).x > 0.5,
        );
    }
    return run;
}

// Scan step `k` along `axis` at `texel`: the box grown by the boxes 2^k texels away on
// each side not yet closed. Step 0 drops the previous axis' flags and starts this one.
fn veneer_fill_step(t: texture_2d<f32>, edge: u32, texel: vec2i, axis: u32, k: u32) -> vec4f {
    let here = veneer_fill_load(t, edge, texel);
    let n = i32(textureDimensions(t)[axis]);
    let s = 1 << k;
    if here.x > 0.5 || (k > 0u && s >= n) {
        return here;
    }
    let direction = select(vec2i(1, 0), vec2i(0, 1), axis == 1u);
    var run = veneer_fill_run_at(t, edge, texel, axis, k, 0);
    for (var side = 0; side < 2; side++) {
        if run.closed[side] {
            continue;
        }
        let sign = 2 * side - 1;
        if veneer_fill_load(t, edge, texel + direction * sign * s).x > 0.5 {
            run.closed[side] = true;
            continue;
        }
        let other = veneer_fill_run_at(t, edge, texel, axis, k, sign * s);
        let shift = f32(sign * s);
        run.lo = min(run.lo, other.lo + shift);
        run.hi = max(run.hi, other.hi + shift);
        run.across = vec2f(min(run.across.x, other.across.x), max(run.across.y, other.across.y));
        run.closed[side] = run.closed[side] || other.closed[side];
    }
    if run.hi - run.lo + 1.0 >= f32(n) {
        // The cell reaches all the way round the axis: its box is the whole tile.
        let position = f32(texel[axis]);
        run.lo = -position;
        run.hi = f32(n) - 1.0 - position;
        run.closed = vec2<bool>(true);
    }
    return veneer_fill_encode(run, axis);
}

// What the Flood fill node reads of the cell under a point (zero outside the mask).
struct veneer_flood_fill_result {
    value: f32,
    colour: vec3f,
    uv: vec2f,
    gradient: f32,
    centre: vec2f,
}

// The cell of labelled buffer `t` under domain coordinate `uv`: a random value and
// colour per cell (keyed by its box and `seed`), the point's place in the box (0 to 1),
// a ramp across the box in a random direction per cell, and the box's centre in domain
// units.
fn veneer_flood_fill(t: texture_2d<f32>, edge: u32, uv: vec2f, seed: f32) -> veneer_flood_fill_result {
    let dims = vec2i(textureDimensions(t));
    let size = vec2f(dims);
    let place = veneer_buffer_place(uv, size, edge) + 0.5;
    let base = floor(place);
    let texel = vec2i(base);
    let state = veneer_buffer_texel(t, edge, texel);
    var result: veneer_flood_fill_result;
    if state.x > 0.5 {
        return result;
    }
    let lo = ceil(state.xz);
    let hi = floor(state.yw);
    let extent = hi - lo + 1.0;
    result.uv = (place - base - lo) / extent;
    var corner = vec2i(veneer_edge_index(texel.x, dims.x, edge), veneer_edge_index(texel.y, dims.y, edge)) + vec2i(lo);
    if edge == 0u {
        corner = vec2i(veneer_edge_index(corner.x, dims.x, 0u), veneer_edge_index(corner.y, dims.y, 0u));
    }
    let key = vec3u(bitcast<vec2u>(corner), u32(extent.x) | (u32(extent.y) << 14u));
    let first = veneer_pcg3d(key ^ veneer_cell_bits(vec3f(seed)));
    let random = veneer_unit_floats(first);
    result.value = random.x;
    result.colour = veneer_unit_floats(veneer_pcg3d(first));
    let angle = 6.283185307179586 * random.y;
    let direction = vec2f(cos(angle), sin(angle));
    result.gradient = 0.5 + dot(result.uv - 0.5, direction) / (abs(direction.x) + abs(direction.y));
    result.centre = (vec2f(corner) + 0.5 * extent) / size;
    return result;
}
