//! What shows behind a metallic-roughness material: the environment, sharp or blurred,
//! drawn before the mesh over the whole target with the material's exposure and tone
//! mapper.

struct VeneerBackdropOut {
    @builtin(position) clip: vec4f,
    @location(0) ndc: vec2f,
}

@vertex
fn veneer_backdrop_vertex(@builtin(vertex_index) index: u32) -> VeneerBackdropOut {
    let ndc = vec2f(f32((index << 1u) & 2u), f32(index & 2u)) * 2.0 - 1.0;
    return VeneerBackdropOut(vec4f(ndc, 1.0, 1.0), ndc);
}

// How blurred the blurred backdrop is, as a GGX roughness.
const VENEER_BACKDROP_BLUR: f32 = 0.35;

@fragment
fn veneer_backdrop_fragment(input: VeneerBackdropOut) -> @location(0) vec4f {
    let view = veneer_mesh_view;
    let near = view.inverse_view_projection * vec4f(input.ndc, 0.0, 1.0);
    let far = view.inverse_view_projection * vec4f(input.ndc, 1.0, 1.0);
    let d = far.xyz / far.w - near.xyz / near.w;
    var radiance: vec3f;
    if view.backdrop == 1u {
        radiance = textureSampleLevel(veneer_environment_source, veneer_environment_sampler, veneer_environment_uv(d), 0.0).rgb;
    } else {
        radiance = veneer_environment_specular(d, VENEER_BACKDROP_BLUR);
    }
    return vec4f(veneer_display(radiance), 1.0);
}
