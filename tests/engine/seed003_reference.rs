//! The faithful GeoTexture presets (`graphs/thesis_c*.ron`) against transcriptions of
//! seed 003's appendix C fragment shaders, C.2 to C.6, and the brick preset against its
//! §3.1 Cg shader (the pattern part: everything up
//! to the lighting), written from the thesis's GLSL and not from the node code.
//!
//! Each transcription is evaluated at the same surface points, field values and times as
//! the CPU evaluator runs the preset graph, and every material channel is compared:
//! diffuse colour (albedo), specular colour, shininess, bump (the thesis adds one scalar
//! to every component of the normal), alpha, emission (the thesis's ambient colour) and
//! height (C.6's displacement). Both run in f64 and differ only by rounding (the node
//! graph orders some sums differently), so the tolerance is 1e-7.
//!
//! The thesis leaves its uniforms (`distanceThreshold`, `thresholdLayer1..3`,
//! `bumpScale`, `stripeWidth`, `frequency`) to the application; each `const` below is the
//! value the preset shows in a labelled Constant node (`noiseScale`, a parameter of the
//! Worley node, too). Its noise primitives (`snoise`, `fractalsum`, `turbulence`,
//! `fractalcell`, appendices A and B) are built here on our simplex basis, whose own tests
//! pin it (`gpuCellNoise3D` transcribed line by line on it); the loops are the thesis's
//! `for (f = 1.0; f < 5.0; f *= 2.0) value += noise(p * f) / f`.

use crate::support::{Samples, root};
use veneer::eval::{Evaluator, Material, Surface};
use veneer::graph::Shading;
use veneer::nodes::formulas::noise;
use veneer::nodes::settings::Basis;

type V3 = [f64; 3];
type V4 = [f64; 4];

/// What one fragment's pattern gives the lighting.
#[derive(Debug)]
struct Channels {
    diffuse: V3,
    specular: V3,
    shininess: f64,
    bump: f64,
    alpha: f64,
    emission: V3,
    height: f64,
}

impl Channels {
    /// An opaque, flat, unlit-nothing fragment of diffuse colour `diffuse`.
    fn new(diffuse: V3, specular: V3, shininess: f64) -> Channels {
        Channels {
            diffuse,
            specular,
            shininess,
            bump: 0.0,
            alpha: 1.0,
            emission: [0.0; 3],
            height: 0.0,
        }
    }
}

// ---- GLSL built-ins and appendices A and B

fn smoothstep(edge0: f64, edge1: f64, x: f64) -> f64 {
    if edge0 == edge1 {
        // GLSL leaves equal edges undefined; (x - e0) / 0 clamps to a step on drivers.
        return if x > edge0 { 1.0 } else { 0.0 };
    }
    let t = ((x - edge0) / (edge1 - edge0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

fn mix(a: f64, b: f64, t: f64) -> f64 {
    a * (1.0 - t) + b * t
}

fn mix3(a: V3, b: V3, t: f64) -> V3 {
    [0, 1, 2].map(|i| mix(a[i], b[i], t))
}

fn mix4(a: V4, b: V4, t: f64) -> V4 {
    [0, 1, 2, 3].map(|i| mix(a[i], b[i], t))
}

fn times(p: V3, s: f64) -> V3 {
    p.map(|c| c * s)
}

fn rgb(v: V4) -> V3 {
    [v[0], v[1], v[2]]
}

fn snoise(p: V3) -> f64 {
    noise::signed(Basis::Simplex, p)
}

/// `sum over f = 1, 2, 4 of octave(p * f) / f`.
fn octaves(p: V3, octave: impl Fn(V3) -> f64) -> f64 {
    let mut value = 0.0;
    let mut f = 1.0;
    while f < 5.0 {
        value += octave(times(p, f)) / f;
        f *= 2.0;
    }
    value
}

fn fractalsum(p: V3) -> f64 {
    octaves(p, snoise)
}

fn turbulence(p: V3) -> f64 {
    octaves(p, |q| snoise(q).abs())
}

/// The `noiseScale` uniform of C.2 and C.3 and the `#define` of C.5 (the only value the
/// thesis gives; the presets use it for all three).
const NOISE_SCALE: f64 = 2.2;

/// Appendix B's `gpuCellNoise3D(xyz).x`, line by line: the feature point of the cell at
/// corner `(xi + x, yi + y, zi + z)` sits at that corner plus `snoise` of the corner times
/// `noiseScale` (the listing assigns the float to a `vec3`, which splats it), and the
/// nearest of the 27 cells' points gives F1.
fn gpu_cell_noise_f1(xyz: V3) -> f64 {
    let [xi, yi, zi] = xyz.map(f64::floor);
    let [xf, yf, zf] = [xyz[0] - xi, xyz[1] - yi, xyz[2] - zi];
    let mut dist1 = 9999999.0f64;
    for z in -1..=1 {
        for y in -1..=1 {
            for x in -1..=1 {
                let corner = [xi + f64::from(x), yi + f64::from(y), zi + f64::from(z)];
                let s = snoise(corner) * NOISE_SCALE;
                let cell = [
                    s + (f64::from(x) - xf),
                    s + (f64::from(y) - yf),
                    s + (f64::from(z) - zf),
                ];
                dist1 = dist1.min(cell[0] * cell[0] + cell[1] * cell[1] + cell[2] * cell[2]);
            }
        }
    }
    dist1.sqrt()
}

/// `fractalcell(p, 1.0, 5.0, 2.0).x`: the fractal sum of the nearest feature distance.
fn fractalcell_x(p: V3) -> f64 {
    octaves(p, gpu_cell_noise_f1)
}

/// `position * cellScale + time * 0.5`, the flowing Worley domain of C.2, C.3 and C.5.
fn flowing(p: V3, cell_scale: f64, time: f64) -> V3 {
    times(p, cell_scale).map(|c| c + time * 0.5)
}

// ---- C.2 to C.6

/// C.2's `distanceThreshold` (a uniform in the thesis).
const C2_THRESHOLD: f64 = 0.3;

fn c2_sand_water(p: V3, d: [f64; 2], time: f64) -> Channels {
    let fv_specular = [0.549, 0.528, 0.164];
    let fv_diffuse_water = [0.177, 0.503, 0.413];
    let fv_diffuse_land = [0.894, 0.969, 0.755];
    let (bump_scale, sand_noise_scale, cell_scale, shore_width) = (0.15, 1000.0, 7.0, 0.0485);
    let distance_value = d[0];
    let shore = 1.0
        - smoothstep(
            distance_value - shore_width * 0.5,
            distance_value + shore_width * 0.5,
            C2_THRESHOLD + shore_width,
        );
    let water_bump = fractalcell_x(flowing(p, cell_scale, time));
    let sand_bump = snoise(times(p, sand_noise_scale));
    let mut out = Channels::new(
        mix3(fv_diffuse_land, fv_diffuse_water, shore),
        fv_specular,
        12.0,
    );
    out.bump = mix(sand_bump, water_bump, shore) * bump_scale;
    out
}

/// C.3's `distanceThreshold`.
const C3_THRESHOLD: f64 = 0.25;

fn c3_moss_granite(p: V3, d: [f64; 2], time: f64) -> Channels {
    let fv_specular = [0.549, 0.528, 0.164];
    let fv_diffuse_granite = [0.222, 0.219, 0.174];
    let fv_diffuse_moss = [0.094, 0.142, 0.061];
    let bump_scale = 1.0;
    let (granite_noise_scale, moss_noise_scale, cell_scale, shore_width) = (115.0, 163.0, 7.0, 0.1);
    let distance_value = d[0];
    let shore = 1.0
        - smoothstep(
            distance_value - shore_width * 0.5,
            distance_value + shore_width * 0.5,
            C3_THRESHOLD + shore_width,
        );
    let moss_cells = 1.0 - fractalcell_x(flowing(p, cell_scale, time));
    let bump = mix(
        moss_cells + turbulence(times(p, moss_noise_scale)),
        turbulence(times(p, granite_noise_scale)) * 0.5,
        shore,
    ) * bump_scale;
    // fvTotalSpecular = mix(0, fvSpecular * pow(...), shore), added at half strength.
    let specular = fv_specular.map(|c| mix(0.0, c, shore) * 0.5);
    let mut out = Channels::new(
        mix3(fv_diffuse_moss, fv_diffuse_granite, shore),
        specular,
        12.0,
    );
    out.bump = bump;
    out
}

/// C.4's `thresholdLayer1..3` and `bumpScale`.
const C4_THRESHOLDS: [f64; 3] = [0.6, 0.4, 0.15];
const C4_BUMP_SCALE: f64 = 0.1;

fn c4_paint_metal_rust(p: V3, d: [f64; 2], _time: f64) -> Channels {
    let [threshold_layer1, threshold_layer2, threshold_layer3] = C4_THRESHOLDS;
    let (fv_specular1, fv_diffuse1, mut bump1) = ([1.0; 4], [0.11, 0.16, 0.48, 1.0], 1.0);
    let (fv_specular2, mut fv_diffuse2, mut bump2) =
        ([0.18, 0.18, 0.18, 1.0], [0.64, 0.64, 0.64, 1.0], 0.8);
    let (fv_specular3, mut fv_diffuse3, mut bump3) =
        ([0.0, 0.0, 0.0, 1.0], [0.29, 0.17, 0.13, 1.0], 1.0);
    let (metal_noise_scale, rust_noise_scale) = (5.0, 4.62);
    let (rust_border_noise_scale, rust_border_noise_scale2, paint_border_noise_scale) =
        (0.0, 10.0, 0.0);
    let distance_value = d[0];
    let threshold_width = 0.005;
    let threshold1 = smoothstep(
        distance_value - threshold_width,
        distance_value + threshold_width,
        threshold_layer1 + snoise(times(p, paint_border_noise_scale)),
    );
    let threshold2 = smoothstep(
        distance_value - 0.08,
        distance_value + 0.08,
        threshold_layer2 + snoise(times(p, rust_border_noise_scale)),
    );
    let threshold3 = smoothstep(
        distance_value - 0.0,
        distance_value + 0.0,
        threshold_layer3 + snoise(times(p, rust_border_noise_scale2)) * 0.01,
    );
    // vec4 -= float subtracts from every component, alpha included.
    let metal = fractalsum(times(p, metal_noise_scale)) * 0.1;
    fv_diffuse2 = fv_diffuse2.map(|c| c - metal);
    let rust = fractalsum(times(p, rust_noise_scale));
    let stain = rust * (distance_value - threshold_layer2.clamp(0.0, 1.5) - 0.5) * 0.3;
    fv_diffuse3 = fv_diffuse3.map(|c| c - stain);
    let alpha_mod = (rust * (distance_value - threshold_layer2 - 0.5) * 16.0).clamp(0.0, 1000.0);
    fv_diffuse3[3] -= 0.1 * alpha_mod;

    let nest = |a: V4, b: V4, c: V4| {
        mix4(
            mix4(mix4(a, b, threshold1), c, threshold2),
            [0.0; 4],
            threshold3,
        )
    };
    let fv_diffuse = nest(fv_diffuse1, fv_diffuse2, fv_diffuse3);
    let fv_specular = nest(fv_specular1, fv_specular2, fv_specular3);

    bump1 *= -threshold1;
    bump2 *= snoise(times(p, 400.0)) * 0.025;
    let length3 = fv_diffuse3.iter().map(|c| c * c).sum::<f64>().sqrt();
    bump3 = bump2 + length3 * 0.5 * bump3;
    let bump = mix(
        mix(mix(bump1, bump2, threshold1), bump3, threshold2),
        0.0,
        threshold3,
    );

    let mut out = Channels::new(rgb(fv_diffuse), rgb(fv_specular), 60.0);
    out.bump = bump * C4_BUMP_SCALE;
    out.alpha = fv_diffuse[3];
    out
}

/// C.5's `thresholdLayer1..2` and `bumpScale`.
const C5_THRESHOLDS: [f64; 2] = [0.45, 0.3];
const C5_BUMP_SCALE: f64 = 0.1;

fn c5_water_lava(p: V3, d: [f64; 2], time: f64) -> Channels {
    let [threshold_layer1, threshold_layer2] = C5_THRESHOLDS;
    let (cell_scale, rock_noise_scale, lava_border_noise_range) = (65.16720, 47.0, 0.03);
    let (fv_ambient1, fv_specular1, mut fv_diffuse1, mut bump1) = (
        [0.39, 0.09, 0.09],
        [0.79, 0.76, 0.24],
        [0.27, 0.08, 0.06],
        -0.04,
    );
    let (fv_ambient2, fv_specular2, fv_diffuse2, mut bump2) =
        ([0.0; 3], [0.78, 0.78, 0.78], [0.21, 0.43, 0.48], -0.16);
    let (fv_ambient3, fv_specular3, fv_diffuse3, mut bump3) =
        ([0.0; 3], [0.07, 0.07, 0.07], [0.14, 0.14, 0.14], 0.66);
    let (distance_value1, distance_value2) = (d[0], d[1]);
    let (threshold_width1, threshold_width2) = (0.01, 0.05);
    let threshold1 = smoothstep(
        distance_value1 - threshold_width1,
        distance_value1 + threshold_width1,
        threshold_layer1 + snoise(times(p, 10.0)) * lava_border_noise_range,
    );
    let threshold2 = smoothstep(
        distance_value2 - threshold_width2,
        distance_value2 + threshold_width2,
        threshold_layer2,
    );
    let worley = fractalcell_x(flowing(p, cell_scale, time));
    bump1 *= worley;
    bump1 -= 1.0;
    let glow = [0.20, 0.15, 0.05];
    fv_diffuse1 = [0, 1, 2].map(|i| fv_diffuse1[i] + glow[i] * worley);
    bump2 *= worley;
    bump3 *= turbulence(times(p, rock_noise_scale));

    let nest =
        |rock: V3, lava: V3, water: V3| mix3(mix3(rock, lava, threshold1), water, threshold2);
    let mut out = Channels::new(
        nest(fv_diffuse3, fv_diffuse1, fv_diffuse2),
        nest(fv_specular3, fv_specular1, fv_specular2),
        26.0,
    );
    out.emission = nest(fv_ambient3, fv_ambient1, fv_ambient2);
    out.bump = mix(mix(bump3, bump1, threshold1), bump2, threshold2) * C5_BUMP_SCALE;
    out
}

/// C.6's `stripeWidth`, `frequency` and `bumpScale`; `animation2` is the time.
const C6_STRIPE_WIDTH: f64 = 0.5;
const C6_FREQUENCY: f64 = 120.0;
const C6_BUMP_SCALE: f64 = 0.02;

/// One wave of C.6.3 (the tessellation evaluation shader's displacement).
fn c6_wave(distance_value: f64, animation2: f64) -> f64 {
    let (stripe_width, animation) = (C6_STRIPE_WIDTH, 0.0);
    let north = smoothstep(
        distance_value - stripe_width * 0.5,
        distance_value + stripe_width * 0.5,
        animation,
    );
    let south = 1.0
        - smoothstep(
            distance_value - stripe_width * 0.5,
            distance_value + stripe_width * 0.5,
            animation + stripe_width,
        );
    let bump = north + south;
    let isolines = (animation2 + distance_value * (C6_FREQUENCY * (1.0 - distance_value))).sin()
        * (1.0 - distance_value);
    (1.0 - bump) * isolines
}

fn c6_waves(_p: V3, d: [f64; 2], time: f64) -> Channels {
    let mut bump = c6_wave(d[0], time);
    if d[1] > 0.0 {
        bump += c6_wave(d[1], time);
    }
    // C.6.4: grey diffuse, white specular of power 60.
    let mut out = Channels::new([0.5; 3], [1.0; 3], 60.0);
    out.height = bump * C6_BUMP_SCALE;
    out
}

// ---- the comparison

impl Samples {
    /// A distance value: uniform on [0, 1] half the time, otherwise within 0.1 of one
    /// of `edges` (where the fronts are narrow).
    fn distance(&mut self, edges: &[f64]) -> f64 {
        if edges.is_empty() || self.unit() < 0.5 {
            return self.unit();
        }
        let edge = edges[(self.unit() * edges.len() as f64) as usize % edges.len()];
        (edge + (self.unit() - 0.5) * 0.2).clamp(0.0, 1.0)
    }
}

/// Seed 003's lighting as a listing writes it: `fvNormal = normalize(Normal) + bump`
/// (not normalised again), N·L as it comes or, in C.4 and C.5, |N·L|, the reflection
/// `normalize(2 N (N·L) − L)`, and `ambient + diffuse · N·L + specular · pow(max(R·V, 0),
/// power)` (the ambient is the preset's emission). C.6.4 replaces the ambient and diffuse
/// terms by the environment its sphere map shows, which is left out here on both sides
/// (the renderer's, seen in the snapshot).
fn listing_lighting(thesis: &Channels, normal: V3, light: V3, view: V3, shading: Shading) -> V3 {
    let n = normal.map(|x| x + thesis.bump);
    let dot = |a: V3, b: V3| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let n_dot_l = match shading {
        Shading::ThesisAbsolute => dot(n, light).abs(),
        _ => dot(n, light),
    };
    let reflected = [0, 1, 2].map(|i| 2.0 * n[i] * n_dot_l - light[i]);
    let r = times(reflected, 1.0 / dot(reflected, reflected).sqrt());
    let highlight = dot(r, view).max(0.0).powf(thesis.shininess);
    let lit = thesis.specular.map(|s| s * highlight);
    if shading == Shading::ThesisSphereMap {
        return lit;
    }
    [0, 1, 2].map(|i| thesis.emission[i] + thesis.diffuse[i] * n_dot_l + lit[i])
}

/// Veneer's thesis shadings, as `shaders/render_lit_thesis*.wgsl` and the mesh fragment
/// (the normal plus the material's bump, as it is) compute them from a material; the
/// sphere map's environment term left out (see [`listing_lighting`]).
fn veneer_thesis_lighting(
    material: &Material<f64>,
    normal: V3,
    light: V3,
    view: V3,
    shading: Shading,
) -> V3 {
    let n = [0, 1, 2].map(|i| normal[i] + material.bump[i]);
    let dot = |a: V3, b: V3| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let n_dot_l = if shading == Shading::ThesisAbsolute {
        dot(n, light).abs()
    } else {
        dot(n, light)
    };
    let reflected = [0, 1, 2].map(|i| 2.0 * n[i] * n_dot_l - light[i]);
    let r = times(
        reflected,
        1.0 / dot(reflected, reflected).max(1.0e-30).sqrt(),
    );
    let highlight = dot(r, view).max(0.0).powf(material.shininess.max(1.0));
    let diffuse = if shading == Shading::ThesisSphereMap {
        0.0
    } else {
        n_dot_l
    };
    [0, 1, 2].map(|i| {
        material.albedo[i] * diffuse
            + material.specular[i] * highlight
            + material.emission[i] * material.emission_strength
    })
}

/// A random unit vector.
fn direction(samples: &mut Samples) -> V3 {
    let v = [0, 1, 2].map(|_| samples.unit() * 2.0 - 1.0);
    let length = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-9);
    times(v, 1.0 / length)
}

fn check(preset: &str, edges: [&[f64]; 2], reference: fn(V3, [f64; 2], f64) -> Channels) {
    let graph = veneer::graph::load(&root(&format!("graphs/{preset}.ron"))).expect("preset loads");
    // C.4 and C.5 light by |N·L|, C.6 adds its sphere map, the others by N·L.
    let expected = match preset {
        "thesis_c4_paint_metal_rust" | "thesis_c5_water_lava" => Shading::ThesisAbsolute,
        "thesis_c6_waves" => Shading::ThesisSphereMap,
        _ => Shading::Thesis,
    };
    assert_eq!(graph.shading, expected, "{preset} is lit as its listing");
    let evaluator = Evaluator::new(&graph).expect("preset checks");
    let mut samples = Samples(0x5eed_0003);
    let mut worst = 0.0_f64;
    for _ in 0..3000 {
        let position = [0, 1, 2].map(|_| samples.unit() * 2.0 - 1.0);
        let fields = [samples.distance(edges[0]), samples.distance(edges[1])];
        let time = samples.unit() * 20.0;
        let mut surface = Surface::<f64>::at(position);
        surface.fields = [fields[0], fields[1], 0.0, 0.0];
        surface.time = time;
        let ours: Material<f64> = evaluator.eval(&surface);
        let thesis = reference(position, fields, time);
        let pairs = [
            ("diffuse", ours.albedo, thesis.diffuse),
            ("specular", ours.specular, thesis.specular),
            ("bump", ours.bump, [thesis.bump; 3]),
            ("emission", ours.emission, thesis.emission),
            ("alpha", [ours.alpha; 3], [thesis.alpha; 3]),
            ("shininess", [ours.shininess; 3], [thesis.shininess; 3]),
            ("height", [ours.height; 3], [thesis.height; 3]),
        ];
        for (channel, a, b) in pairs {
            let error = (0..3).map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max);
            worst = worst.max(error);
            assert!(
                error <= 1e-7,
                "{preset}: {channel} is {a:?}, the thesis gives {b:?} at position {position:?}, \
                 fields {fields:?}, time {time}"
            );
        }
        // The whole fragment: the channels lit as the listing lights them, under a
        // random normal, light and eye.
        let (normal, light, view) = (
            direction(&mut samples),
            direction(&mut samples),
            direction(&mut samples),
        );
        let ours = veneer_thesis_lighting(&ours, normal, light, view, expected);
        let listing = listing_lighting(&thesis, normal, light, view, expected);
        let error = (0..3)
            .map(|i| (ours[i] - listing[i]).abs())
            .fold(0.0, f64::max);
        worst = worst.max(error);
        assert!(
            error <= 1e-6,
            "{preset}: lit {ours:?}, the listing gives {listing:?} at position {position:?}, \
             normal {normal:?}, light {light:?}, eye {view:?}"
        );
    }
    eprintln!("{preset}: largest difference from the thesis {worst:e}");
}

#[test]
fn c2_sand_water_matches_the_thesis() {
    check(
        "thesis_c2_sand_water",
        [&[C2_THRESHOLD + 0.0485], &[]],
        c2_sand_water,
    );
}

#[test]
fn c3_moss_granite_matches_the_thesis() {
    check(
        "thesis_c3_moss_granite",
        [&[C3_THRESHOLD + 0.1], &[]],
        c3_moss_granite,
    );
}

#[test]
fn c4_paint_metal_rust_matches_the_thesis() {
    check(
        "thesis_c4_paint_metal_rust",
        [&C4_THRESHOLDS, &[]],
        c4_paint_metal_rust,
    );
}

#[test]
fn c5_water_lava_matches_the_thesis() {
    check(
        "thesis_c5_water_lava",
        [&C5_THRESHOLDS[..1], &C5_THRESHOLDS[1..]],
        c5_water_lava,
    );
}

#[test]
fn c6_waves_match_the_thesis() {
    check(
        "thesis_c6_waves",
        [&[0.0, C6_STRIPE_WIDTH], &[0.0, C6_STRIPE_WIDTH]],
        c6_waves,
    );
}

// ---- §3.1: the procedural brick texture (Cg), `graphs/thesis_brick.ron`

const BRICK_WIDTH: f64 = 0.25;
const BRICK_HEIGHT: f64 = 0.08;
const MORTAR_THICKNESS: f64 = 0.01;

/// `brick_f` as the thesis writes it, at texture coordinates (s, t).
fn brick_f(scoord: f64, tcoord: f64) -> V3 {
    let (brick, mortar) = ([0.5, 0.15, 0.14], [0.5, 0.5, 0.5]);
    let bm_width = BRICK_WIDTH + MORTAR_THICKNESS;
    let bm_height = BRICK_HEIGHT + MORTAR_THICKNESS;
    let mwf = MORTAR_THICKNESS * 0.5 / bm_width;
    let mhf = MORTAR_THICKNESS * 0.5 / bm_height;
    let step = |edge: f64, x: f64| if x >= edge { 1.0 } else { 0.0 };
    let frac = |x: f64| x - x.floor();
    let mut ss = scoord / bm_width;
    let mut tt = tcoord / bm_height;
    if frac(tt * 0.5) > 0.5 {
        ss += 0.5;
    }
    ss -= ss.floor();
    tt -= tt.floor();
    let w = step(mwf, ss) - step(1.0 - mwf, ss);
    let h = step(mhf, tt) - step(1.0 - mhf, tt);
    [0, 1, 2].map(|i| mortar[i] + (brick[i] - mortar[i]) * w * h)
}

/// With its row jitter at 0 the preset is Fig. 3.1: the preset turns the thesis's plane
/// so that the bricks lie along x in flat renders (s = −x, t = z; the pattern is the same
/// under s → −s, the stagger being half a brick and the mortar centred on the joints).
#[test]
fn the_brick_preset_is_the_thesis_brick_shader_without_jitter() {
    let mut graph = veneer::graph::load(&root("graphs/thesis_brick.ron")).expect("preset loads");
    let jitter = graph
        .nodes
        .iter()
        .find(|node| node.label == "rowJitter")
        .expect("the preset's row jitter")
        .id;
    graph.set_input(jitter, "value", veneer::graph::Value::Float(0.0));
    let evaluator = Evaluator::new(&graph).expect("preset checks");
    let mut samples = Samples(0x5eed_0031);
    let mut mortar = 0;
    for _ in 0..3000 {
        let (x, z) = (samples.unit() * 6.0 - 3.0, samples.unit() * 6.0 - 3.0);
        let ours: Material<f64> = evaluator.eval(&Surface::<f64>::at([x, 0.0, z]));
        let thesis = brick_f(-x, z);
        mortar += usize::from((thesis[1] - 0.5).abs() < 1e-9);
        let error = (0..3)
            .map(|i| (ours.albedo[i] - thesis[i]).abs())
            .fold(0.0, f64::max);
        assert!(
            error < 1e-12,
            "at x = {x}, z = {z}: {:?} against {thesis:?}",
            ours.albedo
        );
    }
    // About 15% of the wall is mortar: the samples see both.
    assert!((300..700).contains(&mortar), "{mortar} mortar samples");
}

#[test]
fn the_brick_preset_jitters_its_rows() {
    let graph = veneer::graph::load(&root("graphs/thesis_brick.ron")).expect("preset loads");
    let evaluator = Evaluator::new(&graph).expect("preset checks");
    // Along one line of the wall, each row's vertical joints move by its own amount:
    // some points the thesis shader puts on a brick are mortar here, and the other way.
    let differing = (0..2000)
        .map(|index| {
            let (x, z) = (
                -2.0 + index as f64 * 0.002,
                0.3 + (index % 37) as f64 * 0.09,
            );
            let ours: Material<f64> = evaluator.eval(&Surface::<f64>::at([x, 0.0, z]));
            let thesis = brick_f(-x, z);
            (0..3).any(|i| (ours.albedo[i] - thesis[i]).abs() > 1e-9)
        })
        .filter(|&differs| differs)
        .count();
    assert!(differing > 40, "only {differing} of 2000 points moved");
}

/// The listings' uniforms are the presets' parameters under the listings' names, so a
/// sweep is `--set distanceThreshold=0.12`: each sets the node labelled with the name,
/// whose value the transcriptions above read.
#[test]
fn the_listings_uniforms_are_parameters_with_their_names() {
    let uniforms: [(&str, &[&str]); 8] = [
        (
            "thesis_c2_sand_water",
            &["distanceThreshold", "bumpScale", "noiseScale"],
        ),
        (
            "thesis_c3_moss_granite",
            &["distanceThreshold", "noiseScale"],
        ),
        (
            "thesis_c4_paint_metal_rust",
            &[
                "thresholdLayer1",
                "thresholdLayer2",
                "thresholdLayer3",
                "bumpScale",
            ],
        ),
        (
            "thesis_c5_water_lava",
            &[
                "thresholdLayer1",
                "thresholdLayer2",
                "bumpScale",
                "noiseScale",
            ],
        ),
        (
            "thesis_c6_waves",
            &["stripeWidth", "frequency", "bumpScale"],
        ),
        (
            "thesis_c6_waves_adaptive",
            &["stripeWidth", "frequency", "bumpScale"],
        ),
        ("thesis_fig1_1_fronts", &["distanceThreshold"]),
        ("thesis_fig5_7_opacity", &["distanceThreshold"]),
    ];
    for (preset, names) in uniforms {
        let mut graph = veneer::graph::load(&root(&format!("graphs/{preset}.ron"))).unwrap();
        for &name in names {
            let parameter = (graph.parameters.iter())
                .find(|p| p.name == name)
                .unwrap_or_else(|| panic!("{preset} exposes no {name}"))
                .clone();
            let node = graph.nodes.iter().find(|n| n.id == parameter.node).unwrap();
            assert!(
                node.label == name || node.label.contains(name),
                "{preset}: {name} sets '{}'",
                node.label
            );
            // A value within the parameter's range, unlike any preset's.
            let (low, high) = parameter.range.expect("the uniforms have ranges");
            let value = low + 0.377 * (high - low);
            let given = veneer::graph::parameters::Given::Number(value);
            veneer::graph::parameters::set(&mut graph, name, &given).unwrap();
            let node = graph.nodes.iter().find(|n| n.id == parameter.node).unwrap();
            assert_eq!(
                node.inputs.get(parameter.pin.as_str()),
                Some(&veneer::graph::Value::Float(value)),
                "{preset}: {name}"
            );
        }
    }
}

/// The GPU lights as [`veneer_thesis_lighting`] does: `render_lit_thesis.wgsl` over a
/// flat render of materials, normals and eyes varying with the point, both with N·L and
/// with |N·L|.
#[test]
fn the_gpu_lights_as_the_thesis_shading_is_transcribed() {
    let gpu = crate::support::gpu();
    let lighting = concat!(
        include_str!("../../shaders/render_lit_thesis_phong.wgsl"),
        include_str!("../../shaders/render_lit_thesis.wgsl")
    );
    let surface: String = (veneer::codegen::library::SURFACE.lines())
        .filter(|line| !line.starts_with("//!"))
        .map(|line| format!("{line}\n"))
        .collect();
    let rect = veneer::render::FlatRect {
        x0: -3.3,
        z0: -2.7,
        x1: 4.1,
        z1: 4.7,
        y: 0.37,
    };
    for shading in [Shading::Thesis, Shading::ThesisAbsolute] {
        let absolute = shading == Shading::ThesisAbsolute;
        let source = format!(
            "{surface}\nconst VENEER_ABSOLUTE_N_DOT_L: bool = {absolute};\n{lighting}
fn veneer_material(s: VeneerSurface) -> VeneerMaterial {{
    let c = fract(s.position * vec3f(0.31, 0.47, 0.73));
    let n = normalize(vec3f(c.x - 0.5, 0.6, c.z - 0.5));
    let v = normalize(vec3f(c.z - 0.2, 1.0, c.x - 0.7));
    let l = normalize(vec3f(0.3, 0.8, -0.5));
    let m = VeneerMaterial(c, 1.0, vec3f(0.5, 0.4, 0.3), 12.0, vec3f(c.y * 0.3 - 0.15), 0.0, vec3f(0.1, 0.0, 0.05), 0.0, 0.5, vec3f(0.0, 0.0, 1.0), 1.0, 1.0);
    let lit = veneer_shade(m, veneer_lit_normal(n + m.bump), v, l);
    return VeneerMaterial(clamp(lit, vec3f(0.0), vec3f(1.0)), 1.0, vec3f(0.0), 1.0, vec3f(0.0), 0.0, vec3f(0.0), 0.0, 0.5, vec3f(0.0, 0.0, 1.0), 1.0, 1.0);
}}
"
        );
        let renderer =
            veneer::render::FlatRenderer::new(gpu, &source).expect("the lighting compiles");
        let pixels = renderer.render(gpu, rect, 32, 0.0).expect("renders");
        let unit = |v: V3| times(v, 1.0 / (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt());
        let mut worst = 0.0f64;
        for (point, pixel) in veneer::render::flat_points(rect, 32)
            .into_iter()
            .zip(pixels)
        {
            let fract = |x: f64| x - x.floor();
            let c =
                [point[0] * 0.31, point[1] * 0.47, point[2] * 0.73].map(|x| fract(x as f32 as f64));
            let material = Material::<f64> {
                albedo: c,
                alpha: 1.0,
                specular: [0.5, 0.4, 0.3],
                shininess: 12.0,
                bump: [c[1] * 0.3 - 0.15; 3],
                height: 0.0,
                emission: [0.1, 0.0, 0.05],
                metallic: 0.0,
                roughness: 0.5,
                normal: [0.0, 0.0, 1.0],
                emission_strength: 1.0,
                occlusion: 1.0,
            };
            let normal = unit([c[0] - 0.5, 0.6, c[2] - 0.5]);
            let view = unit([c[2] - 0.2, 1.0, c[0] - 0.7]);
            let light = unit([0.3, 0.8, -0.5]);
            let lit = veneer_thesis_lighting(&material, normal, light, view, shading);
            for k in 0..3 {
                let error = (f64::from(pixel[k]) - lit[k].clamp(0.0, 1.0)).abs();
                worst = worst.max(error);
            }
        }
        assert!(worst <= 1e-4, "|N·L| {absolute}: worst difference {worst}");
    }
}
