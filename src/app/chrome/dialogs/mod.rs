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

pub(in crate::app) mod contents;
pub(in crate::app) mod frame;

use crate::app::chrome::dialogs::frame::{Choice, Frame, default_path, typed_path};
use crate::app::chrome::file_browser::{Browsed, Browser, Purpose};
use crate::app::session::document::Document;
use crate::app::session::recovery::Recovery;
use crate::codegen::ParamMode;
use crate::codegen::export::Target;
use egui::{Context, Id, Key, Modal};
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
    /// Save the document to this file, then go on with what the save was asked for
    /// (the prompt about unsaved work of an untitled graph).
    SaveAs(PathBuf, Option<Pending>),
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
    /// Bake the material into a model file (glTF or USD) on the preview mesh, maps `size`
    /// pixels.
    ExportModel {
        path: PathBuf,
        size: u32,
        format: crate::bake::ModelFormat,
    },
    /// Write a MaterialX document with the material's maps beside it.
    ExportMaterialx {
        path: PathBuf,
        settings: crate::bake::MaterialxSettings,
    },
    /// Bake the material's maps into `<stem>_<map>.<ext>` files.
    ExportMaps {
        stem: PathBuf,
        settings: crate::bake::BakeSettings,
    },
    /// Show a mesh file in the preview.
    LoadMesh(String),
    /// Light metallic-roughness previews with a panorama file.
    LoadEnvironment(String),
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
        /// What to do once saved (Save in the prompt about unsaved work).
        then: Option<Pending>,
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
    ExportModel {
        path: String,
        size: u32,
        format: crate::bake::ModelFormat,
    },
    ExportMaterialx {
        path: String,
        size: u32,
        surface: crate::bake::SurfaceModel,
        tier: crate::bake::Tier,
    },
    /// The maps as files beside each other (`path` names the first, `<stem>_<map>.<ext>`).
    ExportMaps {
        path: String,
        size: u32,
        /// Which of [`crate::bake::Map::ALL`] to write.
        maps: [bool; 10],
        format: crate::bake::Format,
        /// One tile of a repeating texture over the unit square, its seams checked.
        tile: bool,
    },
    LoadMesh {
        path: String,
    },
    LoadEnvironment {
        path: String,
    },
    /// Save as onto an existing file: asks before replacing it (and what to do once
    /// saved).
    Replace(PathBuf, Option<Pending>),
    Discard(Pending),
    /// Autosaved work of windows that did not exit cleanly, newest first.
    Recover(Vec<Recovery>),
    Message(String),
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

impl Dialog {
    /// The Open dialog.
    pub fn open() -> Dialog {
        Dialog::Open {
            path: String::new(),
        }
    }
    /// Save as, suggesting the current file or the graph's name; once saved, `then`.
    pub fn save_as(document: &Document, then: Option<Pending>) -> Dialog {
        Dialog::SaveAs {
            then,
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

    /// Bake the material onto the preview mesh as a model file in `format`.
    pub fn export_model(document: &Document, format: crate::bake::ModelFormat) -> Dialog {
        Dialog::ExportModel {
            path: default_path(document, format.extension()),
            size: 1024,
            format,
        }
    }

    /// Write a MaterialX document (OpenPBR Surface to start with) with the maps beside it.
    pub fn export_materialx(document: &Document) -> Dialog {
        Dialog::ExportMaterialx {
            path: default_path(document, "mtlx"),
            size: 1024,
            surface: crate::bake::SurfaceModel::OpenPbr,
            tier: crate::bake::Tier::Baked,
        }
    }

    /// Bake the material's maps (albedo, normal and height to start with) over the
    /// preview square, or as one tile of a repeating texture.
    pub fn export_maps(document: &Document) -> Dialog {
        let chosen = [
            crate::bake::Map::Albedo,
            crate::bake::Map::Normal,
            crate::bake::Map::Height,
        ];
        Dialog::ExportMaps {
            path: default_path(document, "png"),
            size: 1024,
            maps: crate::bake::Map::ALL.map(|map| chosen.contains(&map)),
            format: crate::bake::Format::Png8,
            tile: false,
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
            | Dialog::SaveAs { path, .. }
            | Dialog::ExportShader { path, .. }
            | Dialog::ExportPng { path, .. }
            | Dialog::ExportModel { path, .. }
            | Dialog::ExportMaterialx { path, .. }
            | Dialog::ExportMaps { path, .. }
            | Dialog::LoadMesh { path }
            | Dialog::LoadEnvironment { path } => Some(path),
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
            Dialog::LoadEnvironment { .. } => Purpose::Pick {
                title: "Light with an environment",
                kind: "HDR panoramas",
                extensions: &["hdr", "exr"],
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
            Dialog::ExportModel { format, .. } => Purpose::Save {
                title: format.title(),
                kind: format.name(),
                extension: format.extension(),
            },
            Dialog::ExportMaterialx { .. } => Purpose::Save {
                title: "Export MaterialX",
                kind: "MaterialX document",
                extension: "mtlx",
            },
            Dialog::ExportMaps { format, .. } => Purpose::Save {
                title: "Export maps",
                kind: "Maps",
                extension: format.extension(),
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
                        Dialog::SaveAs { then, .. } => (None, Some(Action::SaveAs(path, then))),
                        Dialog::Open { .. }
                        | Dialog::LoadMesh { .. }
                        | Dialog::LoadEnvironment { .. } => self.confirm(document),
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
                Dialog::Replace(path, then) => (None, Some(Action::SaveAs(path, then))),
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
            Dialog::SaveAs { path, then } if !path.trim().is_empty() => {
                let path = typed_path(path);
                if path.exists() && document.path.as_ref() != Some(&path) {
                    return (Some(Dialog::Replace(path, then.clone())), None);
                }
                Action::SaveAs(path, then.clone())
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
            Dialog::ExportModel { path, size, format } if !path.trim().is_empty() => {
                Action::ExportModel {
                    path: typed_path(path),
                    size: *size,
                    format: *format,
                }
            }
            Dialog::ExportMaterialx {
                path,
                size,
                surface,
                tier,
            } if !path.trim().is_empty() => Action::ExportMaterialx {
                path: typed_path(path),
                settings: crate::bake::MaterialxSettings {
                    tier: *tier,
                    surface: *surface,
                    size: *size,
                    time: 0.0,
                },
            },
            Dialog::ExportMaps {
                path,
                size,
                maps,
                format,
                tile,
            } if !path.trim().is_empty() => Action::ExportMaps {
                // `wood.png` (or `wood`) names the maps `wood_albedo.png` and so on.
                stem: typed_path(path).with_extension(""),
                settings: crate::bake::BakeSettings {
                    surface: if *tile {
                        crate::bake::BakeSurface::Tile(None)
                    } else {
                        crate::bake::BakeSurface::Plane(None)
                    },
                    size: *size,
                    maps: (crate::bake::Map::ALL.iter().zip(maps))
                        .filter(|(_, chosen)| **chosen)
                        .map(|(map, _)| *map)
                        .collect(),
                    format: *format,
                    normal: crate::bake::NormalConvention::OpenGl,
                    time: 0.0,
                },
            },
            Dialog::LoadMesh { path } if !path.trim().is_empty() => {
                Action::LoadMesh(typed_path(path).display().to_string())
            }
            Dialog::LoadEnvironment { path } if !path.trim().is_empty() => {
                Action::LoadEnvironment(typed_path(path).display().to_string())
            }
            Dialog::Replace(path, then) => Action::SaveAs(path.clone(), then.clone()),
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
            Dialog::Replace(path, then) => (
                Some(Dialog::SaveAs {
                    path: path.display().to_string(),
                    then,
                }),
                None,
            ),
            // Recovery files stay, to be offered at the next start.
            _ => (None, None),
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
