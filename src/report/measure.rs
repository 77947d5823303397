//! Sampling and timing shared by the report's sections.

use crate::eval::{Evaluator, Surface};
use crate::graph::Graph;
use crate::render::{FlatRect, FlatRenderer, GpuContext, RenderError};
use std::time::Instant;

/// The wall time of each of `runs` calls of `work` (after one untimed warm-up call), in
/// milliseconds.
pub fn samples_ms(runs: usize, mut work: impl FnMut()) -> Vec<f64> {
    samples(runs, || {
        let started = Instant::now();
        work();
        started.elapsed().as_secs_f64() * 1e3
    })
}

/// The median of `runs` values of `sample` (after one warm-up call whose value is left
/// out).
pub fn median(runs: usize, sample: impl FnMut() -> f64) -> f64 {
    median_of(&samples(runs, sample))
}

/// `runs` values of `sample` (at least one), after one warm-up call whose value is left
/// out.
pub fn samples(runs: usize, mut sample: impl FnMut() -> f64) -> Vec<f64> {
    sample();
    (0..runs.max(1)).map(|_| sample()).collect()
}

/// The median of `values` (the upper one of an even count; NaN when empty).
pub fn median_of(values: &[f64]) -> f64 {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    sorted.get(sorted.len() / 2).copied().unwrap_or(f64::NAN)
}

/// The mean of `values` and their standard deviation (sample, n − 1; 0 for one value).
pub fn mean_deviation(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let squares = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>();
    (mean, (squares / (n - 1.0).max(1.0)).sqrt())
}

/// The albedo at each point by the CPU evaluator in f32 or f64, and the time it took.
pub fn cpu_albedo(graph: &Graph, points: &[[f64; 3]], double: bool) -> (Vec<[f64; 3]>, f64) {
    let evaluator = Evaluator::new(graph).expect("report graphs check");
    let started = Instant::now();
    let albedo = points
        .iter()
        .map(|&p| {
            if double {
                evaluator.eval(&Surface::<f64>::at(p)).albedo
            } else {
                evaluator.eval(&Surface::<f32>::at(p)).albedo.map(f64::from)
            }
        })
        .collect();
    (albedo, started.elapsed().as_secs_f64() * 1e3)
}

/// The albedo of a flat render by the GPU (f32), as f64.
pub fn gpu_albedo(
    gpu: &GpuContext,
    renderer: &FlatRenderer,
    rect: FlatRect,
    size: u32,
) -> Result<Vec<[f64; 3]>, RenderError> {
    Ok(renderer
        .render(gpu, rect, size, 0.0)?
        .iter()
        .map(|p| [p[0], p[1], p[2]].map(f64::from))
        .collect())
}

/// Largest and mean absolute difference over every channel.
pub fn errors(values: &[[f64; 3]], reference: &[[f64; 3]]) -> (f64, f64) {
    let differences: Vec<f64> = values
        .iter()
        .zip(reference)
        .flat_map(|(a, b)| (0..3).map(move |k| (a[k] - b[k]).abs()))
        .map(|d| if d.is_finite() { d } else { f64::INFINITY })
        .collect();
    let max = differences.iter().copied().fold(0.0, f64::max);
    (
        max,
        differences.iter().sum::<f64>() / differences.len().max(1) as f64,
    )
}

/// The processor's name and core count, for the report's captions.
pub fn machine() -> String {
    let model = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|info| {
            info.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| std::env::consts::ARCH.to_string());
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    format!("{model}, {cores} cores")
}
