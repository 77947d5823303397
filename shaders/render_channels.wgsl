//! The material outputs a bake reads back, selected by `channels`, shared by the flat and
//! UV-layout renders: 0 = (albedo, alpha), 1 = (specular, shininess), 2 = (height, bump
//! plus the tangent-space normal's tilt in `frame`), 3 = (metallic, roughness, occlusion,
//! shininess), 4 = (emission × emission strength, clamped to the finite range, 0).

fn veneer_bake_channels(material: VeneerMaterial, channels: u32, frame: mat3x3f) -> vec4u {
    var values = vec4f(material.albedo, material.alpha);
    if channels == 1u {
        values = vec4f(material.specular, material.shininess);
    } else if channels == 2u {
        values = vec4f(material.height, material.bump + veneer_tilt(frame, material.normal));
    } else if channels == 3u {
        values = vec4f(material.metallic, material.roughness, material.occlusion, material.shininess);
    } else if channels == 4u {
        values = vec4f(clamp(material.emission * material.emission_strength, vec3f(-3.0e38), vec3f(3.0e38)), 0.0);
    }
    return bitcast<vec4u>(values);
}
