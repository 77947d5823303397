//! Periodic patterns: sine bands, triangle waves, tiles and rings.

// Marble bands of seed 000: 0.5 + 0.5 sin(frequency x + distortion turbulence).
fn veneer_sine_band(x: f32, frequency: f32, distortion: f32, turbulence: f32) -> f32 {
    return 0.5 + 0.5 * sin(veneer_sine_band_phase(x, frequency, distortion, turbulence));
}

// The sine band's phase, frequency x + distortion turbulence, the products and the sum
// clamped to the finite range.
fn veneer_sine_band_phase(x: f32, frequency: f32, distortion: f32, turbulence: f32) -> f32 {
    return veneer_finite_f32(veneer_finite_f32(frequency * x) + veneer_finite_f32(distortion * turbulence));
}

// 0 -> 1 -> 0 once per period of `x * frequency` (the ring profile of seed 001), the
// product clamped to the finite range.
fn veneer_triangle_wave(x: f32, frequency: f32) -> f32 {
    let r = fract(veneer_finite_f32(x * frequency)) * 2.0;
    return select(r, 2.0 - r, r > 1.0);
}

// Length of tile (not gap) in [0, x] along each axis, for cells whose first `gap` is mortar.
fn veneer_tile_integral(x: vec2f, gap: vec2f) -> vec2f {
    return floor(x) * (1.0 - gap) + max(fract(x) - gap, vec2f(0.0));
}

// Share of [x - width/2, x + width/2] covered by tile: the box-filtered tile mask of
// seed 004, centred on the pixel (seed 004 filters [x, x + width], half a filter off,
// which at joints narrower than a pixel is worse than no filter), faded to the mean
// 1 - gap past Nyquist (a box wider than a tile only ripples about it); a hard step
// where the width is 0.
fn veneer_tile_coverage(x: vec2f, gap: vec2f, width: vec2f) -> vec2f {
    let hard = step(gap, fract(x));
    let half = width * 0.5;
    let soft = (veneer_tile_integral(x + half, gap) - veneer_tile_integral(x - half, gap)) / max(width, vec2f(1.0e-30));
    let band_limited = mix(1.0 - gap, soft, veneer_nyquist_fade_vec2f(width));
    return select(band_limited, hard, width <= vec2f(0.0));
}

struct veneer_tiles_result {
    mask: f32,    // 1 on a tile, 0 in the mortar
    cell: vec2f,  // integer id of the tile
    local: vec2f, // position inside the tile, in [0, 1)
}

// Tiles of `size` over the xz plane; every other row (along x) shifted by `row_offset`
// tiles in z; mortar takes the first `gap` of each tile (clamped to [0, 1]); `blur` is
// the filter width. The position in tiles and the filter width in tiles are clamped to
// +-1e30, so no sum or difference of them overflows.
fn veneer_tiles(p: vec3f, size: vec2f, gap: vec2f, row_offset: f32, blur: f32) -> veneer_tiles_result {
    let safe_size = select(size, vec2f(1.0), abs(size) < vec2f(1.0e-20));
    let limit = vec2f(1.0e30);
    var t = clamp(p.xz / safe_size, -limit, limit);
    t.y += select(0.0, row_offset, fract(t.x * 0.5) > 0.5);
    let width = clamp(vec2f(blur) / abs(safe_size), -limit, limit);
    let coverage = veneer_tile_coverage(t, clamp(gap, vec2f(0.0), vec2f(1.0)), width);
    return veneer_tiles_result(coverage.x * coverage.y, ceil(t), fract(t));
}

// The pixel's extent over the xz plane at `p`: the larger of `fwidth(p)` along x and z
// (seed 004 filters its flagstone joints over it). Fragment stage only.
fn veneer_plane_footprint(p: vec3f) -> f32 {
    let extent = fwidth(p);
    return max(extent.x, extent.z);
}

// Concentric rings about an axis: 0.5 + 0.5 sin(2 pi frequency r).
fn veneer_rings(p: vec3f, origin: vec3f, axis: vec3f, frequency: f32) -> f32 {
    return 0.5 + 0.5 * sin(veneer_rings_phase(p, origin, axis, frequency));
}

// The rings' phase, 2 pi frequency r at distance r from the axis, the products clamped to
// the finite range.
fn veneer_rings_phase(p: vec3f, origin: vec3f, axis: vec3f, frequency: f32) -> f32 {
    let r = veneer_cylindrical(p, origin, axis).y;
    return veneer_finite_f32(veneer_finite_f32(6.283185307 * frequency) * r);
}
