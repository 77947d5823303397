//! The material outputs a bake reads back, selected by `channels`, shared by the flat and
//! UV-layout renders: 0 = (albedo, alpha), 1 = (specular, shininess), 2 = (height, bump).

fn veneer_bake_channels(material: VeneerMaterial, channels: u32) -> vec4u {
    var values = vec4f(material.albedo, material.alpha);
    if channels == 1u {
        values = vec4f(material.specular, material.shininess);
    } else if channels == 2u {
        values = vec4f(material.height, material.bump);
    }
    return bitcast<vec4u>(values);
}
