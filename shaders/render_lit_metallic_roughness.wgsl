//! Metallic-roughness lighting: Cook-Torrance GGX for the key light, split-sum
//! image-based lighting from the environment (render_environment.wgsl), emission, then
//! exposure, the tone mapper and sRGB encoding.

// Cook-Torrance GGX (Trowbridge-Reitz distribution, Smith height-correlated
// visibility, Schlick Fresnel) of the key light, as glTF 2.0's appendix B gives it,
// with a Lambert diffuse for the dielectric part; radiance towards the eye per unit
// light, cos θ included.
fn veneer_ggx_light(n: vec3f, v: vec3f, l: vec3f, base: vec3f, metallic: f32, roughness: f32) -> vec3f {
    let h = normalize(l + v);
    let n_l = max(dot(n, l), 0.0);
    let n_v = max(dot(n, v), 1.0e-4);
    let n_h = max(dot(n, h), 0.0);
    let v_h = max(dot(v, h), 0.0);
    let alpha = max(roughness * roughness, 1.0e-3);
    let f0 = mix(vec3f(0.04), base, metallic);
    let fresnel = f0 + (1.0 - f0) * pow(1.0 - v_h, 5.0);
    let distribution = veneer_ggx_distribution(n_h, alpha);
    let visibility = veneer_smith_visibility(n_v, n_l, alpha);
    let diffuse = (1.0 - fresnel) * (1.0 - metallic) * base / VENEER_PI;
    return (diffuse + fresnel * distribution * visibility) * n_l;
}

// What the environment reflects towards v (split sum, Karis 2013): prefiltered radiance
// along the mirror direction times F0's directional albedo from the BRDF table, and
// the irradiance times the diffuse share the specular leaves.
fn veneer_image_based_light(n: vec3f, v: vec3f, base: vec3f, metallic: f32, roughness: f32) -> vec3f {
    let n_v = max(dot(n, v), 1.0e-4);
    let f0 = mix(vec3f(0.04), base, metallic);
    let scale_bias = veneer_environment_brdf(n_v, roughness);
    let specular_albedo = f0 * scale_bias.x + scale_bias.y;
    let specular = veneer_environment_specular(reflect(-v, n), roughness) * specular_albedo;
    let diffuse = veneer_environment_irradiance(n) * base * (1.0 - metallic) * (1.0 - specular_albedo);
    return diffuse + specular;
}

// The normal the lighting takes, from the mesh's unit normal plus the material's
// perturbation: a unit vector.
fn veneer_lit_normal(perturbed: vec3f) -> vec3f {
    return normalize(perturbed);
}

fn veneer_shade(material: VeneerMaterial, n: vec3f, v: vec3f, l: vec3f) -> vec3f {
    let base = clamp(material.albedo, vec3f(0.0), vec3f(1.0));
    let metallic = clamp(material.metallic, 0.0, 1.0);
    let roughness = clamp(material.roughness, 0.0, 1.0);
    let direct = veneer_ggx_light(n, v, l, base, metallic, roughness) * veneer_mesh_view.key_light;
    let ambient = veneer_image_based_light(n, v, base, metallic, roughness) * clamp(material.occlusion, 0.0, 1.0);
    let emitted = clamp(material.emission * material.emission_strength, vec3f(-1.0e18), vec3f(1.0e18));
    return veneer_display(direct + ambient + emitted);
}
