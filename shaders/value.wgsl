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
