// Seed 000, Listing 4 (procedural wood), written out as one function: the reference the
// wood preset graph must reproduce. Needs seed000_noise.wgsl.

fn veneer_material(s: VeneerSurface) -> VeneerMaterial {
    let pos = s.position;
    let axis_point = vec3f(25.0, 0.0, 25.0);
    let axis = normalize(vec3f(0.2, 1.0, -0.1));
    let up = select(vec3f(0.0, 1.0, 0.0), vec3f(1.0, 0.0, 0.0), abs(axis.y) > 0.95);
    let u = normalize(cross(up, axis));
    let v = cross(axis, u);
    let t = dot(pos - axis_point, axis);
    let radial = pos - (axis_point + t * axis);
    let r = length(radial);
    let p = pos * 0.20;
    let coarse = 2.0 * seed_fbm(p * 2.0) - 1.0;
    let fine = 2.0 * seed_fbm(p * 6.0 + 13.7) - 1.0;
    let warped = r + 0.35 * coarse + 0.10 * fine;
    let phase = 0.5 * (warped + 0.25 * warped * warped);
    let ring_sharp = smoothstep(0.25, 0.85, 0.5 + 0.5 * sin(phase));
    let angle = atan2(dot(radial, v), dot(radial, u));
    let grain = smoothstep(0.35, 0.75, seed_fbm(vec3f(t * 0.6, angle, 0.0) + pos * 0.05));
    var color = mix(vec3f(0.33, 0.17, 0.08), vec3f(0.62, 0.42, 0.22), ring_sharp);
    color *= mix(0.85, 1.05, grain);
    color *= 0.95 + 0.10 * seed_fbm(pos * 0.08 + 4.2);
    return VeneerMaterial(color, 1.0, vec3f(0.0), 1.0, vec3f(0.0), 0.0, vec3f(0.0), 0.0, 0.5, vec3f(0.0, 0.0, 1.0), 1.0, 1.0);
}
