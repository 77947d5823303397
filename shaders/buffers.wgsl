//! Buffers: the textures that passes render, read at texels and between them. Every
//! function takes the buffer and its edge mode first (0 wraps, 1 clamps, 2 mirrors), the
//! pair the compiler hands a node for each sampled input. A buffer spans the domain
//! coordinate (the surface uv) from 0 to 1; texel i's centre lies at (i + 0.5) / size.

// Index `i` of an axis of `n` texels under edge mode `edge`: wrapped, clamped, or
// mirrored (..., 1, 0, 0, 1, ..., n - 1, n - 1, n - 2, ...). Scalar integers only.
fn veneer_edge_index(i: i32, n: i32, edge: u32) -> i32 {
    if edge == 1u {
        return clamp(i, 0, n - 1);
    }
    if edge == 2u {
        let period = 2 * n;
        let m = ((i % period) + period) % period;
        return select(m, period - 1 - m, m >= n);
    }
    return ((i % n) + n) % n;
}

// Texel `texel` of buffer `t`, beyond the edges by `edge`.
fn veneer_buffer_texel(t: texture_2d<f32>, edge: u32, texel: vec2i) -> vec4f {
    let size = vec2i(textureDimensions(t));
    let x = veneer_edge_index(texel.x, size.x, edge);
    let y = veneer_edge_index(texel.y, size.y, edge);
    return textureLoad(t, vec2i(x, y), 0);
}

// The place of domain coordinate `uv` among the texel centres of a buffer of `size`
// texels (texel i's centre at i), first brought near the buffer so that any coordinate,
// however large, gives a finite place: by whole periods when wrapping, by two periods
// when mirroring, to one buffer beyond each edge when clamping.
fn veneer_buffer_place(uv: vec2f, size: vec2f, edge: u32) -> vec2f {
    var near = uv - floor(uv);
    if edge == 1u {
        near = clamp(uv, vec2f(-1.0), vec2f(2.0));
    } else if edge == 2u {
        near = uv - 2.0 * floor(uv * 0.5);
    }
    return near * size - 0.5;
}

// Buffer `t` at domain coordinate `uv`, interpolated bilinearly between texel centres.
fn veneer_buffer_bilinear(t: texture_2d<f32>, edge: u32, uv: vec2f) -> vec4f {
    let place = veneer_buffer_place(uv, vec2f(textureDimensions(t)), edge);
    let base = floor(place);
    let f = place - base;
    let i = vec2i(base);
    let top = mix(veneer_buffer_texel(t, edge, i), veneer_buffer_texel(t, edge, i + vec2i(1, 0)), f.x);
    let bottom = mix(veneer_buffer_texel(t, edge, i + vec2i(0, 1)), veneer_buffer_texel(t, edge, i + vec2i(1, 1)), f.x);
    return mix(top, bottom, f.y);
}

// The Catmull-Rom weights of the four texels around a place `f` (0..1) past the second.
fn veneer_catmull_rom(f: f32) -> vec4f {
    let f2 = f * f;
    let f3 = f2 * f;
    return vec4f(
        -0.5 * f3 + f2 - 0.5 * f,
        1.5 * f3 - 2.5 * f2 + 1.0,
        -1.5 * f3 + 2.0 * f2 + 0.5 * f,
        0.5 * f3 - 0.5 * f2,
    );
}

// Buffer `t` at domain coordinate `uv`, interpolated bicubically (Catmull-Rom, 4x4
// texels): sharper than bilinear when a buffer is magnified.
fn veneer_buffer_bicubic(t: texture_2d<f32>, edge: u32, uv: vec2f) -> vec4f {
    let place = veneer_buffer_place(uv, vec2f(textureDimensions(t)), edge);
    let base = floor(place);
    let wx = veneer_catmull_rom(place.x - base.x);
    let wy = veneer_catmull_rom(place.y - base.y);
    let i = vec2i(base) - vec2i(1);
    var sum = vec4f(0.0);
    for (var y = 0; y < 4; y++) {
        var row = vec4f(0.0);
        for (var x = 0; x < 4; x++) {
            row += wx[x] * veneer_buffer_texel(t, edge, i + vec2i(x, y));
        }
        sum += wy[y] * row;
    }
    return sum;
}

// One axis (`axis` one texel along x or y) of a Gaussian blur at `texel`: `radius`
// texels is three standard deviations, and the taps reach ceil(radius) texels each
// side (at most 1024), weighted exp(-k^2 / 2 sigma^2) and normalised. Summed in f32 from
// the centre outwards, so wide radii do not band.
fn veneer_blur_axis(t: texture_2d<f32>, edge: u32, texel: vec2i, axis: vec2i, radius: f32) -> vec4f {
    let sigma = max(radius, 1.0e-3) / 3.0;
    let reach = i32(ceil(clamp(radius, 0.0, 1024.0)));
    var sum = veneer_buffer_texel(t, edge, texel);
    var weight = 1.0;
    for (var k = 1; k <= reach; k++) {
        let w = exp(-0.5 * f32(k * k) / (sigma * sigma));
        let pair = veneer_buffer_texel(t, edge, texel + k * axis) + veneer_buffer_texel(t, edge, texel - k * axis);
        sum += w * pair;
        weight += 2.0 * w;
    }
    return sum / weight;
}

// The tangent-space normal of the height (first lane) in `t` at `uv`: Sobel differences
// of the bilinear height one texel apart, as slopes per domain unit times `strength`;
// `y_sign` 1 points y up the image (OpenGL), -1 down (DirectX).
fn veneer_height_normal(t: texture_2d<f32>, edge: u32, uv: vec2f, strength: f32, y_sign: f32) -> vec3f {
    let size = vec2f(textureDimensions(t));
    let d = 1.0 / size;
    var h: array<f32, 9>;
    for (var k = 0; k < 9; k++) {
        let offset = vec2f(f32(k % 3 - 1), f32(k / 3 - 1));
        h[k] = veneer_buffer_bilinear(t, edge, uv + offset * d).x;
    }
    let du = (h[2] + 2.0 * h[5] + h[8] - h[0] - 2.0 * h[3] - h[6]) * size.x / 8.0;
    let dv = (h[6] + 2.0 * h[7] + h[8] - h[0] - 2.0 * h[1] - h[2]) * size.y / 8.0;
    return veneer_safe_normalize_vec3f(vec3f(-strength * du, y_sign * strength * dv, 1.0));
}
