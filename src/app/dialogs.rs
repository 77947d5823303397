//! Modal dialogs: file paths for open, save as and export; the prompt before losing
//! unsaved work; recovery after a crash; messages. A dialog only reads the document:
//! what the user decides comes back as an [`Action`] for the editor to carry out.

use super::Document;
use super::recovery::Recovery;
use crate::codegen::ParamMode;
use crate::codegen::export::Target;
use egui::{Context, Id, Modal};
use std::path::PathBuf;

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
    /// Open the autosaved work.
    Recover(Recovery),
    /// Forget the autosaved work.
    ForgetRecovery,
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
    Discard(Pending),
    Recover(Recovery),
    Message(String),
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
    format!("{stem}.{extension}")
}

impl Dialog {
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

    /// Shows the dialog over `document`; returns the dialog to show next frame (`None`
    /// once closed) and what the user asked for, if anything.
    pub fn show(mut self, ctx: &Context, document: &Document) -> (Option<Dialog>, Option<Action>) {
        let mut next: Option<Option<Dialog>> = None;
        let mut action = None;
        Modal::new(Id::new("veneer dialog")).show(ctx, |ui| {
            ui.set_min_width(420.0);
            match &mut self {
                Dialog::Open { path } => {
                    ui.heading("Open graph");
                    let edit = ui.text_edit_singleline(path);
                    let enter = edit.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
                    ui.horizontal(|ui| {
                        if ui.button("Open").clicked() || enter {
                            next = Some(None);
                            action = Some(Action::Open(PathBuf::from(path.trim())));
                        }
                        if ui.button("Cancel").clicked() {
                            next = Some(None);
                        }
                    });
                }
                Dialog::SaveAs { path } => {
                    ui.heading("Save graph as");
                    ui.text_edit_singleline(path);
                    ui.horizontal(|ui| {
                        if ui.button("Save").clicked() {
                            next = Some(None);
                            action = Some(Action::SaveAs(PathBuf::from(path.trim())));
                        }
                        if ui.button("Cancel").clicked() {
                            next = Some(None);
                        }
                    });
                }
                Dialog::ExportShader { path, target, uniform } => {
                    ui.heading("Export shader");
                    ui.label("veneer_material for another engine; non-WGSL targets add the veneer_fragment entry point.");
                    let before = *target;
                    let selected = target.name();
                    egui::ComboBox::from_label("language").selected_text(selected).show_ui(ui, |ui| {
                        for (option, name, _) in Target::ALL {
                            ui.selectable_value(target, option, name);
                        }
                    });
                    if *target != before {
                        *path = std::path::Path::new(path.trim()).with_extension(target.extension()).display().to_string();
                    }
                    ui.checkbox(uniform, "parameters as a uniform block (instead of baked constants)");
                    ui.text_edit_singleline(path);
                    ui.horizontal(|ui| {
                        if ui.button("Export").clicked() {
                            let params = if *uniform { ParamMode::Uniform } else { ParamMode::Baked };
                            next = Some(None);
                            action = Some(Action::ExportShader { path: PathBuf::from(path.trim()), target: *target, params });
                        }
                        if ui.button("Cancel").clicked() {
                            next = Some(None);
                        }
                    });
                }
                Dialog::ExportPng { path, size, flat } => {
                    ui.heading("Export PNG");
                    ui.text_edit_singleline(path);
                    ui.add(egui::Slider::new(size, 16..=4096).text("size (px)"));
                    ui.checkbox(flat, "flat albedo over the preview square (instead of the lit mesh)");
                    ui.horizontal(|ui| {
                        if ui.button("Export").clicked() {
                            next = Some(None);
                            action = Some(Action::ExportPng { path: PathBuf::from(path.trim()), size: *size, flat: *flat });
                        }
                        if ui.button("Cancel").clicked() {
                            next = Some(None);
                        }
                    });
                }
                Dialog::LoadMesh { path } => {
                    ui.heading("Preview on a mesh file");
                    ui.label(format!("OBJ, STL, PLY or glTF ({})", crate::mesh::EXTENSIONS.join(", ")));
                    ui.text_edit_singleline(path);
                    ui.horizontal(|ui| {
                        if ui.button("Load").clicked() {
                            next = Some(None);
                            action = Some(Action::LoadMesh(path.trim().to_string()));
                        }
                        if ui.button("Cancel").clicked() {
                            next = Some(None);
                        }
                    });
                }
                Dialog::Discard(pending) => {
                    ui.heading("Unsaved changes");
                    ui.label(format!("{} has changes that are not saved.", document.title().trim_end_matches(" — Veneer")));
                    ui.horizontal(|ui| {
                        if ui.button("Save").clicked() {
                            action = Some(Action::SaveThen(pending.clone()));
                            next = Some(None);
                        }
                        if ui.button("Discard").clicked() {
                            action = Some(Action::Discard(pending.clone()));
                            next = Some(None);
                        }
                        if ui.button("Cancel").clicked() {
                            next = Some(None);
                        }
                    });
                }
                Dialog::Recover(saved) => {
                    ui.heading("Recover unsaved work?");
                    let from = saved.original.as_ref().map(|p| p.display().to_string()).unwrap_or_else(|| "an unsaved graph".into());
                    ui.label(format!("Veneer did not exit cleanly last time. Autosaved work from {from} is available."));
                    ui.horizontal(|ui| {
                        if ui.button("Recover").clicked() {
                            action = Some(Action::Recover(saved.clone()));
                            next = Some(None);
                        }
                        if ui.button("Discard").clicked() {
                            action = Some(Action::ForgetRecovery);
                            next = Some(None);
                        }
                    });
                }
                Dialog::Message(message) => {
                    ui.heading("Veneer");
                    ui.label(message.as_str());
                    if ui.button("OK").clicked() {
                        next = Some(None);
                    }
                }
            }
        });
        match next {
            Some(replacement) => (replacement, action),
            None => (Some(self), action),
        }
    }
}
