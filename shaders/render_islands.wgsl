//! Filling the texels of a buffer over a mesh's UV layout that no triangle covers with
//! the value of the nearest covered texel, so that blurs and filtered reads at an
//! island's border read the island rather than empty texels. Covered texels are seeds
//! (each holding its own coordinates, -1 elsewhere); jump flooding spreads to every
//! texel the nearest seed it finds; the fill copies that seed's texel.

@group(0) @binding(0) var<uniform> veneer_island_step: vec4i;  // x: the step, in texels
@group(0) @binding(1) var veneer_island_seeds: texture_2d<i32>;
@group(0) @binding(2) var veneer_island_source: texture_2d<f32>;

@vertex
fn veneer_island_seed_vertex(@location(2) uv: vec2f) -> @builtin(position) vec4f {
    return vec4f(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, 0.0, 1.0);
}

@fragment
fn veneer_island_seed_fragment(@builtin(position) pixel: vec4f) -> @location(0) vec4i {
    return vec4i(vec2i(pixel.xy), 0, 0);
}

// The nearest of the seeds found at the texel and its eight neighbours `step` away
// (ties to the first in row order, so every run picks the same).
@fragment
fn veneer_island_jump_fragment(@builtin(position) pixel: vec4f) -> @location(0) vec4i {
    let texel = vec2i(pixel.xy);
    let size = vec2i(textureDimensions(veneer_island_seeds));
    let step = veneer_island_step.x;
    var best = vec2i(-1);
    var best_distance = 0x7fffffff;
    for (var dy = -1; dy <= 1; dy++) {
        for (var dx = -1; dx <= 1; dx++) {
            let at = texel + vec2i(dx, dy) * step;
            if (at.x < 0 || at.y < 0 || at.x >= size.x || at.y >= size.y) {
                continue;
            }
            let seed = textureLoad(veneer_island_seeds, at, 0).xy;
            if (seed.x < 0) {
                continue;
            }
            let d = seed - texel;
            let distance = d.x * d.x + d.y * d.y;
            if (distance < best_distance) {
                best = seed;
                best_distance = distance;
            }
        }
    }
    return vec4i(best, 0, 0);
}

// The source's texel at the nearest seed (0 when the layout covers no texel at all).
@fragment
fn veneer_island_fill_fragment(@builtin(position) pixel: vec4f) -> @location(0) vec4f {
    let seed = textureLoad(veneer_island_seeds, vec2i(pixel.xy), 0).xy;
    if (seed.x < 0) {
        return vec4f(0.0);
    }
    return textureLoad(veneer_island_source, seed, 0);
}
