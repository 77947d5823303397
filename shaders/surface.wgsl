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
}
