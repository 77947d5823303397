//! Fitting, measured in one run:
//! - **Recovery**: every preset in `graphs/` with at least three exposed continuous
//!   parameters that reach the albedo is rendered (on the CPU, in f32 as the GPU
//!   renders) at values drawn at random (seeded, away from the ranges' ends), then
//!   fitted from its own values with the default settings and a 60 s budget: the median
//!   normalised parameter error and the loss left, against **random search** over the
//!   same parameters given the same wall time, and against the fit with `--global` (its
//!   later starts searched by an evolution strategy first). Beside them, why a fit from afar misses:
//!   each coordinate's **basin** at the truth (how far along it a start may lie and
//!   still slide back, the others true; [`basin_width`]), and the median error of a fit
//!   (`--aligned`, the target being the graph's own render) started within ±0.1 of the
//!   truth.
//! - **Gradient cost**: the derivative of a loss by every parameter of wood's full graph
//!   at 128² against rendering it.
//!
//! `cargo bench --bench fit` prints both as Markdown tables (the README's).

use std::time::{Duration, Instant};
use veneer::fit::image::Canvas;
use veneer::fit::loss::Loss;
use veneer::fit::recovery::{basin_width, draw_truth, median, median_error, near};
use veneer::fit::{FitSettings, Prepared, fit, prepare, random_search};

/// The seed of the drawn values.
const SEED: u64 = 11;
/// The side of the compared images.
const SIZE: u32 = 128;
/// The side of the images a basin scan compares (the fit's coarse size).
const BASIN_SIZE: u32 = 64;
/// A basin narrower than this (in normalised units) is missed by a start any farther.
const NARROW: f64 = 0.1;
/// How far from the truth the nearby starts are drawn.
const NEAR: f64 = 0.1;

/// The prepared presets that qualify, by file name.
fn presets() -> Vec<(String, Prepared)> {
    let mut paths: Vec<_> = std::fs::read_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/graphs"))
        .expect("graphs/")
        .filter_map(|entry| entry.ok().map(|entry| entry.path()))
        .filter(|path| path.extension().is_some_and(|e| e == "ron"))
        .collect();
    paths.sort();
    paths
        .into_iter()
        .filter_map(|path| {
            let graph = veneer::graph::load(&path).ok()?;
            let prepared = prepare(&graph, None).ok()?;
            let names = (prepared.space.coordinates.iter()).map(|c| c.parameter);
            let parameters: std::collections::BTreeSet<usize> = names.collect();
            let name = path.file_name()?.to_string_lossy().into_owned();
            (parameters.len() >= 3).then_some((name, prepared))
        })
        .collect()
}

/// The basins of `prepared`'s coordinates at `truth`: the median width of those the
/// image shows, how many are narrower than [`NARROW`], how many it does not show.
fn basins(prepared: &Prepared, truth: &[f64]) -> (f64, usize, usize) {
    let canvas = Canvas {
        evaluator: &prepared.evaluator,
        rect: prepared.rect,
        size: BASIN_SIZE,
    };
    let space = &prepared.space;
    let loss = Loss::new(1);
    let target = loss.target(&canvas.render(space, truth), true);
    let evaluate = |places: &[f64]| loss.evaluate(&canvas.render(space, places), &target).0;
    let flat_below = 1e-6 * evaluate(&space.start()).total();
    let widths: Vec<Option<f64>> = (0..truth.len())
        .map(|k| basin_width(&canvas, (&loss, &target), space, truth, k, flat_below))
        .collect();
    let shown: Vec<f64> = widths.iter().flatten().copied().collect();
    let (narrow, flat) = (
        shown.iter().filter(|&&w| w < NARROW).count(),
        widths.len() - shown.len(),
    );
    (median(shown), narrow, flat)
}

fn recovery() {
    println!(
        "| graph | coordinates | basin width: median (< {NARROW} / flat) | median error | loss left | fit s | random search loss left (draws) | `--global`: median error | loss left | s | median error from ±{NEAR} of the truth |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for (name, prepared) in presets() {
        let Prepared {
            evaluator,
            space,
            rect,
        } = &prepared;
        let canvas = Canvas {
            evaluator,
            rect: *rect,
            size: SIZE,
        };
        let truth = draw_truth(space, SEED);
        let photo = canvas.render(space, &truth).to_photo();
        let settings = FitSettings {
            budget: Some(Duration::from_secs(60)),
            ..FitSettings::default()
        };
        let clock = Instant::now();
        let fitted = fit(evaluator, *rect, space, &photo, &settings, |_| true);
        let seconds = clock.elapsed();
        let searched = random_search(evaluator, *rect, space, &photo, &settings, seconds);
        let start = fitted.initial.total();
        let global = FitSettings {
            global: true,
            ..settings.clone()
        };
        let clock = Instant::now();
        let searched_globally = fit(evaluator, *rect, space, &photo, &global, |_| true);
        let global_seconds = clock.elapsed().as_secs_f64();
        let (width, narrow, flat) = basins(&prepared, &truth);
        let nearby = space.starting_at(&near(&truth, NEAR, SEED));
        let aligned = FitSettings {
            aligned: true,
            ..settings
        };
        let from_near = fit(evaluator, *rect, &nearby, &photo, &aligned, |_| true);
        println!(
            "| {name} | {} | {width:.3} ({narrow} / {flat}) | {:.3} | {:.1}% | {:.1} | {:.1}% ({}) | {:.3} | {:.1}% | {global_seconds:.1} | {:.3} |",
            space.coordinates.len(),
            median_error(&fitted.places, &truth),
            100.0 * fitted.parts.total() / start,
            seconds.as_secs_f64(),
            100.0 * searched.loss / start,
            searched.draws,
            median_error(&searched_globally.places, &truth),
            100.0 * searched_globally.parts.total() / start,
            median_error(&from_near.places, &truth),
        );
    }
}

fn gradient_cost() {
    let graph = veneer::graph::load(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/graphs/wood.ron"
    )))
    .expect("wood loads");
    let Prepared {
        evaluator,
        space,
        rect,
    } = prepare(&graph, None).expect("wood fits");
    let canvas = Canvas {
        evaluator: &evaluator,
        rect,
        size: SIZE,
    };
    let places = space.start();
    let weights = vec![[1.0, 1.0, 1.0]; (SIZE * SIZE) as usize];
    let time = |work: &dyn Fn()| {
        work();
        let clock = Instant::now();
        for _ in 0..5 {
            work();
        }
        clock.elapsed().as_secs_f64() / 5.0
    };
    let render = time(&|| {
        std::hint::black_box(canvas.render(&space, &places));
    });
    let gradient = time(&|| {
        std::hint::black_box(canvas.pull_back(&space, &places, &weights));
    });
    println!();
    println!(
        "| wood at {SIZE}², {} coordinates | ms | × render |",
        space.coordinates.len()
    );
    println!("|---|---|---|");
    println!("| render (f32) | {:.1} | 1.0 |", 1e3 * render);
    println!(
        "| gradient (taped, reverse mode) | {:.1} | {:.1} |",
        1e3 * gradient,
        gradient / render
    );
}

fn main() {
    // `cargo test --benches` runs this with `--bench` absent: nothing to measure then.
    if !std::env::args().any(|arg| arg == "--bench") {
        return;
    }
    recovery();
    gradient_cost();
}
