//! Seed 003's lighting terms, as its appendix C listings write them: the bumped normal as
//! the listings leave it, `normalize(N) + bump`, not normalised again; N·L as it comes or,
//! where the listing takes it, |N·L| (VENEER_ABSOLUTE_N_DOT_L, set by the pipeline); the
//! light's reflection R = normalize(2 N (N·L) - L) for Phong's highlight. Shared by
//! render_lit_thesis.wgsl and render_lit_thesis_sphere_map.wgsl.

// The normal the lighting takes, from the mesh's unit normal plus the material's
// perturbation: as it is.
fn veneer_lit_normal(perturbed: vec3f) -> vec3f {
    return perturbed;
}

// N·L as the listing takes it.
fn veneer_thesis_n_dot_l(n: vec3f, l: vec3f) -> f32 {
    return select(dot(n, l), abs(dot(n, l)), VENEER_ABSOLUTE_N_DOT_L);
}

// The light's reflection about the normal, normalize(2 N (N·L) - L) (finite when it is
// the zero vector).
fn veneer_thesis_reflection(n: vec3f, l: vec3f, n_dot_l: f32) -> vec3f {
    let reflected = 2.0 * n * n_dot_l - l;
    return reflected * inverseSqrt(max(dot(reflected, reflected), 1.0e-30));
}
