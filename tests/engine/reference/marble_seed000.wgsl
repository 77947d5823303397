// Seed 000, Listing 5 (procedural marble), written out as one function: the reference the
// marble preset graph must reproduce.

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

fn veneer_material(s: VeneerSurface) -> VeneerMaterial {
    let pos = s.position;
    let x = dot(pos, normalize(vec3f(0.2, 0.6, 0.77)));
    let warp = 2.0 * seed_fbm(pos * 0.15 * 2.0) - 1.0;
    let bands = 0.5 + 0.5 * sin(x * 3.0 + 10.0 * warp);
    let veins = smoothstep(0.25, 0.75, bands);
    let color = mix(vec3f(0.20, 0.20, 0.25), vec3f(0.92, 0.92, 0.94), veins);
    return VeneerMaterial(color, 1.0, vec3f(0.0), 1.0, vec3f(0.0), 0.0);
}
