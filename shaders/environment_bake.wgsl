//! Derives the image-based lighting maps from an environment panorama, one full-target
//! triangle per map level: the GGX-prefiltered specular chain (split-sum, n = v = r),
//! the diffuse irradiance (over π) and the split-sum BRDF table (scale, bias of F0).
//! Follows ggx.wgsl (its GGX terms and panorama mapping).

struct VeneerBake {
    target_size: vec2f,
    roughness: f32,
    samples: u32,
    // The panorama's texels at level 0 and its level count, for filtered importance
    // sampling; the level the irradiance integrates over.
    source_texels: f32,
    source_levels: f32,
    irradiance_level: u32,
    padding: u32,
}

@group(0) @binding(0) var<uniform> veneer_bake: VeneerBake;
@group(0) @binding(1) var veneer_bake_source: texture_2d<f32>;
@group(0) @binding(2) var veneer_bake_sampler: sampler;

@vertex
fn veneer_bake_vertex(@builtin(vertex_index) index: u32) -> @builtin(position) vec4f {
    let corner = vec2f(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4f(corner * 2.0 - 1.0, 0.0, 1.0);
}

// The i-th of n points of the Hammersley set.
fn veneer_hammersley(i: u32, n: u32) -> vec2f {
    return vec2f(f32(i) / f32(n), f32(reverseBits(i)) * 2.3283064365386963e-10);
}

// A GGX-distributed half vector round `n` for roughness² `alpha`.
fn veneer_ggx_half(xi: vec2f, alpha: f32, n: vec3f) -> vec3f {
    let phi = 2.0 * VENEER_PI * xi.x;
    let cos_theta = sqrt((1.0 - xi.y) / (1.0 + (alpha * alpha - 1.0) * xi.y));
    let sin_theta = sqrt(1.0 - cos_theta * cos_theta);
    let up = select(vec3f(1.0, 0.0, 0.0), vec3f(0.0, 0.0, 1.0), abs(n.z) < 0.999);
    let tangent = normalize(cross(up, n));
    let bitangent = cross(n, tangent);
    return normalize(tangent * (sin_theta * cos(phi)) + bitangent * (sin_theta * sin(phi)) + n * cos_theta);
}

fn veneer_bake_uv_here(position: vec4f) -> vec2f {
    return position.xy / veneer_bake.target_size;
}

// The radiance GGX of this level's roughness reflects towards a viewer straight along
// the normal, weighted by n·l (Karis 2013); each sample read from the panorama level
// whose texels cover its share of the lobe (filtered importance sampling, Křivánek and
// Colbert 2008), so a few hundred samples leave no noise.
@fragment
fn veneer_bake_prefilter(@builtin(position) position: vec4f) -> @location(0) vec4f {
    let n = veneer_equirect_direction(veneer_bake_uv_here(position));
    if veneer_bake.roughness <= 0.0 {
        return vec4f(textureSampleLevel(veneer_bake_source, veneer_bake_sampler, veneer_equirect_uv(n), 0.0).rgb, 1.0);
    }
    let alpha = veneer_bake.roughness * veneer_bake.roughness;
    let texel_solid_angle = 4.0 * VENEER_PI / veneer_bake.source_texels;
    var sum = vec3f(0.0);
    var weight = 0.0;
    for (var i = 0u; i < veneer_bake.samples; i += 1u) {
        let h = veneer_ggx_half(veneer_hammersley(i, veneer_bake.samples), alpha, n);
        let l = 2.0 * dot(n, h) * h - n;
        let n_l = dot(n, l);
        if n_l > 0.0 {
            // With n = v the pdf of l is D(n·h) / 4.
            let pdf = veneer_ggx_distribution(max(dot(n, h), 0.0), alpha) * 0.25;
            let sample_solid_angle = 1.0 / (f32(veneer_bake.samples) * pdf + 1.0e-6);
            let level = clamp(0.5 * log2(sample_solid_angle / texel_solid_angle) + 1.0, 0.0, veneer_bake.source_levels - 1.0);
            sum += textureSampleLevel(veneer_bake_source, veneer_bake_sampler, veneer_equirect_uv(l), level).rgb * n_l;
            weight += n_l;
        }
    }
    return vec4f(sum / max(weight, 1.0e-6), 1.0);
}

// Irradiance over π (what a white Lambertian surface facing this way reflects): the sum
// over every texel of a small level of the panorama, each weighted by its solid angle
// and its cosine.
@fragment
fn veneer_bake_irradiance(@builtin(position) position: vec4f) -> @location(0) vec4f {
    let n = veneer_equirect_direction(veneer_bake_uv_here(position));
    let level = i32(veneer_bake.irradiance_level);
    let size = textureDimensions(veneer_bake_source, level);
    let step = vec2f(2.0 * VENEER_PI / f32(size.x), VENEER_PI / f32(size.y));
    var sum = vec3f(0.0);
    for (var row = 0u; row < size.y; row += 1u) {
        let v = (f32(row) + 0.5) / f32(size.y);
        let row_solid_angle = step.x * step.y * sin(v * VENEER_PI);
        for (var column = 0u; column < size.x; column += 1u) {
            let d = veneer_equirect_direction(vec2f((f32(column) + 0.5) / f32(size.x), v));
            let cosine = dot(n, d);
            if cosine > 0.0 {
                sum += textureLoad(veneer_bake_source, vec2u(column, row), level).rgb * (cosine * row_solid_angle);
            }
        }
    }
    return vec4f(sum / VENEER_PI, 1.0);
}

// The split-sum table: for n·v along x and roughness along y, the scale and bias of F0
// in the directional albedo of GGX with Smith height-correlated visibility (the same BRDF
// as the key light's).
@fragment
fn veneer_bake_brdf(@builtin(position) position: vec4f) -> @location(0) vec4f {
    let uv = veneer_bake_uv_here(position);
    let n_v = max(uv.x, 1.0e-4);
    let alpha = max(uv.y * uv.y, 1.0e-3);
    let v = vec3f(sqrt(1.0 - n_v * n_v), 0.0, n_v);
    let n = vec3f(0.0, 0.0, 1.0);
    var scale = 0.0;
    var bias = 0.0;
    for (var i = 0u; i < veneer_bake.samples; i += 1u) {
        let h = veneer_ggx_half(veneer_hammersley(i, veneer_bake.samples), alpha, n);
        let l = 2.0 * dot(v, h) * h - v;
        let n_l = l.z;
        let n_h = max(h.z, 0.0);
        let v_h = max(dot(v, h), 0.0);
        if n_l > 0.0 {
            // BRDF · n·l / pdf with pdf = D n·h / (4 v·h): the distribution cancels.
            let g = veneer_smith_visibility(n_v, n_l, alpha) * 4.0 * v_h * n_l / max(n_h, 1.0e-6);
            let fresnel = pow(1.0 - v_h, 5.0);
            scale += (1.0 - fresnel) * g;
            bias += fresnel * g;
        }
    }
    return vec4f(scale, bias, 0.0, 1.0) / vec4f(f32(veneer_bake.samples), f32(veneer_bake.samples), 1.0, 1.0);
}
