//! Modal dialogs: file paths for open, save as and export; the prompt before losing
//! unsaved work; recovery after a crash; messages.

use super::recovery::{self, Recovery};
use super::{Document, VeneerApp};
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

    /// Shows the dialog; returns the dialog to show next frame (`None` once closed).
    pub fn show(mut self, ctx: &Context, app: &mut VeneerApp) -> Option<Dialog> {
        let mut next: Option<Option<Dialog>> = None;
        Modal::new(Id::new("veneer dialog")).show(ctx, |ui| {
            ui.set_min_width(420.0);
            match &mut self {
                Dialog::Open { path } => {
                    ui.heading("Open graph");
                    let edit = ui.text_edit_singleline(path);
                    let enter = edit.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
                    ui.horizontal(|ui| {
                        if ui.button("Open").clicked() || enter {
                            let path = PathBuf::from(path.trim());
                            next = Some(None);
                            app.guard(Pending::Open(path));
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
                            let target = PathBuf::from(path.trim());
                            next = Some(match app.document.save_as(&target) {
                                Ok(()) => {
                                    app.remember(&target);
                                    app.message = Some(format!("saved {}", target.display()));
                                    recovery::clear(&app.recovery_file);
                                    None
                                }
                                Err(error) => Some(Dialog::Message(error)),
                            });
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
                    let selected = Target::ALL.iter().find(|(t, _)| t == target).map(|(_, n)| *n).unwrap_or_default();
                    egui::ComboBox::from_label("language").selected_text(selected).show_ui(ui, |ui| {
                        for (option, name) in Target::ALL {
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
                            next = Some(export_shader(app, PathBuf::from(path.trim()), *target, params));
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
                            next = Some(export_png(app, PathBuf::from(path.trim()), *size, *flat));
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
                            next = Some(app.load_mesh(path.trim()).err().map(Dialog::Message));
                        }
                        if ui.button("Cancel").clicked() {
                            next = Some(None);
                        }
                    });
                }
                Dialog::Discard(action) => {
                    ui.heading("Unsaved changes");
                    ui.label(format!("{} has changes that are not saved.", app.document.title().trim_end_matches(" — Veneer")));
                    ui.horizontal(|ui| {
                        if ui.button("Save").clicked() {
                            app.save();
                            if !app.document.is_dirty() {
                                app.perform(action.clone());
                            }
                            next = Some(None);
                        }
                        if ui.button("Discard").clicked() {
                            app.perform(action.clone());
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
                            app.load(Document::recovered(saved.graph.clone(), saved.original.clone()));
                            next = Some(None);
                        }
                        if ui.button("Discard").clicked() {
                            recovery::clear(&app.recovery_file);
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
            Some(replacement) => replacement,
            None => Some(self),
        }
    }
}

fn export_shader(
    app: &mut VeneerApp,
    path: PathBuf,
    target: Target,
    params: ParamMode,
) -> Option<Dialog> {
    let result = crate::codegen::export::export(&app.document.graph, target, params)
        .map_err(|error| error.to_string())
        .and_then(|bytes| {
            crate::fsutil::write_atomic(&path, &bytes)
                .map_err(|e| format!("{}: {e}", path.display()))
        });
    match result {
        Ok(()) => {
            app.message = Some(format!("exported {}", path.display()));
            None
        }
        Err(error) => Some(Dialog::Message(error)),
    }
}

fn export_png(app: &mut VeneerApp, path: PathBuf, size: u32, flat: bool) -> Option<Dialog> {
    let Some(state) = &app.render_state else {
        return Some(Dialog::Message("no GPU: cannot render".into()));
    };
    let gpu = crate::render::GpuContext::on_device(
        state.adapter.clone(),
        state.device.clone(),
        state.queue.clone(),
    );
    let view = if flat {
        crate::render::View::PreviewFlat
    } else {
        crate::render::View::Mesh(Some(app.preview.mesh.clone()))
    };
    let result = crate::render::render_graph(
        &gpu,
        &app.document.graph,
        &view,
        size,
        app.preview.view.time,
    )
    .map_err(|error| error.to_string())
    .and_then(|image| image.to_png().map_err(|e| e.to_string()))
    .and_then(|png| {
        crate::fsutil::write_atomic(&path, &png).map_err(|e| format!("{}: {e}", path.display()))
    });
    match result {
        Ok(()) => {
            app.message = Some(format!("exported {}", path.display()));
            None
        }
        Err(error) => Some(Dialog::Message(error)),
    }
}
