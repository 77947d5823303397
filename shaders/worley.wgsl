//! Cellular (Worley 1996) noise: distances to the nearest feature points.

// Distance of offset `d` under metric 0 (Euclidean), 1 (Manhattan) or 2 (Chebyshev).
fn veneer_metric(d: vec3f, metric: i32) -> f32 {
    let a = abs(d);
    switch metric {
        case 1: { return a.x + a.y + a.z; }
        case 2: { return max(a.x, max(a.y, a.z)); }
        default: { return length(d); }
    }
}

// The three smallest feature distances (F1, F2, F3) around `p`; one feature point per
// cell, displaced from the cell centre by up to `jitter` / 2 per axis (`jitter` clamped
// to [-1, 1], where every feature point stays in its cell, so distances stay small).
fn veneer_worley(point: vec3f, jitter: f32, metric: i32) -> vec3f {
    let p = veneer_lattice_domain(point);
    let spread = clamp(jitter, -1.0, 1.0);
    let cell = floor(p);
    var f = vec3f(1.0e9);
    for (var z = -1; z <= 1; z++) {
        for (var y = -1; y <= 1; y++) {
            for (var x = -1; x <= 1; x++) {
                let c = cell + vec3f(f32(x), f32(y), f32(z));
                let r = veneer_unit_floats(veneer_pcg3d(veneer_cell_bits(c)));
                let feature = c + 0.5 + spread * (r - 0.5);
                let d = veneer_metric(p - feature, metric);
                if d < f.x {
                    f = vec3f(d, f.x, f.y);
                } else if d < f.y {
                    f = vec3f(f.x, d, f.y);
                } else if d < f.z {
                    f.z = d;
                }
            }
        }
    }
    return f;
}

// F1, F2, F3 over the GeoTextures thesis's feature points (seed 003, appendix B's
// gpuCellNoise3D): each cell's corner moved along (1, 1, 1) by signed simplex noise at
// the corner times `spread` (the thesis's noiseScale), unclamped, so that past 0.5 points
// stray beyond the 27 cells searched, as in the thesis.
fn veneer_worley_simplex(point: vec3f, spread: f32, metric: i32) -> vec3f {
    let p = veneer_lattice_domain(point);
    var f = vec3f(1.0e9);
    for (var k = 0; k < 27; k++) {
        let c = floor(p) + vec3f(vec3i(k % 3, (k / 3) % 3, k / 9) - 1);
        let feature = c + spread * veneer_noise_simplex_signed(c);
        f = veneer_nearest_three(f, veneer_metric(p - feature, metric));
    }
    return f;
}

// The three smallest of F1 <= F2 <= F3 and a new distance `d`, in order.
fn veneer_nearest_three(f: vec3f, d: f32) -> vec3f {
    return select(select(select(f, vec3f(f.xy, d), d < f.z), vec3f(f.x, d, f.y), d < f.y), vec3f(d, f.xy), d < f.x);
}

// Feature 0 = F1, 1 = F2, 2 = F3, 3 = F2 - F1.
fn veneer_worley_feature(f: vec3f, feature: i32) -> f32 {
    switch feature {
        case 1: { return f.y; }
        case 2: { return f.z; }
        case 3: { return f.y - f.x; }
        default: { return f.x; }
    }
}

// Fractal Worley: `octaves` octaves of a feature, frequency times `lacunarity`, amplitude
// times `gain`; the frequency, the amplitude and the sum clamped to the finite range.
fn veneer_CELLS_fractal(p: vec3f, jitter: f32, metric: i32, feature: i32, octaves: i32, lacunarity: f32, gain: f32) -> f32 {
    var sum = 0.0;
    var amp = 1.0;
    var freq = 1.0;
    for (var i = 0; i < octaves; i++) {
        sum = clamp(sum + amp * veneer_worley_feature(veneer_CELLS(p * freq, jitter, metric), feature), -3.0e38, 3.0e38);
        freq = clamp(freq * lacunarity, -3.0e38, 3.0e38);
        amp = clamp(amp * gain, -3.0e38, 3.0e38);
    }
    return sum;
}

// `veneer_worley` repeating every `period` cells along each axis: the point is moved by
// whole periods near the origin and the cells whose feature points are hashed are
// wrapped (the feature points themselves stay beside the point).
fn veneer_worley_periodic(point: vec3f, jitter: f32, metric: i32, period: i32) -> vec3f {
    let p = veneer_lattice_periodic(point, period);
    let spread = clamp(jitter, -1.0, 1.0);
    var f = vec3f(1.0e9);
    for (var k = 0; k < 27; k++) {
        let c = floor(p) + vec3f(vec3i(k % 3, (k / 3) % 3, k / 9) - 1);
        let r = veneer_unit_floats(veneer_pcg3d(veneer_cell_bits(veneer_wrap_cell(c, period))));
        let d = veneer_metric(p - (c + 0.5 + spread * (r - 0.5)), metric);
        f = veneer_nearest_three(f, d);
    }
    return f;
}

// `veneer_worley_fractal` repeating every `period` cells: octave i spans the nearest
// whole number of cells to `period` times its frequency (`veneer_octave_period`).
fn veneer_worley_fractal_periodic(p: vec3f, jitter: f32, metric: i32, feature: i32, octaves: i32, lacunarity: f32, gain: f32, period: i32) -> f32 {
    var sum = 0.0;
    var amp = 1.0;
    var freq = 1.0;
    for (var i = 0; i < octaves; i++) {
        let cells = veneer_octave_period(period, freq, 1);
        let f = veneer_worley_periodic(p * (f32(cells) / f32(period)), jitter, metric, cells);
        sum = clamp(sum + amp * veneer_worley_feature(f, feature), -3.0e38, 3.0e38);
        freq = clamp(freq * lacunarity, -3.0e38, 3.0e38);
        amp = clamp(amp * gain, -3.0e38, 3.0e38);
    }
    return sum;
}
