//! Entry points of a node's texel-space stage: `veneer_stage` at every texel.

@fragment
fn veneer_pass_fragment(@builtin(position) pixel: vec4f) -> @location(0) vec4f {
    return veneer_stage(vec2i(pixel.xy));
}
