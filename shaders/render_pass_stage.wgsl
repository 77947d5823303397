//! Entry points of a node's texel-space stage: `veneer_stage` at every texel.

@vertex
fn veneer_pass_vertex(@builtin(vertex_index) index: u32) -> @builtin(position) vec4f {
    let corner = vec2f(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4f(corner * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn veneer_pass_fragment(@builtin(position) pixel: vec4f) -> @location(0) vec4f {
    return veneer_stage(vec2i(pixel.xy));
}
