//! Coordinate nodes: transforms, projections, cylindrical coordinates and domain warping.

// Unit vector along `v`; zero (not NaN) when `v` is too short to normalise. A vector
// whose square overflows (past 1e38) is scaled by 2^-100 first (exact).
fn veneer_safe_normalize_TYPE(v: TYPE) -> TYPE {
    let squared = dot(v, v);
    let unit = normalize(select(v, v * 7.888609052e-31, squared > 1.0e38));
    return select(unit, TYPE(0.0), squared < 1.0e-30);
}

// `p * scale` clamped to +-1e38: a rotation of it (which keeps its length, at most
// sqrt(3) times that) and each step of the rotation stay finite.
fn veneer_scaled(p: vec3f, scale: vec3f) -> vec3f {
    return clamp(p * scale, vec3f(-1.0e38), vec3f(1.0e38));
}

// `p * scale + offset` (a transform without rotation), clamped like `veneer_transform`.
fn veneer_scale_offset(p: vec3f, scale: vec3f, offset: vec3f) -> vec3f {
    return veneer_finite_vec3f(veneer_scaled(p, scale) + offset);
}

// `rotate(p * scale) + offset`, with Euler angles in degrees applied about x, then y, then
// z; the scaled point clamped to +-1e38 and the result to the finite range.
fn veneer_transform(p: vec3f, scale: vec3f, rotation: vec3f, offset: vec3f) -> vec3f {
    let a = radians(rotation);
    let c = cos(a);
    let s = sin(a);
    var q = veneer_scaled(p, scale);
    q = vec3f(q.x, c.x * q.y - s.x * q.z, s.x * q.y + c.x * q.z);
    q = vec3f(c.y * q.x + s.y * q.z, q.y, -s.y * q.x + c.y * q.z);
    q = vec3f(c.z * q.x - s.z * q.y, s.z * q.x + c.z * q.y, q.z);
    return veneer_finite_vec3f(q + offset);
}

// Half of `p - origin` (an exact scaling, so it cannot overflow), scaled down by a further
// 2^-100 (exact) where it is too long to square, and the factor that undoes the scaling.
fn veneer_half_offset(p: vec3f, origin: vec3f) -> vec4f {
    let half = 0.5 * p - 0.5 * origin;
    let far = dot(half, half) > 1.0e36;
    return vec4f(select(half, half * 7.888609052e-31, far), select(2.0, 2.5353012004e30, far));
}

// Coordinate of `p` along `direction` measured from `origin`, clamped to the finite range.
fn veneer_project(p: vec3f, origin: vec3f, direction: vec3f) -> f32 {
    let half = veneer_half_offset(p, origin);
    return veneer_finite_f32(half.w * dot(half.xyz, veneer_safe_normalize_vec3f(direction)));
}

// Cylindrical coordinates (t along the axis, radius r, angle theta) of `p` about the
// axis through `origin`, t and r clamped to the finite range. The reference up vector
// switches to x when the axis is within about 18 degrees of y, so the basis never
// degenerates (seed 000). Computed on half of `p - origin` (see `veneer_half_offset`).
fn veneer_cylindrical(p: vec3f, origin: vec3f, axis: vec3f) -> vec3f {
    let d = veneer_safe_normalize_vec3f(axis);
    let up = select(vec3f(0.0, 1.0, 0.0), vec3f(1.0, 0.0, 0.0), abs(d.y) > 0.95);
    let u = veneer_safe_normalize_vec3f(cross(up, d));
    let v = cross(d, u);
    let half = veneer_half_offset(p, origin);
    let relative = half.xyz;
    let t = dot(relative, d);
    let radial = relative - t * d;
    // On the axis the angle is undefined (WGSL's atan2(0, 0) is), and within 1e-5 of
    // |p - origin| from it the radial vector is rounding noise: call the angle 0 there.
    let across = vec2f(dot(radial, u), dot(radial, v));
    let on_axis = dot(across, across) <= 1.0e-10 * dot(relative, relative);
    let theta = select(atan2(across.y, across.x), 0.0, on_axis);
    return vec3f(veneer_finite_vec2f(half.w * vec2f(t, length(radial))), theta);
}

// `p` displaced by signed noise of the basis in each axis (decorrelated by offsets).
fn veneer_warp_BASIS(p: vec3f, strength: f32, scale: f32) -> vec3f {
    let q = p * scale;
    let w = vec3f(
        veneer_noise_BASIS_signed(q),
        veneer_noise_BASIS_signed(q + vec3f(31.4, 47.2, 12.9)),
        veneer_noise_BASIS_signed(q + vec3f(-23.7, 8.3, 51.1)),
    );
    return veneer_finite_vec3f(p + strength * w);
}

// `veneer_warp_BASIS` by noise repeating every `period` cells (at `p * scale`), so a
// periodic pattern sampled at the warped point still repeats.
fn veneer_warp_BASIS_periodic(p: vec3f, strength: f32, scale: f32, period: i32) -> vec3f {
    let q = p * scale;
    let offsets = array(vec3f(0.0), vec3f(31.4, 47.2, 12.9), vec3f(-23.7, 8.3, 51.1));
    var w = vec3f(0.0);
    for (var axis = 0; axis < 3; axis++) {
        w[axis] = veneer_noise_BASIS_signed_periodic(q + offsets[axis], period);
    }
    return veneer_finite_vec3f(p + strength * w);
}
