//! Entry points of the mesh preview: the material on a mesh, lit by the graph's shading
//! (Blinn-Phong as in the seeds, or metallic-roughness).

struct VeneerMeshView {
    view_projection: mat4x4f,
    eye: vec4f,            // camera position, mesh space
    light_direction: vec4f, // towards the light, unit
    placement: vec4f,      // texture-space centre (xyz) and size (w) of the mesh
    time: f32,
    ambient: f32,
    unlit: u32,            // 1: show the albedo only (the flat 2D view)
    tone_map: u32,         // metallic-roughness: veneer_tone_map's kind
    exposure_scale: f32,   // metallic-roughness: light × this before tone mapping
}

@group(0) @binding(0) var<uniform> veneer_mesh_view: VeneerMeshView;

struct VeneerVertexOut {
    @builtin(position) clip: vec4f,
    @location(0) position: vec3f,
    @location(1) normal: vec3f,
    @location(2) uv: vec2f,
    @location(3) fields: vec4f,
}

struct VeneerVertexIn {
    @location(0) position: vec3f,
    @location(1) normal: vec3f,
    @location(2) uv: vec2f,
    @location(3) fields: vec4f,  // distance fields, 0 where none was computed
}

// The vertex at `position` (mesh space, moved or not) with the rest of `input`.
fn veneer_vertex_at(input: VeneerVertexIn, position: vec3f) -> VeneerVertexOut {
    var out: VeneerVertexOut;
    out.clip = veneer_mesh_view.view_projection * vec4f(position, 1.0);
    out.position = position;
    out.normal = input.normal;
    out.uv = input.uv;
    out.fields = input.fields;
    return out;
}

@vertex
fn veneer_mesh_vertex(input: VeneerVertexIn) -> VeneerVertexOut {
    return veneer_vertex_at(input, input.position);
}

// The normal perturbation of a height relief (mesh units) over the surface, from the
// screen-space derivatives of the height and the position (Mikkelsen's surface
// gradient); 0 where the height is constant. Displaced meshes take their silhouette
// from the vertex stage and their shading from this.
fn veneer_height_bump(position: vec3f, normal: vec3f, height: f32) -> vec3f {
    let dx = dpdx(position);
    let dy = dpdy(position);
    let across_y = cross(dy, normal);
    let across_x = cross(normal, dx);
    let det = dot(dx, across_y);
    let gradient = sign(det) * (dpdx(height) * across_y + dpdy(height) * across_x);
    return select(-gradient / abs(det), vec3f(0.0), abs(det) < 1.0e-20);
}

// Where a texture-space point of the mesh sits.
fn veneer_texture_position(position: vec3f) -> vec3f {
    return position * veneer_mesh_view.placement.w + veneer_mesh_view.placement.xyz;
}

// Cook-Torrance GGX (Trowbridge-Reitz distribution, Smith height-correlated
// visibility, Schlick Fresnel) of the key light, as glTF 2.0's appendix B gives it,
// with a Lambert diffuse for the dielectric part; radiance towards the eye per unit
// light, cos θ included.
fn veneer_ggx_light(n: vec3f, v: vec3f, l: vec3f, base: vec3f, metallic: f32, roughness: f32) -> vec3f {
    let h = normalize(l + v);
    let n_l = max(dot(n, l), 0.0);
    let n_v = max(dot(n, v), 1.0e-4);
    let n_h = max(dot(n, h), 0.0);
    let v_h = max(dot(v, h), 0.0);
    let alpha = max(roughness * roughness, 1.0e-3);
    let alpha2 = alpha * alpha;
    let f0 = mix(vec3f(0.04), base, metallic);
    let fresnel = f0 + (1.0 - f0) * pow(1.0 - v_h, 5.0);
    let d = n_h * n_h * (alpha2 - 1.0) + 1.0;
    let distribution = alpha2 / (VENEER_PI * d * d);
    let visibility = 0.5 / max(n_l * sqrt(n_v * n_v * (1.0 - alpha2) + alpha2) + n_v * sqrt(n_l * n_l * (1.0 - alpha2) + alpha2), 1.0e-8);
    let diffuse = (1.0 - fresnel) * (1.0 - metallic) * base / VENEER_PI;
    return (diffuse + fresnel * distribution * visibility) * n_l;
}

const VENEER_PI: f32 = 3.14159265358979;

// The sRGB transfer function (linear light to the encoded value a display shows).
fn veneer_srgb_encode(linear: vec3f) -> vec3f {
    let c = clamp(linear, vec3f(0.0), vec3f(1.0));
    return select(1.055 * pow(c, vec3f(1.0 / 2.4)) - 0.055, 12.92 * c, c <= vec3f(0.0031308));
}

@fragment
fn veneer_mesh_fragment(input: VeneerVertexOut, @builtin(front_facing) front: bool) -> @location(0) vec4f {
    let view = veneer_mesh_view;
    let normal = normalize(input.normal);
    let surface = VeneerSurface(veneer_texture_position(input.position), normal, input.uv, input.fields, view.time);
    let material = veneer_material(surface);
    // VENEER_HEIGHT (set by the pipeline): the material's height can be non-zero.
    var relief = vec3f(0.0);
    if VENEER_HEIGHT {
        relief = veneer_height_bump(input.position, normal, material.height / max(view.placement.w, 1.0e-6));
    }
    // VENEER_NORMAL (set by the pipeline): the tangent-space normal can be tilted.
    var tilt = vec3f(0.0);
    if VENEER_NORMAL {
        tilt = veneer_tilt(veneer_tangent_frame(input.position, normal, input.uv), material.normal);
    }
    // VENEER_MIN_ALPHA, VENEER_MAX_ALPHA (set by the pipeline): the alphas this pass
    // draws; what is below a cutoff is cut out, what another pass draws is left to it.
    if material.alpha < VENEER_MIN_ALPHA || material.alpha >= VENEER_MAX_ALPHA {
        discard;
    }
    // VENEER_RELIEF (set by the pipeline): a bump, a height or a tilt perturbs the normal.
    var n = normal;
    if VENEER_RELIEF {
        n = normalize(normal + material.bump + relief + tilt);
    }
    // A back face (drawn where the material can be cut away or see-through) is lit
    // from its own side.
    n = select(-n, n, front);
    let l = view.light_direction.xyz;
    let v = normalize(view.eye.xyz - input.position);
    let emitted = material.emission * material.emission_strength;
    var color: vec3f;
    // VENEER_METALLIC_ROUGHNESS (set by the pipeline): the graph's shading.
    if VENEER_METALLIC_ROUGHNESS {
        let base = clamp(material.albedo, vec3f(0.0), vec3f(1.0));
        let metallic = clamp(material.metallic, 0.0, 1.0);
        let roughness = clamp(material.roughness, 0.0, 1.0);
        let direct = veneer_ggx_light(n, v, l, base, metallic, roughness) * VENEER_KEY_LIGHT;
        let ambient = veneer_ambient(n, v, base, metallic, roughness) * clamp(material.occlusion, 0.0, 1.0);
        color = veneer_srgb_encode(veneer_tone_map((direct + ambient + emitted) * view.exposure_scale, view.tone_map));
    } else {
        let h = normalize(l + v);
        let lambert = max(dot(n, l), 0.0);
        let highlight = select(0.0, pow(max(dot(n, h), 0.0), max(material.shininess, 1.0)), lambert > 0.0);
        color = material.albedo * (view.ambient + (1.0 - view.ambient) * lambert) + material.specular * highlight
            + emitted;
    }
    color = select(color, material.albedo, view.unlit == 1u);
    // VENEER_BLENDED (set by the pipeline): this pass blends by the material's alpha.
    let alpha = select(1.0, clamp(material.alpha, 0.0, 1.0), VENEER_BLENDED);
    return vec4f(clamp(color, vec3f(0.0), vec3f(1.0)), alpha);
}

// Irradiance of the key light (linear units) on metallic-roughness materials.
const VENEER_KEY_LIGHT: f32 = 2.5;
// The uniform sky light metallic-roughness materials see besides the key light.
const VENEER_SKY: vec3f = vec3f(0.30, 0.32, 0.36);

// What a uniform sky of radiance VENEER_SKY reflects: Lambert diffuse, and specular by
// Karis's analytic fit of the split-sum environment BRDF ("Physically Based Shading on
// Mobile", 2014).
fn veneer_ambient(n: vec3f, v: vec3f, base: vec3f, metallic: f32, roughness: f32) -> vec3f {
    let n_v = max(dot(n, v), 1.0e-4);
    let c0 = vec4f(-1.0, -0.0275, -0.572, 0.022);
    let c1 = vec4f(1.0, 0.0425, 1.04, -0.04);
    let r = roughness * c0 + c1;
    let a004 = min(r.x * r.x, exp2(-9.28 * n_v)) * r.x + r.y;
    let scale_bias = vec2f(-1.04, 1.04) * a004 + r.zw;
    let f0 = mix(vec3f(0.04), base, metallic);
    let specular = f0 * scale_bias.x + scale_bias.y;
    let diffuse = base * (1.0 - metallic) * (1.0 - specular);
    return (diffuse + specular) * VENEER_SKY;
}
