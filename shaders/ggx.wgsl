//! GGX microfacet terms (glTF 2.0 appendix B), shared by the key light and by the
//! environment maps derived for image-based lighting; and the panorama mapping both use.

const VENEER_PI: f32 = 3.14159265358979;

// Trowbridge-Reitz (GGX) distribution at n·h for roughness² `alpha`.
fn veneer_ggx_distribution(n_h: f32, alpha: f32) -> f32 {
    let alpha2 = alpha * alpha;
    let d = n_h * n_h * (alpha2 - 1.0) + 1.0;
    return alpha2 / (VENEER_PI * d * d);
}

// Smith height-correlated visibility (the geometry term over 4 n·l n·v).
fn veneer_smith_visibility(n_v: f32, n_l: f32, alpha: f32) -> f32 {
    let alpha2 = alpha * alpha;
    return 0.5 / max(n_l * sqrt(n_v * n_v * (1.0 - alpha2) + alpha2) + n_v * sqrt(n_l * n_l * (1.0 - alpha2) + alpha2), 1.0e-8);
}

// The panorama coordinates of direction `d` (need not be unit): the top row looks up
// (+y), the centre column along −z, columns turning towards +x rightwards (as
// render/environment/mod.rs says).
fn veneer_equirect_uv(d: vec3f) -> vec2f {
    let u = 0.5 + atan2(d.x, -d.z) / (2.0 * VENEER_PI);
    let v = acos(clamp(d.y / max(length(d), 1.0e-20), -1.0, 1.0)) / VENEER_PI;
    return vec2f(u, v);
}

// The unit direction of panorama coordinates `uv`.
fn veneer_equirect_direction(uv: vec2f) -> vec3f {
    let theta = uv.y * VENEER_PI;
    let phi = (uv.x - 0.5) * 2.0 * VENEER_PI;
    return vec3f(sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi));
}
