//! Hashes from lattice cells to pseudo-random numbers.

// The sine hash of seed 000: cheap, but its value depends on the GPU's sin and it
// loses all randomness once dot(p, k) is large (see `veneer report`).
fn veneer_lattice_sine(cell: vec3f) -> f32 {
    let h = dot(cell, vec3f(127.1, 311.7, 74.7));
    return fract(sin(h) * 43758.5453);
}

// `p` within the lattice's range (+-2147483520 per axis, where the cells' integer
// coordinates saturate anyway): every lattice noise samples its point through this, so
// any coordinate (an overflowed product too) gives a finite value.
fn veneer_lattice_domain(p: vec3f) -> vec3f {
    let limit = vec3f(2147483520.0);
    return clamp(p, -limit, limit);
}

// Integer coordinates of a lattice cell, clamped to the i32 range so that any finite
// coordinate maps to a well-defined cell on every device.
fn veneer_cell_bits(cell: vec3f) -> vec3u {
    let limit = vec3f(2147483520.0);
    return bitcast<vec3u>(vec3i(clamp(cell, -limit, limit)));
}

// PCG3D (Jarzynski and Olano 2020): three rounds of an LCG mixed across lanes.
fn veneer_pcg3d(seed: vec3u) -> vec3u {
    var v = seed * 1664525u + 1013904223u;
    v.x += v.y * v.z;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v ^= v >> vec3u(16u);
    v.x += v.y * v.z;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    return v;
}

// Top 24 bits of each lane as floats in [0, 1): exact, so CPU and GPU agree bit for bit.
fn veneer_unit_floats(bits: vec3u) -> vec3f {
    return vec3f(bits >> vec3u(8u)) * (1.0 / 16777216.0);
}

// The PCG hash of a lattice cell, in [0, 1).
fn veneer_lattice_pcg(cell: vec3f) -> f32 {
    return veneer_unit_floats(veneer_pcg3d(veneer_cell_bits(cell))).x;
}

// `p` within the lattice's range and moved by whole periods into [0, period) per axis
// (up to rounding): a periodic noise samples its point through this, so its cells stay
// small whatever the coordinate, and the cell wrap below is exact.
fn veneer_lattice_periodic(point: vec3f, period: i32) -> vec3f {
    let p = veneer_lattice_domain(point);
    let span = f32(period);
    return p - span * floor(p / span);
}

// A lattice cell wrapped into [0, period) per axis: noise hashing the wrapped cells
// repeats every `period` cells along x, y and z. In floats, exact for the whole-number
// cells near the origin that `veneer_lattice_periodic` leaves (integer vector remainders
// do not survive every back-end).
fn veneer_wrap_cell(cell: vec3f, period: i32) -> vec3f {
    let span = f32(period);
    return cell - span * floor(cell / span);
}
