//! Modal dialogs: file paths for open, save as and export; the prompt before losing
//! unsaved work; recovery after a crash; messages. A dialog only reads the document:
//! what the user decides comes back as an [`Action`] for the editor to carry out.
//!
//! Every dialog is modal (a backdrop takes the clicks meant for what is underneath),
//! Enter confirms and Escape cancels. A path dialog opens with its path selected in a
//! focused field, so typing replaces it, and offers a file browser. Prompts that can lose
//! or overwrite work default to the safe choice, keep their destructive buttons on the
//! left (where no dialog has its confirm button) and enable them only a moment after
//! they appear, so that a click meant for the dialog before never lands on them.

use super::Document;
use super::file_browser::{Browsed, Browser, Purpose};
use super::recovery::Recovery;
use crate::codegen::ParamMode;
use crate::codegen::export::Target;
use egui::{Context, Id, Key, Modal, Ui};
use std::hash::{Hash, Hasher};
use std::path::PathBuf;

/// The width of every dialog, so that one replacing another keeps its edges.
const WIDTH: f32 = 520.0;

/// Seconds a destructive button stays disabled after its dialog appears (longer than a
/// double click).
pub const ARM_SECONDS: f64 = 0.6;

/// What to do once the user has decided about unsaved changes.
#[derive(Clone, Debug, PartialEq)]
pub enum Pending {
    New,
    Open(PathBuf),
    Preset(&'static str),
    Quit,
}

/// What the user decided in a dialog, for the editor to carry out.
#[derive(Clone, Debug, PartialEq)]
pub enum Action {
    /// Open a graph file (asking first about unsaved changes).
    Open(PathBuf),
    /// Save the document to this file.
    SaveAs(PathBuf),
    /// Write the material as a shader for `target`.
    ExportShader {
        path: PathBuf,
        target: Target,
        params: ParamMode,
    },
    /// Write a PNG of the lit preview mesh, or of the flat albedo.
    ExportPng {
        path: PathBuf,
        size: u32,
        flat: bool,
    },
    /// Show a mesh file in the preview.
    LoadMesh(String),
    /// Save the unsaved changes, then go on if they were saved.
    SaveThen(Pending),
    /// Drop the unsaved changes and go on.
    Discard(Pending),
    /// Open autosaved work (and remove its recovery file once this window has it).
    Recover(Box<Recovery>),
    /// Forget autosaved work: remove this recovery file.
    ForgetRecovery(PathBuf),
}

/// An open dialog.
pub enum Dialog {
    Open {
        path: String,
    },
    SaveAs {
        path: String,
    },
    ExportShader {
        path: String,
        target: Target,
        uniform: bool,
    },
    ExportPng {
        path: String,
        size: u32,
        flat: bool,
    },
    LoadMesh {
        path: String,
    },
    /// Save as onto an existing file: asks before replacing it.
    Replace(PathBuf),
    Discard(Pending),
    /// Autosaved work of windows that did not exit cleanly, newest first.
    Recover(Vec<Recovery>),
    Message(String),
}

/// What the user chose in a dialog this frame.
enum Choice {
    /// The default button, or Enter.
    Confirm,
    /// Cancel, or Escape.
    Cancel,
    /// Open the file browser.
    Browse,
    /// Save the unsaved changes first.
    Save,
    /// Drop the unsaved changes, or replace the file.
    Destroy,
    /// Recover the autosaved work at this index.
    Recover(usize),
    /// Forget the autosaved work at this index.
    Forget(usize),
}

/// What one frame of a dialog knows and collects.
struct Frame {
    /// The dialog's first frame (or the first after the browser closed): focus its field
    /// or default button.
    first: bool,
    /// Destructive buttons respond (the dialog has been up for [`ARM_SECONDS`]).
    armed: bool,
    /// Widgets that act on Enter themselves when focused (buttons, check boxes).
    claims: Vec<Id>,
    choice: Option<Choice>,
}

impl Frame {
    fn choose(&mut self, clicked: bool, choice: Choice) {
        if clicked && self.choice.is_none() {
            self.choice = Some(choice);
        }
    }

    /// A plain button.
    fn button(&mut self, ui: &mut Ui, label: &str, choice: Choice) {
        let response = ui.button(label);
        self.claims.push(response.id);
        self.choose(response.clicked(), choice);
    }

    /// The button Enter presses: focused when the dialog opens.
    fn default_button(&mut self, ui: &mut Ui, label: &str, choice: Choice) {
        let response = ui.button(label);
        if self.first {
            response.request_focus();
        }
        self.claims.push(response.id);
        self.choose(response.clicked(), choice);
    }

    /// A button that loses or overwrites work: enabled once the dialog has been up a moment.
    fn destructive_button(&mut self, ui: &mut Ui, label: &str, choice: Choice) {
        let response = ui.add_enabled(self.armed, egui::Button::new(label));
        self.claims.push(response.id);
        self.choose(response.clicked(), choice);
    }

    /// A check box (Enter toggles it when focused).
    fn checkbox(&mut self, ui: &mut Ui, value: &mut bool, label: &str) {
        let response = ui.checkbox(value, label);
        self.claims.push(response.id);
    }

    /// The path field: full width, focused with its text selected when the dialog opens.
    fn path_field(&mut self, ui: &mut Ui, path: &mut String) {
        let mut output = egui::TextEdit::singleline(path)
            .desired_width(f32::INFINITY)
            .hint_text("type a path, or Browse…")
            .show(ui);
        if self.first {
            output.response.request_focus();
            let all = egui::text::CCursorRange::two(
                egui::text::CCursor::new(0),
                egui::text::CCursor::new(path.chars().count()),
            );
            output.state.cursor.set_char_range(Some(all));
            output.state.store(ui.ctx(), output.response.id);
        }
    }

    /// The bottom row of a path dialog: Browse on the left; Cancel and the confirm
    /// button (rightmost) on the right.
    fn path_buttons(&mut self, ui: &mut Ui, confirm: &str) {
        ui.add_space(4.0);
        ui.horizontal(|ui| {
            self.button(ui, "Browse…", Choice::Browse);
            ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                self.button(ui, confirm, Choice::Confirm);
                self.button(ui, "Cancel", Choice::Cancel);
            });
        });
    }
}

/// Which dialog is up, for the state kept between its frames.
#[derive(Clone, Copy)]
struct Opened {
    kind: u64,
    /// The editor's clock when it appeared.
    at: f64,
    /// Whether its field or default button still needs the focus.
    focus: bool,
}

fn default_path(document: &Document, extension: &str) -> String {
    let stem = document
        .path
        .as_ref()
        .and_then(|p| p.file_stem())
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| {
            if document.graph.name.is_empty() {
                "material".into()
            } else {
                document.graph.name.to_lowercase().replace(' ', "_")
            }
        });
    let file = format!("{stem}.{extension}");
    // Beside the document's file, if it has one.
    match document.path.as_ref().and_then(|p| p.parent()) {
        Some(folder) if !folder.as_os_str().is_empty() => folder.join(file).display().to_string(),
        _ => file,
    }
}

/// The path the user typed: trimmed, with a leading `~` for the home folder.
fn typed_path(text: &str) -> PathBuf {
    let text = text.trim();
    match (text.strip_prefix("~/"), std::env::var_os("HOME")) {
        (Some(rest), Some(home)) => PathBuf::from(home).join(rest),
        _ if text == "~" => std::env::var_os("HOME")
            .map(PathBuf::from)
            .unwrap_or_default(),
        _ => PathBuf::from(text),
    }
}

/// How long ago `time` was, in words.
fn ago(time: Option<std::time::SystemTime>) -> String {
    let Some(elapsed) = time.and_then(|t| t.elapsed().ok()) else {
        return String::new();
    };
    let minutes = elapsed.as_secs() / 60;
    match minutes {
        0 => ", autosaved less than a minute ago".into(),
        1 => ", autosaved a minute ago".into(),
        2..=119 => format!(", autosaved {minutes} minutes ago"),
        _ if minutes < 48 * 60 => format!(", autosaved {} hours ago", minutes / 60),
        _ => format!(", autosaved {} days ago", minutes / (24 * 60)),
    }
}

impl Dialog {
    /// The Open dialog.
    pub fn open() -> Dialog {
        Dialog::Open {
            path: String::new(),
        }
    }
    /// Save as, suggesting the current file or the graph's name.
    pub fn save_as(document: &Document) -> Dialog {
        Dialog::SaveAs {
            path: document
                .path
                .as_ref()
                .map(|p| p.display().to_string())
                .unwrap_or_else(|| default_path(document, "ron")),
        }
    }
    /// Export the material as a shader (WGSL by default).
    pub fn export_shader(document: &Document) -> Dialog {
        Dialog::ExportShader {
            path: default_path(document, "wgsl"),
            target: Target::Wgsl,
            uniform: false,
        }
    }
    /// Export a PNG of the preview or of the flat albedo.
    pub fn export_png(document: &Document) -> Dialog {
        Dialog::ExportPng {
            path: default_path(document, "png"),
            size: 1024,
            flat: false,
        }
    }

    fn kind(&self) -> u64 {
        let mut hasher = std::collections::hash_map::DefaultHasher::new();
        std::mem::discriminant(self).hash(&mut hasher);
        hasher.finish()
    }

    /// The typed path of a path dialog.
    fn path_mut(&mut self) -> Option<&mut String> {
        match self {
            Dialog::Open { path }
            | Dialog::SaveAs { path }
            | Dialog::ExportShader { path, .. }
            | Dialog::ExportPng { path, .. }
            | Dialog::LoadMesh { path } => Some(path),
            _ => None,
        }
    }

    /// What the file browser chooses for this dialog.
    fn purpose(&self) -> Option<Purpose> {
        Some(match self {
            Dialog::Open { .. } => Purpose::Pick {
                title: "Open graph",
                kind: "Veneer graphs",
                extensions: &["ron"],
            },
            Dialog::LoadMesh { .. } => Purpose::Pick {
                title: "Preview on a mesh file",
                kind: "Meshes",
                extensions: &crate::mesh::EXTENSIONS,
            },
            Dialog::SaveAs { .. } => Purpose::Save {
                title: "Save graph as",
                kind: "Veneer graph",
                extension: "ron",
            },
            Dialog::ExportShader { target, .. } => Purpose::Save {
                title: "Export shader",
                kind: target.name(),
                extension: target.extension(),
            },
            Dialog::ExportPng { .. } => Purpose::Save {
                title: "Export PNG",
                kind: "PNG image",
                extension: "png",
            },
            _ => return None,
        })
    }

    /// Shows the dialog over `document` (or the file browser it opened); returns the
    /// dialog to show next frame (`None` once closed) and what the user asked for, if
    /// anything.
    pub fn show(
        mut self,
        ctx: &Context,
        document: &Document,
        browser: &mut Browser,
    ) -> (Option<Dialog>, Option<Action>) {
        let memory = Id::new("veneer dialog");
        let kind = self.kind();
        let now = ctx.input(|input| input.time);
        let mut opened = ctx
            .data(|data| data.get_temp::<Opened>(memory))
            .filter(|opened| opened.kind == kind)
            .unwrap_or(Opened {
                kind,
                at: now,
                focus: true,
            });
        if browser.is_open() {
            let outcome = match browser.update(ctx) {
                Browsed::Browsing => (Some(self), None),
                Browsed::Cancelled => (Some(self), None),
                Browsed::Picked(path) => {
                    if let Some(typed) = self.path_mut() {
                        *typed = path.display().to_string();
                    }
                    match self {
                        // The browser asked before replacing a file.
                        Dialog::SaveAs { .. } => (None, Some(Action::SaveAs(path))),
                        Dialog::Open { .. } | Dialog::LoadMesh { .. } => self.confirm(document),
                        // Exports go back to their options.
                        dialog => (Some(dialog), None),
                    }
                }
            };
            // Back in the dialog, its field has the focus again.
            opened.focus = true;
            remember(ctx, memory, &outcome, kind, opened);
            return outcome;
        }

        let armed = now - opened.at >= ARM_SECONDS;
        if !armed {
            ctx.request_repaint_after(std::time::Duration::from_secs_f64(
                ARM_SECONDS - (now - opened.at) + 0.01,
            ));
        }
        let mut frame = Frame {
            first: opened.focus,
            armed,
            claims: Vec::new(),
            choice: None,
        };
        if frame.first {
            // A menu or combo box that opened the dialog closes: the dialog has the keyboard.
            egui::Popup::close_all(ctx);
        }
        let popup_open = egui::Popup::is_any_open(ctx);
        Modal::new(memory.with(kind)).show(ctx, |ui| {
            ui.set_width(WIDTH);
            self.contents(ui, document, &mut frame);
        });
        if frame.choice.is_none() && !popup_open && !frame.first {
            let focused = ctx.memory(|memory| memory.focused());
            let (enter, escape) = ctx.input(|input| {
                (
                    input.key_pressed(Key::Enter),
                    input.key_pressed(Key::Escape),
                )
            });
            if escape {
                frame.choice = Some(Choice::Cancel);
            } else if enter && focused.is_none_or(|id| !frame.claims.contains(&id)) {
                frame.choice = Some(Choice::Confirm);
            }
        }
        opened.focus = false;
        let outcome = match frame.choice {
            None => (Some(self), None),
            Some(Choice::Confirm) => self.confirm(document),
            Some(Choice::Cancel) => self.cancel(),
            Some(Choice::Browse) => {
                if let (Some(purpose), Some(path)) = (self.purpose(), self.path_mut()) {
                    browser.open(purpose, path);
                }
                (Some(self), None)
            }
            Some(Choice::Save) => match self {
                Dialog::Discard(pending) => (None, Some(Action::SaveThen(pending))),
                dialog => (Some(dialog), None),
            },
            Some(Choice::Destroy) => match self {
                Dialog::Discard(pending) => (None, Some(Action::Discard(pending))),
                Dialog::Replace(path) => (None, Some(Action::SaveAs(path))),
                dialog => (Some(dialog), None),
            },
            Some(Choice::Recover(index)) => match self {
                Dialog::Recover(mut saved) if index < saved.len() => (
                    None,
                    Some(Action::Recover(Box::new(saved.swap_remove(index)))),
                ),
                dialog => (Some(dialog), None),
            },
            Some(Choice::Forget(index)) => match self {
                Dialog::Recover(mut saved) if index < saved.len() => {
                    let forgotten = saved.remove(index);
                    let rest = (!saved.is_empty()).then_some(Dialog::Recover(saved));
                    (rest, Some(Action::ForgetRecovery(forgotten.file)))
                }
                dialog => (Some(dialog), None),
            },
        };
        remember(ctx, memory, &outcome, kind, opened);
        outcome
    }

    /// Enter, or the confirm button.
    fn confirm(self, document: &Document) -> (Option<Dialog>, Option<Action>) {
        let action = match &self {
            Dialog::Open { path } if !path.trim().is_empty() => Action::Open(typed_path(path)),
            Dialog::SaveAs { path } if !path.trim().is_empty() => {
                let path = typed_path(path);
                if path.exists() && document.path.as_ref() != Some(&path) {
                    return (Some(Dialog::Replace(path)), None);
                }
                Action::SaveAs(path)
            }
            Dialog::ExportShader {
                path,
                target,
                uniform,
            } if !path.trim().is_empty() => Action::ExportShader {
                path: typed_path(path),
                target: *target,
                params: if *uniform {
                    ParamMode::Uniform
                } else {
                    ParamMode::Baked
                },
            },
            Dialog::ExportPng { path, size, flat } if !path.trim().is_empty() => {
                Action::ExportPng {
                    path: typed_path(path),
                    size: *size,
                    flat: *flat,
                }
            }
            Dialog::LoadMesh { path } if !path.trim().is_empty() => {
                Action::LoadMesh(typed_path(path).display().to_string())
            }
            Dialog::Replace(path) => Action::SaveAs(path.clone()),
            // The safe choice: keep the unsaved changes and stay.
            Dialog::Discard(_) | Dialog::Message(_) => return (None, None),
            Dialog::Recover(saved) if !saved.is_empty() => {
                Action::Recover(Box::new(saved[0].clone()))
            }
            // Nothing typed yet: stay.
            _ => return (Some(self), None),
        };
        (None, Some(action))
    }

    /// Escape, or the Cancel button.
    fn cancel(self) -> (Option<Dialog>, Option<Action>) {
        match self {
            // Back to Save as, with the path to change.
            Dialog::Replace(path) => (
                Some(Dialog::SaveAs {
                    path: path.display().to_string(),
                }),
                None,
            ),
            // Recovery files stay, to be offered at the next start.
            _ => (None, None),
        }
    }

    fn contents(&mut self, ui: &mut Ui, document: &Document, frame: &mut Frame) {
        match self {
            Dialog::Open { path } => {
                ui.heading("Open graph");
                frame.path_field(ui, path);
                frame.path_buttons(ui, "Open");
            }
            Dialog::SaveAs { path } => {
                ui.heading("Save graph as");
                frame.path_field(ui, path);
                frame.path_buttons(ui, "Save");
            }
            Dialog::ExportShader {
                path,
                target,
                uniform,
            } => {
                ui.heading("Export shader");
                ui.label("veneer_material for another engine; non-WGSL targets add the veneer_fragment entry point.");
                frame.path_field(ui, path);
                let before = *target;
                let combo = egui::ComboBox::from_label("language")
                    .selected_text(target.name())
                    .show_ui(ui, |ui| {
                        for (option, name, _) in Target::ALL {
                            ui.selectable_value(target, option, name);
                        }
                    });
                frame.claims.push(combo.response.id);
                if *target != before {
                    *path = std::path::Path::new(path.trim())
                        .with_extension(target.extension())
                        .display()
                        .to_string();
                }
                frame.checkbox(
                    ui,
                    uniform,
                    "parameters as a uniform block (instead of baked constants)",
                );
                frame.path_buttons(ui, "Export");
            }
            Dialog::ExportPng { path, size, flat } => {
                ui.heading("Export PNG");
                frame.path_field(ui, path);
                ui.add(egui::Slider::new(size, 16..=4096).text("size (px)"));
                frame.checkbox(
                    ui,
                    flat,
                    "flat albedo over the preview square (instead of the lit mesh)",
                );
                frame.path_buttons(ui, "Export");
            }
            Dialog::LoadMesh { path } => {
                ui.heading("Preview on a mesh file");
                ui.label(format!(
                    "OBJ, STL, PLY or glTF ({})",
                    crate::mesh::EXTENSIONS.join(", ")
                ));
                frame.path_field(ui, path);
                frame.path_buttons(ui, "Load");
            }
            Dialog::Replace(path) => {
                ui.heading("Replace file?");
                ui.label(format!(
                    "{} already exists. Replace it with this graph?",
                    path.display()
                ));
                ui.add_space(4.0);
                ui.horizontal(|ui| {
                    frame.destructive_button(ui, "Replace", Choice::Destroy);
                    ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                        frame.default_button(ui, "Cancel", Choice::Cancel);
                    });
                });
            }
            Dialog::Discard(pending) => {
                ui.heading("Unsaved changes");
                let name = document.title();
                let name = name.trim_end_matches(" — Veneer").trim_start_matches("* ");
                let then = match pending {
                    Pending::New => "starting a new graph".to_string(),
                    Pending::Open(path) => format!(
                        "opening {}",
                        path.file_name()
                            .map(|n| n.to_string_lossy().into_owned())
                            .unwrap_or_else(|| path.display().to_string())
                    ),
                    Pending::Preset(name) => format!("opening the {name} preset"),
                    Pending::Quit => "quitting".to_string(),
                };
                ui.label(format!(
                    "{name} has changes that are not saved. Save them before {then}?"
                ));
                ui.add_space(4.0);
                ui.horizontal(|ui| {
                    frame.destructive_button(ui, "Save", Choice::Save);
                    frame.destructive_button(ui, "Discard", Choice::Destroy);
                    ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                        frame.default_button(ui, "Cancel", Choice::Cancel);
                    });
                });
            }
            Dialog::Recover(saved) => {
                ui.heading("Recover unsaved work?");
                ui.label(if saved.len() == 1 {
                    "Veneer ended last time with work that was not saved. It was autosaved:"
                        .to_string()
                } else {
                    format!(
                        "{} Veneer windows ended with work that was not saved. It was autosaved:",
                        saved.len()
                    )
                });
                for (index, recovery) in saved.iter().enumerate() {
                    let from = recovery
                        .original
                        .as_ref()
                        .map(|p| p.display().to_string())
                        .unwrap_or_else(|| format!("an unsaved graph ({})", recovery.graph.name));
                    ui.horizontal(|ui| {
                        frame.destructive_button(ui, "Discard", Choice::Forget(index));
                        ui.label(format!("{from}{}", ago(recovery.saved)));
                        ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                            if index == 0 {
                                frame.default_button(ui, "Recover", Choice::Recover(index));
                            } else {
                                frame.button(ui, "Recover", Choice::Recover(index));
                            }
                        });
                    });
                }
                ui.add_space(4.0);
                ui.horizontal(|ui| {
                    ui.weak("Later keeps it for the next start.");
                    ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                        frame.button(ui, "Later", Choice::Cancel);
                    });
                });
            }
            Dialog::Message(message) => {
                ui.heading("Veneer");
                ui.label(message.as_str());
                ui.add_space(4.0);
                ui.horizontal(|ui| {
                    ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                        frame.default_button(ui, "OK", Choice::Confirm);
                    });
                });
            }
        }
    }
}

/// Keeps the state of the dialog that stays up; forgets it when the dialog closes or
/// another replaces it.
fn remember(
    ctx: &Context,
    memory: Id,
    outcome: &(Option<Dialog>, Option<Action>),
    kind: u64,
    opened: Opened,
) {
    match &outcome.0 {
        Some(next) if next.kind() == kind => {
            ctx.data_mut(|data| data.insert_temp(memory, opened));
        }
        _ => ctx.data_mut(|data| data.remove::<Opened>(memory)),
    }
}
