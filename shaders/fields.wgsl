//! Materials driven by geodesic distance fields (seed 003): propagation fronts, nested
//! layers, isolines, and bump reliefs of noise.

// How much of the surface a material spreading from the sources covers: 1 near them,
// falling smoothly to 0 where `distance + noise` passes the threshold; the fall is
// centred `centre` widths past the threshold and spans `softness` widths either side
// (seed 003's smoothstep fronts: §5.2.4 is centre 1, softness 1/2; C.4 and C.5 are
// centre 0, softness 1); a hard edge at width 0. The edges and the sum are clamped to the
// finite range.
fn veneer_front(distance: f32, threshold: f32, width: f32, noise: f32, centre: f32, softness: f32) -> f32 {
    let w = max(width, 0.0);
    let s = max(softness, 0.0);
    let low = veneer_finite_f32(threshold + veneer_finite_f32(centre - s) * w);
    let high = veneer_finite_f32(threshold + veneer_finite_f32(centre + s) * w);
    return 1.0 - veneer_smoothstep(low, high, veneer_finite_f32(distance + noise));
}

// 1 on the lines where `value` is a multiple of `spacing`, falling to 0 at `width` from
// them (in the value's units); no lines when the spacing or the width is 0. The value in
// periods is clamped to the finite range.
fn veneer_isolines(value: f32, spacing: f32, width: f32) -> f32 {
    let period = max(spacing, 1.0e-30);
    let offset = abs(fract(veneer_finite_f32(value / period) + 0.5) - 0.5) * period;
    let line = 1.0 - veneer_smoothstep(0.0, max(width, 0.0), offset);
    return select(line, 0.0, spacing <= 0.0 || width <= 0.0);
}

// A relief of basis noise at `p * scale` as a bump: minus `strength` times the noise
// gradient per noise cell (central differences a hundredth of a cell apart), clamped to
// the finite range.
fn veneer_noise_bump_BASIS(p: vec3f, scale: f32, strength: f32) -> vec3f {
    let q = p * scale;
    let h = 0.01;
    let gradient = vec3f(
        veneer_noise_BASIS(q + vec3f(h, 0.0, 0.0)) - veneer_noise_BASIS(q - vec3f(h, 0.0, 0.0)),
        veneer_noise_BASIS(q + vec3f(0.0, h, 0.0)) - veneer_noise_BASIS(q - vec3f(0.0, h, 0.0)),
        veneer_noise_BASIS(q + vec3f(0.0, 0.0, h)) - veneer_noise_BASIS(q - vec3f(0.0, 0.0, h)),
    ) / (2.0 * h);
    return veneer_finite_vec3f(-strength * gradient);
}

// `veneer_noise_bump_BASIS` of the noise repeating every `period` cells: the gradient of
// `veneer_noise_BASIS_periodic`, one axis at a time.
fn veneer_noise_bump_BASIS_periodic(p: vec3f, scale: f32, strength: f32, period: i32) -> vec3f {
    let q = p * scale;
    let h = 0.01;
    var gradient = vec3f(0.0);
    for (var axis = 0; axis < 3; axis++) {
        var step = vec3f(0.0);
        step[axis] = h;
        let rise = veneer_noise_BASIS_periodic(q + step, period) - veneer_noise_BASIS_periodic(q - step, period);
        gradient[axis] = rise / (2.0 * h);
    }
    return veneer_finite_vec3f(-strength * gradient);
}
