//! Fractal sums whose octaves each turn by a fixed rotation, so that the lattice of one
//! octave never lines up with the next (seed 000's discussion: "applying a small domain
//! rotation per octave can reduce directional artifacts").

// `p` turned by a fixed rotation: the golden angle 360 (1 - 1 / phi) = 137.50776405
// degrees about the axis (1, 2, 3) / sqrt(14) (Rodrigues' formula; rows rounded to nine
// decimals, orthonormal to 2e-10). The golden angle is an irrational fraction of a turn,
// so no number of octaves brings the lattice back to its first orientation, whereas
// Quilez's fBm matrix (0, .8, .6; -.8, .36, -.48; -.6, -.48, .64) turns by exactly 90
// degrees and repeats every fourth octave. Clamped to the finite range.
fn veneer_octave_rotate(p: vec3f) -> vec3f {
    let q = vec3f(
        dot(vec3f(-0.613271101, -0.293401571, 0.733358081), p),
        dot(vec3f(0.789792679, -0.240977770, 0.564054287), p),
        dot(vec3f(0.011228581, 0.925119037, 0.379511115), p),
    );
    return clamp(q, vec3f(-3.0e38), vec3f(3.0e38));
}

// The fractal sum of the same name without `_rotated`, except that octave i samples the
// basis at R^i p times its frequency (R: the fixed octave rotation; octave 0 unturned; p
// clamped to the finite range, so that its turns are finite).
// Sum of `octaves` octaves; each multiplies the frequency by `lacunarity` and the
// amplitude by `gain` (clamped to the finite range, as are the sums). With `normalize`
// the sum is divided by the sum of amplitudes. Octave i counts fully below `cutoff - 1`,
// fades to its average over the next octave and is replaced by its average from
// `cutoff` on (as in the unturned sums).
fn veneer_MODE_rotated_BASIS(p: vec3f, octaves: i32, lacunarity: f32, gain: f32, amplitude: f32, normalize: bool, cutoff: f32) -> f32 {
    var sum = 0.0;
    var amp = amplitude;
    var freq = 1.0;
    var total = 0.0;
    var q = veneer_finite_vec3f(p);
    let mean = veneer_octave_mean_MODE();
    let evaluated = min(octaves, i32(clamp(ceil(cutoff), 0.0, 64.0)));
    for (var i = 0; i < evaluated; i++) {
        let shown = clamp(cutoff - f32(i), 0.0, 1.0);
        sum = clamp(sum + amp * (shown * veneer_octave_MODE_BASIS(q * freq) + (1.0 - shown) * mean), -3.0e38, 3.0e38);
        total = min(total + abs(amp), 3.0e38);
        freq = clamp(freq * lacunarity, -3.0e38, 3.0e38);
        amp = clamp(amp * gain, -3.0e38, 3.0e38);
        q = veneer_octave_rotate(q);
    }
    for (var i = evaluated; i < octaves; i++) {
        sum = clamp(sum + amp * mean, -3.0e38, 3.0e38);
        total = min(total + abs(amp), 3.0e38);
        amp = clamp(amp * gain, -3.0e38, 3.0e38);
    }
    return select(sum, sum / total, normalize && total > 0.0);
}
