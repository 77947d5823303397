//! Entry points of the flat render: the material's albedo over the plane y = Y, one
//! sample per pixel centre (the `veneer render --flat` contract). The f32 bits go to an
//! integer target, which every backend can render to and which reads back exactly.

struct VeneerFlatView {
    rect: vec4f,          // x0, z0, x1, z1
    pixel_offset: vec2f,  // of this tile within the whole image
    plane_y: f32,
    size: f32,            // the whole image's width and height in pixels
    time: f32,
    channels: u32,        // which outputs (render_channels.wgsl)
    domain_uv: u32,       // 1: uv is the pixel's place in the rectangle (multi-pass materials); 0: uv 0
}

@group(0) @binding(0) var<uniform> veneer_flat_view: VeneerFlatView;

@vertex
fn veneer_flat_vertex(@builtin(vertex_index) index: u32) -> @builtin(position) vec4f {
    let corner = vec2f(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4f(corner * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn veneer_flat_fragment(@builtin(position) pixel: vec4f) -> @location(0) vec4u {
    let view = veneer_flat_view;
    let t = (pixel.xy + view.pixel_offset) / view.size;
    let position = vec3f(view.rect.x + (view.rect.z - view.rect.x) * t.x, view.plane_y, view.rect.y + (view.rect.w - view.rect.y) * t.y);
    let uv = select(vec2f(0.0), t, view.domain_uv == 1u);
    let surface = VeneerSurface(position, vec3f(0.0, 1.0, 0.0), uv, VENEER_FLAT_FIELDS, view.time);
    let material = veneer_material(surface);
    // The plane's tangent frame: x along +x, y up the image (-z), z the normal (+y).
    let frame = mat3x3f(vec3f(1.0, 0.0, 0.0), vec3f(0.0, 0.0, -1.0), vec3f(0.0, 1.0, 0.0));
    return veneer_bake_channels(material, view.channels, frame);
}
