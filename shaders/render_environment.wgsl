//! The environment's maps as the mesh preview reads them (render/environment/maps.rs
//! derives them): panoramas looked up by direction (ggx.wgsl's mapping), turned about +y
//! by the view's `environment_turn`.

@group(0) @binding(1) var veneer_environment_source: texture_2d<f32>;
@group(0) @binding(2) var veneer_environment_prefiltered: texture_2d<f32>;
@group(0) @binding(3) var veneer_environment_irradiance_map: texture_2d<f32>;
@group(0) @binding(4) var veneer_environment_brdf_table: texture_2d<f32>;
@group(0) @binding(5) var veneer_environment_sampler: sampler;

// Panorama coordinates of mesh-space direction `d` (the top row looks up, the centre
// column along −z before the turn).
fn veneer_environment_uv(d: vec3f) -> vec2f {
    let turn = veneer_mesh_view.environment_turn;
    // The environment turned by θ: look up the direction turned by −θ.
    return veneer_equirect_uv(vec3f(turn.x * d.x - turn.y * d.z, d.y, turn.y * d.x + turn.x * d.z));
}

// Radiance arriving from `d`, prefiltered for GGX of `roughness` (0 sharp … 1 matte).
fn veneer_environment_specular(d: vec3f, roughness: f32) -> vec3f {
    let last = f32(textureNumLevels(veneer_environment_prefiltered) - 1u);
    return textureSampleLevel(veneer_environment_prefiltered, veneer_environment_sampler, veneer_environment_uv(d), roughness * last).rgb;
}

// Irradiance over π on a surface facing `n`.
fn veneer_environment_irradiance(n: vec3f) -> vec3f {
    return textureSampleLevel(veneer_environment_irradiance_map, veneer_environment_sampler, veneer_environment_uv(n), 0.0).rgb;
}

// F0's scale and bias in GGX's directional albedo at n·v and roughness (texel centres
// hold the table's samples; the coordinates stay off its wrapping edges).
fn veneer_environment_brdf(n_v: f32, roughness: f32) -> vec2f {
    let size = vec2f(textureDimensions(veneer_environment_brdf_table));
    let uv = clamp(vec2f(n_v, roughness), 0.5 / size, 1.0 - 0.5 / size);
    return textureSampleLevel(veneer_environment_brdf_table, veneer_environment_sampler, uv, 0.0).rg;
}
