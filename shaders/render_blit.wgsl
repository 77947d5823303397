//! Draws an offscreen render into the editor's panel (a full-viewport triangle).

@group(0) @binding(0) var veneer_blit_texture: texture_2d<f32>;
@group(0) @binding(1) var veneer_blit_sampler: sampler;

struct VeneerBlitOut {
    @builtin(position) clip: vec4f,
    @location(0) uv: vec2f,
}

@vertex
fn veneer_blit_vertex(@builtin(vertex_index) index: u32) -> VeneerBlitOut {
    let corner = vec2f(f32((index << 1u) & 2u), f32(index & 2u));
    return VeneerBlitOut(vec4f(corner * 2.0 - 1.0, 0.0, 1.0), vec2f(corner.x, 1.0 - corner.y));
}

// For targets that store display values as they are.
@fragment
fn veneer_blit_fragment(input: VeneerBlitOut) -> @location(0) vec4f {
    return textureSample(veneer_blit_texture, veneer_blit_sampler, input.uv);
}

// For sRGB targets, which encode what they are given: decode first so the image shows unchanged.
@fragment
fn veneer_blit_fragment_srgb(input: VeneerBlitOut) -> @location(0) vec4f {
    let c = textureSample(veneer_blit_texture, veneer_blit_sampler, input.uv);
    let linear = select(pow((c.rgb + 0.055) / 1.055, vec3f(2.4)), c.rgb / 12.92, c.rgb <= vec3f(0.04045));
    return vec4f(linear, c.a);
}
