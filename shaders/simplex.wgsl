//! 3D simplex noise (Perlin 2001, after Gustavson's formulation) with PCG-hashed gradients.

// Contribution of one simplex corner at offset `d` from the point.
fn veneer_simplex_corner(cell: vec3f, d: vec3f) -> f32 {
    let falloff = max(0.6 - dot(d, d), 0.0);
    let f2 = falloff * falloff;
    return f2 * f2 * veneer_gradient_dot(cell, d);
}

// Simplex noise remapped to [0, 1].
fn veneer_noise_simplex(point: vec3f) -> f32 {
    let p = veneer_lattice_domain(point);
    let skew = (p.x + p.y + p.z) * (1.0 / 3.0);
    let i = floor(p + skew);
    let unskew = (i.x + i.y + i.z) * (1.0 / 6.0);
    let x0 = p - (i - unskew);
    let g = step(x0.yzx, x0.xyz);
    let l = 1.0 - g;
    let i1 = min(g, l.zxy);
    let i2 = max(g, l.zxy);
    let x1 = x0 - i1 + (1.0 / 6.0);
    let x2 = x0 - i2 + (2.0 / 6.0);
    let x3 = x0 - 1.0 + 0.5;
    let n = veneer_simplex_corner(i, x0) + veneer_simplex_corner(i + i1, x1)
        + veneer_simplex_corner(i + i2, x2) + veneer_simplex_corner(i + 1.0, x3);
    return 0.5 + 0.5 * clamp(32.0 * n, -1.0, 1.0);
}
