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

// A simplex-lattice (skewed) cell wrapped so that shifting space by `period` along any
// axis leaves it unchanged: such a shift is a lattice vector when `period` is a multiple
// of 3. The cell's unskewed coordinates (times 6) are reduced modulo 6 · `period` and
// skewed back; whole numbers throughout, exact in floats near the origin.
fn veneer_wrap_simplex_cell(cell: vec3f, period: i32) -> vec3f {
    let span = f32(period);
    let turns = floor((6.0 * cell - (cell.x + cell.y + cell.z)) / (6.0 * span));
    return cell - span * turns - (span / 3.0) * (turns.x + turns.y + turns.z);
}

// Simplex noise in [0, 1] repeating every `period` units along each axis (`period` a
// multiple of 3; the corners' cells are wrapped).
fn veneer_noise_simplex_periodic(point: vec3f, period: i32) -> f32 {
    let p = veneer_lattice_periodic(point, period);
    let i = floor(p + (p.x + p.y + p.z) * (1.0 / 3.0));
    let x0 = p - (i - (i.x + i.y + i.z) * (1.0 / 6.0));
    let g = step(x0.yzx, x0.xyz);
    let i1 = min(g, (1.0 - g).zxy);
    let i2 = max(g, (1.0 - g).zxy);
    var n = veneer_simplex_corner(veneer_wrap_simplex_cell(i, period), x0);
    n += veneer_simplex_corner(veneer_wrap_simplex_cell(i + i1, period), x0 - i1 + (1.0 / 6.0));
    n += veneer_simplex_corner(veneer_wrap_simplex_cell(i + i2, period), x0 - i2 + (2.0 / 6.0));
    n += veneer_simplex_corner(veneer_wrap_simplex_cell(i + 1.0, period), x0 - 1.0 + 0.5);
    return 0.5 + 0.5 * clamp(32.0 * n, -1.0, 1.0);
}
