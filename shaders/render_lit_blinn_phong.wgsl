//! The seeds' lighting (Blinn-Phong materials): the key light's Lambert diffuse over a
//! share of ambient light, a Blinn-Phong highlight, and the emission added on top (each
//! term clamped to +-1e18, far past white, so that their sum is finite).

// The normal the lighting takes, from the mesh's unit normal plus the material's
// perturbation: a unit vector.
fn veneer_lit_normal(perturbed: vec3f) -> vec3f {
    return normalize(perturbed);
}

fn veneer_shade(material: VeneerMaterial, n: vec3f, v: vec3f, l: vec3f) -> vec3f {
    let view = veneer_mesh_view;
    let h = normalize(l + v);
    let lambert = max(dot(n, l), 0.0);
    let highlight = select(0.0, pow(max(dot(n, h), 0.0), max(material.shininess, 1.0)), lambert > 0.0);
    let limit = vec3f(1.0e18);
    let diffuse = clamp(material.albedo * (view.ambient + (1.0 - view.ambient) * lambert), -limit, limit);
    return diffuse + clamp(material.specular * highlight, -limit, limit)
        + clamp(material.emission * material.emission_strength, -limit, limit);
}
