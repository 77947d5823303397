//! Safe arithmetic: results stay finite for every finite input.

// a / b, 0 where b is 0, clamped to the finite f32 range.
fn veneer_safe_div_TYPE(a: TYPE, b: TYPE) -> TYPE {
    let q = select(a / b, TYPE(0.0), b == TYPE(0.0));
    return clamp(q, TYPE(-3.0e38), TYPE(3.0e38));
}

// pow(a, b) for a > 0; 0 where a <= 0 (where pow is undefined), clamped to the finite range.
fn veneer_safe_pow_TYPE(a: TYPE, b: TYPE) -> TYPE {
    let base = max(a, TYPE(1.0e-30));
    return select(min(pow(base, b), TYPE(3.0e38)), TYPE(0.0), a <= TYPE(0.0));
}

// Hermite smoothstep from edge0 to edge1; falls instead of rises when the edges are
// reversed, and is a step at the edge when they are equal.
fn veneer_smoothstep(edge0: f32, edge1: f32, x: f32) -> f32 {
    let t = veneer_linearstep(edge0, edge1, x);
    return t * t * (3.0 - 2.0 * t);
}

// Clamped linear ramp from edge0 to edge1 (a step at the edge when they are equal).
fn veneer_linearstep(edge0: f32, edge1: f32, x: f32) -> f32 {
    let span = edge1 - edge0;
    let t = clamp((x - edge0) / select(span, 1.0, span == 0.0), 0.0, 1.0);
    return select(t, step(edge0, x), span == 0.0);
}

// Linear map of x from [from_min, from_max] to [to_min, to_max].
fn veneer_remap(x: f32, from_min: f32, from_max: f32, to_min: f32, to_max: f32) -> f32 {
    return to_min + veneer_safe_div_f32(x - from_min, from_max - from_min) * (to_max - to_min);
}

// One segment of a linear colour ramp: blend towards `next` as t goes from p0 to p1.
fn veneer_ramp_linear(current: vec3f, next: vec3f, t: f32, p0: f32, p1: f32) -> vec3f {
    return mix(current, next, veneer_linearstep(p0, p1, t));
}

// One segment of a constant colour ramp: switch to `next` once t reaches p1.
fn veneer_ramp_constant(current: vec3f, next: vec3f, t: f32, p1: f32) -> vec3f {
    return select(current, next, t >= p1);
}
