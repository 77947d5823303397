//! The tile sampler's cost on the flat albedo render (`FlatRenderer::render`, what
//! `veneer render --flat` and a plane bake draw), in one run:
//! - **rotation**: a 64×64 grid with every instance turned at random (rotation_random 1)
//!   against the same grid unturned (the baseline); the target is rotated ≤ 3× unrotated;
//! - **instances per pixel, not in all**: a 16×16 grid against a 256×256 one whose
//!   instances take the same share of their cells (scale 0.9), so that each pixel is
//!   reached by as many instances; the ratio should be near 1.
//!
//! Every sampler scales its instances at random (scale_random 0.3) and draws a gradient
//! noise in each instance's frame as its pattern. Beside each time, the CPU twin's search
//! (`formulas::instances::search`) counts, over a sample of points, the cells examined
//! and the instances reaching the point (whose patterns are evaluated): the evidence
//! that the neighbour search stays tight. A constant albedo gives the floor every render
//! pays (drawing and reading back size² pixels).
//!
//! `VENEER_BENCH_SIZE=512 cargo bench --bench tile_sampler` (default size 2048;
//! `VENEER_BENCH_RUNS`, default 5, the timed renders per row after one warm-up, taken
//! in turns across the rows; each row shows its median).

use std::time::{Duration, Instant};
use veneer::bake::UNIT_TILE;
use veneer::codegen::compile;
use veneer::graph::{Basis, Graph, NodeKind, Value};
use veneer::nodes::formulas::instances::{self, GridSettings, TileBlend};
use veneer::nodes::{Noise, TileSampler};
use veneer::render::{FlatRenderer, GpuContext};

/// Each instance's size as a share of its cell, and how much smaller at random.
const SCALE: f64 = 0.9;
const SCALE_RANDOM: f64 = 0.3;
/// Points the CPU search is run at, per configuration.
const SEARCH_POINTS: u32 = 1 << 16;

/// A sampler of `cells`×`cells` instances, turned at random (±180°) or not at all.
#[derive(Clone, Copy)]
struct Sampler {
    cells: u32,
    rotated: bool,
}

impl Sampler {
    fn label(self) -> String {
        format!("{0}×{0}, {1}", self.cells, turn(self.rotated))
    }

    fn rotation_random(self) -> f64 {
        if self.rotated { 1.0 } else { 0.0 }
    }

    /// The sampler's inputs that differ from their defaults (rotation stays 0).
    fn inputs(self) -> [(&'static str, f64); 5] {
        let cells = f64::from(self.cells);
        [
            ("columns", cells),
            ("rows", cells),
            ("rotation_random", self.rotation_random()),
            ("scale", SCALE),
            ("scale_random", SCALE_RANDOM),
        ]
    }

    /// The material: the sampler's height as the albedo, its pattern a noise.
    fn graph(self) -> Graph {
        let mut graph = Graph::default();
        let sampler = graph.add(
            "sampler",
            NodeKind::TileSampler(TileSampler {
                blend: TileBlend::Max,
            }),
        );
        for (pin, value) in self.inputs() {
            graph.set_input(sampler, pin, Value::Float(value));
        }
        let grain = graph.add(
            "grain",
            NodeKind::Noise(Noise {
                basis: Basis::Gradient,
                period: 0,
            }),
        );
        graph.set_input(grain, "scale", Value::Float(4.0));
        let material = graph.add("material", NodeKind::Material);
        graph.connect(grain, "value", sampler, "pattern");
        graph.connect(sampler, "height", material, "albedo");
        graph
    }

    /// The grid as the node's inputs give it to the CPU twin.
    fn settings(self) -> GridSettings<f64> {
        let cells = f64::from(self.cells);
        GridSettings {
            size: [1.0, 1.0],
            counts: [cells, cells],
            offsets: [0.0, 0.0],
            jitter: 0.0,
            rotation: 0.0,
            rotation_random: self.rotation_random(),
            scale: SCALE,
            scale_xy: [1.0, 1.0],
            scale_random: SCALE_RANDOM,
            seed: 0.0,
            footprint: 0.0,
            // One instance per cell (0), whatever the field's type.
            splat: Default::default(),
        }
    }

    /// Mean cells examined and instances reaching a point (patterns evaluated), over
    /// points of the unit tile spread by the R2 low-discrepancy sequence (no beating
    /// with the grid).
    fn search_counts(self) -> (f64, f64) {
        let settings = self.settings();
        let (mut cells, mut reached) = (0u64, 0u64);
        for n in 0..SEARCH_POINTS {
            let n = f64::from(n);
            let p = [
                (0.5 + n * 0.754_877_666_246_692_8).fract(),
                0.0,
                (0.5 + n * 0.569_840_290_998_053_3).fract(),
            ];
            let grid = instances::setup(p, &settings);
            let (first_row, last_row) = instances::rows(&grid);
            for row in first_row..=last_row {
                let (first, last) = instances::columns(&grid, row);
                cells += (last - first + 1).max(0) as u64;
            }
            instances::search(&grid, |_| reached += 1);
        }
        let points = f64::from(SEARCH_POINTS);
        (cells as f64 / points, reached as f64 / points)
    }
}

/// A whole-number setting from the environment.
fn setting(name: &str, default: u32) -> u32 {
    std::env::var(name)
        .ok()
        .map(|text| {
            text.parse()
                .unwrap_or_else(|_| panic!("{name}: not a number"))
        })
        .unwrap_or(default)
}

/// A material's flat albedo renderer at size², timed in turns with the others (so that
/// a change in the machine's load falls on every row alike).
struct Timed {
    flat: FlatRenderer,
    times: Vec<Duration>,
}

impl Timed {
    /// Compiles `graph` and renders it once (the warm-up).
    fn new(gpu: &GpuContext, graph: &Graph, size: u32) -> Timed {
        let compiled = compile(graph, &Default::default()).expect("the graph compiles");
        let flat = FlatRenderer::for_compiled(gpu, &compiled).expect("the pipeline builds");
        flat.render(gpu, UNIT_TILE, size, 0.0).expect("renders");
        Timed {
            flat,
            times: Vec::new(),
        }
    }

    fn run(&mut self, gpu: &GpuContext, size: u32) {
        let started = Instant::now();
        let pixels = self
            .flat
            .render(gpu, UNIT_TILE, size, 0.0)
            .expect("renders");
        self.times.push(started.elapsed());
        std::hint::black_box(pixels);
    }

    fn median(&self) -> Duration {
        let mut times = self.times.clone();
        times.sort();
        times[times.len() / 2]
    }
}

/// The ratio of two times, and of their parts above the floor.
fn ratio(time: Duration, baseline: Duration, floor: Duration) -> String {
    let above = |t: Duration| t.saturating_sub(floor).as_secs_f64();
    format!(
        "{:.2}× ({:.2}× above the floor)",
        time.as_secs_f64() / baseline.as_secs_f64(),
        above(time) / above(baseline).max(1e-9)
    )
}

fn main() {
    let size = setting("VENEER_BENCH_SIZE", 2048);
    let runs = setting("VENEER_BENCH_RUNS", 5).max(1);
    let gpu = GpuContext::new().expect("a wgpu adapter");
    println!(
        "tile sampler: flat albedo render at {size}² on {}, median of {runs} in turns",
        gpu.adapter_description()
    );
    let mut constant = Graph::default();
    let material = constant.add("material", NodeKind::Material);
    constant.set_input(material, "albedo", Value::Color(0.5, 0.5, 0.5));
    let samplers: Vec<Sampler> = [16, 64, 256]
        .into_iter()
        .flat_map(|cells| [false, true].map(|rotated| Sampler { cells, rotated }))
        .collect();
    let mut floor = Timed::new(&gpu, &constant, size);
    let mut timed: Vec<Timed> = (samplers.iter())
        .map(|sampler| Timed::new(&gpu, &sampler.graph(), size))
        .collect();
    for _ in 0..runs {
        floor.run(&gpu, size);
        timed.iter_mut().for_each(|row| row.run(&gpu, size));
    }
    let floor = floor.median();
    println!(
        "{:<28} {:>9.1} ms",
        "constant albedo (the floor)",
        ms(floor)
    );
    println!(
        "{:<28} {:>12} {:>15} {:>16}",
        "sampler", "time", "cells searched", "instances/point"
    );
    for (sampler, row) in samplers.iter().zip(&timed) {
        let (searched, reached) = sampler.search_counts();
        println!(
            "{:<28} {:>9.1} ms {searched:>15.3} {reached:>16.3}",
            sampler.label(),
            ms(row.median())
        );
    }
    let time = |cells, rotated| {
        let at = (samplers.iter())
            .position(|s| (s.cells, s.rotated) == (cells, rotated))
            .expect("measured");
        timed[at].median()
    };
    println!(
        "64×64 rotated / unrotated (target ≤ 3×): {}",
        ratio(time(64, true), time(64, false), floor)
    );
    for rotated in [false, true] {
        println!(
            "256×256 / 16×16 at equal coverage, {} (target ≈ 1): {}",
            turn(rotated),
            ratio(time(256, rotated), time(16, rotated), floor)
        );
    }
}

fn turn(rotated: bool) -> &'static str {
    if rotated { "rotated" } else { "unrotated" }
}

fn ms(time: Duration) -> f64 {
    time.as_secs_f64() * 1e3
}
