//! Distance to the nearest border of a Worley cell (Inigo Quilez, "Voronoi - edges",
//! 2012, in 3D): the true Euclidean distance to the boundary of the Voronoi cell that
//! holds the point, which F2 - F1 only approximates.

// Offset from the point to the feature point of the cell `g` cells from `cell`, the point
// being at `f` within `cell`: the Worley feature points (one per cell, at the cell centre
// displaced by up to `jitter` / 2 per axis, PCG-hashed), computed relative to the point
// so that far from the origin only the cell's hash loses precision, not the offsets.
// `jitter` is clamped to [-1, 1], where every feature point stays in its cell.
fn veneer_worley_edge_feature(cell: vec3f, g: vec3f, f: vec3f, jitter: f32) -> vec3f {
    let r = veneer_unit_floats(veneer_pcg3d(veneer_cell_bits(cell + g)));
    return g + 0.5 + clamp(jitter, -1.0, 1.0) * (r - 0.5) - f;
}

// The distance from p to the nearest border of its Voronoi cell (Euclidean), >= 0: 0 on
// the borders, at most 0.5 for jitter 0 (cubes), about 0.58 at most for jitter 1 (the
// largest of 4e5 samples); `jitter` is clamped to [-1, 1]. First pass: the nearest
// feature point a over the 3x3x3 cells around p. Second pass: over the 5x5x5 cells
// around a's cell, the least distance from p to the bisector plane of a and another
// feature point b, which is ((a + b) / 2) . (b - a) / |b - a| in offsets from p
// (coincident points are skipped).
fn veneer_worley_edge(point: vec3f, jitter: f32) -> f32 {
    let p = veneer_lattice_domain(point);
    let cell = floor(p);
    let f = p - cell;
    var nearest = vec3f(0.0);
    var nearest_cell = vec3f(0.0);
    var best = 1.0e9;
    for (var z = -1; z <= 1; z++) {
        for (var y = -1; y <= 1; y++) {
            for (var x = -1; x <= 1; x++) {
                let g = vec3f(f32(x), f32(y), f32(z));
                let r = veneer_worley_edge_feature(cell, g, f, jitter);
                let d = dot(r, r);
                if d < best {
                    best = d;
                    nearest = r;
                    nearest_cell = g;
                }
            }
        }
    }
    var edge = 1.0e9;
    for (var z = -2; z <= 2; z++) {
        for (var y = -2; y <= 2; y++) {
            for (var x = -2; x <= 2; x++) {
                let g = nearest_cell + vec3f(f32(x), f32(y), f32(z));
                let r = veneer_worley_edge_feature(cell, g, f, jitter);
                let between = r - nearest;
                let length2 = dot(between, between);
                if length2 > 1.0e-12 {
                    edge = min(edge, dot(0.5 * (nearest + r), between) / sqrt(length2));
                }
            }
        }
    }
    return max(edge, 0.0);
}
