//! Shapes as signed distances over the xz plane (negative inside; after Inigo Quilez's
//! 2D distance functions), their booleans, and fills and profiles made from a distance.
//! The CPU evaluator's `formulas::sdf` is the same arithmetic. Points and sizes are
//! first held within +-1e9 (`veneer_sd_limit`), where every square stays finite in f32.

// `x` within +-1e9: a shape's point or size, so that no product of two overflows.
fn veneer_sd_limit(x: vec2f) -> vec2f {
    return clamp(x, vec2f(-1.0e9), vec2f(1.0e9));
}

// A circle of `radius`.
fn veneer_sd_disc(p: vec2f, radius: f32) -> f32 {
    return length(veneer_sd_limit(p)) - veneer_sd_limit(vec2f(radius)).x;
}

// An ellipse of `radii` (the distance is approximate off the axes: exact on the curve and
// along both axes).
fn veneer_sd_ellipse(point: vec2f, radii: vec2f) -> f32 {
    let p = veneer_sd_limit(point);
    let r = max(abs(veneer_sd_limit(radii)), vec2f(1.0e-4));
    let k0 = length(p / r);
    let k1 = length(p / (r * r));
    return veneer_finite_f32(select(-min(r.x, r.y), k0 * (k0 - 1.0) / k1, k1 > 0.0));
}

// A rectangle of half sizes `half`, its corners rounded by `corner` (0: sharp).
fn veneer_sd_box(point: vec2f, half: vec2f, corner: f32) -> f32 {
    let p = veneer_sd_limit(point);
    let h = abs(veneer_sd_limit(half));
    let r = clamp(corner, 0.0, min(h.x, h.y));
    let d = abs(p) - (h - vec2f(r));
    return veneer_finite_f32(length(max(d, vec2f(0.0))) + min(max(d.x, d.y), 0.0) - r);
}

// A regular polygon of `sides` (3 or more) whose corners lie on a circle of `radius`,
// a corner straight up (+z).
fn veneer_sd_polygon(point: vec2f, size: f32, sides: f32) -> f32 {
    let p = veneer_sd_limit(point);
    let radius = veneer_sd_limit(vec2f(size)).x;
    let n = clamp(floor(sides + 0.5), 3.0, 64.0);
    let half_angle = 3.14159265 / n;
    let corner = vec2f(cos(half_angle), sin(half_angle));
    let turned = veneer_sd_sector(p, half_angle);
    var q = turned - radius * corner;
    q.y += clamp(-q.y, 0.0, radius * corner.y);
    return veneer_finite_f32(length(q) * sign(q.x));
}

// A star of `points` (2 or more) tips on a circle of `radius`; `sharpness` from 0 (a
// polygon of twice the points) to 1 (the thinnest tips).
fn veneer_sd_star(point: vec2f, size: f32, points: f32, sharpness: f32) -> f32 {
    let p = veneer_sd_limit(point);
    let radius = veneer_sd_limit(vec2f(size)).x;
    let n = clamp(floor(points + 0.5), 2.0, 64.0);
    let m = mix(n, 2.0, clamp(sharpness, 0.0, 1.0));
    let half_angle = 3.14159265 / n;
    let edge_angle = 3.14159265 / m;
    let corner = vec2f(cos(half_angle), sin(half_angle));
    let edge = vec2f(cos(edge_angle), sin(edge_angle));
    var q = veneer_sd_sector(p, half_angle) - radius * corner;
    q += edge * clamp(-dot(q, edge), 0.0, radius * corner.y / edge.y);
    return veneer_finite_f32(length(q) * sign(q.x));
}

// `p` turned into the first of the sectors 2 * half_angle wide around the origin, the
// first centred on +z, mirrored onto its upper half: (distance along, across).
fn veneer_sd_sector(p: vec2f, half_angle: f32) -> vec2f {
    let span = 2.0 * half_angle;
    let angle = atan2(p.x, p.y) + half_angle;
    let within = angle - span * floor(angle / span) - half_angle;
    return length(p) * vec2f(cos(within), abs(sin(within)));
}

// A segment from `a` to `b`, `radius` thick (a capsule; radius 0: the segment's distance).
fn veneer_sd_segment(p: vec2f, a: vec2f, b: vec2f, radius: f32) -> f32 {
    let pa = veneer_sd_limit(p) - veneer_sd_limit(a);
    let ba = veneer_sd_limit(b) - veneer_sd_limit(a);
    let along = clamp(dot(pa, ba) / max(dot(ba, ba), 1.0e-20), 0.0, 1.0);
    return length(pa - ba * along) - veneer_sd_limit(vec2f(radius)).x;
}

// A ring of `radius` along its middle and `thickness` across.
fn veneer_sd_ring(p: vec2f, radius: f32, thickness: f32) -> f32 {
    let sizes = veneer_sd_limit(vec2f(radius, thickness));
    return abs(length(veneer_sd_limit(p)) - sizes.x) - 0.5 * abs(sizes.y);
}

// A bell: 1 at the centre falling smoothly to 0 at `radius` ((1 - r^2)^2 of the
// distance over the radius).
fn veneer_bell(p: vec2f, radius: f32) -> f32 {
    let r = length(veneer_sd_limit(p)) / max(abs(veneer_sd_limit(vec2f(radius)).x), 1.0e-20);
    let inner = max(0.0, 1.0 - r * r);
    return inner * inner;
}

// The polynomial smooth minimum of `a` and `b` over `k` (0: the minimum).
fn veneer_smooth_min(a: f32, b: f32, k: f32) -> f32 {
    let w = max(k, 1.0e-20);
    let h = clamp(0.5 + 0.5 * (b - a) / w, 0.0, 1.0);
    return veneer_finite_f32(mix(b, a, h) - max(k, 0.0) * h * (1.0 - h));
}

// Union (0), subtraction of `b` from `a` (1) or intersection (2) of two distances,
// smoothed over `k`.
fn veneer_sd_boolean(a: f32, b: f32, k: f32, op: u32) -> f32 {
    switch op {
        case 1u: {
            return -veneer_smooth_min(-a, b, k);
        }
        case 2u: {
            return -veneer_smooth_min(-a, -b, k);
        }
        default: {
            return veneer_smooth_min(a, b, k);
        }
    }
}

// The coverage of a shape at distance `d`, its edge spread over `width` (0: a hard
// edge, 1 inside and at the edge).
fn veneer_shape_fill(d: f32, width: f32) -> f32 {
    let w = max(width, 0.0);
    let hard = select(0.0, 1.0, d <= 0.0);
    let soft = clamp(0.5 - d / max(w, 1.0e-30), 0.0, 1.0);
    return select(hard, soft, w > 0.0);
}

// The profiles of a shape made from distance `d` (an outline `thickness` wide when
// above 0): its fill over `width`, a bevel rising over `bevel` inside, and glows
// falling over `outer` outside and over `inner` inside.
fn veneer_sdf_profiles(d: f32, thickness: f32, bevel: f32, outer: f32, inner: f32, width: f32) -> veneer_sdf_profiles_result {
    let shape = select(d, abs(d) - 0.5 * thickness, thickness > 0.0);
    let fill = veneer_shape_fill(shape, width);
    let rise = clamp(-shape / max(bevel, 1.0e-20), 0.0, 1.0);
    let out = clamp(1.0 - shape / max(outer, 1.0e-20), 0.0, 1.0);
    let into = clamp(1.0 + shape / max(inner, 1.0e-20), 0.0, 1.0);
    let outside = select(0.0, out * out, shape > 0.0);
    let inside = select(0.0, into * into, shape <= 0.0);
    return veneer_sdf_profiles_result(fill, rise * rise * (3.0 - 2.0 * rise), outside, inside);
}

struct veneer_sdf_profiles_result {
    fill: f32,
    bevel: f32,
    glow: f32,
    inner_glow: f32,
}

// A shape's distance and its coverage with the edge spread over `width`.
struct veneer_shape_result {
    distance: f32,
    fill: f32,
}

// Distance `d` with its fill over `width`.
fn veneer_shape(d: f32, width: f32) -> veneer_shape_result {
    return veneer_shape_result(d, veneer_shape_fill(d, width));
}
