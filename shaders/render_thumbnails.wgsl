//! Entry points of the node thumbnails: one material module drawn into square tiles of
//! an atlas, each tile with its own parameter block (which picks the node it shows).
//! A tile samples the plane y = Y over the preview square like the flat render, with
//! uv running 0 to 1 across the tile, fields 0; albedo clamped to [0, 1] goes to an
//! 8-bit target without colour-space conversion.

struct VeneerThumbnailView {
    rect: vec4f,   // x0, z0, x1, z1
    plane_y: f32,
    time: f32,
    tile: f32,     // a tile's width and height in pixels
    padding: f32,
}

@group(0) @binding(0) var<uniform> veneer_thumbnail_view: VeneerThumbnailView;

@vertex
fn veneer_thumbnail_vertex(@builtin(vertex_index) index: u32) -> @builtin(position) vec4f {
    let corner = vec2f(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4f(corner * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn veneer_thumbnail_fragment(@builtin(position) pixel: vec4f) -> @location(0) vec4f {
    let view = veneer_thumbnail_view;
    let t = (pixel.xy - floor(pixel.xy / view.tile) * view.tile) / view.tile;
    let position = vec3f(view.rect.x + (view.rect.z - view.rect.x) * t.x, view.plane_y, view.rect.y + (view.rect.w - view.rect.y) * t.y);
    let surface = VeneerSurface(position, vec3f(0.0, 1.0, 0.0), t, VENEER_FLAT_FIELDS, view.time);
    let material = veneer_material(surface);
    return vec4f(clamp(material.albedo, vec3f(0.0), vec3f(1.0)), 1.0);
}
