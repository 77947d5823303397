// Seed 000's Listings 1-3 (hash, value noise, five-octave fBm), shared by the wood and
// marble references.

fn seed_hash(p: vec3f) -> f32 {
    return fract(sin(dot(p, vec3f(127.1, 311.7, 74.7))) * 43758.5453);
}

fn seed_value_noise(p: vec3f) -> f32 {
    let i = floor(p);
    let f = fract(p);
    let u = f * f * (3.0 - 2.0 * f);
    let x00 = mix(seed_hash(i), seed_hash(i + vec3f(1.0, 0.0, 0.0)), u.x);
    let x10 = mix(seed_hash(i + vec3f(0.0, 1.0, 0.0)), seed_hash(i + vec3f(1.0, 1.0, 0.0)), u.x);
    let x01 = mix(seed_hash(i + vec3f(0.0, 0.0, 1.0)), seed_hash(i + vec3f(1.0, 0.0, 1.0)), u.x);
    let x11 = mix(seed_hash(i + vec3f(0.0, 1.0, 1.0)), seed_hash(i + vec3f(1.0, 1.0, 1.0)), u.x);
    return mix(mix(x00, x10, u.y), mix(x01, x11, u.y), u.z);
}

fn seed_fbm(p: vec3f) -> f32 {
    var sum = 0.0;
    var amplitude = 0.5;
    var frequency = 1.0;
    for (var octave = 0; octave < 5; octave++) {
        sum += amplitude * seed_value_noise(p * frequency);
        frequency *= 2.0;
        amplitude *= 0.5;
    }
    return sum;
}
