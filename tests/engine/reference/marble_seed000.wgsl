// Seed 000, Listing 5 (procedural marble), written out as one function: the reference the
// marble preset graph must reproduce. Needs seed000_noise.wgsl.

fn veneer_material(s: VeneerSurface) -> VeneerMaterial {
    let pos = s.position;
    let x = dot(pos, normalize(vec3f(0.2, 0.6, 0.77)));
    let warp = 2.0 * seed_fbm(pos * 0.15 * 2.0) - 1.0;
    let bands = 0.5 + 0.5 * sin(x * 3.0 + 10.0 * warp);
    let veins = smoothstep(0.25, 0.75, bands);
    let color = mix(vec3f(0.20, 0.20, 0.25), vec3f(0.92, 0.92, 0.94), veins);
    return VeneerMaterial(color, 1.0, vec3f(0.0), 1.0, vec3f(0.0), 0.0, vec3f(0.0), 0.0, 0.5, vec3f(0.0, 0.0, 1.0), 1.0, 1.0);
}
