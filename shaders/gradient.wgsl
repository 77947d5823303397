//! Improved Perlin gradient noise with PCG-hashed gradients.

// Dot product of the hashed edge gradient of `cell` with the offset `d` (Perlin 2002's 12 edges).
fn veneer_gradient_dot(cell: vec3f, d: vec3f) -> f32 {
    let h = veneer_pcg3d(veneer_cell_bits(cell)).x & 15u;
    let u = select(d.y, d.x, h < 8u);
    let v = select(select(d.z, d.x, h == 12u || h == 14u), d.y, h < 4u);
    return select(-u, u, (h & 1u) == 0u) + select(-v, v, (h & 2u) == 0u);
}

// Gradient noise remapped to [0, 1].
fn veneer_noise_gradient(point: vec3f) -> f32 {
    let p = veneer_lattice_domain(point);
    let i = floor(p);
    let f = p - i;
    let u = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
    let n000 = veneer_gradient_dot(i + vec3f(0.0, 0.0, 0.0), f - vec3f(0.0, 0.0, 0.0));
    let n100 = veneer_gradient_dot(i + vec3f(1.0, 0.0, 0.0), f - vec3f(1.0, 0.0, 0.0));
    let n010 = veneer_gradient_dot(i + vec3f(0.0, 1.0, 0.0), f - vec3f(0.0, 1.0, 0.0));
    let n110 = veneer_gradient_dot(i + vec3f(1.0, 1.0, 0.0), f - vec3f(1.0, 1.0, 0.0));
    let n001 = veneer_gradient_dot(i + vec3f(0.0, 0.0, 1.0), f - vec3f(0.0, 0.0, 1.0));
    let n101 = veneer_gradient_dot(i + vec3f(1.0, 0.0, 1.0), f - vec3f(1.0, 0.0, 1.0));
    let n011 = veneer_gradient_dot(i + vec3f(0.0, 1.0, 1.0), f - vec3f(0.0, 1.0, 1.0));
    let n111 = veneer_gradient_dot(i + vec3f(1.0, 1.0, 1.0), f - vec3f(1.0, 1.0, 1.0));
    let nx00 = mix(n000, n100, u.x);
    let nx10 = mix(n010, n110, u.x);
    let nx01 = mix(n001, n101, u.x);
    let nx11 = mix(n011, n111, u.x);
    let n = mix(mix(nx00, nx10, u.y), mix(nx01, nx11, u.y), u.z);
    return 0.5 + 0.5 * clamp(n, -1.0, 1.0);
}

// Gradient noise in [0, 1] repeating every `period` cells along each axis (the cells
// whose gradients are hashed are wrapped).
fn veneer_noise_gradient_periodic(point: vec3f, period: i32) -> f32 {
    let p = veneer_lattice_periodic(point, period);
    let i = floor(p);
    let f = p - i;
    var n: array<f32, 8>;
    for (var k = 0u; k < 8u; k++) {
        let corner = veneer_cell_corner(k);
        n[k] = veneer_gradient_dot(veneer_wrap_cell(i + corner, period), f - corner);
    }
    let u = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
    return 0.5 + 0.5 * clamp(veneer_trilinear(n, u), -1.0, 1.0);
}
