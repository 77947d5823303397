//! What the editor does with the actions its dialogs return: open, save, export, load a
//! mesh, go on after the prompt about unsaved work, recover autosaved work.

use crate::app::VeneerApp;
use crate::app::chrome::dialogs::{Action, Dialog, Pending};
use crate::app::session::document::Document;
use crate::app::session::export_job::{ExportJob, Outcome};
use crate::app::session::recovery;
use crate::codegen::export::Target;
use crate::codegen::{CompileOptions, ParamMode};
use crate::graph::Graph;
use std::path::{Path, PathBuf};

impl VeneerApp {
    /// Carries out what the user decided in a dialog; a failure shows a message.
    pub(in crate::app) fn apply(&mut self, ctx: &egui::Context, action: Action) {
        let done = match action {
            Action::Open(path) => {
                self.guard(Pending::Open(path));
                Ok(None)
            }
            Action::SaveAs(path, then) => {
                let before = self.session.document.graph.clone();
                let saved = self.session.document.save_as(&path).map(|()| {
                    // Saved into another folder, its file paths were rewritten: the view
                    // shows them as they are now.
                    if self.session.document.graph.nodes != before.nodes
                        || self.session.document.graph.groups != before.groups
                    {
                        self.rebuild_snarl();
                    }
                    self.remember(&path);
                    self.session.saved();
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
            Action::ExportPng { path, size, flat } => self.export_png(ctx, path, size, flat),
            Action::ExportModel { path, size, format } => {
                self.export_model(ctx, path, size, format)
            }
            Action::ExportMaterialx { path, settings } => {
                self.export_materialx(ctx, path, settings)
            }
            Action::ExportMaps { stem, settings } => self.export_maps(ctx, stem, settings),
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
    pub(in crate::app) fn autosave_tick(
        &mut self,
        ctx: &egui::Context,
        copy: Option<std::sync::Arc<crate::graph::Graph>>,
    ) {
        let now = ctx.input(|input| input.time);
        let revision = self.session.revision.number;
        match self
            .session
            .autosave
            .tick(now, &self.session.document, revision, copy)
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

    /// Takes in the outcome of the export running on its thread, once it has ended.
    pub(in crate::app) fn poll_export(&mut self) {
        let Some(job) = &self.session.export else {
            return;
        };
        let Some(outcome) = job.poll() else {
            return;
        };
        let cancelled = job.cancelled();
        self.session.export = None;
        match outcome {
            Ok(message) => self.chrome.message = Some(message),
            Err(_) if cancelled => self.chrome.message = Some("export cancelled".into()),
            Err(error) => self.chrome.dialog = Some(Dialog::Message(error)),
        }
    }

    /// Starts `work` on a thread of its own, writing `path` (one export at a time).
    fn start_export(
        &mut self,
        ctx: &egui::Context,
        path: &Path,
        work: impl FnOnce(&dyn Fn(u64, u64) -> bool) -> Outcome + Send + 'static,
    ) -> Result<Option<String>, String> {
        if let Some(job) = &self.session.export {
            return Err(format!(
                "{} is still being exported: wait for it, or cancel it in the status bar",
                job.what
            ));
        }
        let what = path.file_name().map_or_else(
            || path.display().to_string(),
            |name| name.to_string_lossy().into_owned(),
        );
        self.session.export = Some(ExportJob::start(ctx, what, work));
        Ok(None)
    }

    /// Renders the document as the preview shows it (its lighting, environment and
    /// tone mapping), or its flat albedo, into a PNG, on a thread of its own.
    fn export_png(
        &mut self,
        ctx: &egui::Context,
        path: PathBuf,
        size: u32,
        flat: bool,
    ) -> Result<Option<String>, String> {
        let gpu = self.export_gpu()?;
        let view = if flat {
            crate::render::View::PreviewFlat
        } else {
            crate::render::View::Mesh(Some(self.preview.state.mesh.clone()))
        };
        let compiled = self.compiled_for_export()?;
        let (time, look) = (self.preview.state.view.time, self.preview.state.look());
        self.start_export(ctx, &path.clone(), move |_| {
            let image =
                crate::render::render_material_with(&gpu, &compiled, &view, size, time, look)
                    .map_err(|error| error.to_string())?
                    .image;
            let png = image.to_png().map_err(|error| error.to_string())?;
            crate::fsutil::write_atomic(&path, &png)
                .map_err(|e| format!("{}: {e}", path.display()))?;
            Ok(format!("exported {}", path.display()))
        })
    }

    /// Bakes the document onto the preview mesh as a model file in `format` (glTF or
    /// USD), on a thread of its own that reports its tiles (and stops, writing nothing,
    /// when cancelled).
    fn export_model(
        &mut self,
        ctx: &egui::Context,
        path: PathBuf,
        size: u32,
        format: crate::bake::ModelFormat,
    ) -> Result<Option<String>, String> {
        if let Some(why) = format.refuses(&path) {
            return Err(format!("{}: {why}", path.display()));
        }
        let gpu = self.export_gpu()?;
        let compiled = self.compiled_for_export()?;
        let settings = crate::bake::ModelSettings {
            mesh: Some(self.preview.state.mesh.clone()),
            size,
            time: self.preview.state.view.time,
        };
        self.start_export(ctx, &path.clone(), move |report| {
            let written = format
                .export(&gpu, &compiled, &settings, &path, report)
                .map_err(|error| error.to_string())?;
            Ok(exported(&written))
        })
    }

    /// Writes the document as a MaterialX document with its maps beside it, on a thread
    /// of its own that reports its tiles (and stops, writing nothing, when cancelled).
    fn export_materialx(
        &mut self,
        ctx: &egui::Context,
        path: PathBuf,
        mut settings: crate::bake::MaterialxSettings,
    ) -> Result<Option<String>, String> {
        let gpu = self.export_gpu()?;
        let compiled = self.compiled_for_export()?;
        settings.time = self.preview.state.view.time;
        self.start_export(ctx, &path.clone(), move |report| {
            let written = crate::bake::export_materialx(&gpu, &compiled, &settings, &path, report)
                .map_err(|error| error.to_string())?;
            Ok(exported(&written.files))
        })
    }

    /// The document compiled with its parameters baked, as exports want it.
    fn compiled_for_export(&self) -> Result<crate::codegen::Compiled, String> {
        crate::codegen::compile(&self.session.document.graph, &CompileOptions::default())
            .map_err(|error| error.to_string())
    }

    /// Bakes the document's maps into `<stem>_<map>.<ext>` files on a thread of its
    /// own that reports its tiles (and stops, writing nothing, when cancelled); a tile
    /// says how far its edges are from continuing each other, or why it was refused.
    fn export_maps(
        &mut self,
        ctx: &egui::Context,
        stem: PathBuf,
        mut settings: crate::bake::BakeSettings,
    ) -> Result<Option<String>, String> {
        if settings.maps.is_empty() {
            return Err("choose at least one map to export".into());
        }
        let gpu = self.export_gpu()?;
        let compiled = self.compiled_for_export()?;
        settings.time = self.preview.state.view.time;
        let stems = [stem.as_path()];
        crate::bake::check_outputs(&stems, &settings).map_err(|error| error.to_string())?;
        self.start_export(ctx, &stem.clone(), move |report| {
            // (Measuring a photo's edges reads all its texels: on the export's thread.)
            let seamed = match settings.surface {
                crate::bake::BakeSurface::Tile(_) => {
                    crate::bake::bitmap_seams::seamed_bitmaps(&compiled)
                }
                _ => Vec::new(),
            };
            let written = crate::bake::bake(&gpu, &compiled, &settings, &stem, report)
                .map_err(|error| error.to_string())?;
            let names: Vec<String> = written
                .iter()
                .map(|m| m.path.display().to_string())
                .collect();
            let seams = written
                .iter()
                .filter_map(|m| m.seams)
                .map(|s| s.worst())
                .reduce(f32::max);
            let tiles = seams.map_or(String::new(), |worst| {
                let worst = crate::bake::tile::seam_text(worst);
                format!("; they tile (opposite edges differ by up to {worst})")
            });
            let warnings: String = seamed
                .iter()
                .map(|seamed| format!("; but {seamed}"))
                .collect();
            Ok(format!("exported {}{tiles}{warnings}", names.join(", ")))
        })
    }
}

/// Writes `graph` as a shader for `target` to `path`: a multi-pass material as its
/// module there and, beside it, a module per pass and the manifest, all together.
fn export_shader(
    graph: &Graph,
    path: &Path,
    target: Target,
    params: ParamMode,
) -> Result<(), String> {
    let options = CompileOptions::with_params(params);
    let compiled = crate::codegen::compile(graph, &options).map_err(|e| e.to_string())?;
    if compiled.passes.is_empty() {
        let bytes = crate::codegen::export::export_compiled(&compiled, target)
            .map_err(|e| e.to_string())?;
        return crate::fsutil::write_atomic(path, &bytes)
            .map_err(|e| format!("{}: {e}", path.display()));
    }
    let files = crate::codegen::manifest::export_beside(&compiled, target, path)
        .map_err(|e| e.to_string())?;
    let writes =
        (files.iter()).map(|(path, naming, bytes)| (path.as_path(), *naming, bytes.as_slice()));
    crate::fsutil::write_together(writes)
        .map_err(|(path, error)| format!("{}: {error}", path.display()))
}

/// The status line of an export that wrote `written`.
fn exported(written: &[PathBuf]) -> String {
    let names: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
    format!("exported {}", names.join(", "))
}
