//! Tests of the WGSL items of the new node families (white noise, value-gradient noise,
//! Gabor noise, rotated fractals, Worley edge distance, colour, map range): each
//! validates with naga on its own, and the GPU computes what its CPU twin computes.

use super::real::{V3, scale};
use super::{band_limit, colour, gabor, octaves, ranges, worley_edge};
use crate::codegen::library::{SURFACE, closure, instance};
use crate::nodes::settings::{Basis, FractalMode};
use crate::render::{FlatRect, FlatRenderer, GpuContext, flat_points};
use std::sync::OnceLock;

/// The new library files (`shaders/<family>.wgsl`).
const FAMILIES: [&str; 8] = [
    "band_limit",
    "white",
    "value_gradient",
    "gabor",
    "fractal_rotated",
    "worley_edge",
    "colour",
    "map_range",
];

const MODES: [&str; 3] = ["fbm", "turbulence", "fractal_sum"];
const BASES: [&str; 4] = ["value_sine", "value_pcg", "gradient", "simplex"];
const TYPES: [&str; 3] = ["f32", "vec2f", "vec3f"];

/// Every item of the new files by name, templates instantiated, with its family.
fn new_items() -> Vec<(String, &'static str)> {
    let mut names = Vec::new();
    for family in FAMILIES {
        let path = format!("{}/shaders/{family}.wgsl", env!("CARGO_MANIFEST_DIR"));
        let source = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
        for line in source.lines() {
            let Some(rest) = line.strip_prefix("fn ") else {
                continue;
            };
            let name: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            if name.contains("MODE") {
                for mode in MODES {
                    for basis in BASES {
                        let concrete = name.replace("MODE", mode).replace("BASIS", basis);
                        names.push((concrete, family));
                    }
                }
            } else if name.contains("TYPE") {
                for ty in TYPES {
                    names.push((name.replace("TYPE", ty), family));
                }
            } else {
                names.push((name, family));
            }
        }
    }
    names
}

#[test]
fn every_new_item_is_found_in_its_own_family_and_validates_alone() {
    let items = new_items();
    assert_eq!(items.len(), 23 + 3 + 5 + 1 + 12 + 2 + 14 + 7);
    for (name, family) in items {
        let item = instance(&name).unwrap_or_else(|| panic!("no library item {name}"));
        assert_eq!(
            item.family, family,
            "{name} resolves to another family's item"
        );
        let source: String = closure([name.as_str()])
            .iter()
            .map(|item| item.text.clone() + "\n")
            .collect();
        if let Err(error) = crate::codegen::validate(&source) {
            panic!("{name} does not validate: {error}\n{source}");
        }
    }
}

fn gpu() -> &'static GpuContext {
    static GPU: OnceLock<GpuContext> = OnceLock::new();
    GPU.get_or_init(|| {
        GpuContext::new().unwrap_or_else(|error| panic!("this test needs a wgpu adapter: {error}"))
    })
}

/// The colour inputs the material below derives from the position.
fn inputs(p: V3<f32>) -> (V3<f32>, V3<f32>) {
    let c = [p[0] * 0.31, p[1] * 0.47, p[2] * 0.73].map(|x| x - x.floor());
    let d = [p[2] * 0.53, p[0] * 0.29, p[1] * 0.61].map(|x| x - x.floor());
    (c, d)
}

/// A material whose albedo is `expr` (a vec3f of `p`, `c` and `d`), with the library
/// items `roots` need.
fn material(roots: &[&str], expr: &str) -> String {
    let mut source: String = SURFACE
        .lines()
        .filter(|line| !line.starts_with("//!"))
        .map(|line| format!("{line}\n"))
        .collect();
    for item in closure(roots.iter().copied()) {
        source.push('\n');
        source.push_str(&item.text);
    }
    source.push_str(&format!(
        "\nfn veneer_material(s: VeneerSurface) -> VeneerMaterial {{
    let p = s.position;
    let c = fract(vec3f(p.x * 0.31, p.y * 0.47, p.z * 0.73));
    let d = fract(vec3f(p.z * 0.53, p.x * 0.29, p.y * 0.61));
    return VeneerMaterial({expr}, 1.0, vec3f(0.0), 1.0, vec3f(0.0), 0.0, vec3f(0.0), 0.0, 0.5, vec3f(0.0, 0.0, 1.0), 1.0, 1.0);
}}\n"
    ));
    source
}

type Twin = fn(V3<f32>, V3<f32>, V3<f32>) -> V3<f32>;

struct Case {
    roots: &'static [&'static str],
    expr: &'static str,
    cpu: Twin,
    tolerance: f32,
}

fn splat(x: f32) -> V3<f32> {
    [x; 3]
}

fn cases() -> Vec<Case> {
    let case = |roots, expr, cpu: Twin, tolerance| Case {
        roots,
        expr,
        cpu,
        tolerance,
    };
    vec![
        case(
            &["veneer_band_limited_sine"],
            "vec3f(veneer_band_limited_sine(p.x * 7.0, c.x * 9.0), veneer_band_limited_sine(p.z * 3.0, d.y * 2.0), veneer_band_limited_sine(p.x * 2.0 + p.z, 0.0))",
            |p, c, d| {
                [
                    band_limit::band_limited_sine(p[0] * 7.0, c[0] * 9.0),
                    band_limit::band_limited_sine(p[2] * 3.0, d[1] * 2.0),
                    band_limit::band_limited_sine(p[0] * 2.0 + p[2], 0.0),
                ]
            },
            2.0e-4,
        ),
        case(
            &["veneer_band_limited_triangle", "veneer_band_limited_floor"],
            "vec3f(veneer_band_limited_triangle(p.x * 1.3, c.y * 1.5), veneer_band_limited_triangle(p.z * 2.1, d.x * 0.4), veneer_band_limited_floor(p.x * 2.3, c.z * 1.2))",
            |p, c, d| {
                [
                    band_limit::band_limited_triangle(p[0] * 1.3, c[1] * 1.5),
                    band_limit::band_limited_triangle(p[2] * 2.1, d[0] * 0.4),
                    band_limit::band_limited_floor(p[0] * 2.3, c[2] * 1.2),
                ]
            },
            1.0e-5,
        ),
        case(
            &[
                "veneer_band_limited_smoothstep",
                "veneer_band_limited_step_f32",
            ],
            "vec3f(veneer_band_limited_smoothstep(-0.5, 1.5, p.x, c.x * 2.0), veneer_band_limited_smoothstep(1.0, -1.0, p.z, d.z), veneer_band_limited_step_f32(0.3, p.x * 0.5, c.y))",
            |p, c, d| {
                [
                    band_limit::band_limited_smoothstep(-0.5, 1.5, p[0], c[0] * 2.0),
                    band_limit::band_limited_smoothstep(1.0, -1.0, p[2], d[2]),
                    band_limit::band_limited_step(0.3, p[0] * 0.5, c[1]),
                ]
            },
            1.0e-5,
        ),
        case(
            &["veneer_white_noise"],
            "vec3f(veneer_white_noise(p * 3.7))",
            |p, _, _| splat(gabor::white_noise(scale(p, 3.7))),
            0.0,
        ),
        case(
            &["veneer_white_noise_color"],
            "veneer_white_noise_color(p * 3.7)",
            |p, _, _| gabor::white_noise_color(scale(p, 3.7)),
            0.0,
        ),
        case(
            &["veneer_noise_value_gradient"],
            "vec3f(veneer_noise_value_gradient(p * 2.3))",
            |p, _, _| splat(gabor::value_gradient(scale(p, 2.3))),
            1.0e-5,
        ),
        case(
            &["veneer_gabor"],
            "vec3f(veneer_gabor(p * 1.3, 3.0, 0.0, vec3f(0.0)), veneer_gabor(p, 2.0, 1.0, vec3f(1.0, 0.5, 0.0)), veneer_gabor(p * 0.7, 5.0, 0.6, vec3f(0.0, 0.0, 2.0)))",
            |p, _, _| {
                [
                    gabor::gabor(scale(p, 1.3), 3.0, 0.0, [0.0; 3]),
                    gabor::gabor(p, 2.0, 1.0, [1.0, 0.5, 0.0]),
                    gabor::gabor(scale(p, 0.7), 5.0, 0.6, [0.0, 0.0, 2.0]),
                ]
            },
            2.0e-4,
        ),
        case(
            &["veneer_octave_rotate"],
            "veneer_octave_rotate(p)",
            |p, _, _| octaves::octave_rotate(p),
            2.0e-6,
        ),
        case(
            &[
                "veneer_fbm_rotated_gradient",
                "veneer_turbulence_rotated_simplex",
                "veneer_fractal_sum_rotated_value_pcg",
            ],
            "vec3f(veneer_fbm_rotated_gradient(p, 5, 2.0, 0.5, 1.0, true, 1.0e9), veneer_turbulence_rotated_simplex(p, 4, 2.1, 0.6, 1.0, true, 1.0e9), veneer_fractal_sum_rotated_value_pcg(p, 6, 1.9, 0.5, 0.8, false, 1.0e9))",
            |p, _, _| {
                [
                    octaves::fractal_rotated(
                        FractalMode::Fbm,
                        Basis::Gradient,
                        p,
                        5,
                        [2.0, 0.5, 1.0],
                        true,
                        1.0e9,
                    ),
                    octaves::fractal_rotated(
                        FractalMode::Turbulence,
                        Basis::Simplex,
                        p,
                        4,
                        [2.1, 0.6, 1.0],
                        true,
                        1.0e9,
                    ),
                    octaves::fractal_rotated(
                        FractalMode::FractalSum,
                        Basis::ValuePcg,
                        p,
                        6,
                        [1.9, 0.5, 0.8],
                        false,
                        1.0e9,
                    ),
                ]
            },
            1.0e-4,
        ),
        case(
            &["veneer_worley_edge"],
            "vec3f(veneer_worley_edge(p * 2.1, 0.9), veneer_worley_edge(p, 0.0), veneer_worley_edge(p * 1.7, 1.0))",
            |p, _, _| {
                [
                    worley_edge::worley_edge(scale(p, 2.1), 0.9),
                    worley_edge::worley_edge(p, 0.0),
                    worley_edge::worley_edge(scale(p, 1.7), 1.0),
                ]
            },
            1.0e-4,
        ),
        case(
            &["veneer_rgb_to_hsv"],
            "veneer_rgb_to_hsv(c)",
            |_, c, _| colour::rgb_to_hsv(c),
            1.0e-5,
        ),
        case(
            &["veneer_hsv_to_rgb"],
            "veneer_hsv_to_rgb(c * 1.3 - 0.1)",
            |_, c, _| colour::hsv_to_rgb(c.map(|x| x * 1.3 - 0.1)),
            1.0e-5,
        ),
        case(
            &["veneer_hue_saturation_value"],
            "veneer_hue_saturation_value(c, 0.3, 1.4, 0.8)",
            |_, c, _| colour::hue_saturation_value(c, 0.3, 1.4, 0.8),
            1.0e-5,
        ),
        case(
            &["veneer_brightness_contrast"],
            "veneer_brightness_contrast(c, 0.1, 0.4)",
            |_, c, _| colour::brightness_contrast(c, 0.1, 0.4),
            1.0e-6,
        ),
        case(
            &["veneer_gamma"],
            "veneer_gamma(c - 0.2, 2.2)",
            |_, c, _| colour::gamma(c.map(|x| x - 0.2), 2.2),
            1.0e-5,
        ),
        case(
            &["veneer_invert"],
            "veneer_invert(c, 0.7)",
            |_, c, _| colour::invert(c, 0.7),
            1.0e-6,
        ),
        case(
            &["veneer_levels"],
            "veneer_levels(c, 0.1, 0.9, 1.6, 0.05, 0.95)",
            |_, c, _| colour::levels(c, 0.1, 0.9, 1.6, 0.05, 0.95),
            1.0e-5,
        ),
        case(
            &["veneer_blend_multiply"],
            "veneer_blend_multiply(c, d, 0.65)",
            |_, c, d| colour::blend_multiply(c, d, 0.65),
            1.0e-6,
        ),
        case(
            &["veneer_blend_screen"],
            "veneer_blend_screen(c, d, 0.65)",
            |_, c, d| colour::blend_screen(c, d, 0.65),
            1.0e-6,
        ),
        case(
            &["veneer_blend_overlay"],
            "veneer_blend_overlay(c, d, 0.65)",
            |_, c, d| colour::blend_overlay(c, d, 0.65),
            1.0e-6,
        ),
        case(
            &["veneer_blend_soft_light"],
            "veneer_blend_soft_light(c, d, 0.65)",
            |_, c, d| colour::blend_soft_light(c, d, 0.65),
            1.0e-6,
        ),
        case(
            &["veneer_blend_difference"],
            "veneer_blend_difference(c, d, 0.65)",
            |_, c, d| colour::blend_difference(c, d, 0.65),
            1.0e-6,
        ),
        case(
            &["veneer_map_range_linear", "veneer_map_range_stepped"],
            "vec3f(veneer_map_range_linear(p.x, -2.0, 3.0, 10.0, -4.0, false), veneer_map_range_linear(p.z, -1.0, 1.0, 0.0, 1.0, true), veneer_map_range_stepped(p.x, -2.0, 3.0, 0.0, 1.0, 4.0, false))",
            |p, _, _| {
                [
                    ranges::map_range_linear(p[0], -2.0, 3.0, 10.0, -4.0, false),
                    ranges::map_range_linear(p[2], -1.0, 1.0, 0.0, 1.0, true),
                    ranges::map_range_stepped(p[0], -2.0, 3.0, 0.0, 1.0, 4.0, false),
                ]
            },
            1.0e-5,
        ),
        case(
            &["veneer_map_range_smooth", "veneer_map_range_smoother"],
            "vec3f(veneer_map_range_smooth(p.x, -2.0, 3.0, 1.0, 5.0), veneer_map_range_smoother(p.z, 3.0, -2.0, 1.0, 5.0), 0.0)",
            |p, _, _| {
                [
                    ranges::map_range_smooth(p[0], -2.0, 3.0, 1.0, 5.0),
                    ranges::map_range_smoother(p[2], 3.0, -2.0, 1.0, 5.0),
                    0.0,
                ]
            },
            1.0e-5,
        ),
        case(
            &["veneer_histogram_scan"],
            "vec3f(veneer_histogram_scan(p.x * 0.3, p.z * 0.2, 0.6), veneer_histogram_scan(p.z * 0.3, 0.5, 0.0), veneer_histogram_scan(p.x, 0.7, 1.0))",
            |p, _, _| {
                [
                    ranges::histogram_scan(p[0] * 0.3, p[2] * 0.2, 0.6),
                    ranges::histogram_scan(p[2] * 0.3, 0.5, 0.0),
                    ranges::histogram_scan(p[0], 0.7, 1.0),
                ]
            },
            1.0e-5,
        ),
    ]
}

#[test]
fn the_gpu_computes_what_the_cpu_twins_compute() {
    let rects = [
        FlatRect {
            x0: -3.3,
            z0: -2.7,
            x1: 4.1,
            z1: 4.7,
            y: 0.37,
        },
        FlatRect {
            x0: 1000.3,
            z0: -2000.7,
            x1: 1013.9,
            z1: -1987.1,
            y: 517.25,
        },
    ];
    let size = 16;
    let mut failures = Vec::new();
    for case in cases() {
        let source = material(case.roots, case.expr);
        let renderer = FlatRenderer::new(gpu(), &source)
            .unwrap_or_else(|error| panic!("{}: {error}\n{source}", case.expr));
        let (mut worst, mut outside, mut count) = (0.0f32, 0, 0);
        for rect in rects {
            let pixels = renderer.render(gpu(), rect, size, 0.0).expect("renders");
            for (point, pixel) in flat_points(rect, size).into_iter().zip(pixels) {
                let p = point.map(|x| x as f32);
                let (c, d) = inputs(p);
                let expected = (case.cpu)(p, c, d);
                let error = (0..3)
                    .map(|k| (pixel[k] - expected[k]).abs() / expected[k].abs().max(1.0))
                    .fold(0.0f32, f32::max);
                worst = worst.max(error);
                outside += usize::from(error > case.tolerance);
                count += 1;
            }
        }
        // A few points may sit on a discontinuity (a cell border of white noise, a step,
        // the red end of the hue) where rounding picks either side.
        if outside * 100 > count {
            failures.push(format!(
                "{}: {outside} of {count} points off by more than {} (worst {worst})",
                case.expr, case.tolerance
            ));
        }
        eprintln!("{}: worst {worst:e}, {outside} outside", case.roots[0]);
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
