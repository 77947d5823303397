//! The exported interface: what a material reads and what it returns (DESIGN.md contract).

struct VeneerSurface {
    position: vec3f,  // object-space position (solid texturing)
    normal: vec3f,    // unit object-space normal
    uv: vec2f,
    fields: vec4f,    // up to four distance fields, normalised to [0, 1]; 0 when unused
    time: f32,        // seconds
}

struct VeneerMaterial {
    albedo: vec3f,
    alpha: f32,
    specular: vec3f,
    shininess: f32,
    bump: vec3f,      // perturbation added to the normal before lighting; 0 when flat
    height: f32,      // displacement along the normal
    emission: vec3f,  // light given off whatever the lighting, added to the lit colour; 0 when none
    metallic: f32,    // 0 dielectric .. 1 metal (metallic-roughness shading)
    roughness: f32,   // perceptual roughness, 0 mirror .. 1 matte (metallic-roughness shading)
    normal: vec3f,    // tangent-space normal (x along +u, y up the image, z out); (0, 0, 1) when flat
    emission_strength: f32, // multiplies emission; 1 unless set
    occlusion: f32,   // ambient occlusion, 1 unoccluded
}
