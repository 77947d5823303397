//! Value noise: hashed lattice values, trilinearly interpolated with a smoothstep kernel (seed 000).

// Value noise in [0, 1] with the lattice hash HASH.
fn veneer_noise_value_HASH(point: vec3f) -> f32 {
    let p = veneer_lattice_domain(point);
    let i = floor(p);
    let f = fract(p);
    let u = f * f * (3.0 - 2.0 * f);
    let n000 = veneer_lattice_HASH(i + vec3f(0.0, 0.0, 0.0));
    let n100 = veneer_lattice_HASH(i + vec3f(1.0, 0.0, 0.0));
    let n010 = veneer_lattice_HASH(i + vec3f(0.0, 1.0, 0.0));
    let n110 = veneer_lattice_HASH(i + vec3f(1.0, 1.0, 0.0));
    let n001 = veneer_lattice_HASH(i + vec3f(0.0, 0.0, 1.0));
    let n101 = veneer_lattice_HASH(i + vec3f(1.0, 0.0, 1.0));
    let n011 = veneer_lattice_HASH(i + vec3f(0.0, 1.0, 1.0));
    let n111 = veneer_lattice_HASH(i + vec3f(1.0, 1.0, 1.0));
    let nx00 = mix(n000, n100, u.x);
    let nx10 = mix(n010, n110, u.x);
    let nx01 = mix(n001, n101, u.x);
    let nx11 = mix(n011, n111, u.x);
    let nxy0 = mix(nx00, nx10, u.y);
    let nxy1 = mix(nx01, nx11, u.y);
    return mix(nxy0, nxy1, u.z);
}

// Any basis remapped from [0, 1] to [-1, 1].
fn veneer_noise_BASIS_signed(p: vec3f) -> f32 {
    return 2.0 * veneer_noise_BASIS(p) - 1.0;
}

// Corner `k` (0..8) of a lattice cell: bit 0 is x, bit 1 is y, bit 2 is z.
fn veneer_cell_corner(k: u32) -> vec3f {
    return vec3f(vec3u(k, k >> 1u, k >> 2u) & vec3u(1u));
}

// The eight corner values `n` (in `veneer_cell_corner` order) blended by the weights `u`,
// along x, then y, then z.
fn veneer_trilinear(n: array<f32, 8>, u: vec3f) -> f32 {
    let x00 = mix(n[0], n[1], u.x);
    let x10 = mix(n[2], n[3], u.x);
    let x01 = mix(n[4], n[5], u.x);
    let x11 = mix(n[6], n[7], u.x);
    return mix(mix(x00, x10, u.y), mix(x01, x11, u.y), u.z);
}

// Value noise in [0, 1] with the lattice hash HASH, repeating every `period` cells along
// each axis (the cells hashed are wrapped).
fn veneer_noise_value_HASH_periodic(point: vec3f, period: i32) -> f32 {
    let p = veneer_lattice_periodic(point, period);
    let i = floor(p);
    let f = fract(p);
    var n: array<f32, 8>;
    for (var k = 0u; k < 8u; k++) {
        n[k] = veneer_lattice_HASH(veneer_wrap_cell(i + veneer_cell_corner(k), period));
    }
    return veneer_trilinear(n, f * f * (3.0 - 2.0 * f));
}

// A periodic basis remapped from [0, 1] to [-1, 1].
fn veneer_noise_BASIS_signed_periodic(p: vec3f, period: i32) -> f32 {
    return 2.0 * veneer_noise_BASIS_periodic(p, period) - 1.0;
}
