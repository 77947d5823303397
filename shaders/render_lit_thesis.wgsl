//! Seed 003's lighting, as its appendix C listings write it (the terms are in
//! render_lit_thesis_phong.wgsl): the diffuse colour times N·L, Phong's highlight
//! pow(max(R·V, 0), shininess), not gated by N·L, and no ambient fill (the listings'
//! ambient colours are the material's emission); each term clamped to +-1e18 so that
//! their sum is finite.

fn veneer_shade(material: VeneerMaterial, n: vec3f, v: vec3f, l: vec3f) -> vec3f {
    let n_dot_l = veneer_thesis_n_dot_l(n, l);
    let r = veneer_thesis_reflection(n, l, n_dot_l);
    let highlight = pow(max(dot(r, v), 0.0), max(material.shininess, 1.0));
    let limit = vec3f(1.0e18);
    return clamp(material.albedo * n_dot_l, -limit, limit)
        + clamp(material.specular * highlight, -limit, limit)
        + clamp(material.emission * material.emission_strength, -limit, limit);
}
