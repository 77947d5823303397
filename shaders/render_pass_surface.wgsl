//! Entry points of a material's surface passes over the flat domain: `veneer_pass` at
//! every texel centre of its buffer, the texel's place in the rectangle as the surface
//! uv (the domain coordinate) and its position computed as `render_flat.wgsl` does.

struct VeneerPassView {
    rect: vec4f,  // x0, z0, x1, z1
    size: vec2f,  // the buffer's width and height in texels
    plane_y: f32,
    time: f32,
}

@group(0) @binding(0) var<uniform> veneer_pass_view: VeneerPassView;

@fragment
fn veneer_pass_fragment(@builtin(position) pixel: vec4f) -> @location(0) vec4f {
    let view = veneer_pass_view;
    let t = pixel.xy / view.size;
    let position = vec3f(view.rect.x + (view.rect.z - view.rect.x) * t.x, view.plane_y, view.rect.y + (view.rect.w - view.rect.y) * t.y);
    return veneer_pass(VeneerSurface(position, vec3f(0.0, 1.0, 0.0), t, VENEER_FLAT_FIELDS, view.time));
}
