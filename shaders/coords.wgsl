//! Coordinate nodes: transforms, projections, cylindrical coordinates and domain warping.

// Unit vector along `v`; zero (not NaN) when `v` is too short to normalise.
fn veneer_safe_normalize_TYPE(v: TYPE) -> TYPE {
    return select(normalize(v), TYPE(0.0), dot(v, v) < 1.0e-30);
}

// `rotate(p * scale) + offset`, with Euler angles in degrees applied about x, then y, then z.
fn veneer_transform(p: vec3f, scale: vec3f, rotation: vec3f, offset: vec3f) -> vec3f {
    let a = radians(rotation);
    let c = cos(a);
    let s = sin(a);
    var q = p * scale;
    q = vec3f(q.x, c.x * q.y - s.x * q.z, s.x * q.y + c.x * q.z);
    q = vec3f(c.y * q.x + s.y * q.z, q.y, -s.y * q.x + c.y * q.z);
    q = vec3f(c.z * q.x - s.z * q.y, s.z * q.x + c.z * q.y, q.z);
    return q + offset;
}

// Coordinate of `p` along `direction` measured from `origin`.
fn veneer_project(p: vec3f, origin: vec3f, direction: vec3f) -> f32 {
    return dot(p - origin, veneer_safe_normalize_vec3f(direction));
}

// Cylindrical coordinates (t along the axis, radius r, angle theta) of `p` about the
// axis through `origin`. The reference up vector switches to x when the axis is
// within about 18 degrees of y, so the basis never degenerates (seed 000).
fn veneer_cylindrical(p: vec3f, origin: vec3f, axis: vec3f) -> vec3f {
    let d = veneer_safe_normalize_vec3f(axis);
    let up = select(vec3f(0.0, 1.0, 0.0), vec3f(1.0, 0.0, 0.0), abs(d.y) > 0.95);
    let u = veneer_safe_normalize_vec3f(cross(up, d));
    let v = cross(d, u);
    let t = dot(p - origin, d);
    let radial = p - (origin + t * d);
    // On the axis the angle is undefined (WGSL's atan2(0, 0) is), and within 1e-5 of
    // |p - origin| from it the radial vector is rounding noise: call the angle 0 there.
    let across = vec2f(dot(radial, u), dot(radial, v));
    let on_axis = dot(across, across) <= 1.0e-10 * dot(p - origin, p - origin);
    let theta = select(atan2(across.y, across.x), 0.0, on_axis);
    return vec3f(t, length(radial), theta);
}

// `p` displaced by signed noise of the basis in each axis (decorrelated by offsets).
fn veneer_warp_BASIS(p: vec3f, strength: f32, scale: f32) -> vec3f {
    let q = p * scale;
    let w = vec3f(
        veneer_noise_BASIS_signed(q),
        veneer_noise_BASIS_signed(q + vec3f(31.4, 47.2, 12.9)),
        veneer_noise_BASIS_signed(q + vec3f(-23.7, 8.3, 51.1)),
    );
    return p + strength * w;
}
