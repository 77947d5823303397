//! The fit itself: Adam on the normalised coordinates (kept within [0, 1]), at a coarse
//! size first, from several starts: the graph's own values, then the best of many random
//! draws (screened by their loss alone, which costs a fraction of a step) — or, with
//! `global`, the best of a search without derivatives ([`evolution`]) from the graph's
//! values and from screened draws. The best start is then refined at twice the side,
//! and twice again, up to the full size. The best places seen are kept, the time budget
//! is respected (checked before every step and generation) and the caller may stop it at
//! any step. For a given seed, step count and size, the result is the same on every run
//! (a budget that cuts it short makes it depend on the machine's speed).

use super::Draws;
use super::evolution;
use super::image::{Canvas, Image};
use super::loss::{Loss, LossParts, Target};
use super::space::Space;
use crate::eval::Evaluator;
use crate::render::FlatRect;
use std::time::{Duration, Instant};

/// How a fit runs.
#[derive(Clone, Debug)]
pub struct FitSettings {
    /// The side of the final images, in pixels.
    pub size: u32,
    /// Adam steps per start at the coarse size (half as many refine the best at twice
    /// the side, a quarter at four times, … up to the full size); with `global`, each
    /// start after the first searches for half as many generations before its steps.
    pub steps: usize,
    /// Starts: the graph's values, then random draws (with `global`: a global search
    /// from the graph's values, then from random draws).
    pub starts: usize,
    /// Stop when this much time has passed.
    pub budget: Option<Duration>,
    /// Draws the random starts and the loss's directions.
    pub seed: u64,
    /// Whether the photo is the graph's own render over the same square (adds the
    /// pixel-aligned part).
    pub aligned: bool,
    /// Whether the starts after the first search globally ([`evolution`]) before their
    /// steps; otherwise they descend from screened random draws.
    pub global: bool,
}

impl Default for FitSettings {
    /// 40 steps from each of 3 starts at the coarse size, refined at 128², seed 1, no
    /// budget, the photo not aligned, no global search.
    fn default() -> FitSettings {
        FitSettings {
            size: 128,
            steps: 40,
            starts: 3,
            budget: None,
            seed: 1,
            aligned: false,
            global: false,
        }
    }
}

/// Adam's step size in normalised units.
const LEARNING_RATE: f64 = 0.03;
/// The side of the coarse stage's images (or the full size, if smaller).
const COARSE: u32 = 64;
/// The step, in normalised units, of the loss's central difference where the tape
/// gives no derivative.
const STEP: f64 = 0.02;
/// Random draws screened for each random start.
const SCREENED_PER_START: usize = 16;

/// Where a fit is, for progress reports.
#[derive(Clone, Debug)]
pub struct Progress {
    /// Which start (0 the graph's values), or `None` while refining the best.
    pub start: Option<usize>,
    pub step: usize,
    /// Steps in all, refinement included.
    pub total_steps: usize,
    /// The loss at `places`.
    pub loss: f64,
    pub seconds: f64,
    /// The normalised places this step starts from.
    pub places: Vec<f64>,
}

/// How one start ended (at the coarse size).
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct StartResult {
    pub initial: f64,
    pub best: f64,
}

/// What a fit found.
#[derive(Clone, Debug)]
pub struct Fitted {
    /// The best normalised places.
    pub places: Vec<f64>,
    /// The toggles' and choices' values found, in the order of the space's `discrete`
    /// (apply them with [`Space::with_choices`]).
    pub choices: Vec<f64>,
    /// The loss there, at the full size.
    pub parts: LossParts,
    /// The loss at the graph's own values, at the full size.
    pub initial: LossParts,
    pub starts: Vec<StartResult>,
    /// Steps taken in all.
    pub steps: usize,
    pub seconds: f64,
    /// Whether the budget or the caller stopped it before every step ran.
    pub cut_short: bool,
}

/// The square crop of `photo`'s middle, resampled to `size`×`size`.
pub fn resample(photo: &image::Rgb32FImage, size: u32) -> Image {
    let side = photo.width().min(photo.height());
    let (x, y) = ((photo.width() - side) / 2, (photo.height() - side) / 2);
    let square = image::imageops::crop_imm(photo, x, y, side, side).to_image();
    let resized =
        image::imageops::resize(&square, size, size, image::imageops::FilterType::Triangle);
    Image {
        size,
        pixels: (resized.pixels()).map(|p| p.0.map(f64::from)).collect(),
    }
}

/// One stage's canvas and target.
struct Stage<'e> {
    canvas: Canvas<'e>,
    target: Target,
}

impl<'e> Stage<'e> {
    fn new(
        evaluator: &'e Evaluator,
        rect: FlatRect,
        size: u32,
        photo: &image::Rgb32FImage,
        loss: &Loss,
        aligned: bool,
    ) -> Stage<'e> {
        Stage {
            canvas: Canvas {
                evaluator,
                rect,
                size,
            },
            target: loss.target(&resample(photo, size), aligned),
        }
    }

    /// The stage at the settings' full size (with the aligned part where they ask).
    fn full(
        evaluator: &'e Evaluator,
        rect: FlatRect,
        photo: &image::Rgb32FImage,
        loss: &Loss,
        settings: &FitSettings,
    ) -> Stage<'e> {
        let (size, aligned) = (settings.size, settings.aligned);
        Stage::new(evaluator, rect, size, photo, loss, aligned)
    }

    /// The loss at `places`, and its derivative by each pixel.
    fn loss(&self, loss: &Loss, space: &Space, places: &[f64]) -> (LossParts, Vec<[f64; 3]>) {
        loss.evaluate(&self.canvas.render(space, places), &self.target)
    }

    /// The derivative by each of `places` of the loss whose derivative by each pixel
    /// there is `by_pixel`: exact through the tape; where the tape has none for a
    /// coordinate (it only moves steps, floors or cells: a tile's size, a threshold with
    /// no softness), the loss's central difference instead.
    fn gradient(
        &self,
        loss: &Loss,
        space: &Space,
        places: &[f64],
        by_pixel: &[[f64; 3]],
    ) -> Vec<f64> {
        let mut gradient = self.canvas.pull_back(space, places, by_pixel);
        for (k, derivative) in gradient.iter_mut().enumerate() {
            if *derivative == 0.0 {
                let at = |t: f64| {
                    let mut moved = places.to_vec();
                    moved[k] = t.clamp(0.0, 1.0);
                    (self.loss(loss, space, &moved).0.total(), moved[k])
                };
                let ((up, high), (down, low)) = (at(places[k] + STEP), at(places[k] - STEP));
                *derivative = (up - down) / (high - low);
            }
        }
        gradient
    }
}

/// Adam's running moments.
struct Adam {
    first: Vec<f64>,
    second: Vec<f64>,
    steps: i32,
}

impl Adam {
    fn new(count: usize) -> Adam {
        Adam {
            first: vec![0.0; count],
            second: vec![0.0; count],
            steps: 0,
        }
    }

    /// `places` moved one step against `gradient`, kept within [0, 1].
    fn step(&mut self, places: &mut [f64], gradient: &[f64]) {
        const BETA1: f64 = 0.9;
        const BETA2: f64 = 0.999;
        self.steps += 1;
        let (fix1, fix2) = (1.0 - BETA1.powi(self.steps), 1.0 - BETA2.powi(self.steps));
        for k in 0..places.len() {
            let g = gradient[k];
            self.first[k] = BETA1 * self.first[k] + (1.0 - BETA1) * g;
            self.second[k] = BETA2 * self.second[k] + (1.0 - BETA2) * g * g;
            let (m, v) = (self.first[k] / fix1, self.second[k] / fix2);
            places[k] = (places[k] - LEARNING_RATE * m / (v.sqrt() + 1e-12)).clamp(0.0, 1.0);
        }
    }
}

/// What one descent found: the lowest loss and its places, the first loss, the steps
/// taken and whether it was stopped before its last.
struct Descent {
    best: f64,
    places: Vec<f64>,
    initial: f64,
    steps: usize,
    stopped: bool,
}

/// Adam from `places` for `steps` steps on `stage`, asking `go_on(step, loss, places)`
/// before each.
fn descend(
    stage: &Stage,
    loss: &Loss,
    space: &Space,
    mut places: Vec<f64>,
    steps: usize,
    mut go_on: impl FnMut(usize, f64, &[f64]) -> bool,
) -> Descent {
    let mut adam = Adam::new(places.len());
    let (mut best, mut best_places, mut initial) = (f64::INFINITY, places.clone(), None);
    for step in 0..=steps {
        let (parts, by_pixel) = stage.loss(loss, space, &places);
        let total = parts.total();
        initial.get_or_insert(total);
        if total < best {
            (best, best_places) = (total, places.clone());
        }
        let stopped = step < steps && !go_on(step, total, &places);
        if step == steps || stopped {
            return Descent {
                best,
                places: best_places,
                initial: initial.unwrap_or(total),
                steps: step,
                stopped,
            };
        }
        let gradient = stage.gradient(loss, space, &places, &by_pixel);
        adam.step(&mut places, &gradient);
    }
    unreachable!("the last step returns")
}

/// The toggles' and choices' values (in the order of `space.discrete`) that lower the
/// loss on `stage` most at `places`: each tried option by option, the others as found so
/// far, twice over (so that two which depend on each other settle).
fn search_choices(stage: &Stage, loss: &Loss, space: &Space, places: &[f64]) -> Vec<f64> {
    let mut choices = space.choices();
    if choices.is_empty() {
        return choices;
    }
    let total = |choices: &[f64]| {
        let space = space.with_choices(choices);
        stage.loss(loss, &space, places).0.total()
    };
    let mut lowest = total(&choices);
    for _ in 0..2 {
        for (k, discrete) in space.discrete.iter().enumerate() {
            for &option in &discrete.options {
                if option == choices[k] {
                    continue;
                }
                let mut tried = choices.clone();
                tried[k] = option;
                let value = total(&tried);
                if value < lowest {
                    (lowest, choices) = (value, tried);
                }
            }
        }
    }
    choices
}

/// Fits `space` (of the graph `evaluator` evaluates) so that its albedo over `rect`
/// looks like `photo` (in the albedo's own encoding), calling `progress` before every
/// step (answering `false` stops it, keeping the best found).
pub fn fit(
    evaluator: &Evaluator,
    rect: FlatRect,
    space: &Space,
    photo: &image::Rgb32FImage,
    settings: &FitSettings,
    mut progress: impl FnMut(&Progress) -> bool,
) -> Fitted {
    let clock = Instant::now();
    let loss = Loss::new(settings.seed);
    let coarse_size = COARSE.min(settings.size);
    // The pixel-aligned part only pins the pattern's phase once the statistics have
    // brought it near, so it joins in the last stage.
    let coarse_aligned = settings.aligned && settings.size <= coarse_size;
    let coarse = Stage::new(evaluator, rect, coarse_size, photo, &loss, coarse_aligned);
    // The refinements: twice the side each time up to the full size, each with half the
    // steps of the one before (at least two), the aligned part in the last.
    let mut sides = Vec::new();
    let mut side = coarse_size;
    while side < settings.size {
        side = (2 * side).min(settings.size);
        sides.push(side);
    }
    let refinements: Vec<(Stage, usize)> = (sides.iter().enumerate())
        .map(|(k, &side)| {
            let aligned = settings.aligned && side == settings.size;
            let steps = (settings.steps >> (k + 1)).max(2);
            (
                Stage::new(evaluator, rect, side, photo, &loss, aligned),
                steps,
            )
        })
        .collect();
    let refine_steps: usize = refinements.iter().map(|(_, steps)| steps).sum();
    let start_count = settings.starts.max(1);
    // A search that changes a toggle or choice after the starts adds half a start.
    let follow_steps = if space.discrete.is_empty() {
        0
    } else {
        settings.steps / 2
    };
    // With `global`, each later start's search runs half as many generations as it has
    // steps, and the second start searches from the graph's values (one draw fewer).
    let (generations, searched_starts) = match settings.global {
        true => (settings.steps / 2, start_count - 1),
        false => (0, 0),
    };
    let total_steps =
        settings.steps * start_count + generations * searched_starts + follow_steps + refine_steps;
    let random_starts = start_count - 1 - usize::from(settings.global && start_count > 1);
    let mut taken = 0;
    // Whether another step may run: the budget and the caller allow it.
    let mut go_on = |start: Option<usize>, taken: usize, loss: f64, places: &[f64]| {
        let report = Progress {
            start,
            step: taken,
            total_steps,
            loss,
            seconds: clock.elapsed().as_secs_f64(),
            places: places.to_vec(),
        };
        let within = settings
            .budget
            .is_none_or(|budget| clock.elapsed() < budget);
        within && progress(&report)
    };
    // The toggles and choices searched at the graph's own values first, so that the
    // starts descend with them.
    let first_choices = search_choices(&coarse, &loss, space, &space.start());
    let chosen = space.with_choices(&first_choices);
    let mut draws = Draws::new(settings.seed);
    // Screening takes at most half the budget, leaving the rest to the steps.
    let screening = || (settings.budget).is_none_or(|budget| clock.elapsed() < budget / 2);
    // The random draws, screened while the budget allows (the rest keep their order).
    let draws: Vec<Vec<f64>> = (0..SCREENED_PER_START * random_starts)
        .map(|_| space.coordinates.iter().map(|_| draws.uniform()).collect())
        .collect();
    let mut screened: Vec<(f64, Vec<f64>)> = Vec::new();
    for places in draws {
        let total = match screening() {
            true => coarse.loss(&loss, &chosen, &places).0.total(),
            false => f64::INFINITY,
        };
        screened.push((total, places));
    }
    screened.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut screened = screened.into_iter().map(|(_, places)| places);
    let mut starts = Vec::new();
    let mut best: Option<Descent> = None;
    let mut stopped = false;
    for start in 0..start_count {
        // The first start descends from the graph's values, the others from screened
        // draws; with `global` they search first, the second from the graph's values.
        let mut initial = None;
        let places = match start {
            0 => space.start(),
            _ if !settings.global => screened.next().expect("a screened draw per start"),
            _ => {
                let mean = match start {
                    1 => space.start(),
                    _ => screened.next().expect("a screened draw per later start"),
                };
                let evolved = evolution::search(
                    mean,
                    generations,
                    settings.seed ^ start as u64,
                    |places| coarse.loss(&loss, &chosen, places).0.total(),
                    |generation, best, places| go_on(Some(start), taken + generation, best, places),
                );
                taken += evolved.generations;
                initial = Some(evolved.initial);
                evolved.places
            }
        };
        let descent = descend(
            &coarse,
            &loss,
            &chosen,
            places,
            settings.steps,
            |step, loss, places| go_on(Some(start), taken + step, loss, places),
        );
        taken += descent.steps;
        starts.push(StartResult {
            initial: initial.unwrap_or(descent.initial),
            best: descent.best,
        });
        stopped = descent.stopped;
        if best.as_ref().is_none_or(|b| descent.best < b.best) {
            best = Some(descent);
        }
        if stopped {
            break;
        }
    }
    let mut places = best.expect("one start at least").places;
    // Searched again at the best start's places; where that changes them, the
    // continuous ones follow at the coarse size before the refinements.
    let choices = search_choices(&coarse, &loss, &chosen, &places);
    let searched = space.with_choices(&choices);
    let follow = (choices != first_choices).then_some((&coarse, settings.steps / 2));
    let stages = follow
        .into_iter()
        .chain(refinements.iter().map(|(stage, n)| (stage, *n)));
    for (stage, steps) in stages {
        if stopped {
            break;
        }
        let descent = descend(stage, &loss, &searched, places, steps, |step, loss, at| {
            go_on(None, taken + step, loss, at)
        });
        taken += descent.steps;
        stopped = descent.stopped;
        places = descent.places;
    }
    let stage = refinements.last().map_or(&coarse, |(stage, _)| stage);
    let initial = stage.loss(&loss, space, &space.start()).0;
    let mut parts = stage.loss(&loss, &searched, &places).0;
    let mut choices = choices;
    // Never worse than where it started (a start chosen at the coarse size may be, at
    // the full size, when the budget cut its refinement short).
    if parts.total() > initial.total() {
        (places, parts, choices) = (space.start(), initial, space.choices());
    }
    Fitted {
        parts,
        initial,
        places,
        choices,
        starts,
        steps: taken,
        seconds: clock.elapsed().as_secs_f64(),
        cut_short: stopped,
    }
}

/// What random search found: the lowest loss (at the full size) and its places, and how
/// many draws it tried.
#[derive(Clone, Debug)]
pub struct Searched {
    pub loss: f64,
    pub places: Vec<f64>,
    pub draws: usize,
}

/// The baseline a fit is measured against: uniform random draws of the places, each
/// rendered at the full size and its loss taken (no derivatives), for `duration` (one
/// draw at least), the best kept.
pub fn random_search(
    evaluator: &Evaluator,
    rect: FlatRect,
    space: &Space,
    photo: &image::Rgb32FImage,
    settings: &FitSettings,
    duration: Duration,
) -> Searched {
    let clock = Instant::now();
    let loss = Loss::new(settings.seed);
    let stage = Stage::full(evaluator, rect, photo, &loss, settings);
    let mut draws = Draws::new(settings.seed ^ 0x5EA2C4);
    let mut best = Searched {
        loss: f64::INFINITY,
        places: space.start(),
        draws: 0,
    };
    while best.draws == 0 || clock.elapsed() < duration {
        let places: Vec<f64> = space.coordinates.iter().map(|_| draws.uniform()).collect();
        let total = stage.loss(&loss, space, &places).0.total();
        best.draws += 1;
        if total < best.loss {
            (best.loss, best.places) = (total, places);
        }
    }
    best
}
