//! The report's material sections: precision (GPU f32 and CPU f32 against CPU f64),
//! hash choice and octave budget.

use super::level_of_detail::shown_in_grey;
use super::measure::{cpu_albedo, errors, gpu_albedo, median};
use super::plot::{Plot, Series};
use super::table::{Table, number};
use super::{Context, Section};
use crate::codegen::{CompileOptions, Detail, compile};
use crate::graph::{Basis, Graph, NodeKind, PRESETS, Value};
use crate::nodes::{Fbm, Noise, Turbulence, Worley};
use crate::render::{FlatRect, FlatRenderer, flat_points, preview_rect};

/// A graph showing one scalar node's output as grey, at `scale`.
fn single_node(kind: NodeKind, scale: f64) -> Graph {
    let mut graph = Graph::default();
    let node = graph.add("under test", kind);
    graph.set_input(node, "scale", Value::Float(scale));
    shown_in_grey(&mut graph, node, "value");
    graph
}

/// The flat renderer of `graph`, compiled once with noise detail `detail`.
pub(super) fn renderer(
    ctx: &Context,
    graph: &Graph,
    detail: Detail,
) -> Result<FlatRenderer, String> {
    let compiled =
        compile(graph, &CompileOptions::with_detail(detail)).map_err(|e| e.to_string())?;
    FlatRenderer::new(ctx.gpu, compiled.source()).map_err(|e| e.to_string())
}

/// GPU time per megapixel of a flat render of `graph` over `rect`.
pub(super) fn gpu_ms_per_megapixel(ctx: &Context, renderer: &FlatRenderer, rect: FlatRect) -> f64 {
    let size = ctx.timing_size;
    let ms = median(ctx.repetitions, || {
        renderer
            .shading_time(ctx.gpu, rect, size, 0.0)
            .map_or(f64::NAN, |time| time.as_secs_f64() * 1e3)
    });
    ms / (f64::from(size * size) / 1e6)
}

/// Precision: every preset and each noise family, GPU f32 and CPU f32 against CPU f64.
pub fn precision(ctx: &Context) -> Result<Section, String> {
    let mut cases: Vec<(String, Graph, FlatRect)> = PRESETS
        .iter()
        .filter_map(|(name, _)| crate::graph::preset(name).map(|g| (name.to_string(), g)))
        .map(|(name, graph)| {
            let rect = preview_rect(&graph.preview);
            (name, graph, rect)
        })
        .collect();
    let square = FlatRect {
        x0: -4.0,
        z0: -4.0,
        x1: 4.0,
        z1: 4.0,
        y: 0.3,
    };
    for basis in Basis::ALL {
        cases.push((
            format!("noise ({basis:?})"),
            single_node(NodeKind::Noise(Noise { basis, period: 0 }), 2.0),
            square,
        ));
        let fbm = NodeKind::Fbm(Fbm {
            basis,
            octaves: 6,
            normalize: true,
            rotate: false,
            period: 0,
        });
        cases.push((format!("fBm 6 ({basis:?})"), single_node(fbm, 2.0), square));
    }
    let worley = NodeKind::Worley(Worley {
        feature: crate::graph::WorleyFeature::F1,
        metric: crate::graph::Metric::Euclidean,
        octaves: 3,
        period: 0,
        points: crate::graph::FeaturePoints::Hashed,
    });
    cases.push(("Worley, 3 octaves".into(), single_node(worley, 2.0), square));
    let mut table = Table::new(&[
        "material",
        "GPU f32 max",
        "GPU f32 mean",
        "CPU f32 max",
        "CPU f32 mean",
        "GPU ms/MP",
        "CPU f32 ms/MP",
        "CPU f64 ms/MP",
    ]);
    let (mut gpu_points, mut cpu_points) = (Vec::new(), Vec::new());
    let size = ctx.sample_size;
    for (name, graph, rect) in &cases {
        let points = flat_points(*rect, size);
        let (reference, f64_ms) = cpu_albedo(graph, &points, true);
        let (single, f32_ms) = cpu_albedo(graph, &points, false);
        let flat = renderer(ctx, graph, Detail::Full)?;
        let gpu = gpu_albedo(ctx.gpu, &flat, *rect, size).map_err(|e| e.to_string())?;
        let gpu_ms = gpu_ms_per_megapixel(ctx, &flat, *rect);
        let per_mp = |ms: f64| ms / (points.len() as f64 / 1e6);
        let (gpu_max, gpu_mean) = errors(&gpu, &reference);
        let (cpu_max, cpu_mean) = errors(&single, &reference);
        gpu_points.push((gpu_ms, gpu_mean.max(1e-9)));
        cpu_points.push((per_mp(f32_ms), cpu_mean.max(1e-9)));
        table.push(vec![
            name.clone(),
            number(gpu_max, 2),
            number(gpu_mean, 2),
            number(cpu_max, 2),
            number(cpu_mean, 2),
            number(gpu_ms, 3),
            number(per_mp(f32_ms), 3),
            number(per_mp(f64_ms), 3),
        ]);
        (ctx.progress)();
    }
    Ok(Section {
        title: "Precision: f32 on the GPU and the CPU against an f64 reference".into(),
        text: format!(
            "Albedo of every preset over its preview square and of each noise family over [-4, 4]², {size}² points, each evaluated by the GPU flat render (f32), the CPU evaluator in f32 and in f64; errors are absolute, over the three channels, against f64. GPU time per megapixel is the median of {} flat renders at {}²; CPU times are one pass over the {size}² points. The sine-hash families (`ValueSine`, the wood and marble presets) are chaotic in their constants: f32 and f64 disagree almost everywhere (see *Hash choice*), which is why their errors are large; the PCG families agree to rounding.",
            ctx.repetitions, ctx.timing_size
        ),
        table,
        plot: Plot {
            title: "Precision against time".into(),
            x_label: "time per megapixel (ms)".into(),
            y_label: "mean absolute error against f64".into(),
            series: vec![
                Series {
                    name: "GPU f32".into(),
                    points: gpu_points,
                    joined: false,
                },
                Series {
                    name: "CPU f32".into(),
                    points: cpu_points,
                    joined: false,
                },
            ],
        },
    })
}

/// Neighbour correlation, mean and variance of a scalar image (one channel).
fn statistics(values: &[f64], size: usize) -> (f64, f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let variance = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n;
    let mut covariance = 0.0;
    let mut pairs = 0.0;
    for (k, v) in values.iter().enumerate() {
        if k % size + 1 < size {
            covariance += (v - mean) * (values[k + 1] - mean);
            pairs += 1.0;
        }
    }
    (mean, variance, covariance / pairs / variance.max(1e-30))
}

/// Hash choice: the seed's sine hash against PCG3D, at the origin and far from it.
pub fn hashes(ctx: &Context) -> Result<Section, String> {
    let mut table = Table::new(&[
        "hash",
        "offset",
        "mean",
        "variance",
        "neighbour correlation",
        "CPU f32 = GPU (share within 1e-3)",
        "fBm 8 GPU ms/MP",
    ]);
    let mut series = Vec::new();
    for basis in [Basis::ValueSine, Basis::ValuePcg] {
        let lattice = single_node(NodeKind::Noise(Noise { basis, period: 0 }), 1.0);
        let fbm = single_node(
            NodeKind::Fbm(Fbm {
                basis,
                octaves: 8,
                normalize: true,
                rotate: false,
                period: 0,
            }),
            1.0,
        );
        let fbm_renderer = renderer(ctx, &fbm, Detail::Full)?;
        let flat = renderer(ctx, &lattice, Detail::Full)?;
        let mut points = Vec::new();
        for offset in [0.0, 1.0e4, 1.0e6] {
            // Pixel centres on whole numbers: each pixel is one lattice value.
            let size = ctx.sample_size;
            let rect = FlatRect {
                x0: offset - 0.5,
                z0: -0.5,
                x1: offset + f64::from(size) - 0.5,
                z1: f64::from(size) - 0.5,
                y: 0.0,
            };
            let gpu = gpu_albedo(ctx.gpu, &flat, rect, size).map_err(|e| e.to_string())?;
            let (cpu, _) = cpu_albedo(&lattice, &flat_points(rect, size), false);
            let values: Vec<f64> = gpu.iter().map(|p| p[0]).collect();
            let (mean, variance, correlation) = statistics(&values, size as usize);
            let agree = gpu
                .iter()
                .zip(&cpu)
                .filter(|(a, b)| (a[0] - b[0]).abs() <= 1e-3)
                .count() as f64
                / gpu.len() as f64;
            let speed = gpu_ms_per_megapixel(ctx, &fbm_renderer, rect);
            points.push((speed, correlation.abs().max(1e-4)));
            table.push(vec![
                format!("{basis:?}"),
                number(offset, 2),
                number(mean, 3),
                number(variance, 3),
                number(correlation, 2),
                format!("{:.1}%", 100.0 * agree),
                number(speed, 3),
            ]);
            (ctx.progress)();
        }
        series.push(Series {
            name: format!("{basis:?} (origin, 1e4, 1e6)"),
            points,
            joined: true,
        });
    }
    Ok(Section {
        title: "Hash choice: sine hash against PCG3D".into(),
        text: "Value noise sampled at whole-number points (one lattice value per pixel) of a square at the origin and shifted by 10⁴ and 10⁶: the statistics of a good hash are mean 0.5, variance 1/12 ≈ 0.083 and neighbour correlation 0; the agreement column is the share of points where the CPU evaluator (f32) and the GPU give the same value within 10⁻³. Speed is an 8-octave fBm of each hash, rendered flat. The sine hash loses its randomness far from the origin (f32 `sin` of large arguments) and never agrees bit-for-bit between CPU and GPU; PCG3D works on integer cells and agrees everywhere.".into(),
        table,
        plot: Plot {
            title: "Hash: cost against neighbour correlation".into(),
            x_label: "fBm 8 time per megapixel (ms)".into(),
            y_label: "|neighbour correlation| (lower is better)".into(),
            series,
        },
    })
}

/// Octave budget: fBm and turbulence with 1…N octaves against a 16-octave reference.
pub fn octaves(ctx: &Context) -> Result<Section, String> {
    let mut table = Table::new(&["kind", "octaves", "RMS error", "max error", "GPU ms/MP"]);
    let mut series = Vec::new();
    let rect = FlatRect {
        x0: -2.0,
        z0: -2.0,
        x1: 2.0,
        z1: 2.0,
        y: 0.3,
    };
    let points = flat_points(rect, ctx.sample_size / 2);
    let kind = |turbulence: bool, octaves: u32| {
        let basis = Basis::Gradient;
        if turbulence {
            NodeKind::Turbulence(Turbulence {
                basis,
                octaves,
                normalize: false,
                rotate: false,
                period: 0,
            })
        } else {
            NodeKind::Fbm(Fbm {
                basis,
                octaves,
                normalize: false,
                rotate: false,
                period: 0,
            })
        }
    };
    for turbulence in [false, true] {
        let name = if turbulence { "turbulence" } else { "fBm" };
        let (reference, _) = cpu_albedo(&single_node(kind(turbulence, 16), 4.0), &points, true);
        let mut line = Vec::new();
        for octaves in 1..=ctx.max_octaves {
            let graph = single_node(kind(turbulence, octaves), 4.0);
            let (values, _) = cpu_albedo(&graph, &points, true);
            let (max, _) = errors(&values, &reference);
            let rms = (values
                .iter()
                .zip(&reference)
                .map(|(a, b)| (a[0] - b[0]).powi(2))
                .sum::<f64>()
                / values.len() as f64)
                .sqrt();
            let speed = gpu_ms_per_megapixel(ctx, &renderer(ctx, &graph, Detail::Full)?, rect);
            line.push((speed, rms.max(1e-9)));
            table.push(vec![
                name.into(),
                octaves.to_string(),
                number(rms, 2),
                number(max, 2),
                number(speed, 3),
            ]);
        }
        (ctx.progress)();
        series.push(Series {
            name: name.into(),
            points: line,
            joined: true,
        });
    }
    Ok(Section {
        title: "Octave budget: what each octave buys".into(),
        text: "Gradient-noise fBm and turbulence (lacunarity 2, gain 0.5, scale 4) with 1 to N octaves against the same sum with 16 octaves, evaluated in f64 over [-2, 2]²; the error halves with each octave (the gain) while the time grows linearly. Each point of the plot is one octave count.".into(),
        table,
        plot: Plot {
            title: "Octaves: error against time".into(),
            x_label: "GPU time per megapixel (ms)".into(),
            y_label: "RMS error against 16 octaves".into(),
            series,
        },
    })
}
