//! Entry points of UV-layout baking: each triangle drawn at its texture coordinates, the
//! material evaluated at its object-space position. Texels no triangle covers keep the
//! clear value (all bits set: NaN), so the baker can fill them in. The lanes of
//! `fields` set in `texel_lanes` are read per texel from `veneer_uv_texel_fields` (mesh
//! fields cast from every texel, at its size, read nearest), the others interpolated
//! between the vertices.

struct VeneerUvView {
    placement: vec4f,  // texture-space centre (xyz) and size (w) of the mesh
    tile: vec4f,       // this tile's first texel (xy) and size in texels (zw)
    size: f32,         // the whole map's width and height in texels
    time: f32,
    channels: u32,     // which outputs (render_channels.wgsl)
    texel_lanes: u32,  // bit k: lane k of `fields` comes from veneer_uv_texel_fields
}

@group(0) @binding(0) var<uniform> veneer_uv_view: VeneerUvView;
@group(0) @binding(1) var veneer_uv_texel_fields: texture_2d<f32>;

/// The fields at this fragment: the vertices' interpolated, with the lanes of
/// `texel_lanes` from the texel fields' texel under it.
fn veneer_uv_fields(interpolated: vec4f, pixel: vec2f) -> vec4f {
    let view = veneer_uv_view;
    let dims = textureDimensions(veneer_uv_texel_fields);
    let at = vec2u((pixel + view.tile.xy) * f32(dims.x) / view.size);
    let stored = textureLoad(veneer_uv_texel_fields, min(at, dims - 1u), 0);
    let lanes = (vec4u(view.texel_lanes) & vec4u(1u, 2u, 4u, 8u)) != vec4u(0u);
    return select(interpolated, stored, lanes);
}

struct VeneerUvOut {
    @builtin(position) clip: vec4f,
    @location(0) position: vec3f,
    @location(1) normal: vec3f,
    @location(2) uv: vec2f,
    @location(3) fields: vec4f,
}

@vertex
fn veneer_uv_vertex(
    @location(0) position: vec3f,
    @location(1) normal: vec3f,
    @location(2) uv: vec2f,
    @location(3) fields: vec4f,
) -> VeneerUvOut {
    let view = veneer_uv_view;
    let texel = (uv * view.size - view.tile.xy) / view.tile.zw;
    var out: VeneerUvOut;
    out.clip = vec4f(texel.x * 2.0 - 1.0, 1.0 - texel.y * 2.0, 0.0, 1.0);
    out.position = position;
    out.normal = normal;
    out.uv = uv;
    out.fields = fields;
    return out;
}

@fragment
fn veneer_uv_fragment(input: VeneerUvOut) -> @location(0) vec4u {
    let view = veneer_uv_view;
    let position = input.position * view.placement.w + view.placement.xyz;
    let normal = normalize(input.normal);
    // Screen space is UV space here, so the frame's derivatives are the layout's own.
    let frame = veneer_tangent_frame(input.position, normal, input.uv);
    let fields = veneer_uv_fields(input.fields, input.clip.xy);
    let material = veneer_material(VeneerSurface(position, normal, input.uv, fields, view.time));
    return veneer_bake_channels(material, view.channels, frame);
}
