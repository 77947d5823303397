//! Entry points of a material's surface passes over a mesh's UV layout: each triangle
//! drawn at its texture coordinates (a buffer spans uv 0 to 1, its top row at v = 0),
//! `veneer_pass` evaluated at the point's texture-space position, as the mesh preview
//! and the UV bake place it.

struct VeneerPassMeshView {
    placement: vec4f,  // texture-space centre (xyz) and size (w) of the mesh
    time: f32,
}

@group(0) @binding(0) var<uniform> veneer_pass_mesh_view: VeneerPassMeshView;

struct VeneerPassMeshOut {
    @builtin(position) clip: vec4f,
    @location(0) position: vec3f,
    @location(1) normal: vec3f,
    @location(2) uv: vec2f,
    @location(3) fields: vec4f,
}

@vertex
fn veneer_pass_mesh_vertex(
    @location(0) position: vec3f,
    @location(1) normal: vec3f,
    @location(2) uv: vec2f,
    @location(3) fields: vec4f,
) -> VeneerPassMeshOut {
    var out: VeneerPassMeshOut;
    out.clip = vec4f(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, 0.0, 1.0);
    out.position = position;
    out.normal = normal;
    out.uv = uv;
    out.fields = fields;
    return out;
}

@fragment
fn veneer_pass_mesh_fragment(input: VeneerPassMeshOut) -> @location(0) vec4f {
    let view = veneer_pass_mesh_view;
    let position = input.position * view.placement.w + view.placement.xyz;
    let surface = VeneerSurface(position, normalize(input.normal), input.uv, input.fields, view.time);
    return veneer_pass(surface);
}
