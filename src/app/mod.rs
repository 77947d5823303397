//! The node editor: an egui-snarl graph on the left, the live material on a mesh and
//! the inspector on the right, a status bar below. Behind the default `gui` feature.

mod actions;
mod add_node;
mod allocator;
mod catalogue;
mod clipboard;
mod dialog_contents;
mod dialog_frame;
mod dialogs;
mod document;
mod drawing_thread;
mod fields;
mod file_browser;
mod frame_clock;
mod graph_view;
mod group_edit;
mod group_inspector;
mod group_interface_editor;
mod history;
mod inspector;
mod levels;
mod live;
mod menus;
mod navigation;
mod node_text;
mod painting;
mod parameters_panel;
mod preview;
mod preview_panel;
mod preview_worker;
mod probe;
mod ramp_bar;
mod recovery;
mod scope;
mod sync;
mod thumbnail_keys;
mod thumbnail_worker;
mod thumbnails;
mod widgets;
mod wire_pointer;
mod wires;

pub use crate::graph::{PRESETS, preset};
pub use document::Document;
pub use frame_clock::{FRAME_LOG_HEADER, FrameLog};
pub use live::{LiveMaterial, UNIFORM_SLOTS};
pub use probe::{AtlasGraph, atlas_graph};
pub use sync::FrameProfile;
pub use thumbnails::{TILE_PIXELS, Thumbnails, placement, tile_params};

use crate::graph::{AlphaMode, Graph, Node, Shading};
use dialogs::{Dialog, Pending};
use egui::{Key, KeyboardShortcut, Modifiers, Ui};
use egui_snarl::Snarl;
use egui_snarl::ui::SnarlWidget;
use graph_view::{Viewer, snarl_from_graph};
use navigation::{Framing, Navigation};
use preview::{MaterialFrame, PreviewState, Previews};
use preview_worker::{Slot, TessellationInput};
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
            app.frame_log = frame_log.take();
            Ok(Box::new(app))
        }),
    )
    .map_err(|error| format!("cannot open the editor window: {error}"))
}

/// The editor's state.
pub struct VeneerApp {
    pub document: Document,
    snarl: Snarl<Node>,
    pub live: LiveMaterial,
    /// The selected node's output, compiled for its thumbnail.
    pub thumbnail: LiveMaterial,
    /// Thumbnails on the nodes and on hovered wires.
    pub thumbnails: thumbnails::Thumbnails,
    /// Where pins and nodes were drawn in the last frame.
    spots: wires::SharedSpots,
    /// The output carried by the wire under the pointer.
    hovered_wire: Option<crate::graph::PinRef>,
    /// The node the primary button went down on, and where it was then.
    node_drag: Option<(egui_snarl::NodeId, egui::Pos2)>,
    preview: PreviewState,
    /// The pictures of the preview and of the selected node, drawn on another thread.
    previews: Previews,
    /// Nodes selected in the graph (snarl ids).
    selection: Vec<egui_snarl::NodeId>,
    /// The node groups entered: the graph view shows the innermost one's definition.
    scope: scope::Scope,
    /// Bumped whenever the graph view starts afresh (entering or leaving a group,
    /// grouping): the view's id, so that its selection is not carried over.
    view_generation: u64,
    /// The node picked by a plain click.
    clicked: Option<egui_snarl::NodeId>,
    /// The graph view's transform and the gestures moving it.
    navigation: Navigation,
    /// A message for the status bar (saved, exported, refused wire…).
    pub message: Option<String>,
    dialog: Option<Dialog>,
    /// The add-node search (Space, Tab, Shift+A) and where the graph is on screen.
    add: add_node::AddNode,
    recent: Vec<PathBuf>,
    /// This window's autosave of unsaved work.
    autosave: recovery::Autosave,
    /// The file browser a path dialog opened.
    browser: file_browser::Browser,
    /// The material handed to each preview slot (main, node), kept between frames.
    frames: [FrameCache; 2],
    /// The selected node's output as a graph of its own, for the graph revision and
    /// node it was made for.
    probe: Option<((u64, crate::graph::NodeId), Option<Graph>)>,
    /// The preview mesh's distance fields: solving, picking sources, viewing.
    fields: fields::FieldState,
    /// The field view's material (a colour scale with isolines of one field).
    field_view: LiveMaterial,
    field_view_frame: FrameCache,
    /// The graph checked at a revision, for refining a displaced preview mesh.
    tessellation_graph: Option<(u64, Arc<crate::graph::CheckedGraph>)>,
    render_state: Option<eframe::egui_wgpu::RenderState>,
    allowed_to_close: bool,
    /// Beside which windows autosave unsaved work (and the recent files are kept).
    recovery_file: PathBuf,
    /// The window title last sent.
    title: String,
    /// How many times the graph has changed, and what followed which change.
    revision: sync::Revision,
    /// Where the main thread's time went in the last frame.
    pub profile: FrameProfile,
    /// Frames a second and main-thread time over the last second.
    frame_clock: frame_clock::FrameClock,
    /// Where each frame is written down, when asked (`veneer edit --frame-log`).
    frame_log: Option<FrameLog>,
    /// Whether the status bar shows the frame rate (View → Frame rate).
    show_frame_rate: bool,
    /// Whether the document had unsaved changes when input last arrived.
    dirty: bool,
}

impl VeneerApp {
    /// The editor on `path` (or the wood preset), autosaving to the default recovery file.
    pub fn new(cc: &eframe::CreationContext<'_>, path: Option<PathBuf>) -> VeneerApp {
        recovery::watch_termination(&cc.egui_ctx);
        VeneerApp::with_recovery_file(cc, path, recovery::default_path())
    }

    /// The editor on `path` (or the wood preset), autosaving beside `recovery_file` to a
    /// file of its own, with the preview's GPU resources installed. Offers the work that
    /// windows which did not exit cleanly left there.
    pub fn with_recovery_file(
        cc: &eframe::CreationContext<'_>,
        path: Option<PathBuf>,
        recovery_file: PathBuf,
    ) -> VeneerApp {
        let render_state = cc.wgpu_render_state.clone();
        let wood = preset("wood").expect("the wood preset is embedded");
        let mut app = VeneerApp {
            preview: PreviewState::for_graph(&wood.preview),
            snarl: snarl_from_graph(&wood),
            document: Document::new(wood, None),
            previews: Previews::new(&cc.egui_ctx, render_state.is_some()),
            live: LiveMaterial::in_storage(),
            thumbnail: LiveMaterial::in_storage(),
            thumbnails: Default::default(),
            spots: Default::default(),
            hovered_wire: None,
            node_drag: None,
            selection: Vec::new(),
            scope: Default::default(),
            view_generation: 0,
            clicked: None,
            navigation: Default::default(),
            message: None,
            dialog: None,
            add: Default::default(),
            recent: recovery::load_recent(&recovery_file),
            autosave: recovery::Autosave::new(recovery::window_file(&recovery_file)),
            browser: Default::default(),
            frames: Default::default(),
            probe: None,
            fields: Default::default(),
            field_view: LiveMaterial::in_storage(),
            field_view_frame: FrameCache::default(),
            tessellation_graph: None,
            render_state,
            allowed_to_close: false,
            recovery_file,
            title: String::new(),
            revision: Default::default(),
            profile: Default::default(),
            frame_clock: Default::default(),
            frame_log: None,
            show_frame_rate: false,
            dirty: false,
        };
        app.navigation.frame(Framing::Open);
        if let Some(path) = path {
            app.open(path);
        }
        let orphans = recovery::orphans(&app.recovery_file);
        if !orphans.is_empty() {
            app.dialog = Some(Dialog::Recover(orphans));
        }
        app.live.update(&app.document.graph);
        app
    }

    /// Shows a mesh file (OBJ, STL, PLY, glTF) in the preview; a bad file is refused with a message.
    pub fn load_mesh(&mut self, path: &str) -> Result<(), String> {
        let mesh = crate::mesh::preview_mesh(path).map_err(|error| error.to_string())?;
        self.preview.mesh = path.to_string();
        self.preview.file = Some(Arc::new(mesh));
        Ok(())
    }

    /// Lights metallic-roughness previews with the panorama at `path`; returns its name.
    pub fn load_environment(&mut self, path: &str) -> Result<String, String> {
        let environment = crate::render::Environment::named(path).map_err(|e| e.to_string())?;
        let name = environment.name.clone();
        self.preview.environment = preview_worker::EnvironmentChoice(
            (name != crate::render::SKY).then(|| Arc::new(environment)),
        );
        Ok(name)
    }

    /// Replaces the document (after open, new, preset or recovery).
    fn load(&mut self, document: Document) {
        self.preview.follow(&document.graph.preview);
        let mesh = document.graph.preview.mesh.clone();
        if crate::mesh::primitive(&mesh).is_some() || self.load_mesh(&mesh).is_err() {
            self.preview.mesh = mesh;
            self.preview.file = None;
        }
        self.scope = Default::default();
        self.snarl = snarl_from_graph(&document.graph);
        self.document = document;
        self.selection.clear();
        self.clicked = None;
        self.navigation = Navigation::default();
        self.navigation.frame(Framing::Open);
        self.live.update(&self.document.graph);
    }

    /// Opens a graph file; a bad file is refused with a message and loses nothing.
    pub fn open(&mut self, path: PathBuf) {
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
                self.message = (stacked > 0).then(|| {
                    format!(
                        "{} nodes lay on top of others and were laid out; save to keep it",
                        crate::messages::thousands(stacked)
                    )
                });
            }
            Err(error) => self.dialog = Some(Dialog::Message(error.to_string())),
        }
    }

    /// Puts `path` first in the recent files, kept across sessions.
    pub(crate) fn remember(&mut self, path: &std::path::Path) {
        self.recent.retain(|p| p != path);
        self.recent.insert(0, path.to_path_buf());
        self.recent.truncate(8);
        if let Err(error) = recovery::save_recent(&self.recovery_file, &self.recent) {
            self.message = Some(format!("cannot remember recent files: {error}"));
        }
    }

    /// Runs `action` now, or after asking what to do with unsaved changes.
    fn guard(&mut self, action: Pending) {
        if self.document.is_dirty() {
            self.dialog = Some(Dialog::Discard(action));
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
                self.allowed_to_close = true;
                self.autosave.forget();
            }
        }
    }

    /// Saves to the document's file, or asks for one.
    pub fn save(&mut self) {
        match self.document.save() {
            Ok(path) => {
                self.remember(&path);
                self.message = Some(format!("saved {}", path.display()));
                self.autosave.forget();
            }
            Err(_) if self.document.path.is_none() => {
                self.dialog = Some(Dialog::save_as(&self.document))
            }
            Err(error) => self.dialog = Some(Dialog::Message(error)),
        }
    }

    /// Undoes the last edit (inside a group too; a group undone away is left).
    pub fn undo(&mut self) {
        if let Some(graph) = self.document.history.undo() {
            self.clicked = None;
            self.document.graph = graph;
            self.rebuild_snarl();
        }
    }

    /// Redoes the last undone edit.
    pub fn redo(&mut self) {
        if let Some(graph) = self.document.history.redo() {
            self.clicked = None;
            self.document.graph = graph;
            self.rebuild_snarl();
        }
    }

    /// The groups entered, outermost first (empty at the top level).
    pub fn group_path(&self) -> Vec<String> {
        self.scope
            .levels
            .iter()
            .map(|level| level.group.clone())
            .collect()
    }

    /// Whether the preview shows a mesh whose distance fields are solved and up to date.
    pub fn fields_solved(&self) -> bool {
        self.preview.prepared.is_some() && self.fields.progress().is_none()
    }

    /// The graph view's transform from graph to screen coordinates (node widgets are laid
    /// out in graph coordinates).
    pub fn graph_to_screen(&self) -> egui::emath::TSTransform {
        self.navigation.transform
    }

    /// The labels of the selected nodes, in selection order.
    pub fn selected_labels(&self) -> Vec<String> {
        self.selection
            .iter()
            .filter_map(|node| self.snarl.get_node(*node))
            .map(|node| node.label.clone())
            .collect()
    }

    /// Where the pin `pin` (an output when `output`) was drawn last frame, on screen.
    pub fn pin_on_screen(&self, pin: &crate::graph::PinRef, output: bool) -> Option<egui::Pos2> {
        let (id, node) = self
            .snarl
            .node_ids()
            .find(|(_, node)| node.id == pin.node)?;
        let signature = node.kind.signature();
        let spots = self.spots.borrow();
        let at = if output {
            let output = signature.output(&pin.pin)?.0;
            spots.output(egui_snarl::OutPinId { node: id, output })?
        } else {
            let input = signature.input(&pin.pin)?.0;
            spots.input(egui_snarl::InPinId { node: id, input })?
        };
        Some(self.navigation.transform * at)
    }

    /// Number of materials the preview has built pipelines for (0 without a GPU).
    pub fn pipelines_built(&self) -> u64 {
        self.previews.materials_built()
    }

    /// How many times the graph has changed since the editor started, and how many
    /// frames read the graph view back to find out (frames without input never do).
    pub fn revision(&self) -> (u64, u64) {
        (self.revision.number, self.revision.reads)
    }

    /// How finely the preview's image on screen was drawn: a draft while something is
    /// dragged, full at rest (`None` before the first image).
    pub fn preview_quality(&self) -> Option<crate::render::Quality> {
        self.previews.quality()
    }

    /// Why the preview could not draw its newest material, if it could not.
    pub fn preview_error(&self) -> Option<&str> {
        self.previews.error()
    }

    /// The time the preview shows, and whether it plays.
    pub fn preview_time(&self) -> (f32, bool) {
        (self.preview.view.time, self.preview.playing)
    }

    /// Whether the previews show, at full quality, what was last asked of them (they
    /// are drawn on another thread: tests wait for this before looking).
    pub fn preview_settled(&self) -> bool {
        self.previews.settled()
    }

    fn graph_panel(&mut self, ui: &mut Ui) {
        let mut hint = None;
        let mut dropped = None;
        self.add.set_graph_rect(ui.max_rect());
        // Node titles and pin names are not text to select: a click on a title selects
        // the node, and Ctrl+C copies the node, not the title.
        ui.style_mut().interaction.selectable_labels = false;
        let modifiers =
            self.navigation
                .before(ui.ctx(), ui.max_rect(), &self.snarl, &self.selection);
        let before = self.clicked.take();
        // Inside a group, messages, frames and thumbnails of the top level do not apply:
        // its nodes' ids are the definition's own.
        let in_group = self.scope.current().is_some();
        let (no_errors, no_warnings) = (Default::default(), Default::default());
        let (mut declared, mut expose, mut group_action) = (Vec::new(), None, None);
        let mut viewer = Viewer {
            errors: if in_group {
                &no_errors
            } else {
                &self.live.errors
            },
            warnings: if in_group {
                &no_warnings
            } else {
                &self.live.warnings
            },
            hint: &mut hint,
            dropped: &mut dropped,
            clicked: &mut self.clicked,
            selected: before,
            navigation: &mut self.navigation,
            frames: if in_group {
                &[]
            } else {
                &self.document.graph.frames
            },
            thumbnails: &mut self.thumbnails,
            spots: self.spots.clone(),
            in_group,
            groups: &self.document.graph.groups,
            declared: &mut declared,
            expose: &mut expose,
            group_action: &mut group_action,
        };
        *self.spots.borrow_mut() = Default::default();
        // In big graphs nodes off screen are not laid out at all (our egui-snarl patch).
        let big = self.snarl.node_ids().count() > navigation::BIG_GRAPH;
        let widget = SnarlWidget::new()
            .id_salt(("graph", self.view_generation))
            .style(painting::graph_style(ui.style()))
            .cull_offscreen(big);
        let response = widget.show(&mut self.snarl, &mut viewer, ui);
        self.wire_pointer(ui);
        self.navigation.after(ui.ctx(), modifiers);
        if self.dialog.is_some() {
            // A click on a dialog is not for the node under it.
            self.clicked = before;
        }
        if self.clicked.is_none() && !response.clicked() {
            self.clicked = before.filter(|node| self.snarl.get_node(*node).is_some());
        }
        self.selection = widget.get_selected_nodes(ui);
        if self.navigation.clicked_empty_canvas() && self.dialog.is_none() {
            // A click on empty canvas selects nothing (egui-snarl's own selection goes
            // with a fresh view).
            self.clicked = None;
            if !self.selection.is_empty() {
                self.view_generation += 1;
                self.selection.clear();
            }
        }
        if self.selection.is_empty() {
            self.selection.extend(self.clicked);
        }
        if hint.is_some() {
            self.message = hint;
        }
        declared.extend(expose.and_then(|pin| self.expose_input(pin)));
        self.declare(declared);
        if let Some(action) = group_action {
            self.group_action(action);
        }
        self.breadcrumb(ui.ctx(), ui.max_rect());
        // A right click on empty canvas, or a wire dropped there, opens the add-node search.
        if dropped.is_some() || response.secondary_clicked() {
            self.open_add_node(ui.ctx(), dropped, None);
        }
        self.add_node_popup(ui.ctx());
    }

    /// The inspector of the selected node, or a hint and the comment frames.
    fn inspector(&mut self, ui: &mut Ui) {
        match self.selection.first().copied() {
            Some(node) if self.snarl.get_node(node).is_some() => {
                ui.separator();
                self.inspect(ui, node);
            }
            _ => {
                ui.weak(
                    "Select a node to edit it. Right-click the graph (or press Space) to add one.",
                );
                frames_editor(ui, &mut self.document.graph.frames);
            }
        }
    }

    /// The inspector of node `node` of the graph view.
    fn inspect(&mut self, ui: &mut Ui, node: egui_snarl::NodeId) {
        let shown = &self.snarl[node];
        if let Some(side) = scope::boundary(shown) {
            let group = self
                .scope
                .current()
                .and_then(|name| self.document.graph.groups.get(name));
            let edit =
                group.and_then(|definition| group_interface_editor::show(ui, side, definition));
            if let Some(edit) = edit {
                self.edit_interface(edit);
            }
            return;
        }
        if let Some(name) = crate::graph::group::group_name(shown) {
            let definition = self.document.graph.groups.get(name);
            if let Some(action) = group_inspector::show(ui, node, name, definition) {
                self.group_action(action);
                return;
            }
            ui.separator();
        }
        // Inside a group the nodes' ids are the definition's: the top level's
        // thumbnails and messages are not theirs.
        if self.scope.current().is_some() {
            inspector::show(ui, &mut self.snarl, node, None, None);
            return;
        }
        self.node_thumbnail(ui, node);
        let id = self.snarl[node].id;
        let (error, warning) = (self.live.errors.get(&Some(id)), self.live.warnings.get(&id));
        inspector::show(ui, &mut self.snarl, node, error, warning);
    }

    fn handle_close(&mut self, ctx: &egui::Context) {
        if ctx.input(|input| input.viewport().close_requested()) && !self.allowed_to_close {
            if self.document.is_dirty() {
                ctx.send_viewport_cmd(egui::ViewportCommand::CancelClose);
                self.dialog = Some(Dialog::Discard(Pending::Quit));
            } else {
                self.autosave.forget();
            }
        }
        if self.allowed_to_close {
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
        }
    }
}

/// Set in the generations of field-view materials, so that the preview never mistakes
/// one for the graph's material of the same generation.
const FIELD_VIEW_GENERATIONS: u64 = 1 << 48;

/// What a preview's material is made of, kept between frames: the code (shared until
/// it changes) and the parameter values (worked out again only when the graph changes).
#[derive(Default)]
struct FrameCache {
    code: Option<(u64, Arc<str>)>,
    /// The values, for the code generation and graph revision they were worked out for.
    params: Option<(ParamsKey, Arc<[[f32; 4]]>)>,
}

/// A code generation and a graph revision.
type ParamsKey = (u64, u64);

/// What a preview should draw this frame: `live`'s code and its parameter values for
/// `graph` at `revision` (taken from `cache` while neither changed).
fn material_frame(
    live: &LiveMaterial,
    cache: &mut FrameCache,
    graph: &Graph,
    revision: u64,
) -> Option<MaterialFrame> {
    let module = &live.compiled.as_ref()?.module;
    if cache
        .code
        .as_ref()
        .is_none_or(|(generation, _)| *generation != live.generation)
    {
        cache.code = Some((live.generation, Arc::from(module.source.as_str())));
    }
    let key = (live.generation, revision);
    if cache.params.as_ref().is_none_or(|(seen, _)| *seen != key) {
        cache.params = Some((key, live.params(graph).into()));
    }
    let wgsl = cache.code.as_ref().map(|(_, code)| code.clone())?;
    let params = cache.params.as_ref().map(|(_, params)| params.clone())?;
    Some(MaterialFrame {
        code: crate::render::LiveMaterialCode {
            generation: live.generation,
            wgsl,
            slots: module.params.len(),
            uses: module.uses,
        },
        params,
        tessellation: None,
    })
}

/// Titles, colours and removal of the graph's comment frames.
fn frames_editor(ui: &mut Ui, frames: &mut Vec<crate::graph::Frame>) {
    if frames.is_empty() {
        return;
    }
    ui.separator();
    ui.label("Frames");
    let mut remove = None;
    for (index, frame) in frames.iter_mut().enumerate() {
        ui.horizontal(|ui| {
            ui.text_edit_singleline(&mut frame.title);
            let mut rgb = [frame.color.0, frame.color.1, frame.color.2];
            if ui.color_edit_button_rgb(&mut rgb).changed() {
                frame.color = (rgb[0], rgb[1], rgb[2]);
            }
            if ui.small_button("×").on_hover_text("remove frame").clicked() {
                remove = Some(index);
            }
        });
    }
    if let Some(index) = remove {
        frames.remove(index);
    }
}

impl eframe::App for VeneerApp {
    fn ui(&mut self, ui: &mut Ui, _frame: &mut eframe::Frame) {
        let started = std::time::Instant::now();
        let started_at = std::time::SystemTime::now();
        let cpu_before = frame_clock::thread_cpu_time();
        let ctx = ui.ctx().clone();
        self.previews.receive(&ctx);
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
            .frame(painting::central_panel_frame(ui.style()))
            .show(ui, |ui| {
                let canvas = ui.max_rect();
                self.graph_panel(ui);
                canvas
            });
        painting::paint_panel_margin(ui, central.response.rect, central.inner);
        if let Some(dialog) = self.dialog.take() {
            // A dialog's action may open another dialog (an open that fails shows a
            // message): that one wins over the dialog staying open.
            let (still_open, action) = dialog.show(&ctx, &self.document, &mut self.browser);
            if let Some(action) = action {
                self.apply(action);
            }
            self.dialog = self.dialog.take().or(still_open);
        }
        // After the dialogs too, so that what their buttons did (save, open) shows now.
        self.after_edits(&ctx);
        self.handle_close(&ctx);
        self.profile.total = started.elapsed();
        self.profile.cpu = frame_clock::thread_cpu_time().saturating_sub(cpu_before);
        self.frame_clock.record(started, self.profile.total);
        if let Some(log) = &mut self.frame_log {
            log.record(
                started_at,
                self.profile.total,
                self.revision.number,
                self.live.compiles,
            );
        }
    }

    fn clear_color(&self, visuals: &egui::Visuals) -> [f32; 4] {
        painting::clear_color(visuals)
    }

    fn on_exit(&mut self) {
        if !self.document.is_dirty() {
            self.autosave.forget();
        }
    }
}
