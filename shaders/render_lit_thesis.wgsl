//! Seed 003's lighting, as its appendix C listings write it: the diffuse colour by N·L
//! as it comes (below 0 on the far side, which the frame's clamp turns black) or, where
//! the listing takes it, by |N·L| (VENEER_ABSOLUTE_N_DOT_L, set by the pipeline); Phong's
//! highlight pow(max(R·V, 0), shininess) with R = normalize(2 N (N·L) - L), not gated by
//! N·L; no ambient fill (the listings' ambient colours are the material's emission);
//! the bumped normal as the listings leave it, `normalize(N) + bump`, not normalised
//! again (each term clamped to +-1e18 so that their sum is finite).

// The normal the lighting takes, from the mesh's unit normal plus the material's
// perturbation: as it is.
fn veneer_lit_normal(perturbed: vec3f) -> vec3f {
    return perturbed;
}

fn veneer_shade(material: VeneerMaterial, n: vec3f, v: vec3f, l: vec3f) -> vec3f {
    let n_dot_l = select(dot(n, l), abs(dot(n, l)), VENEER_ABSOLUTE_N_DOT_L);
    let reflected = 2.0 * n * n_dot_l - l;
    let r = reflected * inverseSqrt(max(dot(reflected, reflected), 1.0e-30));
    let highlight = pow(max(dot(r, v), 0.0), max(material.shininess, 1.0));
    let limit = vec3f(1.0e18);
    return clamp(material.albedo * n_dot_l, -limit, limit)
        + clamp(material.specular * highlight, -limit, limit)
        + clamp(material.emission * material.emission_strength, -limit, limit);
}
