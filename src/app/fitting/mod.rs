//! *Fit to image…*: the graph's exposed parameters fitted to a photo (`veneer fit`'s
//! work) on a thread of its own. While it runs the preview shows each step's values and
//! the window the photo beside the fitted albedo and the loss falling; it can be stopped
//! at any step, and its values kept (one undo step) or discarded.

pub(in crate::app) mod window;

use crate::fit::image::{Canvas, Image};
use crate::fit::space::Space;
use crate::fit::{FitSettings, Prepared, Progress, fit, photo_pixels, prepare, read_photo};
use crate::graph::edit::{GraphEdit, Level};
use crate::graph::parameters::{Exposed, Given};
use crate::graph::{Graph, PinRef, Value};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, mpsc};
use std::time::{Duration, Instant};

/// The side of the pictures the window shows, in pixels.
pub(in crate::app) const PICTURE_SIDE: u32 = 128;
/// The least time between two pictures of the fitted albedo.
const PICTURE_INTERVAL: Duration = Duration::from_millis(300);

/// A value the fit gives a parameter: the top-level input it stands for, and the value.
pub(in crate::app) type Assignment = (PinRef, Value);

/// What the fit's thread tells the window.
enum Update {
    /// The photo's compared square, to show.
    Photo(egui::ColorImage),
    /// A step: where the fit is, the values it tries, and (now and then) their albedo.
    Step {
        progress: Progress,
        values: Vec<Assignment>,
        picture: Option<egui::ColorImage>,
    },
    /// The fit ended: the best values found, or why it could not run.
    Ended(Result<Found, String>),
}

/// What a fit found: the best values, their albedo, their loss, and whether it was
/// stopped before its last step.
struct Found {
    values: Vec<Assignment>,
    picture: egui::ColorImage,
    loss: f64,
    stopped: bool,
}

/// How a fit ended.
pub(in crate::app) enum Ended {
    /// It found values of this loss (at the full size), stopped early or not.
    Found { loss: f64, stopped: bool },
    /// It could not run.
    Failed(String),
}

/// The time budget a fit starts with, in seconds (`veneer fit`'s benchmark gives each
/// graph a minute).
pub(in crate::app) const DEFAULT_BUDGET: f64 = 60.0;

/// *Fit to image…*'s part of the editor.
#[derive(Default)]
pub(in crate::app) struct Fitting {
    /// Whether the file browser is choosing the photo.
    pub choosing_photo: bool,
    /// The fit under way or ended, while its window is open.
    pub run: Option<FitRun>,
    /// What the next fit runs with, chosen beside the button.
    pub choices: FitChoices,
    /// Whether `choices` changed since they were last kept for later sessions.
    pub choices_unkept: bool,
}

/// The ranges the editor offers for each of [`FitChoices`].
pub(in crate::app) struct ChoiceRanges {
    pub budget: std::ops::RangeInclusive<f64>,
    pub size: std::ops::RangeInclusive<u32>,
    pub starts: std::ops::RangeInclusive<usize>,
}

/// The seconds, sides and starts a fit may be given in the editor.
pub(in crate::app) const RANGES: ChoiceRanges = ChoiceRanges {
    budget: 1.0..=3600.0,
    size: 8..=2048,
    starts: 1..=64,
};

/// The settings chosen beside *Fit to image…*, kept across sessions
/// ([`crate::app::session::recovery::choices_path`]).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub(in crate::app) struct FitChoices {
    /// The most seconds the next fit may take.
    pub budget: f64,
    /// The side in pixels of the images the next fit compares at the end
    /// (`veneer fit --size`).
    pub size: u32,
    /// How many starts the next fit descends from (`veneer fit --starts`).
    pub starts: usize,
    /// Whether the next fit's later starts search globally first (`veneer fit
    /// --global`).
    pub global: bool,
}

impl FitChoices {
    /// The settings the next fit runs with: `veneer fit`'s defaults but for the budget,
    /// size, starts and global search chosen.
    pub fn settings(&self) -> FitSettings {
        FitSettings {
            budget: Some(Duration::from_secs_f64(self.budget)),
            size: self.size,
            starts: self.starts,
            global: self.global,
            ..FitSettings::default()
        }
    }

    /// The choices as kept in a file written by hand or by another version, each
    /// brought within the range the editor offers (the default where not a number).
    pub fn within_ranges(self) -> FitChoices {
        let defaults = FitChoices::default();
        FitChoices {
            budget: if self.budget.is_finite() {
                self.budget
                    .clamp(*RANGES.budget.start(), *RANGES.budget.end())
            } else {
                defaults.budget
            },
            size: self.size.clamp(*RANGES.size.start(), *RANGES.size.end()),
            starts: self
                .starts
                .clamp(*RANGES.starts.start(), *RANGES.starts.end()),
            global: self.global,
        }
    }
}

impl Default for FitChoices {
    fn default() -> FitChoices {
        let defaults = FitSettings::default();
        FitChoices {
            budget: DEFAULT_BUDGET,
            size: defaults.size,
            starts: defaults.starts,
            global: defaults.global,
        }
    }
}

/// One fit, from its start until its window closes.
pub(in crate::app) struct FitRun {
    pub photo_path: PathBuf,
    /// The side in pixels of the images it compares at the end.
    pub size: u32,
    pub photo: Option<egui::TextureHandle>,
    pub albedo: Option<egui::TextureHandle>,
    /// (seconds, loss) at every step so far.
    pub losses: Vec<[f64; 2]>,
    /// The step reached and the steps in all.
    pub step: (usize, usize),
    /// The values the latest step tried, or the best found once it ended.
    pub values: Vec<Assignment>,
    /// The document's graph with `values`, which the preview draws meanwhile, and a
    /// number that changes with it.
    pub candidate: Option<(Graph, u64)>,
    /// `None` while it runs; then what it found or why it could not run.
    pub ended: Option<Ended>,
    stop: Arc<AtomicBool>,
    updates: mpsc::Receiver<Update>,
}

impl FitRun {
    /// Starts fitting `graph` to the photo at `photo_path` on a thread of its own, as
    /// `settings` say, waking `ctx` whenever there is news.
    pub fn start(
        ctx: &egui::Context,
        graph: Graph,
        photo_path: PathBuf,
        settings: FitSettings,
    ) -> FitRun {
        let stop = Arc::new(AtomicBool::new(false));
        let (sender, updates) = mpsc::channel();
        let (wake, asked_to_stop, path) = (ctx.clone(), Arc::clone(&stop), photo_path.clone());
        let size = settings.size;
        std::thread::Builder::new()
            .name("fit to image".into())
            .spawn(move || {
                let send = |update: Update| {
                    let _ = sender.send(update);
                    wake.request_repaint();
                };
                let ended = fit_on_thread(&graph, &path, &settings, &asked_to_stop, &send);
                send(Update::Ended(ended));
            })
            .expect("the fit's thread starts");
        FitRun {
            photo_path,
            size,
            photo: None,
            albedo: None,
            losses: Vec::new(),
            step: (0, 0),
            values: Vec::new(),
            candidate: None,
            ended: None,
            stop,
            updates,
        }
    }

    /// Asks the fit to stop at its next step, keeping the best values found.
    pub fn stop(&self) {
        self.stop.store(true, Ordering::Relaxed);
    }

    /// Whether [`FitRun::stop`] was asked.
    pub fn stop_asked(&self) -> bool {
        self.stop.load(Ordering::Relaxed)
    }

    /// Takes in what the thread sent since the last frame; `graph` is the document's.
    pub fn receive(&mut self, ctx: &egui::Context, graph: &Graph) {
        let mut values_changed = false;
        loop {
            let update = match self.updates.try_recv() {
                Ok(update) => update,
                Err(mpsc::TryRecvError::Empty) => break,
                Err(mpsc::TryRecvError::Disconnected) => {
                    if self.ended.is_none() {
                        let error = "the fit stopped unexpectedly".to_string();
                        self.ended = Some(Ended::Failed(error));
                    }
                    break;
                }
            };
            match update {
                Update::Photo(image) => self.photo = Some(texture(ctx, "fit photo", image)),
                Update::Step {
                    progress,
                    values,
                    picture,
                } => {
                    self.losses.push([progress.seconds, progress.loss]);
                    self.step = (progress.step, progress.total_steps);
                    self.values = values;
                    values_changed = true;
                    if let Some(picture) = picture {
                        self.albedo = Some(texture(ctx, "fit albedo", picture));
                    }
                }
                Update::Ended(Ok(found)) => {
                    self.values = found.values;
                    values_changed = true;
                    self.albedo = Some(texture(ctx, "fit albedo", found.picture));
                    if !found.stopped {
                        self.step.0 = self.step.1;
                    }
                    self.ended = Some(Ended::Found {
                        loss: found.loss,
                        stopped: found.stopped,
                    });
                }
                Update::Ended(Err(error)) => self.ended = Some(Ended::Failed(error)),
            }
        }
        if values_changed {
            let number = self.candidate.as_ref().map_or(0, |(_, n)| n + 1);
            let mut candidate = graph.clone();
            for (target, value) in &self.values {
                candidate.set_input(target.node, &target.pin, *value);
            }
            self.candidate = Some((candidate, number));
        }
    }

    /// The edit that keeps the values found: one undo step.
    pub fn keep(&self) -> GraphEdit {
        GraphEdit::Batch(
            (self.values.iter())
                .map(|(target, value)| GraphEdit::SetInput {
                    level: Level::Top,
                    node: target.node,
                    pin: target.pin.clone(),
                    value: Some(*value),
                })
                .collect(),
        )
    }
}

/// `image` as a texture of the window's.
fn texture(ctx: &egui::Context, name: &str, image: egui::ColorImage) -> egui::TextureHandle {
    ctx.load_texture(name, image, egui::TextureOptions::NEAREST)
}

/// The fit itself, on its thread: the photo read and shown, the graph prepared, the fit
/// run as `settings` say, each step's values (and now and then their albedo) sent,
/// stopping when asked.
fn fit_on_thread(
    graph: &Graph,
    path: &Path,
    settings: &FitSettings,
    stop: &AtomicBool,
    send: &dyn Fn(Update),
) -> Result<Found, String> {
    let shown = |error: String| format!("{}: {error}", path.display());
    let photo = read_photo(path).map_err(shown)?;
    send(Update::Photo(photo_picture(&photo)));
    let Prepared {
        evaluator,
        space,
        rect,
    } = prepare(graph, None).map_err(|error| error.to_string())?;
    let checked = evaluator.graph();
    let linear = checked.shading.is_linear();
    let pixels = photo_pixels(&photo, linear);
    let canvas = Canvas {
        evaluator: &evaluator,
        rect,
        size: PICTURE_SIDE,
    };
    let assignments = |space: &Space, places: &[f64]| -> Vec<Assignment> {
        (space.fitted_values(places).into_iter())
            .filter_map(|(index, _, lanes)| assignment(&checked.parameters[index], lanes))
            .collect()
    };
    let mut pictured: Option<Instant> = None;
    let fitted = fit(&evaluator, rect, &space, &pixels, settings, |progress| {
        let due = pictured.is_none_or(|at| at.elapsed() >= PICTURE_INTERVAL);
        let picture = due.then(|| {
            pictured = Some(Instant::now());
            albedo_picture(&canvas.render(&space, &progress.places), linear)
        });
        send(Update::Step {
            progress: progress.clone(),
            values: assignments(&space, &progress.places),
            picture,
        });
        !stop.load(Ordering::Relaxed)
    });
    let found = space.with_choices(&fitted.choices);
    Ok(Found {
        values: assignments(&found, &fitted.places),
        picture: albedo_picture(&canvas.render(&found, &fitted.places), linear),
        loss: fitted.parts.total(),
        stopped: fitted.cut_short,
    })
}

/// The value `lanes` give exposed parameter `parameter`, as the input it stands for
/// takes it.
fn assignment(parameter: &Exposed, lanes: Vec<f64>) -> Option<Assignment> {
    let given = match lanes[..] {
        [number] => Given::Number(number),
        _ => Given::List(lanes),
    };
    let value = parameter.value_of(&given).ok()?;
    Some((parameter.target.clone(), value))
}

/// The photo's middle square, as the fit compares it, at [`PICTURE_SIDE`].
fn photo_picture(photo: &image::DynamicImage) -> egui::ColorImage {
    let rgb = photo.to_rgb8();
    let side = rgb.width().min(rgb.height());
    let (x, y) = ((rgb.width() - side) / 2, (rgb.height() - side) / 2);
    let square = image::imageops::crop_imm(&rgb, x, y, side, side).to_image();
    let small = image::imageops::resize(
        &square,
        PICTURE_SIDE,
        PICTURE_SIDE,
        image::imageops::FilterType::Triangle,
    );
    egui::ColorImage::from_rgb([small.width() as usize, small.height() as usize], &small)
}

/// A fitted albedo for display (encoded as sRGB where the albedo is linear).
fn albedo_picture(image: &Image, linear: bool) -> egui::ColorImage {
    let bytes: Vec<u8> = (image.pixels.iter())
        .flat_map(|pixel| {
            pixel.map(|lane| {
                let lane = (lane as f32).clamp(0.0, 1.0);
                let shown = match linear {
                    true => crate::bitmaps::linear_to_srgb(lane),
                    false => lane,
                };
                (shown * 255.0).round() as u8
            })
        })
        .collect();
    let side = image.size as usize;
    egui::ColorImage::from_rgb([side, side], &bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kept_choices_written_by_hand_are_brought_within_range() {
        let dir = std::env::temp_dir().join(format!("veneer-choices-{}", std::process::id()));
        let path = dir.join("choices.ron");
        std::fs::create_dir_all(&dir).expect("a folder");
        std::fs::write(&path, "(budget: 1e9, starts: 0, global: true)").expect("written");
        let kept = crate::app::session::recovery::load_kept::<FitChoices>(&path).within_ranges();
        let defaults = FitChoices::default();
        assert_eq!(
            kept,
            FitChoices {
                budget: 3600.0,
                size: defaults.size,
                starts: 1,
                global: true,
            }
        );
        std::fs::write(&path, "not ron").expect("written");
        let unreadable = crate::app::session::recovery::load_kept::<FitChoices>(&path);
        assert_eq!(unreadable, defaults);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
