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

// The average of one fBm octave (noise in [0, 1]), which stands in for octaves too fine
// to show.
fn veneer_octave_mean_fbm() -> f32 {
    return 0.5;
}

// The average of one turbulence octave (|signed noise|).
fn veneer_octave_mean_turbulence() -> f32 {
    return 0.25;
}

// The average of one fractal-sum octave (signed noise).
fn veneer_octave_mean_fractal_sum() -> f32 {
    return 0.0;
}

// Sum of `octaves` octaves; each multiplies the frequency by `lacunarity` and the
// amplitude by `gain` (the frequency, the amplitude and the sums clamped to the finite
// range, so no octave overflows into a NaN). With `normalize` the sum is divided by the
// sum of amplitudes. Octave i counts fully below `cutoff - 1`, fades to its average over
// the next octave and is replaced by its average from `cutoff` on: those octaves are
// summed in a second loop without any noise, so a coarse footprint shortens the
// expensive one (software rasterisers run both sides of a branch; a shorter loop is what
// saves them work).
fn veneer_MODE_BASIS(p: vec3f, octaves: i32, lacunarity: f32, gain: f32, amplitude: f32, normalize: bool, cutoff: f32) -> f32 {
    var sum = 0.0;
    var amp = amplitude;
    var freq = 1.0;
    var total = 0.0;
    let mean = veneer_octave_mean_MODE();
    let evaluated = min(octaves, i32(clamp(ceil(cutoff), 0.0, 64.0)));
    for (var i = 0; i < evaluated; i++) {
        let shown = clamp(cutoff - f32(i), 0.0, 1.0);
        sum = clamp(sum + amp * (shown * veneer_octave_MODE_BASIS(p * freq) + (1.0 - shown) * mean), -3.0e38, 3.0e38);
        total = min(total + abs(amp), 3.0e38);
        freq = clamp(freq * lacunarity, -3.0e38, 3.0e38);
        amp = clamp(amp * gain, -3.0e38, 3.0e38);
    }
    for (var i = evaluated; i < octaves; i++) {
        sum = clamp(sum + amp * mean, -3.0e38, 3.0e38);
        total = min(total + abs(amp), 3.0e38);
        amp = clamp(amp * gain, -3.0e38, 3.0e38);
    }
    return select(sum, sum / total, normalize && total > 0.0);
}

// How many octaves of noise at `q` (frequency times `lacunarity` per octave) the pixel
// footprint can show: octaves finer than half a pixel are left out (a fractional count
// fades the last one). From the screen-space derivatives of `q` within the lattice's
// range (so they stay finite): fragment stage only.
fn veneer_octave_cutoff(q: vec3f, lacunarity: f32) -> f32 {
    let lattice = veneer_lattice_domain(q);
    let footprint = max(length(dpdx(lattice)), length(dpdy(lattice)));
    let visible = 1.0 + log2(0.5 / max(footprint, 1.0e-30)) / log2(max(lacunarity, 1.0001));
    return select(max(visible, 0.0), 1.0e9, footprint <= 0.0 || lacunarity <= 1.0);
}

// How many lattice cells an octave at `frequency` spans over a noise repeating every
// `period` cells: the nearest whole number of cells (of 3 for simplex noise, whose
// period must be a multiple of 3), at least one step and at most 2^24, so that every
// octave repeats with the first.
fn veneer_octave_period(period: i32, frequency: f32, step: i32) -> i32 {
    let steps = round(f32(period) * abs(frequency) / f32(step));
    return step * i32(clamp(steps, 1.0, 16777216.0 / f32(step)));
}

// One periodic fBm octave.
fn veneer_octave_fbm_BASIS_periodic(q: vec3f, period: i32) -> f32 {
    return veneer_noise_BASIS_periodic(q, period);
}

// One periodic turbulence octave.
fn veneer_octave_turbulence_BASIS_periodic(q: vec3f, period: i32) -> f32 {
    return abs(veneer_noise_BASIS_signed_periodic(q, period));
}

// One periodic fractal-sum octave.
fn veneer_octave_fractal_sum_BASIS_periodic(q: vec3f, period: i32) -> f32 {
    return veneer_noise_BASIS_signed_periodic(q, period);
}

// The fractal sum of `veneer_MODE_BASIS` repeating every `period` cells: octave i spans
// `veneer_octave_period` cells over the period, its frequency that count over `period`
// (the lacunarity's powers rounded to whole cells), so that the sum repeats too. Octaves
// from `cutoff` on count as their average, without sampling the noise.
fn veneer_MODE_BASIS_periodic(p: vec3f, octaves: i32, lacunarity: f32, gain: f32, amplitude: f32, normalize: bool, cutoff: f32, period: i32, step: i32) -> f32 {
    let mean = veneer_octave_mean_MODE();
    var sum = 0.0;
    var total = 0.0;
    var amp = amplitude;
    var freq = 1.0;
    for (var i = 0; i < octaves; i++) {
        let shown = clamp(cutoff - f32(i), 0.0, 1.0);
        var octave = mean;
        if shown > 0.0 {
            let cells = veneer_octave_period(period, freq, step);
            let noise = veneer_octave_MODE_BASIS_periodic(p * (f32(cells) / f32(period)), cells);
            octave = shown * noise + (1.0 - shown) * mean;
        }
        sum = clamp(sum + amp * octave, -3.0e38, 3.0e38);
        total = min(total + abs(amp), 3.0e38);
        freq = clamp(freq * lacunarity, -3.0e38, 3.0e38);
        amp = clamp(amp * gain, -3.0e38, 3.0e38);
    }
    return select(sum, sum / total, normalize && total > 0.0);
}
