//! Distance transforms of a mask buffer by jump flooding: seed the texels on one side of
//! the mask, spread the nearest seed in steps of half the buffer, a quarter, … down to
//! one texel (and a few more steps of one, which mend the rare misses), then turn each
//! texel's seed into a distance in domain units. Across the wrap when the buffer wraps.
//! A texel's state is (seed x, seed y, 1 when it has one, 1).

// The seed state of `texel`: where its mask (first lane) crosses 0.5 nearby when the
// texel is on the seeded side (above 0.5; below it when `inside` is 1, which measures
// inside the mask). The crossing is found by the mask's slope, per axis the steeper of
// the two one-sided differences (`veneer_jfa_steeper`): half a texel out on a hard edge, sub-texel exact on a
// smooth one (a blurred or antialiased mask), so distances follow the edge, not its
// staircase of texels. Within one texel of the texel's centre.
fn veneer_jfa_seed(t: texture_2d<f32>, edge: u32, texel: vec2i, inside: u32) -> vec4f {
    let m = veneer_buffer_texel(t, edge, texel).x;
    if (m > 0.5) == (inside == 1u) {
        return vec4f(0.0, 0.0, 0.0, 1.0);
    }
    let x = vec2f(veneer_buffer_texel(t, edge, texel - vec2i(1, 0)).x, veneer_buffer_texel(t, edge, texel + vec2i(1, 0)).x);
    let y = vec2f(veneer_buffer_texel(t, edge, texel - vec2i(0, 1)).x, veneer_buffer_texel(t, edge, texel + vec2i(0, 1)).x);
    let slope = vec2f(veneer_jfa_steeper(m - x.x, x.y - m), veneer_jfa_steeper(m - y.x, y.y - m));
    let squared = dot(slope, slope);
    var offset = vec2f(0.0);
    if squared > 1.0e-12 {
        offset = (0.5 - m) * slope / squared;
        let length = sqrt(dot(offset, offset));
        if length > 1.0 {
            offset /= length;
        }
    }
    return vec4f(vec2f(texel) + offset, 1.0, 1.0);
}

// Of the differences into and out of a texel along an axis, the one of larger magnitude
// (the first on a tie); none at a peak or a valley, where the mask crosses 0.5 on both
// sides (a line one texel wide).
fn veneer_jfa_steeper(a: f32, b: f32) -> f32 {
    if a * b < 0.0 {
        return 0.0;
    }
    return select(a, b, abs(b) > abs(a));
}

// From texel `texel` to place `seed` in texels, the shorter way across the wrap when
// the buffer wraps (edge 0).
fn veneer_jfa_delta(texel: vec2i, seed: vec2f, size: vec2f, edge: u32) -> vec2f {
    var d = seed - vec2f(texel);
    if edge == 0u {
        d -= size * round(d / size);
    }
    return d;
}

// Jump flooding step `k`: the nearest seed among the texel's own and those of its eight
// neighbours `max(size >> (k + 1), 1)` texels away.
fn veneer_jfa_step(t: texture_2d<f32>, edge: u32, texel: vec2i, k: u32) -> vec4f {
    let dims = vec2i(textureDimensions(t));
    let size = vec2f(dims);
    let step = max(dims.x >> (k + 1u), 1);
    var best = veneer_buffer_texel(t, edge, texel);
    var nearest = 3.4e38;
    if best.z > 0.5 {
        let d = veneer_jfa_delta(texel, best.xy, size, edge);
        nearest = dot(d, d);
    }
    for (var k9 = 0; k9 < 9; k9++) {
        let offset = vec2i(k9 % 3 - 1, k9 / 3 - 1) * step;
        let candidate = veneer_buffer_texel(t, edge, texel + offset);
        if candidate.z > 0.5 {
            let d = veneer_jfa_delta(texel, candidate.xy, size, edge);
            let distance = dot(d, d);
            if distance < nearest {
                nearest = distance;
                best = candidate;
            }
        }
    }
    return best;
}

// The distance in domain units from `texel` to its seed, in every lane but the last
// (`far` when the mask has no seed at all).
fn veneer_jfa_distance(t: texture_2d<f32>, edge: u32, texel: vec2i, far: f32) -> vec4f {
    let state = veneer_buffer_texel(t, edge, texel);
    let size = vec2f(textureDimensions(t));
    var distance = far;
    if state.z > 0.5 {
        distance = length(veneer_jfa_delta(texel, state.xy, size, edge) / size);
    }
    return vec4f(vec3f(distance), 1.0);
}

// A bevel's height from the distance `d` inside a mask: rising over `width` domain units
// from the edge, linearly (profile 0), smoothly (1) or as a quarter circle (2).
fn veneer_bevel(d: f32, width: f32, profile: u32) -> f32 {
    let t = clamp(d / max(width, 1.0e-6), 0.0, 1.0);
    if profile == 1u {
        return t * t * (3.0 - 2.0 * t);
    }
    if profile == 2u {
        // 1 - (1 - t)², without the cancellation that loses small t in f32.
        return sqrt(t * (2.0 - t));
    }
    return t;
}
