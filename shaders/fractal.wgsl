//! Fractal sums over octaves of a basis: fBm, turbulence and fractal sum.

// One fBm octave: the basis in its natural range.
fn veneer_octave_fbm_BASIS(q: vec3f) -> f32 {
    return veneer_noise_BASIS(q);
}

// One turbulence octave: |signed noise|.
fn veneer_octave_turbulence_BASIS(q: vec3f) -> f32 {
    return abs(veneer_noise_BASIS_signed(q));
}

// One fractal-sum octave: signed noise.
fn veneer_octave_fractal_sum_BASIS(q: vec3f) -> f32 {
    return veneer_noise_BASIS_signed(q);
}

// Sum of `octaves` octaves; each multiplies the frequency by `lacunarity` and the
// amplitude by `gain`. With `normalize` the sum is divided by the sum of amplitudes.
fn veneer_MODE_BASIS(p: vec3f, octaves: i32, lacunarity: f32, gain: f32, amplitude: f32, normalize: bool) -> f32 {
    var sum = 0.0;
    var amp = amplitude;
    var freq = 1.0;
    var total = 0.0;
    for (var i = 0; i < octaves; i++) {
        sum += amp * veneer_octave_MODE_BASIS(p * freq);
        total += abs(amp);
        freq *= lacunarity;
        amp *= gain;
    }
    return select(sum, sum / total, normalize && total > 0.0);
}
