//! Safe arithmetic: results stay finite for every finite input.

// `x` clamped to the finite range: a sum or product of finite values is finite or an
// infinity (never NaN), and the clamp turns an infinity into the nearest finite value.
fn veneer_finite_TYPE(x: TYPE) -> TYPE {
    return clamp(x, TYPE(-3.0e38), TYPE(3.0e38));
}

// `a (1 - t) + b t` written out (a GPU's mix may compute a + t (b - a), which overflows
// for far-apart finite values), each product and the sum clamped to the finite range.
fn veneer_mix_TYPE(a: TYPE, b: TYPE, t: f32) -> TYPE {
    return veneer_finite_TYPE(veneer_finite_TYPE(a * (1.0 - t)) + veneer_finite_TYPE(b * t));
}

// The length of `v` for any finite `v`: where its square overflows (past 1e38), the
// length of `v` scaled by 2^-100 and back (exact), clamped to the finite range.
fn veneer_length_TYPE(v: TYPE) -> f32 {
    let scaled = 1.2676506002e30 * length(v * 7.888609052e-31);
    return min(select(length(v), scaled, dot(v, v) > 1.0e38), 3.0e38);
}

// The dot product of `a` and `b` for any finite vectors: each product clamped to
// +-1e38, so that the sum of (at most three of) them cannot overflow.
fn veneer_dot_TYPE(a: TYPE, b: TYPE) -> f32 {
    return dot(clamp(a * b, TYPE(-1.0e38), TYPE(1.0e38)), TYPE(1.0));
}

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

// Clamped linear ramp from edge0 to edge1 (a step at the edge when they are equal). The
// operands are halved first (an exact scaling), so that no difference overflows.
fn veneer_linearstep(edge0: f32, edge1: f32, x: f32) -> f32 {
    let span = 0.5 * edge1 - 0.5 * edge0;
    let t = clamp((0.5 * x - 0.5 * edge0) / select(span, 1.0, span == 0.0), 0.0, 1.0);
    return select(t, step(edge0, x), span == 0.0);
}

// Linear map of x from [from_min, from_max] to [to_min, to_max] (to_min where the source
// range is empty): the linear Map Range without clamping.
fn veneer_remap(x: f32, from_min: f32, from_max: f32, to_min: f32, to_max: f32) -> f32 {
    return veneer_map_range_linear(x, from_min, from_max, to_min, to_max, false);
}

// One segment of a linear colour ramp: blend towards `next` as t goes from p0 to p1.
fn veneer_ramp_linear(current: vec3f, next: vec3f, t: f32, p0: f32, p1: f32) -> vec3f {
    return veneer_mix_vec3f(current, next, veneer_linearstep(p0, p1, t));
}

// One segment of a constant colour ramp: switch to `next` once t reaches p1.
fn veneer_ramp_constant(current: vec3f, next: vec3f, t: f32, p1: f32) -> vec3f {
    return select(current, next, t >= p1);
}
