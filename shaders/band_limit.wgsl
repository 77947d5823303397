//! Band-limited patterns (footprint detail): periodic and thresholding profiles
//! box-filtered analytically over the pixel footprint of the variable they are drawn
//! along, periodic ones fading to their mean past Nyquist. Each `_filtered` function
//! takes the inputs of its unfiltered twin and measures the footprint itself, so it is
//! for the fragment stage only, in uniform control flow. A footprint of 0 gives the
//! unfiltered pattern exactly.

// The pixel footprint of `x`: the width of the box with the spread of x over the pixel,
// sqrt(dpdx^2 + dpdy^2) per lane (a box as wide as the largest derivative alone would
// undercount a diagonal gradient by up to sqrt(2)). Fragment stage only.
fn veneer_footprint_TYPE(x: TYPE) -> TYPE {
    let across = dpdx(x);
    let down = dpdy(x);
    return sqrt(across * across + down * down);
}

// How much of a periodic pattern's variation a box `width` periods wide keeps on top of
// the box filter itself: all of it up to half a period (Nyquist), none from a whole
// period on, where the box holds the mean; smooth in between.
fn veneer_nyquist_fade_TYPE(width: TYPE) -> TYPE {
    return TYPE(1.0) - smoothstep(TYPE(0.5), TYPE(1.0), width);
}

// 0.5 + 0.5 sin(phase) box-filtered over `width` radians of phase: the sine scaled by
// sin(w/2) / (w/2), faded to the mean 0.5 past Nyquist (w >= pi). The scale is its
// Taylor series to the 12th power, within 1e-7 up to Nyquist and 1e-5 at a whole
// period, where the fade has reached 0 (a second sine would cost as much again).
fn veneer_band_limited_sine(phase: f32, width: f32) -> f32 {
    let half = 0.5 * min(abs(width), 6.283185307);
    let h2 = half * half;
    let sinc = 1.0 - h2 / 6.0 * (1.0 - h2 / 20.0 * (1.0 - h2 / 42.0 * (1.0 - h2 / 72.0 * (1.0 - h2 / 110.0 * (1.0 - h2 / 156.0)))));
    return 0.5 + 0.5 * sin(phase) * sinc * veneer_nyquist_fade_f32(half / 3.141592654);
}

// The rounding of a corner at distance `d` from the middle of a box of half-width `h`:
// how far the box's mean of |x - corner| lies above |middle - corner|, (h - d)^2 / (2h)
// while the corner is inside the box, 0 outside it.
fn veneer_corner_rounding(h: f32, d: f32) -> f32 {
    let inside = max(h - d, 0.0);
    return select(inside * inside / (2.0 * h), 0.0, d >= h);
}

// The triangle wave of `t` (0 -> 1 -> 0 each unit, as veneer_triangle_wave)
// box-filtered over `width` units: its value at the middle, raised by the rounding of the
// troughs (at whole t, slope 2 each side) and lowered by that of the peak halfway, faded
// to the mean 0.5 past Nyquist. Up to a whole period wide the box meets at most these
// three corners of the period holding t.
fn veneer_band_limited_triangle(t: f32, width: f32) -> f32 {
    let u = fract(t);
    let h = 0.5 * min(abs(width), 1.0);
    let troughs = veneer_corner_rounding(h, u) + veneer_corner_rounding(h, 1.0 - u);
    let box = 2.0 * min(u, 1.0 - u) + 2.0 * (troughs - veneer_corner_rounding(h, abs(u - 0.5)));
    return mix(0.5, box, veneer_nyquist_fade_f32(2.0 * h));
}

// floor(u) box-filtered over `width` units: floor(u), less the share of the box below
// the step at floor(u), plus the share above the next one; past Nyquist faded to the
// ramp u - 0.5 it averages to.
fn veneer_band_limited_floor(u: f32, width: f32) -> f32 {
    let h = 0.5 * min(abs(width), 1.0);
    let whole = floor(u);
    let f = u - whole;
    let shares = select((max(f + h - 1.0, 0.0) - max(h - f, 0.0)) / (2.0 * h), 0.0, h <= 0.0);
    return mix(u - 0.5, whole + shares, veneer_nyquist_fade_f32(2.0 * h));
}

// Hermite smoothstep rising from edge0 to edge1 (edge0 <= edge1; equal: a step)
// box-filtered over [x - width/2, x + width/2]: the box's shares below, on and above the
// ramp, the ramp's share weighted by the cubic's mean over it (its value at the middle
// of that part plus its second derivative times the half-length squared over 6). Every
// difference is of nearby numbers, so a narrow box loses no precision.
fn veneer_band_limited_rising_smoothstep(edge0: f32, edge1: f32, x: f32, width: f32) -> f32 {
    let h = 0.5 * width;
    let low = x - h;
    let high = x + h;
    let below = clamp((edge0 - low) / width, 0.0, 1.0);
    let above = clamp((high - edge1) / width, 0.0, 1.0);
    let on = max(1.0 - below - above, 0.0);
    let start = max(low, edge0);
    let end = min(high, edge1);
    let half_span = 0.5 * edge1 - 0.5 * edge0;
    let flat = half_span <= 0.0;
    let safe_span = select(half_span, 1.0, flat);
    let t = select(clamp((0.5 * (0.5 * start + 0.5 * end) - 0.5 * edge0) / safe_span, 0.0, 1.0), 0.0, flat);
    let r = select(max(0.5 * end - 0.5 * start, 0.0) / (2.0 * safe_span), 0.0, flat);
    let mean_on = t * t * (3.0 - 2.0 * t) + (1.0 - 2.0 * t) * r * r;
    return select(on * mean_on + above, veneer_smoothstep(edge0, edge1, x), !(width > 0.0));
}

// veneer_smoothstep box-filtered over `width` around x; reversed edges fall.
fn veneer_band_limited_smoothstep(edge0: f32, edge1: f32, x: f32, width: f32) -> f32 {
    let falling = edge0 > edge1;
    let rising = veneer_band_limited_rising_smoothstep(min(edge0, edge1), max(edge0, edge1), x, width);
    return select(rising, 1.0 - rising, falling);
}

// step(edge, x) box-filtered over `width` around x, per lane: the share of the box at or
// above the edge.
fn veneer_band_limited_step_TYPE(edge: f32, x: TYPE, width: TYPE) -> TYPE {
    let share = clamp((x - TYPE(edge)) / max(width, TYPE(1.0e-30)) + TYPE(0.5), TYPE(0.0), TYPE(1.0));
    return select(share, step(TYPE(edge), x), width <= TYPE(0.0));
}

// veneer_sine_band over the pixel footprint of its phase.
fn veneer_sine_band_filtered(x: f32, frequency: f32, distortion: f32, turbulence: f32) -> f32 {
    let phase = veneer_sine_band_phase(x, frequency, distortion, turbulence);
    return veneer_band_limited_sine(phase, veneer_footprint_f32(phase));
}

// veneer_rings over the pixel footprint of their phase.
fn veneer_rings_filtered(p: vec3f, origin: vec3f, axis: vec3f, frequency: f32) -> f32 {
    let phase = veneer_rings_phase(p, origin, axis, frequency);
    return veneer_band_limited_sine(phase, veneer_footprint_f32(phase));
}

// veneer_triangle_wave over the pixel footprint of x * frequency.
fn veneer_triangle_wave_filtered(x: f32, frequency: f32) -> f32 {
    let t = veneer_finite_f32(x * frequency);
    return veneer_band_limited_triangle(t, veneer_footprint_f32(t));
}

// veneer_smoothstep over the pixel footprint of x.
fn veneer_smoothstep_filtered(edge0: f32, edge1: f32, x: f32) -> f32 {
    return veneer_band_limited_smoothstep(edge0, edge1, x, veneer_footprint_f32(x));
}

// step(edge, x) over the pixel footprint of x, per lane.
fn veneer_step_filtered_TYPE(edge: f32, x: TYPE) -> TYPE {
    return veneer_band_limited_step_TYPE(edge, x, veneer_footprint_TYPE(x));
}

// veneer_map_range_stepped with its floor over the pixel footprint of t (steps + 1).
fn veneer_map_range_stepped_filtered(x: f32, from_min: f32, from_max: f32, to_min: f32, to_max: f32, steps: f32, clamp_result: bool) -> f32 {
    let u = clamp(veneer_map_range_factor(x, from_min, from_max) * (steps + 1.0), -3.0e38, 3.0e38);
    let levels = clamp(veneer_band_limited_floor(u, veneer_footprint_f32(u)) / max(steps, 1.0e-30), -3.0e38, 3.0e38);
    return veneer_map_range_to(select(0.0, levels, steps > 0.0), to_min, to_max, clamp_result);
}
