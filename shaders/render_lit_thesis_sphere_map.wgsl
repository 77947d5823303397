//! Seed 003's C.6.4 lighting, the waves' final look: the environment in the direction of
//! the light's reflection R (the listing indexes its sphere map by R, which maps every
//! direction to the sphere map's texel for it; here the environment itself, shown through
//! the exposure and tone mapper as metallic-roughness shows it) plus Phong's highlight;
//! the diffuse term is dropped, as the listing drops it. The emission (the listings'
//! ambient) is added as in render_lit_thesis.wgsl.

fn veneer_shade(material: VeneerMaterial, n: vec3f, v: vec3f, l: vec3f) -> vec3f {
    let n_dot_l = veneer_thesis_n_dot_l(n, l);
    let r = veneer_thesis_reflection(n, l, n_dot_l);
    let highlight = pow(max(dot(r, v), 0.0), max(material.shininess, 1.0));
    let limit = vec3f(1.0e18);
    return veneer_display(veneer_environment_specular(r, 0.0))
        + clamp(material.specular * highlight, -limit, limit)
        + clamp(material.emission * material.emission_strength, -limit, limit);
}
