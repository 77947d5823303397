//! Tone mappers for the previews that light by an environment (metallic-roughness, the
//! thesis's sphere map): scene-linear light to display-linear values in [0, 1], then
//! sRGB-encoded by `veneer_display`, which reads the mesh view's exposure and tone mapper.
//! `kind` is `ToneMap as u32` (render/tone_map.rs holds the CPU twins the tests check
//! against published values).

// Khronos PBR Neutral (Khronos 3D Commerce, 2024): identity below 0.76 up to a small
// toe offset, then a hue-preserving highlight roll-off.
fn veneer_pbr_neutral(colour: vec3f) -> vec3f {
    let start_compression = 0.8 - 0.04;
    let desaturation = 0.15;
    let x = min(colour.r, min(colour.g, colour.b));
    let offset = select(0.04, x - 6.25 * x * x, x < 0.08);
    var c = colour - offset;
    let peak = max(c.r, max(c.g, c.b));
    if peak < start_compression {
        return c;
    }
    let d = 1.0 - start_compression;
    let new_peak = 1.0 - d * d / (peak + d - start_compression);
    c = c * (new_peak / peak);
    let g = 1.0 - 1.0 / (desaturation * (peak - new_peak) + 1.0);
    return mix(c, vec3f(new_peak), g);
}

// ACES fitted (Stephen Hill's fit of the RRT and sRGB ODT, BakingLab 2016).
fn veneer_aces_fitted(colour: vec3f) -> vec3f {
    let input = transpose(mat3x3f(0.59719, 0.35458, 0.04823, 0.07600, 0.90834, 0.01566, 0.02840, 0.13383, 0.83777));
    let output = transpose(mat3x3f(1.60475, -0.53108, -0.07367, -0.10208, 1.10813, -0.00605, -0.00327, -0.07276, 1.07602));
    let v = input * colour;
    let fitted = (v * (v + 0.0245786) - 0.000090537) / (v * (0.983729 * v + 0.4329510) + 0.238081);
    return clamp(output * fitted, vec3f(0.0), vec3f(1.0));
}

// AgX (Troy Sobotka), in the minimal form with a sixth-order fit of its contrast curve
// (Benjamin Wrensch, 2023), base look.
fn veneer_agx(colour: vec3f) -> vec3f {
    let inset = mat3x3f(0.842479062253094, 0.0423282422610123, 0.0423756549057051,
        0.0784335999999992, 0.878468636469772, 0.0784336,
        0.0792237451477643, 0.0791661274605434, 0.879142973793104);
    let outset = mat3x3f(1.19687900512017, -0.0528968517574562, -0.0529716355144438,
        -0.0980208811401368, 1.15190312990417, -0.0980434501171241,
        -0.0990297440797205, -0.0989611768448433, 1.15107367264116);
    let min_ev = -12.47393;
    let max_ev = 4.026069;
    var v = inset * max(colour, vec3f(1.0e-10));
    v = (clamp(log2(v), vec3f(min_ev), vec3f(max_ev)) - min_ev) / (max_ev - min_ev);
    let x2 = v * v;
    let x4 = x2 * x2;
    v = 15.5 * x4 * x2 - 40.14 * x4 * v + 31.96 * x4 - 6.868 * x2 * v + 0.4298 * x2 + 0.1191 * v - 0.00232;
    v = outset * v;
    return pow(clamp(v, vec3f(0.0), vec3f(1.0)), vec3f(2.2));
}

// `colour` through tone mapper `kind` (0 clamp, 1 PBR neutral, 2 ACES fitted, 3 AgX); light
// past 1e9 is white in every one of them and is clamped there, so that none overflows.
fn veneer_tone_map(colour: vec3f, kind: u32) -> vec3f {
    let c = clamp(colour, vec3f(0.0), vec3f(1.0e9));
    switch kind {
        case 1u: { return veneer_pbr_neutral(c); }
        case 2u: { return veneer_aces_fitted(c); }
        case 3u: { return veneer_agx(c); }
        default: { return clamp(c, vec3f(0.0), vec3f(1.0)); }
    }
}

// The sRGB transfer function (linear light to the encoded value a display shows).
fn veneer_srgb_encode(linear: vec3f) -> vec3f {
    let c = clamp(linear, vec3f(0.0), vec3f(1.0));
    return select(1.055 * pow(c, vec3f(1.0 / 2.4)) - 0.055, 12.92 * c, c <= vec3f(0.0031308));
}

// Scene-linear light to the display: exposure, tone mapper, sRGB.
fn veneer_display(light: vec3f) -> vec3f {
    let view = veneer_mesh_view;
    return veneer_srgb_encode(veneer_tone_map(light * view.exposure_scale, view.tone_map));
}
