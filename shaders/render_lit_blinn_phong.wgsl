//! The seeds' lighting (Blinn-Phong materials): the key light's Lambert diffuse over a
//! share of ambient light, a Blinn-Phong highlight, and the emission added on top.

fn veneer_shade(material: VeneerMaterial, n: vec3f, v: vec3f, l: vec3f) -> vec3f {
    let view = veneer_mesh_view;
    let h = normalize(l + v);
    let lambert = max(dot(n, l), 0.0);
    let highlight = select(0.0, pow(max(dot(n, h), 0.0), max(material.shininess, 1.0)), lambert > 0.0);
    return material.albedo * (view.ambient + (1.0 - view.ambient) * lambert) + material.specular * highlight
        + material.emission * material.emission_strength;
}
