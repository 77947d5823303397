//! The node editor: an egui-snarl graph on the left, the live material on a mesh and
//! the inspector on the right, a status bar below. Behind the default `gui` feature.

mod allocator;
mod canvas;
mod chrome;
mod fitting;
mod inspector;
mod preview;
mod priority;
mod session;
mod thumbnails;
mod widgets;

#[cfg(test)]
mod structure_tests;

pub use crate::graph::{PRESETS, preset};
pub use chrome::frame_clock::FrameProfile;
pub use chrome::frame_clock::{FRAME_LOG_HEADER, FrameLog};
pub use preview::background::{BACKGROUND_NODES, UNIFORM_SLOTS};
pub use preview::live::LiveMaterial;
pub use preview::probe::{AtlasGraph, atlas_graph};
pub use session::document::Document;
pub use thumbnails::{TILE_PIXELS, Thumbnails, placement, tile_params};

use crate::graph::{AlphaMode, Graph, Shading};
use canvas::navigation::Framing;
use canvas::snarl_model::snarl_from_graph;
use chrome::dialogs::{Dialog, Pending};
use egui::{Key, KeyboardShortcut, Modifiers, Ui};
use preview::state::MaterialFrame;
use preview::worker::{Slot, TessellationInput};
use std::path::PathBuf;
use std::sync::Arc;

/// Opens the editor window on `path`, or on the wood preset.
/// `frame_log` names a file that gets a line per frame (see [`FrameLog`]).
pub fn run(path: Option<PathBuf>, frame_log: Option<PathBuf>) -> Result<(), String> {
    let mut frame_log = frame_log.as_deref().map(FrameLog::create).transpose()?;
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_inner_size([1400.0, 860.0])
            .with_title("Veneer"),
        renderer: eframe::Renderer::Wgpu,
        ..Default::default()
    };
    allocator::keep_freed_memory();
    eframe::run_native(
        "Veneer",
        options,
        Box::new(move |cc| {
            let mut app = VeneerApp::new(cc, path);
            app.chrome.frame_log = frame_log.take();
            Ok(Box::new(app))
        }),
    )
    .map_err(|error| format!("cannot open the editor window: {error}"))
}

/// The editor: its parts, each owning its state. The document is the truth; the canvas
/// shows it, the preview draws it, the chrome frames the window.
pub struct VeneerApp {
    /// The document, its history, revision, recovery and recent files.
    session: session::Session,
    /// The graph view: the snarl, selection, navigation, the add-node search.
    canvas: canvas::Canvas,
    /// The live material, its pictures, the mesh's fields.
    preview: preview::Preview,
    /// Thumbnails on the nodes and on hovered wires.
    thumbnails: thumbnails::Thumbnails,
    /// Messages, dialogs, the file browser, the frame clock.
    chrome: chrome::Chrome,
    /// *Fit to image…*: the fit under way and its window.
    fitting: fitting::Fitting,
}

impl VeneerApp {
    /// The editor on `path` (or the wood preset), autosaving to the default recovery file.
    pub fn new(cc: &eframe::CreationContext<'_>, path: Option<PathBuf>) -> VeneerApp {
        session::recovery::watch_termination(&cc.egui_ctx);
        VeneerApp::with_recovery_file(cc, path, session::recovery::default_path())
    }

    /// The editor on `path` (or the wood preset), autosaving beside `recovery_file` to a
    /// file of its own, with the preview's GPU resources installed. Offers the work that
    /// windows which did not exit cleanly left there.
    pub fn with_recovery_file(
        cc: &eframe::CreationContext<'_>,
        path: Option<PathBuf>,
        recovery_file: PathBuf,
    ) -> VeneerApp {
        let wood = preset("wood").expect("the wood preset is embedded");
        let mut app = VeneerApp {
            canvas: canvas::Canvas::new(snarl_from_graph(&wood)),
            preview: preview::Preview::new(
                &cc.egui_ctx,
                &wood.preview,
                cc.wgpu_render_state.clone(),
            ),
            fitting: fitting::Fitting {
                choices: session::recovery::load_kept::<fitting::FitChoices>(
                    &session::recovery::choices_path(&recovery_file),
                )
                .within_ranges(),
                ..Default::default()
            },
            session: session::Session::new(Document::new(wood, None), recovery_file),
            thumbnails: Default::default(),
            chrome: Default::default(),
        };
        app.canvas.navigation.frame(Framing::Open);
        if let Some(path) = path {
            app.open(path);
        }
        let orphans = session::recovery::orphans(&app.session.recovery_file);
        if !orphans.is_empty() {
            app.chrome.dialog = Some(Dialog::Recover(orphans));
        }
        app.preview.live.update(&app.session.document.graph);
        app
    }

    /// The document being edited.
    pub fn document(&self) -> &Document {
        &self.session.document
    }

    /// The document, to change it as a script or test does (the editor takes the change
    /// in on the next frame).
    pub fn document_mut(&mut self) -> &mut Document {
        let revision = &mut self.session.revision;
        if revision.outside.is_none() {
            revision.outside = Some(self.session.document.graph.clone());
        }
        &mut self.session.document
    }

    /// The graph's material as last compiled, with its errors and warnings.
    pub fn live(&self) -> &LiveMaterial {
        &self.preview.live
    }

    /// The selected node's output, compiled for its thumbnail.
    pub fn thumbnail(&self) -> &LiveMaterial {
        &self.preview.thumbnail
    }

    /// Thumbnails on the nodes and on hovered wires.
    pub fn thumbnails(&self) -> &Thumbnails {
        &self.thumbnails
    }

    /// The status bar's message, if any.
    pub fn message(&self) -> Option<&str> {
        self.chrome.message.as_deref()
    }

    /// Where the main thread's time went in the last frame.
    pub fn profile(&self) -> FrameProfile {
        self.chrome.profile
    }

    /// Whether an export runs on its thread (the status bar shows its progress).
    pub fn exporting(&self) -> bool {
        self.session.export.is_some()
    }

    /// Whether the preview compiles every octave of the flat view's fractals.
    pub fn set_full_detail(&mut self, full: bool) {
        self.preview.live.full_detail = full;
    }

    /// Shows a mesh file (OBJ, STL, PLY, glTF) in the preview; a bad file is refused with a message.
    pub fn load_mesh(&mut self, path: &str) -> Result<(), String> {
        let mesh = crate::mesh::preview_mesh(path).map_err(|error| error.to_string())?;
        self.preview.state.mesh = path.to_string();
        self.preview.state.file = Some(Arc::new(mesh));
        Ok(())
    }

    /// Lights metallic-roughness previews with the panorama at `path`; returns its name.
    pub fn load_environment(&mut self, path: &str) -> Result<String, String> {
        let environment = crate::render::Environment::named(path).map_err(|e| e.to_string())?;
        let name = environment.name.clone();
        self.preview.state.environment = preview::worker::EnvironmentChoice(
            (name != crate::render::SKY).then(|| Arc::new(environment)),
        );
        Ok(name)
    }

    /// Replaces the document (after open, new, preset or recovery).
    fn load(&mut self, document: Document) {
        self.preview.state.follow(&document.graph.preview);
        // Picking sources and viewing a field are modes of the graph they were chosen on.
        self.preview.fields.picking = None;
        self.preview.fields.view = None;
        let mesh = document.graph.preview.mesh.clone();
        if crate::mesh::primitive(&mesh).is_some() || self.load_mesh(&mesh).is_err() {
            self.preview.state.mesh = mesh;
            self.preview.state.file = None;
        }
        let generation = self.canvas.view_generation + 1;
        self.canvas = canvas::Canvas::new(snarl_from_graph(&document.graph));
        self.canvas.view_generation = generation;
        self.session.document = document;
        self.session.revision.outside = None;
        self.session.revision.gesture = false;
        self.session.revision.replaced();
        self.preview.live.forget();
        self.preview.previews.forget();
        self.preview.live.update(&self.session.document.graph);
    }

    /// Opens a graph file; a bad file is refused with a message and loses nothing.
    pub fn open(&mut self, path: PathBuf) {
        if path
            .extension()
            .is_some_and(|extension| extension.eq_ignore_ascii_case("mtlx"))
        {
            return self.import_materialx(&path);
        }
        match crate::graph::load(&path) {
            Ok(mut graph) => {
                self.remember(&path);
                // Nodes drawn on top of each other hide each other, and ten thousand of
                // them at one point are more geometry than egui draws in a frame.
                let stacked = crate::graph::layout::unstack_levels(&mut graph);
                self.load(if stacked == 0 {
                    Document::new(graph, Some(path))
                } else {
                    Document::recovered(graph, Some(path))
                });
                self.chrome.message = (stacked > 0).then(|| {
                    format!(
                        "{} nodes lay on top of others and were laid out; save to keep it",
                        crate::messages::thousands(stacked)
                    )
                });
            }
            Err(error) => self.chrome.dialog = Some(Dialog::Message(error.to_string())),
        }
    }

    /// Opens MaterialX document `path` as a new graph (unsaved: it has no graph file yet).
    fn import_materialx(&mut self, path: &std::path::Path) {
        let name = path.display().to_string();
        let imported = std::fs::read_to_string(path)
            .map_err(|error| format!("{name}: cannot read: {error}"))
            .and_then(|text| crate::bake::import_materialx(&text, &name));
        match imported {
            Ok(graph) => {
                self.load(Document::recovered(graph, None));
                self.chrome.message = Some(format!(
                    "imported {name}; save it as a graph file to keep it"
                ));
            }
            Err(error) => self.chrome.dialog = Some(Dialog::Message(error)),
        }
    }

    /// Puts `path` first in the recent files, kept across sessions.
    pub(crate) fn remember(&mut self, path: &std::path::Path) {
        self.session.recent.retain(|p| p != path);
        self.session.recent.insert(0, path.to_path_buf());
        self.session.recent.truncate(8);
        if let Err(error) =
            session::recovery::save_recent(&self.session.recovery_file, &self.session.recent)
        {
            self.chrome.message = Some(format!("cannot remember recent files: {error}"));
        }
    }

    /// Runs `action` now, or after asking what to do with unsaved changes.
    fn guard(&mut self, action: Pending) {
        if self.session.document.is_dirty() {
            self.chrome.dialog = Some(Dialog::Discard(action));
        } else {
            self.perform(action);
        }
    }

    fn perform(&mut self, action: Pending) {
        match action {
            Pending::New => {
                let mut graph = Graph {
                    name: "Untitled".into(),
                    ..Graph::default()
                };
                graph.add("material", crate::graph::NodeKind::Material);
                self.load(Document::new(graph, None));
            }
            Pending::Open(path) => self.open(path),
            Pending::Preset(name) => {
                if let Some(graph) = preset(name) {
                    self.load(Document::new(graph, None));
                }
            }
            Pending::Quit => {
                self.session.allowed_to_close = true;
                self.session.autosave.forget();
            }
        }
    }

    /// Saves to the document's file, or asks for one (and then does `then`, when the
    /// save was asked for before going on with it).
    pub fn save(&mut self, then: Option<Pending>) {
        match self.session.document.save() {
            Ok(path) => {
                self.remember(&path);
                self.chrome.message = Some(format!("saved {}", path.display()));
                self.session.saved();
            }
            Err(_) if self.session.document.path.is_none() => {
                self.chrome.dialog = Some(Dialog::save_as(&self.session.document, then))
            }
            Err(error) => self.chrome.dialog = Some(Dialog::Message(error)),
        }
    }

    /// Makes `frames` the graph's comment frames: one edit, when they changed.
    pub(in crate::app) fn set_frames(&mut self, frames: Vec<crate::graph::Frame>) {
        if frames != self.session.document.graph.frames {
            let setting = crate::graph::edit::GraphSetting::Frames(frames);
            self.edit(crate::graph::edit::GraphEdit::Set(setting));
        }
    }

    /// The nodes of the level the graph view shows: the top level's, or those of the
    /// group open.
    pub fn level_nodes(&self) -> Vec<crate::graph::Node> {
        self.canvas.snarl.nodes().cloned().collect()
    }

    /// The groups entered, outermost first (empty at the top level).
    pub fn group_path(&self) -> Vec<String> {
        self.canvas
            .scope
            .levels
            .iter()
            .map(|level| level.group.clone())
            .collect()
    }

    /// Whether the preview shows a mesh whose distance fields are solved and up to date.
    pub fn fields_solved(&self) -> bool {
        self.preview.state.prepared.is_some() && self.preview.fields.progress().is_none()
    }

    /// The graph view's transform from graph to screen coordinates (node widgets are laid
    /// out in graph coordinates).
    pub fn graph_to_screen(&self) -> egui::emath::TSTransform {
        self.canvas.navigation.transform
    }

    /// The labels of the selected nodes, in selection order.
    pub fn selected_labels(&self) -> Vec<String> {
        self.canvas
            .selection
            .iter()
            .filter_map(|node| self.canvas.snarl.get_node(*node))
            .map(|node| node.label.clone())
            .collect()
    }

    /// The ids of the selected nodes, in selection order.
    pub fn selected_nodes(&self) -> Vec<crate::graph::NodeId> {
        self.canvas
            .selection
            .iter()
            .filter_map(|node| self.canvas.snarl.get_node(*node))
            .map(|node| node.id)
            .collect()
    }

    /// Where node `node` of the level shown was drawn last frame, on screen.
    pub fn node_on_screen(&self, node: crate::graph::NodeId) -> Option<egui::Rect> {
        let (id, _) = self
            .canvas
            .snarl
            .node_ids()
            .find(|(_, shown)| shown.id == node)?;
        let rect = *self.canvas.spots.borrow().nodes.get(&id)?;
        Some(self.canvas.navigation.transform * rect)
    }

    /// Where the pin `pin` (an output when `output`) was drawn last frame, on screen.
    pub fn pin_on_screen(&self, pin: &crate::graph::PinRef, output: bool) -> Option<egui::Pos2> {
        let (id, node) = self
            .canvas
            .snarl
            .node_ids()
            .find(|(_, node)| node.id == pin.node)?;
        let signature = node.kind.signature();
        let spots = self.canvas.spots.borrow();
        let at = if output {
            let output = signature.output(&pin.pin)?.0;
            spots.output(egui_snarl::OutPinId { node: id, output })?
        } else {
            let input = signature.input(&pin.pin)?.0;
            spots.input(egui_snarl::InPinId { node: id, input })?
        };
        Some(self.canvas.navigation.transform * at)
    }

    /// Number of materials the preview has built pipelines for (0 without a GPU).
    pub fn pipelines_built(&self) -> u64 {
        self.preview.previews.materials_built()
    }

    /// How many times the graph has changed since the editor started, and how many
    /// frames took edits in from the graph view (frames where nothing was done to it
    /// never do).
    pub fn revision(&self) -> (u64, u64) {
        (self.session.revision.number, self.session.revision.reads)
    }

    /// How finely the preview's image on screen was drawn: a draft while something is
    /// dragged, full at rest (`None` before the first image).
    pub fn preview_quality(&self) -> Option<crate::render::Quality> {
        self.preview.previews.quality()
    }

    /// Why the preview could not draw its newest material, if it could not.
    pub fn preview_error(&self) -> Option<&str> {
        self.preview.previews.error()
    }

    /// The time the preview shows, and whether it plays.
    pub fn preview_time(&self) -> (f32, bool) {
        (self.preview.state.view.time, self.preview.state.playing)
    }

    /// Whether the previews show, at full quality, what was last asked of them (they
    /// are drawn on another thread: tests wait for this before looking).
    pub fn preview_settled(&self) -> bool {
        let live = &self.preview.live;
        // (A compile taken in after the preview was drawn reaches it in the next frame.)
        let handed_over = live.compiled.is_none()
            || self.preview.frames[preview::worker::Slot::Main as usize]
                .has_code_of(live.generation);
        self.preview.previews.settled() && !live.is_compiling() && handed_over
    }

    /// The inspector of the active node, or a hint and the comment frames.
    fn inspector(&mut self, ui: &mut Ui) {
        match self.canvas.selection.active() {
            Some(node) if self.canvas.snarl.get_node(node).is_some() => {
                ui.separator();
                self.inspect(ui, node);
            }
            _ => {
                ui.weak(
                    "Select a node to edit it. Right-click the graph (or press Space) to add one.",
                );
                let mut frames = self.session.document.graph.frames.clone();
                inspector::frames::frames_editor(ui, &mut frames);
                self.set_frames(frames);
            }
        }
    }

    /// The inspector of node `node` of the graph view.
    fn inspect(&mut self, ui: &mut Ui, node: egui_snarl::NodeId) {
        let shown = &self.canvas.snarl[node];
        if let Some(side) = crate::app::canvas::boundary::boundary(shown) {
            let group = self
                .canvas
                .scope
                .current()
                .and_then(|name| self.session.document.graph.groups.get(name));
            let edit =
                group.and_then(|definition| inspector::group_interface::show(ui, side, definition));
            if let Some(edit) = edit {
                self.edit_interface(edit);
            }
            return;
        }
        if let Some(name) = crate::graph::group::group_name(shown) {
            let definition = self.session.document.graph.groups.get(name);
            if let Some(action) = inspector::group::show(ui, node, name, definition) {
                self.group_action(action);
                return;
            }
            ui.separator();
        }
        // Inside a group the nodes' ids are the definition's: the top level's
        // thumbnails and errors are not theirs (its warnings are found for each group).
        if let Some(group) = self.canvas.scope.current() {
            let id = self.canvas.snarl[node].id;
            let warning = self.preview.live.warnings.of_level(Some(group)).get(&id);
            let request = inspector::node::show(ui, &mut self.canvas.snarl, node, None, warning);
            self.choose_file(node, request);
            return;
        }
        self.node_thumbnail(ui, node);
        let id = self.canvas.snarl[node].id;
        let (error, warning) = (
            self.preview.live.errors.get(&Some(id)),
            self.preview.live.warnings.top.get(&id),
        );
        let request = inspector::node::show(ui, &mut self.canvas.snarl, node, error, warning);
        self.choose_file(node, request);
    }

    /// Opens the file browser for a node's file setting, when the inspector asked.
    fn choose_file(
        &mut self,
        node: egui_snarl::NodeId,
        request: Option<inspector::node::FileRequest>,
    ) {
        let Some(request) = request else {
            return;
        };
        let folder = self.session.document.graph.folder.path();
        let current = folder.join(&request.current);
        self.chrome.browser.open(
            chrome::file_browser::Purpose::Pick {
                title: "Choose an image",
                kind: "Images",
                extensions: request.extensions,
            },
            &current.to_string_lossy(),
        );
        self.chrome.choosing_file_for = Some(node);
    }

    /// Shows the file browser a node's file setting opened; stores the chosen file in
    /// the setting, relative to the graph's folder.
    fn file_setting_browser(&mut self, ctx: &egui::Context) {
        let Some(node) = self.chrome.choosing_file_for else {
            return;
        };
        let chrome::file_browser::Browsed::Picked(path) = self.chrome.browser.update(ctx) else {
            if !self.chrome.browser.is_open() {
                self.chrome.choosing_file_for = None;
            }
            return;
        };
        self.chrome.choosing_file_for = None;
        let folder = self.session.document.graph.folder.path().to_path_buf();
        let relative = crate::bitmaps::relative_to(&folder, &path);
        let Some(mut edited) = self.canvas.snarl.get_node(node).cloned() else {
            return;
        };
        for setting in edited.kind.settings() {
            if let crate::nodes::settings::Setting::File { value, .. } = setting {
                *value = relative.to_string_lossy().into_owned();
            }
        }
        self.canvas.snarl[node] = edited;
    }

    fn handle_close(&mut self, ctx: &egui::Context) {
        if ctx.input(|input| input.viewport().close_requested()) && !self.session.allowed_to_close {
            if self.session.document.is_dirty() {
                ctx.send_viewport_cmd(egui::ViewportCommand::CancelClose);
                self.chrome.dialog = Some(Dialog::Discard(Pending::Quit));
            } else {
                self.session.autosave.forget();
            }
        }
        if self.session.allowed_to_close {
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
        }
    }
}

impl eframe::App for VeneerApp {
    fn ui(&mut self, ui: &mut Ui, _frame: &mut eframe::Frame) {
        let started = std::time::Instant::now();
        let started_at = std::time::SystemTime::now();
        let cpu_before = chrome::frame_clock::thread_cpu_time();
        let ctx = ui.ctx().clone();
        self.preview.previews.receive(&ctx);
        self.before_edits(&ctx);
        self.shortcuts(&ctx);
        self.clipboard(&ctx);
        egui::Panel::top("menu").show(ui, |ui| self.menu_bar(ui));
        egui::Panel::bottom("status").show(ui, |ui| self.status_bar(ui));
        egui::Panel::right("side")
            .default_size(460.0)
            .show(ui, |ui| {
                self.preview_panel(ui);
                ui.separator();
                // The selected node first, where a click on it is looked for; the
                // graph's parameters after it.
                egui::ScrollArea::vertical().show(ui, |ui| {
                    self.inspector(ui);
                    self.parameters_panel(ui);
                });
            });
        let central = egui::CentralPanel::default()
            .frame(canvas::painting::central_panel_frame(ui.style()))
            .show(ui, |ui| {
                let canvas = ui.max_rect();
                self.graph_panel(ui);
                canvas
            });
        canvas::painting::paint_panel_margin(ui, central.response.rect, central.inner);
        if let Some(dialog) = self.chrome.dialog.take() {
            // A dialog's action may open another dialog (an open that fails shows a
            // message): that one wins over the dialog staying open.
            let (still_open, action) =
                dialog.show(&ctx, &self.session.document, &mut self.chrome.browser);
            if let Some(action) = action {
                self.apply(&ctx, action);
            }
            self.chrome.dialog = self.chrome.dialog.take().or(still_open);
        }
        self.file_setting_browser(&ctx);
        self.fit_to_image_window(&ctx);
        self.poll_export();
        // After the dialogs too, so that what their buttons did (save, open) shows now.
        self.after_edits(&ctx);
        self.handle_close(&ctx);
        self.chrome.profile.total = started.elapsed();
        self.chrome.profile.cpu = chrome::frame_clock::thread_cpu_time().saturating_sub(cpu_before);
        // Work this frame started on threads of its own begins now.
        preview::background::frame_ended();
        self.chrome
            .frame_clock
            .record(started, self.chrome.profile.total);
        if let Some(log) = &mut self.chrome.frame_log {
            log.record(
                started_at,
                &self.chrome.profile,
                self.session.revision.number,
                self.preview.live.compiles,
            );
        }
    }

    fn clear_color(&self, visuals: &egui::Visuals) -> [f32; 4] {
        canvas::painting::clear_color(visuals)
    }

    fn on_exit(&mut self) {
        if !self.session.document.is_dirty() {
            self.session.autosave.forget();
        }
    }
}
