//! Colour adjustments (Blender's Hue/Saturation/Value, Brightness/Contrast, Gamma and
//! Invert nodes; Photoshop's and Substance's Levels) and blend modes with a factor
//! (Blender's MixRGB). Every function returns a finite colour for any finite input.

// `a (1 - t) + b t` written out (a GPU's mix may compute a + t (b - a), which overflows
// for far-apart finite values), `t` clamped to [0, 1] and the result to the finite range.
fn veneer_colour_mix(a: vec3f, b: vec3f, t: f32) -> vec3f {
    let s = clamp(t, 0.0, 1.0);
    return clamp(a * (1.0 - s) + b * s, vec3f(-3.0e38), vec3f(3.0e38));
}

// RGB to (hue, saturation, value) as Blender's rgb_to_hsv: value = max channel, saturation
// = (max - min) / max, hue in [0, 1] turns (red 0, green 1/3, blue 2/3). Saturation is 1
// where a channel is negative (Blender's would exceed 1), and 0 with hue 0 where max <= 0
// (grey). The hue uses halved channels, an exact scaling, so no difference overflows.
fn veneer_rgb_to_hsv(c: vec3f) -> vec3f {
    let cmax = max(c.x, max(c.y, c.z));
    let cmin = min(c.x, min(c.y, c.z));
    let s = select(select(1.0, (cmax - cmin) / cmax, cmin > 0.0), 0.0, cmax <= 0.0);
    let span = 0.5 * cmax - 0.5 * cmin;
    let d = (vec3f(0.5 * cmax) - 0.5 * c) / select(span, 1.0, span == 0.0);
    let sector = select(select(4.0 + d.y - d.x, 2.0 + d.x - d.z, c.y == cmax), d.z - d.y, c.x == cmax) / 6.0;
    let h = select(sector, sector + 1.0, sector < 0.0);
    return vec3f(select(h, 0.0, s == 0.0 || span == 0.0), s, cmax);
}

// (hue, saturation, value) to RGB as Blender's hsv_to_rgb, with the hue wrapped (any
// number of turns) and the saturation clamped to [0, 1].
fn veneer_hsv_to_rgb(hsv: vec3f) -> vec3f {
    let turn = fract(hsv.x);
    let h = select(turn, 0.0, turn >= 1.0) * 6.0;
    let s = clamp(hsv.y, 0.0, 1.0);
    let v = hsv.z;
    let i = min(floor(h), 5.0);
    let f = h - i;
    let p = v * (1.0 - s);
    let q = v * (1.0 - s * f);
    let t = v * (1.0 - s * (1.0 - f));
    if i == 0.0 {
        return vec3f(v, t, p);
    }
    if i == 1.0 {
        return vec3f(q, v, p);
    }
    if i == 2.0 {
        return vec3f(p, v, t);
    }
    if i == 3.0 {
        return vec3f(p, q, v);
    }
    if i == 4.0 {
        return vec3f(t, p, v);
    }
    return vec3f(v, p, q);
}

// Blender's Hue/Saturation/Value node at factor 1: the hue turned by `hue_shift` turns
// (0: unchanged; Blender's Hue input h is the shift h - 0.5), the saturation times
// `saturation` clamped to [0, 1], the value times `value`.
fn veneer_hue_saturation_value(c: vec3f, hue_shift: f32, saturation: f32, value: f32) -> vec3f {
    let hsv = veneer_rgb_to_hsv(c);
    let h = fract(hsv.x + fract(hue_shift));
    let s = clamp(hsv.y * saturation, 0.0, 1.0);
    let v = clamp(hsv.z * value, -3.0e38, 3.0e38);
    return veneer_hsv_to_rgb(vec3f(h, s, v));
}

// The Hue/Saturation/Value node: the adjusted colour blended over `c` by `factor`.
fn veneer_hue_saturation_value_mix(c: vec3f, hue_shift: f32, saturation: f32, value: f32, factor: f32) -> vec3f {
    return veneer_colour_mix(c, veneer_hue_saturation_value(c, hue_shift, saturation, value), factor);
}

// Blender's Brightness/Contrast: max((1 + contrast) c + brightness - contrast / 2, 0) per
// channel. The channels and the contrast are clamped to +-1e18 and the result to 3e38, so
// no product or sum overflows into a NaN.
fn veneer_brightness_contrast(c: vec3f, brightness: f32, contrast: f32) -> vec3f {
    let k = clamp(contrast, -1.0e18, 1.0e18);
    let x = clamp(c, vec3f(-1.0e18), vec3f(1.0e18));
    return min(max((1.0 + k) * x + (brightness - 0.5 * k), vec3f(0.0)), vec3f(3.0e38));
}

// Blender's Gamma: c^gamma for the positive channels (overflow clamped to 3e38), the
// others unchanged.
fn veneer_gamma(c: vec3f, gamma: f32) -> vec3f {
    return select(c, veneer_safe_pow_vec3f(c, vec3f(gamma)), c > vec3f(0.0));
}

// Blender's Invert: c blended towards 1 - c by `factor` (clamped to [0, 1]).
fn veneer_invert(c: vec3f, factor: f32) -> vec3f {
    return veneer_colour_mix(c, 1.0 - c, factor);
}

// Levels (Photoshop, Substance): each channel's position t between `in_black` and
// `in_white`, clamped to [0, 1] (a step at in_black when they are equal; reversed
// inputs invert), raised to 1 / gamma (gamma clamped to [1e-4, 1e4]; 1 leaves t exactly
// as it is; above 1 brightens the midtones), then carried from `out_black` to `out_white`.
fn veneer_levels(c: vec3f, in_black: f32, in_white: f32, gamma: f32, out_black: f32, out_white: f32) -> vec3f {
    let span = 0.5 * in_white - 0.5 * in_black;
    let ramp = clamp((0.5 * c - 0.5 * in_black) / select(span, 1.0, span == 0.0), vec3f(0.0), vec3f(1.0));
    let t = select(ramp, step(vec3f(in_black), c), span == 0.0);
    let g = clamp(gamma, 1.0e-4, 1.0e4);
    let curved = select(veneer_safe_pow_vec3f(t, vec3f(1.0 / g)), t, g == 1.0);
    return clamp(out_black * (1.0 - curved) + out_white * curved, vec3f(-3.0e38), vec3f(3.0e38));
}

// Blender's Multiply blend: a * b, blended over `a` by `factor`.
fn veneer_blend_multiply(a: vec3f, b: vec3f, factor: f32) -> vec3f {
    return veneer_colour_mix(a, clamp(a * b, vec3f(-3.0e38), vec3f(3.0e38)), factor);
}

// Blender's Screen blend: 1 - (1 - a)(1 - b), blended over `a` by `factor`.
fn veneer_blend_screen(a: vec3f, b: vec3f, factor: f32) -> vec3f {
    let screen = 1.0 - (1.0 - a) * (1.0 - b);
    return veneer_colour_mix(a, clamp(screen, vec3f(-3.0e38), vec3f(3.0e38)), factor);
}

// Blender's Overlay blend: 2ab where a < 0.5, else 1 - 2(1 - a)(1 - b), blended over `a`
// by `factor`. The products are taken before the doubling, so none is infinity times 0.
fn veneer_blend_overlay(a: vec3f, b: vec3f, factor: f32) -> vec3f {
    let overlay = select(1.0 - 2.0 * ((1.0 - a) * (1.0 - b)), 2.0 * (a * b), a < vec3f(0.5));
    return veneer_colour_mix(a, clamp(overlay, vec3f(-3.0e38), vec3f(3.0e38)), factor);
}

// Blender's Soft Light blend, which is Pegtop's formula (1 - 2b) a^2 + 2ab (continuous,
// unlike the W3C/Photoshop piecewise one), blended over `a` by `factor`. The channels are
// clamped to +-1e12 inside the formula, so it cannot overflow.
fn veneer_blend_soft_light(a: vec3f, b: vec3f, factor: f32) -> vec3f {
    let x = clamp(a, vec3f(-1.0e12), vec3f(1.0e12));
    let y = clamp(b, vec3f(-1.0e12), vec3f(1.0e12));
    return veneer_colour_mix(a, (1.0 - 2.0 * y) * x * x + 2.0 * x * y, factor);
}

// Blender's Difference blend: |a - b|, blended over `a` by `factor`.
fn veneer_blend_difference(a: vec3f, b: vec3f, factor: f32) -> vec3f {
    return veneer_colour_mix(a, min(abs(a - b), vec3f(3.0e38)), factor);
}
