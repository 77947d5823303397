//! What the editor does with the actions its dialogs return: open, save, export, load a
//! mesh, go on after the prompt about unsaved work, recover autosaved work.

use crate::app::VeneerApp;
use crate::app::chrome::dialogs::{Action, Dialog, Pending};
use crate::app::session::document::Document;
use crate::app::session::recovery;
use crate::codegen::export::Target;
use crate::codegen::{CompileOptions, ParamMode};
use crate::graph::Graph;
use std::path::Path;

impl VeneerApp {
    /// Carries out what the user decided in a dialog; a failure shows a message.
    pub(in crate::app) fn apply(&mut self, action: Action) {
        let done = match action {
            Action::Open(path) => {
                self.guard(Pending::Open(path));
                Ok(None)
            }
            Action::SaveAs(path, then) => {
                let saved = self.session.document.save_as(&path).map(|()| {
                    self.remember(&path);
                    self.session.autosave.forget();
                    Some(format!("saved {}", path.display()))
                });
                if let (Ok(_), Some(pending)) = (&saved, then) {
                    self.perform(pending);
                }
                saved
            }
            Action::ExportShader {
                path,
                target,
                params,
            } => export_shader(&self.session.document.graph, &path, target, params)
                .map(|()| Some(format!("exported {}", path.display()))),
            Action::ExportPng { path, size, flat } => self
                .export_png(&path, size, flat)
                .map(|()| Some(format!("exported {}", path.display()))),
            Action::ExportGltf { path, size } => self.export_gltf(&path, size).map(|written| {
                Some(format!(
                    "exported {}",
                    written
                        .iter()
                        .map(|p| p.display().to_string())
                        .collect::<Vec<_>>()
                        .join(", ")
                ))
            }),
            Action::LoadMesh(path) => self.load_mesh(&path).map(|()| None),
            Action::LoadEnvironment(path) => self
                .load_environment(&path)
                .map(|name| Some(format!("lit by {name}"))),
            Action::SaveThen(pending) => {
                // An untitled graph asks for a file first, and goes on once saved there.
                self.save(Some(pending.clone()));
                if !self.session.document.is_dirty() {
                    self.perform(pending);
                }
                Ok(None)
            }
            Action::Discard(pending) => {
                // The user dropped this work: it is not to be offered for recovery.
                self.session.autosave.forget();
                self.perform(pending);
                Ok(None)
            }
            Action::Recover(saved) => {
                let saved = *saved;
                self.load(Document::recovered(saved.graph, saved.original));
                // This window autosaves the work now; then the old file can go.
                match self.session.autosave.write_now(&self.session.document) {
                    Ok(()) => {
                        recovery::clear(&saved.file);
                        Ok(None)
                    }
                    Err(error) => Err(format!(
                        "recovered, but cannot autosave it ({error}); {} is kept",
                        saved.file.display()
                    )),
                }
            }
            Action::ForgetRecovery(file) => {
                recovery::clear(&file);
                Ok(None)
            }
        };
        match done {
            Ok(Some(message)) => self.chrome.message = Some(message),
            Ok(None) => {}
            Err(error) => self.chrome.dialog = Some(Dialog::Message(error)),
        }
    }

    /// Autosaves unsaved work (or removes the window's recovery file once the document is
    /// clean); on SIGTERM, SIGINT or SIGHUP, autosaves and closes the window.
    pub(in crate::app) fn autosave_tick(&mut self, ctx: &egui::Context) {
        let now = ctx.input(|input| input.time);
        let revision = self.session.revision.number;
        match self
            .session
            .autosave
            .tick(now, &self.session.document, revision)
        {
            Ok(Some(wait)) => ctx.request_repaint_after(std::time::Duration::from_secs_f64(wait)),
            Ok(None) => {}
            Err(error) => self.chrome.message = Some(format!("autosave failed: {error}")),
        }
        if recovery::termination_requested() && !self.session.allowed_to_close {
            recovery::termination_heard();
            // Unsaved work stays for the next start; a clean document leaves nothing.
            let _ = self.session.autosave.write_now(&self.session.document);
            self.session.allowed_to_close = true;
        }
    }

    /// A context on the window's GPU device, for exports.
    fn export_gpu(&self) -> Result<crate::render::GpuContext, String> {
        let Some(state) = &self.preview.render_state else {
            return Err("no GPU: cannot render".into());
        };
        Ok(crate::render::GpuContext::on_device(
            state.adapter.clone(),
            state.device.clone(),
            state.queue.clone(),
        ))
    }

    /// Renders the document as the preview shows it (its lighting, environment and
    /// tone mapping), or its flat albedo, into a PNG.
    fn export_png(&self, path: &Path, size: u32, flat: bool) -> Result<(), String> {
        let gpu = self.export_gpu()?;
        let view = if flat {
            crate::render::View::PreviewFlat
        } else {
            crate::render::View::Mesh(Some(self.preview.state.mesh.clone()))
        };
        let compiled =
            crate::codegen::compile(&self.session.document.graph, &CompileOptions::default())
                .map_err(|error| error.to_string())?;
        let image = crate::render::render_material_with(
            &gpu,
            &compiled,
            &view,
            size,
            self.preview.state.view.time,
            self.preview.state.look(),
        )
        .map_err(|error| error.to_string())?
        .image;
        let png = image.to_png().map_err(|error| error.to_string())?;
        crate::fsutil::write_atomic(path, &png).map_err(|e| format!("{}: {e}", path.display()))
    }

    /// Bakes the document into a glTF file on the preview mesh; returns the files written.
    fn export_gltf(&self, path: &Path, size: u32) -> Result<Vec<std::path::PathBuf>, String> {
        let gpu = self.export_gpu()?;
        let compiled =
            crate::codegen::compile(&self.session.document.graph, &CompileOptions::default())
                .map_err(|error| error.to_string())?;
        let settings = crate::bake::GltfSettings {
            mesh: Some(self.preview.state.mesh.clone()),
            size,
            time: self.preview.state.view.time,
        };
        crate::bake::export_gltf(&gpu, &compiled, &settings, path, |_, _| {})
            .map_err(|error| error.to_string())
    }
}

/// Writes `graph` as a shader for `target` to `path`.
fn export_shader(
    graph: &Graph,
    path: &Path,
    target: Target,
    params: ParamMode,
) -> Result<(), String> {
    let bytes = crate::codegen::export::export(graph, target, params).map_err(|e| e.to_string())?;
    crate::fsutil::write_atomic(path, &bytes).map_err(|e| format!("{}: {e}", path.display()))
}
