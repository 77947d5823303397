//! Entry points of the mesh preview: the material on a mesh, lit by the graph's shading
//! (Blinn-Phong as in the seeds, or metallic-roughness), whose `veneer_shade` the
//! pipeline adds from render_lit_blinn_phong.wgsl or render_lit_metallic_roughness.wgsl.

struct VeneerMeshView {
    view_projection: mat4x4f,
    inverse_view_projection: mat4x4f,
    eye: vec4f,            // camera position, mesh space
    light_direction: vec4f, // towards the light, unit
    placement: vec4f,      // texture-space centre (xyz) and size (w) of the mesh
    time: f32,
    ambient: f32,
    unlit: u32,            // 1: show the albedo only (the flat 2D view)
    tone_map: u32,         // metallic-roughness: veneer_tone_map's kind
    exposure_scale: f32,   // metallic-roughness: light × this before tone mapping
    key_light: f32,        // metallic-roughness: the key light's irradiance
    environment_turn: vec2f, // metallic-roughness: cos, sin of the environment's turn about +y
    backdrop: u32,         // metallic-roughness: what shows behind the mesh (Backdrop as u32)
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

@fragment
fn veneer_mesh_fragment(input: VeneerVertexOut, @builtin(front_facing) front: bool) -> @location(0) vec4f {
    let view = veneer_mesh_view;
    let normal = normalize(input.normal);
    let surface = VeneerSurface(veneer_texture_position(input.position), normal, input.uv, input.fields, view.time);
    let material = veneer_material(surface);
    // VENEER_HEIGHT (set by the pipeline): the material's height can be non-zero.
    var relief = vec3f(0.0);
    if VENEER_HEIGHT {
        // Heights past 1e18 mesh units slope no more steeply on screen (nor overflow).
        let height = clamp(material.height / max(view.placement.w, 1.0e-6), -1.0e18, 1.0e18);
        relief = veneer_height_bump(input.position, normal, height);
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
    // VENEER_RELIEF (set by the pipeline): a bump, a height or a tilt perturbs the normal
    // (by at most 1e18 per axis, which already turns it all the way, so that it
    // normalises to a finite direction whatever the material gives); the shading's
    // veneer_lit_normal normalises it, or not (the thesis's).
    var n = normal;
    if VENEER_RELIEF {
        let limit = vec3f(1.0e18);
        n = veneer_lit_normal(normal + clamp(material.bump, -limit, limit) + clamp(relief, -limit, limit) + tilt);
    }
    // A back face (drawn where the material can be cut away or see-through) is lit
    // from its own side.
    n = select(-n, n, front);
    let l = view.light_direction.xyz;
    let v = normalize(view.eye.xyz - input.position);
    // veneer_shade comes from the graph's shading: render_lit_blinn_phong.wgsl,
    // render_lit_metallic_roughness.wgsl or render_lit_thesis.wgsl.
    var color = veneer_shade(material, n, v, l);
    color = select(color, material.albedo, view.unlit == 1u);
    // VENEER_BLENDED (set by the pipeline): this pass blends by the material's alpha.
    let alpha = select(1.0, clamp(material.alpha, 0.0, 1.0), VENEER_BLENDED);
    return vec4f(clamp(color, vec3f(0.0), vec3f(1.0)), alpha);
}
