//! The *Fit to image* window: the photo beside the fitted albedo, the loss curve and
//! the step reached, *Stop* while it runs, *Keep* or *Discard* once it ended.

use super::{Ended, FitRun, PICTURE_SIDE, RANGES};
use crate::app::VeneerApp;
use crate::app::chrome::file_browser::{Browsed, Purpose};
use crate::app::session::recovery;
use egui::Ui;

/// The photos the file browser offers.
const PHOTO_EXTENSIONS: &[&str] = &["png", "jpg", "jpeg", "exr", "hdr"];
/// The loss curve's size in points.
const CURVE_SIZE: egui::Vec2 = egui::vec2(2.0 * PICTURE_SIDE as f32 + 8.0, 90.0);

/// What the window's buttons asked for.
enum Choice {
    Stop,
    Keep,
    Discard,
}

/// One of the fit's settings beside its button: a drag value within `range`, its
/// number between `prefix` and `suffix`, and what it does.
fn setting<N: egui::emath::Numeric>(
    ui: &mut Ui,
    value: &mut N,
    range: std::ops::RangeInclusive<N>,
    speed: f64,
    (prefix, suffix): (&str, &str),
    hover: &str,
) {
    let drag = egui::DragValue::new(value).range(range).speed(speed);
    ui.add(drag.prefix(prefix).suffix(suffix))
        .on_hover_text(hover);
}

impl VeneerApp {
    /// The *Fit to image…* button of the Parameters panel: opens the file browser on the
    /// graph's folder to choose the photo (greyed while a fit is open, or where the graph
    /// exposes no parameter, as when only presets are left).
    pub(in crate::app) fn fit_to_image_button(&mut self, ui: &mut Ui, exposes_any: bool) {
        let running = self.fitting.run.is_some();
        let button = ui
            .horizontal(|ui| {
                let button = ui
                    .add_enabled(!running && exposes_any, egui::Button::new("Fit to image…"))
                    .on_hover_text(
                        "fit the parameters so the albedo looks like a photo (veneer fit)",
                    )
                    .on_disabled_hover_text(match running {
                        true => "a fit is open",
                        false => "the graph exposes no parameter to fit",
                    });
                ui.label("within");
                let before = self.fitting.choices.clone();
                let choices = &mut self.fitting.choices;
                let hover = "the most time the fit may take (veneer fit --budget)";
                setting(ui, &mut choices.budget, RANGES.budget, 1.0, ("", " s"), hover);
                ui.label("at");
                let hover = "the side of the images compared at the end; larger sees finer detail and takes longer (veneer fit --size)";
                setting(ui, &mut choices.size, RANGES.size, 4.0, ("", " px"), hover);
                let hover = "the graph's own values, then random draws; more starts search wider and take longer (veneer fit --starts)";
                setting(ui, &mut choices.starts, RANGES.starts, 0.1, ("starts ", ""), hover);
                ui.checkbox(&mut choices.global, "global").on_hover_text(
                    "the starts after the first search the whole range before descending: slower, finds lower losses (veneer fit --global)",
                );
                self.fitting.choices_unkept |= self.fitting.choices != before;
                button
            })
            .inner;
        // Kept once a drag of one of them is let go.
        if self.fitting.choices_unkept && !ui.input(|input| input.pointer.any_down()) {
            self.fitting.choices_unkept = false;
            let path = recovery::choices_path(&self.session.recovery_file);
            if let Err(error) = recovery::save_kept(&path, &self.fitting.choices) {
                self.chrome.message = Some(format!("cannot keep the fit's settings: {error}"));
            }
        }
        if button.clicked() {
            let folder = self.session.document.graph.folder.path().to_path_buf();
            self.chrome.browser.open(
                Purpose::Pick {
                    title: "Fit to image: choose a photo",
                    kind: "Images",
                    extensions: PHOTO_EXTENSIONS,
                },
                &folder.to_string_lossy(),
            );
            self.chrome.choosing_file_for = None;
            self.fitting.choosing_photo = true;
        }
    }

    /// Starts fitting the document's graph to the photo at `path` (what choosing it in
    /// the file browser does; scripts and tests call it directly).
    pub fn fit_to_image(&mut self, ctx: &egui::Context, path: std::path::PathBuf) {
        if let Some(run) = &self.fitting.run {
            run.stop();
        }
        let graph = self.session.document.graph.clone();
        let settings = self.fitting.choices.settings();
        self.fitting.run = Some(FitRun::start(ctx, graph, path, settings));
    }

    /// Whether a fit's window is open, and whether its fit has ended.
    pub fn fitting(&self) -> Option<bool> {
        (self.fitting.run.as_ref()).map(|run| run.ended.is_some())
    }

    /// The file browser choosing the photo, the fit's news, and its window.
    pub(in crate::app) fn fit_to_image_window(&mut self, ctx: &egui::Context) {
        if self.fitting.choosing_photo {
            match self.chrome.browser.update(ctx) {
                Browsed::Browsing => {}
                Browsed::Cancelled => self.fitting.choosing_photo = false,
                Browsed::Picked(path) => {
                    self.fitting.choosing_photo = false;
                    self.fit_to_image(ctx, path);
                }
            }
        }
        let graph = &self.session.document.graph;
        let Some(run) = &mut self.fitting.run else {
            return;
        };
        run.receive(ctx, graph);
        let mut open = true;
        let mut choice = None;
        egui::Window::new("Fit to image")
            .open(&mut open)
            .resizable(false)
            .collapsible(false)
            .show(ctx, |ui| choice = contents(ui, run));
        let choice = match (open, choice) {
            (false, _) => Some(Choice::Discard),
            (true, choice) => choice,
        };
        match choice {
            Some(Choice::Stop) => run.stop(),
            Some(Choice::Keep) => {
                let edit = run.keep();
                self.fitting.run = None;
                if self.edit(edit) {
                    self.chrome.message =
                        Some("kept the fitted values (undo takes them back)".into());
                }
            }
            Some(Choice::Discard) => {
                run.stop();
                self.fitting.run = None;
            }
            None => {}
        }
    }
}

/// The window's contents; what its buttons asked for.
fn contents(ui: &mut Ui, run: &FitRun) -> Option<Choice> {
    let name =
        (run.photo_path.file_name()).map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    ui.label(format!("photo: {name}"));
    let side = egui::vec2(PICTURE_SIDE as f32, PICTURE_SIDE as f32);
    ui.horizontal(|ui| {
        for (texture, caption) in [(&run.photo, "photo"), (&run.albedo, "fitted albedo")] {
            ui.vertical(|ui| {
                match texture {
                    Some(texture) => ui.image((texture.id(), side)),
                    None => ui.add_sized(side, egui::Spinner::new()),
                };
                ui.weak(caption);
            });
        }
    });
    loss_curve(ui, &run.losses);
    let (step, steps) = run.step;
    let loss = run.losses.last().map(|[_, loss]| *loss);
    let seconds = run.losses.last().map_or(0.0, |[seconds, _]| *seconds);
    let fraction = if steps == 0 {
        0.0
    } else {
        step as f32 / steps as f32
    };
    ui.add(egui::ProgressBar::new(fraction).text(format!(
        "step {step} of {steps}, loss {}, {seconds:.1} s",
        loss.map_or("…".to_string(), |loss| format!("{loss:.5}"))
    )));
    match &run.ended {
        None => {
            ui.weak("the preview shows each step's values");
            ui.button("Stop").clicked().then_some(Choice::Stop)
        }
        Some(Ended::Found { loss, stopped }) => {
            let how = match (stopped, run.stop_asked()) {
                (true, true) => format!("stopped at step {step}"),
                (true, false) => format!("the time ran out at step {step}"),
                (false, _) => "done".to_string(),
            };
            ui.label(format!(
                "{how}: the preview shows the best values found (loss {loss:.5} at {side}²)",
                side = run.size
            ));
            ui.horizontal(|ui| {
                if ui.button("Keep").clicked() {
                    Some(Choice::Keep)
                } else if ui.button("Discard").clicked() {
                    Some(Choice::Discard)
                } else {
                    None
                }
            })
            .inner
        }
        Some(Ended::Failed(error)) => {
            ui.colored_label(ui.visuals().error_fg_color, error);
            ui.button("Close").clicked().then_some(Choice::Discard)
        }
    }
}

/// The loss against the step, on a logarithmic scale, and the lowest so far (each start
/// begins high again).
fn loss_curve(ui: &mut Ui, losses: &[[f64; 2]]) {
    let (rect, _) = ui.allocate_exact_size(CURVE_SIZE, egui::Sense::hover());
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 2.0, ui.visuals().extreme_bg_color);
    let logs: Vec<f64> = (losses.iter())
        .map(|[_, loss]| loss.max(1e-12).log10())
        .collect();
    let (low, high) = logs
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    if logs.len() < 2 {
        return;
    }
    let span = (high - low).max(1e-6);
    let last = (logs.len() - 1) as f32;
    let point = |k: usize, v: f64| {
        let x = rect.left() + rect.width() * k as f32 / last;
        let y = rect.bottom() - rect.height() * ((v - low) / span) as f32;
        egui::pos2(x, y)
    };
    let steps = logs.iter().enumerate().map(|(k, &v)| point(k, v));
    let lowest = (logs.iter().enumerate()).scan(f64::INFINITY, |lowest, (k, &v)| {
        *lowest = lowest.min(v);
        Some(point(k, *lowest))
    });
    let visuals = ui.visuals();
    for (points, stroke) in [
        (
            steps.collect(),
            egui::Stroke::new(1.0, visuals.selection.bg_fill),
        ),
        (
            lowest.collect(),
            egui::Stroke::new(1.5, visuals.strong_text_color()),
        ),
    ] {
        painter.add(egui::Shape::line(points, stroke));
    }
    painter.text(
        rect.left_top() + egui::vec2(4.0, 2.0),
        egui::Align2::LEFT_TOP,
        "loss (log scale), lowest so far",
        egui::FontId::proportional(11.0),
        ui.visuals().weak_text_color(),
    );
}
