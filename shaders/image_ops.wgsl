//! Image operations over buffers (see buffers.wgsl): blurs along a line, slope blur,
//! edges, curvature and ambient occlusion from a height, 2D transforms and making a
//! buffer tileable. Each reads its buffer at domain coordinates around `uv`.

// The mean of `samples` bilinear reads of `t` evenly along the segment from `uv - reach`
// to `uv + reach` (the ends included; one read at `uv` when `samples` is 1).
fn veneer_line_blur(t: texture_2d<f32>, edge: u32, uv: vec2f, reach: vec2f, samples: u32) -> vec4f {
    let n = max(samples, 1u);
    if n == 1u {
        return veneer_buffer_bilinear(t, edge, uv);
    }
    var sum = vec4f(0.0);
    for (var k = 0u; k < n; k++) {
        let along = 2.0 * f32(k) / f32(n - 1u) - 1.0;
        sum += veneer_buffer_bilinear(t, edge, uv + along * reach);
    }
    return sum / f32(n);
}

// A blur `length` domain units long through `uv` at `angle` degrees from +u (towards +v).
fn veneer_directional_blur(t: texture_2d<f32>, edge: u32, uv: vec2f, angle: f32, length: f32, samples: u32) -> vec4f {
    let radians = angle * 0.017453292;
    let reach = 0.5 * clamp(length, 0.0, 1.0) * vec2f(cos(radians), sin(radians));
    return veneer_line_blur(t, edge, uv, reach, samples);
}

// The gradient of the first lane of `t` at `uv` per domain unit, by central differences
// of bilinear reads one texel apart.
fn veneer_buffer_gradient(t: texture_2d<f32>, edge: u32, uv: vec2f) -> vec2f {
    let size = vec2f(textureDimensions(t));
    let d = 1.0 / size;
    let du = veneer_buffer_bilinear(t, edge, uv + vec2f(d.x, 0.0)).x - veneer_buffer_bilinear(t, edge, uv - vec2f(d.x, 0.0)).x;
    let dv = veneer_buffer_bilinear(t, edge, uv + vec2f(0.0, d.y)).x - veneer_buffer_bilinear(t, edge, uv - vec2f(0.0, d.y)).x;
    return vec2f(du, dv) * size * 0.5;
}

// Slope blur: `t` blurred at `uv` along the slope of the first lane of `s` (downhill for
// a positive `intensity`), over intensity × slope domain units (at most a quarter tile
// each way): steep places smear, flat ones stay sharp.
fn veneer_slope_blur(t: texture_2d<f32>, t_edge: u32, s: texture_2d<f32>, s_edge: u32, uv: vec2f, intensity: f32, samples: u32) -> vec4f {
    let slope = veneer_buffer_gradient(s, s_edge, uv);
    let reach = clamp(-0.5 * intensity * slope, vec2f(-0.25), vec2f(0.25));
    return veneer_line_blur(t, t_edge, uv + reach, reach, samples);
}

// The edges of the first lane of `t`: the length of its Sobel gradient with taps `width`
// texels apart, per texel, times `strength`, clamped to [0, 1].
fn veneer_edge_detect(t: texture_2d<f32>, edge: u32, uv: vec2f, width: f32, strength: f32) -> f32 {
    let d = max(width, 0.0) / vec2f(textureDimensions(t));
    var h: array<f32, 9>;
    for (var k = 0; k < 9; k++) {
        let offset = vec2f(f32(k % 3 - 1), f32(k / 3 - 1));
        h[k] = veneer_buffer_bilinear(t, edge, uv + offset * d).x;
    }
    let gx = (h[2] + 2.0 * h[5] + h[8] - h[0] - 2.0 * h[3] - h[6]) / 8.0;
    let gy = (h[6] + 2.0 * h[7] + h[8] - h[0] - 2.0 * h[1] - h[2]) / 8.0;
    return clamp(strength * sqrt(gx * gx + gy * gy), 0.0, 1.0);
}

// The curvature of the height (first lane) of `t` at `uv`: 0.5 where flat, brighter on
// ridges, darker in hollows. Minus the Laplacian of taps `radius` domain units apart,
// times `strength`, clamped to [0, 1].
fn veneer_curvature(t: texture_2d<f32>, edge: u32, uv: vec2f, radius: f32, strength: f32) -> f32 {
    let r = max(radius, 0.0);
    let centre = veneer_buffer_bilinear(t, edge, uv).x;
    let around = veneer_buffer_bilinear(t, edge, uv + vec2f(r, 0.0)).x + veneer_buffer_bilinear(t, edge, uv - vec2f(r, 0.0)).x
        + veneer_buffer_bilinear(t, edge, uv + vec2f(0.0, r)).x + veneer_buffer_bilinear(t, edge, uv - vec2f(0.0, r)).x;
    return clamp(0.5 + strength * (4.0 * centre - around), 0.0, 1.0);
}

// Ambient occlusion of the height (first lane, times `depth` domain units) of `t` at
// `uv`, horizon-based: in each of `directions` directions the steepest rise over
// `steps` reads out to `radius` domain units gives the horizon's elevation; the
// occlusion is 1 minus the mean of the horizons' sines (1 unoccluded).
fn veneer_height_occlusion(t: texture_2d<f32>, edge: u32, uv: vec2f, radius: f32, depth: f32, directions: u32, steps: u32) -> f32 {
    let h0 = veneer_buffer_bilinear(t, edge, uv).x * depth;
    let r = max(radius, 1.0e-6);
    let n = max(directions, 1u);
    let m = max(steps, 1u);
    var occluded = 0.0;
    for (var k = 0u; k < n; k++) {
        let angle = 6.2831855 * f32(k) / f32(n);
        let direction = vec2f(cos(angle), sin(angle));
        var rise = 0.0;
        for (var j = 1u; j <= m; j++) {
            let distance = r * f32(j) / f32(m);
            let h = veneer_buffer_bilinear(t, edge, uv + distance * direction).x * depth;
            rise = max(rise, (h - h0) / distance);
        }
        occluded += rise / sqrt(1.0 + rise * rise);
    }
    return 1.0 - occluded / f32(n);
}

// `t` moved by `offset`, turned `angle` degrees and scaled by `scale` about the tile's
// centre: the read at `uv` is at the inverse transform of `uv`. A zero scale reads at
// the centre.
fn veneer_transform_2d_uv(uv: vec2f, offset: vec2f, angle: f32, scale: vec2f) -> vec2f {
    let radians = -angle * 0.017453292;
    let c = cos(radians);
    let s = sin(radians);
    let safe = select(scale, vec2f(1.0e30), abs(scale) < vec2f(1.0e-30));
    let p = (veneer_finite_vec2f(uv - 0.5 - offset)) / safe;
    return vec2f(c * p.x - s * p.y, s * p.x + c * p.y) + 0.5;
}

// `t` made tileable: within `width` (a fraction of the tile, at most a half) of each
// edge it fades to copies moved half a tile, which continue across the edges; the
// result repeats whatever `t` holds.
fn veneer_make_tileable(t: texture_2d<f32>, edge: u32, uv: vec2f, width: f32) -> vec4f {
    let p = uv - floor(uv);
    let w = clamp(width, 1.0e-4, 0.5);
    let near = min(p, 1.0 - p);
    let fade = 1.0 - smoothstep(vec2f(0.0), vec2f(w), near);
    let moved = p + 0.5;
    let a = veneer_buffer_bilinear(t, edge, p);
    let bu = veneer_buffer_bilinear(t, edge, vec2f(moved.x - floor(moved.x), p.y));
    let bv = veneer_buffer_bilinear(t, edge, vec2f(p.x, moved.y - floor(moved.y)));
    let buv = veneer_buffer_bilinear(t, edge, moved - floor(moved));
    return mix(mix(a, bu, fade.x), mix(bv, buv, fade.x), fade.y);
}

// `t` read at `uv` moved `amount` × `intensity` domain units along `angle` degrees from
// +u (a directional warp: wire a mask or noise to `intensity`).
fn veneer_directional_warp_uv(uv: vec2f, intensity: f32, angle: f32, amount: f32) -> vec2f {
    let radians = angle * 0.017453292;
    let reach = clamp(amount * intensity, -1.0e6, 1.0e6);
    return uv + reach * vec2f(cos(radians), sin(radians));
}

// `t` read at `uv` moved downhill along the slope of the first lane of `s`, `amount` ×
// slope domain units (at most a quarter tile each way): a warp by a gradient.
fn veneer_slope_warp(t: texture_2d<f32>, t_edge: u32, s: texture_2d<f32>, s_edge: u32, uv: vec2f, amount: f32) -> vec4f {
    let slope = veneer_buffer_gradient(s, s_edge, uv);
    let reach = clamp(-amount * slope, vec2f(-0.25), vec2f(0.25));
    return veneer_buffer_bilinear(t, t_edge, uv + reach);
}
