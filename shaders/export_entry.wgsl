//! The fragment entry point every non-WGSL export carries: evaluates veneer_material from
//! interpolated inputs and writes (albedo + emission × strength, alpha): the unlit colour,
//! clamped to the finite range. Time comes from a uniform block.

struct VeneerFragmentInput {
    @location(0) position: vec3f,  // object-space position
    @location(1) normal: vec3f,    // unit object-space normal
    @location(2) uv: vec2f,
    @location(3) fields: vec4f,    // distance fields, 0 when unused
}

struct VeneerFrame {
    time: f32,  // seconds
}

@group(0) @binding(0) var<uniform> veneer_frame: VeneerFrame;

@fragment
fn veneer_fragment(input: VeneerFragmentInput) -> @location(0) vec4f {
    let surface = VeneerSurface(input.position, input.normal, input.uv, input.fields, veneer_frame.time);
    let material = veneer_material(surface);
    let emitted = clamp(material.emission * material.emission_strength, vec3f(-1.0e38), vec3f(1.0e38));
    return vec4f(clamp(material.albedo + emitted, vec3f(-3.0e38), vec3f(3.0e38)), material.alpha);
}
