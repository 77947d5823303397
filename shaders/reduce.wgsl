//! Reductions: the minimum, maximum and sum of a buffer's first lane, in passes. A
//! texel's state is (its value, then the minimum, maximum and sum over a window starting
//! at it). Row steps double the windows along the rows (step k adds the window 2^k
//! texels on, where that lies within the row), so each row's first texel ends with the
//! row's totals; column steps do the same down the first column with those, and texel
//! (0, 0) ends with the buffer's. Pairwise sums, exact in the texel count.

// The seed state of `texel`: its value as a one-texel window's minimum, maximum and sum.
fn veneer_reduce_seed(t: texture_2d<f32>, edge: u32, texel: vec2i) -> vec4f {
    return vec4f(veneer_buffer_texel(t, edge, texel).x);
}

// Reduction step `k` along `axis` (0: rows, 1: columns) at `texel`. Column step 0
// starts from the row totals of the first column.
fn veneer_reduce_step(t: texture_2d<f32>, edge: u32, texel: vec2i, axis: u32, k: u32) -> vec4f {
    let size = vec2i(textureDimensions(t));
    let here = textureLoad(t, texel, 0);
    var window = texel;
    if axis == 1u && k == 0u {
        window.x = 0;
    }
    var state = textureLoad(t, window, 0);
    state.x = here.x;
    var next = window;
    next[axis] += 1 << k;
    if next[axis] < size[axis] {
        let other = textureLoad(t, next, 0);
        state = vec4f(here.x, min(state.y, other.y), max(state.z, other.z), state.w + other.w);
    }
    return state;
}

// The minimum, maximum and mean of reduced buffer `t`'s values.
fn veneer_reduced(t: texture_2d<f32>) -> vec3f {
    let total = textureLoad(t, vec2i(0), 0);
    let size = vec2f(textureDimensions(t));
    return vec3f(total.y, total.z, total.w / (size.x * size.y));
}

// `value` stretched so that the range [low, high] fills [0, 1]: 0.5 where the range is
// empty (a flat input has nothing to stretch).
fn veneer_auto_levels(value: f32, low: f32, high: f32) -> f32 {
    let range = high - low;
    if !(range > 1.0e-30) {
        return 0.5;
    }
    return clamp((value - low) / range, 0.0, 1.0);
}

// Reduced buffer `t` read at domain coordinate `uv`: the value there stretched to the
// buffer's range (`veneer_auto_levels`), then the buffer's minimum, maximum and mean.
fn veneer_levels_read(t: texture_2d<f32>, edge: u32, uv: vec2f) -> vec4f {
    let totals = veneer_reduced(t);
    let value = veneer_buffer_bilinear(t, edge, uv).x;
    return vec4f(veneer_auto_levels(value, totals.x, totals.y), totals);
}
