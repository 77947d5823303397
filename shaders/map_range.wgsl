//! Map Range (Blender's node) and Substance's histogram scan. Map Range: x carried from [from_min, from_max] to [to_min, to_max]
//! linearly, in steps, or through smoothstep or smootherstep. Clamping the result to the
//! target range is the `clamp_result` argument of the linear and stepped modes (Blender's
//! Clamp option); the smooth modes stay in the target range by construction. An empty
//! source range (from_min == from_max) maps everything to to_min (Blender gives 0).

// Where x lies from from_min (0) to from_max (1), unclamped; 0 when the range is empty.
// The operands are halved first (an exact scaling) so that no difference overflows, and
// the quotient is clamped to the finite range.
fn veneer_map_range_factor(x: f32, from_min: f32, from_max: f32) -> f32 {
    let span = 0.5 * from_max - 0.5 * from_min;
    let t = (0.5 * x - 0.5 * from_min) / select(span, 1.0, span == 0.0);
    return select(clamp(t, -3.0e38, 3.0e38), 0.0, span == 0.0);
}

// to_min + t (to_max - to_min), halved like the factor, clamped to the finite range; then
// clamped to the target range (either order) when `clamp_result`.
fn veneer_map_range_to(t: f32, to_min: f32, to_max: f32, clamp_result: bool) -> f32 {
    let y = clamp(to_min + t * (0.5 * to_max - 0.5 * to_min) * 2.0, -3.0e38, 3.0e38);
    return select(y, clamp(y, min(to_min, to_max), max(to_min, to_max)), clamp_result);
}

// Linear: to_min + t (to_max - to_min), t = (x - from_min) / (from_max - from_min).
fn veneer_map_range_linear(x: f32, from_min: f32, from_max: f32, to_min: f32, to_max: f32, clamp_result: bool) -> f32 {
    return veneer_map_range_to(veneer_map_range_factor(x, from_min, from_max), to_min, to_max, clamp_result);
}

// Stepped, as Blender: t becomes floor(t (steps + 1)) / steps, so [from_min, from_max)
// takes steps + 1 levels from to_min to to_max (and x = from_max one more, as in
// Blender); to_min everywhere when steps <= 0.
fn veneer_map_range_stepped(x: f32, from_min: f32, from_max: f32, to_min: f32, to_max: f32, steps: f32, clamp_result: bool) -> f32 {
    let t = veneer_map_range_factor(x, from_min, from_max);
    let levels = clamp(floor(t * (steps + 1.0)) / max(steps, 1.0e-30), -3.0e38, 3.0e38);
    return veneer_map_range_to(select(0.0, levels, steps > 0.0), to_min, to_max, clamp_result);
}

// Smooth step: t clamped to [0, 1] through 3t^2 - 2t^3. (Blender's 1 - smoothstep for a
// reversed source range is the same function.)
fn veneer_map_range_smooth(x: f32, from_min: f32, from_max: f32, to_min: f32, to_max: f32) -> f32 {
    let t = clamp(veneer_map_range_factor(x, from_min, from_max), 0.0, 1.0);
    return veneer_map_range_to(t * t * (3.0 - 2.0 * t), to_min, to_max, false);
}

// Smoother step: t clamped to [0, 1] through 6t^5 - 15t^4 + 10t^3 (Perlin's fade).
fn veneer_map_range_smoother(x: f32, from_min: f32, from_max: f32, to_min: f32, to_max: f32) -> f32 {
    let t = clamp(veneer_map_range_factor(x, from_min, from_max), 0.0, 1.0);
    return veneer_map_range_to(t * t * t * (t * (t * 6.0 - 15.0) + 10.0), to_min, to_max, false);
}

// Substance's histogram scan: a ramp from 0 to 1 that is 1 - contrast wide (at least
// 1e-6: a hard threshold at full contrast) sweeps the input's [0, 1] as `position` goes
// from 0 (all black) to 1 (all white); at position 0.5 and contrast 0 the value stays.
fn veneer_histogram_scan(value: f32, position: f32, contrast: f32) -> f32 {
    let width = max(1.0 - clamp(contrast, 0.0, 1.0), 1.0e-6);
    let low = mix(1.0, -width, clamp(position, 0.0, 1.0));
    return clamp((value - low) / width, 0.0, 1.0);
}
