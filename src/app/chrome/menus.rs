//! The editor's menu bar, status bar, keyboard shortcuts and clipboard.

use crate::app::canvas::clipboard;
use crate::app::*;
use crate::messages::counted;

const fn command(key: Key) -> KeyboardShortcut {
    KeyboardShortcut::new(Modifiers::COMMAND, key)
}
const fn command_shift(key: Key) -> KeyboardShortcut {
    KeyboardShortcut::new(Modifiers::COMMAND.plus(Modifiers::SHIFT), key)
}

const NEW: KeyboardShortcut = command(Key::N);
const OPEN: KeyboardShortcut = command(Key::O);
const SAVE: KeyboardShortcut = command(Key::S);
const SAVE_AS: KeyboardShortcut = command_shift(Key::S);
const EXPORT_SHADER: KeyboardShortcut = command(Key::E);
const EXPORT_PNG: KeyboardShortcut = command_shift(Key::E);
const UNDO: KeyboardShortcut = command(Key::Z);
const REDO: KeyboardShortcut = command_shift(Key::Z);
const DUPLICATE: KeyboardShortcut = command(Key::D);
const FRAME_SELECTION: KeyboardShortcut = command(Key::J);
const GROUP: KeyboardShortcut = command(Key::G);
const UNGROUP: KeyboardShortcut = KeyboardShortcut::new(Modifiers::ALT, Key::G);
/// Node thumbnails on or off (plain T, outside text fields).
const THUMBNAILS: Key = Key::T;

/// Seconds a status message stays (fading over the last one).
pub const MESSAGE_SECONDS: f64 = 6.0;

/// A menu entry with its shortcut on the right.
fn entry(ui: &mut Ui, label: &str, shortcut: &str, enabled: bool) -> bool {
    let response = ui.add_enabled(enabled, egui::Button::new(label).shortcut_text(shortcut));
    // Screen readers (and tests) know the entry by its name, and its shortcut as such.
    response.widget_info(|| egui::WidgetInfo::labeled(egui::WidgetType::Button, enabled, label));
    ui.ctx().accesskit_node_builder(response.id, |node| {
        node.set_keyboard_shortcut(shortcut);
    });
    let clicked = response.clicked();
    if clicked {
        // Close the menu, whatever clicked the entry: a dialog it opens has the keyboard.
        ui.close();
    }
    clicked
}

/// A menu entry for a keyboard shortcut, with the shortcut on the right.
fn shortcut_entry(ui: &mut Ui, label: &str, shortcut: &KeyboardShortcut, enabled: bool) -> bool {
    let text = ui.ctx().format_shortcut(shortcut);
    entry(ui, label, &text, enabled)
}

impl VeneerApp {
    pub(in crate::app) fn shortcuts(&mut self, ctx: &egui::Context) {
        if self.chrome.dialog.is_some() {
            // A dialog has the keyboard (Enter, Escape, typing): nothing reaches the graph.
            return;
        }
        let typing = ctx.memory(|memory| memory.focused().is_some());
        let pressed =
            |shortcut: KeyboardShortcut| ctx.input_mut(|input| input.consume_shortcut(&shortcut));
        // Shift variants first: Ctrl+S also matches Ctrl+Shift+S. The file's commands
        // work while a field has the keyboard.
        if pressed(SAVE_AS) {
            self.chrome.dialog = Some(Dialog::save_as(&self.session.document, None));
        } else if pressed(SAVE) {
            self.save(None);
        }
        if pressed(EXPORT_PNG) {
            self.chrome.dialog = Some(Dialog::export_png(&self.session.document));
        } else if pressed(EXPORT_SHADER) {
            self.chrome.dialog = Some(Dialog::export_shader(&self.session.document));
        }
        if pressed(OPEN) {
            self.chrome.dialog = Some(Dialog::open());
        }
        if pressed(NEW) {
            self.guard(Pending::New);
        }
        // The graph's commands not while typing: Ctrl+Z undoes the text, Ctrl+D, Ctrl+J
        // and Ctrl+G are no field's to take.
        if typing {
            return;
        }
        if pressed(REDO) {
            self.redo();
        } else if pressed(UNDO) {
            self.undo();
        }
        if pressed(DUPLICATE) {
            self.duplicate_at_mouse(ctx);
        }
        if pressed(FRAME_SELECTION) {
            self.frame_selection();
        }
        if pressed(GROUP) {
            self.group_selection();
        }
        if pressed(UNGROUP) {
            self.ungroup_selection();
        }
        let pressed = |modifiers, key| pressed(KeyboardShortcut::new(modifiers, key));
        // (Not while typing: a field or the add-node search has the keys then.)
        let delete = [Key::Delete, Key::Backspace, Key::X];
        if delete.into_iter().any(|key| pressed(Modifiers::NONE, key)) {
            for node in self.editable_selection() {
                self.canvas.snarl.remove_node(node);
            }
            self.canvas.selection.clear();
        }
        if pressed(Modifiers::NONE, Key::F) || pressed(Modifiers::NONE, Key::Home) {
            self.canvas.navigation.frame(Framing::All);
        }
        if pressed(Modifiers::NONE, Key::Period) && !self.canvas.selection.is_empty() {
            self.canvas.navigation.frame(Framing::Selection);
        }
        if pressed(Modifiers::NONE, THUMBNAILS) {
            self.thumbnails.enabled = !self.thumbnails.enabled;
        }
        if pressed(Modifiers::NONE, Key::Space) {
            self.open_add_node(ctx, None, Some(" "));
        } else if pressed(Modifiers::NONE, Key::Tab) {
            // Tab enters the selected group node or leaves the group shown; else it
            // opens the search.
            if self.tab() {
                // The key is ours: egui does not move the keyboard focus with it.
                ctx.memory_mut(|memory| memory.move_focus(egui::FocusDirection::None));
            } else {
                self.open_add_node(ctx, None, Some("\t"));
            }
        } else if pressed(Modifiers::SHIFT, Key::A) {
            self.open_add_node(ctx, None, Some("A"));
        }
    }

    /// Copy and paste travel as events (the platform clipboard holds RON text).
    pub(in crate::app) fn clipboard(&mut self, ctx: &egui::Context) {
        if self.chrome.dialog.is_some() {
            return;
        }
        let events = ctx.input(|input| input.events.clone());
        for event in events {
            match event {
                egui::Event::Copy if !self.editable_selection().is_empty() => {
                    ctx.copy_text(clipboard::copy(
                        &self.canvas.snarl,
                        &self.editable_selection(),
                    ));
                }
                egui::Event::Paste(text) if ctx.memory(|m| m.focused().is_none()) => {
                    self.paste_at_mouse(ctx, &text);
                }
                _ => {}
            }
        }
    }

    pub(in crate::app) fn menu_bar(&mut self, ui: &mut Ui) {
        egui::MenuBar::new().ui(ui, |ui| {
            ui.menu_button("File", |ui| {
                if shortcut_entry(ui, "New", &NEW, true) {
                    self.guard(Pending::New);
                }
                if shortcut_entry(ui, "Open…", &OPEN, true) {
                    self.chrome.dialog = Some(Dialog::open());
                }
                ui.menu_button("Open preset", |ui| {
                    for (name, _) in PRESETS {
                        if ui.button(name).clicked() {
                            self.guard(Pending::Preset(name));
                        }
                    }
                });
                ui.menu_button("Open recent", |ui| {
                    for path in self.session.recent.clone() {
                        if ui.button(path.display().to_string()).clicked() {
                            self.guard(Pending::Open(path));
                        }
                    }
                });
                if shortcut_entry(ui, "Save", &SAVE, true) {
                    self.save(None);
                }
                if shortcut_entry(ui, "Save as…", &SAVE_AS, true) {
                    self.chrome.dialog = Some(Dialog::save_as(&self.session.document, None));
                }
                ui.separator();
                if shortcut_entry(ui, "Export shader…", &EXPORT_SHADER, true) {
                    self.chrome.dialog = Some(Dialog::export_shader(&self.session.document));
                }
                if shortcut_entry(ui, "Export PNG…", &EXPORT_PNG, true) {
                    self.chrome.dialog = Some(Dialog::export_png(&self.session.document));
                }
                if entry(ui, "Export glTF…", "", true) {
                    let glb = crate::bake::ModelFormat::Gltf;
                    self.chrome.dialog = Some(Dialog::export_model(&self.session.document, glb));
                }
                if entry(ui, "Export USD…", "", true) {
                    let usd = crate::bake::ModelFormat::Usd;
                    self.chrome.dialog = Some(Dialog::export_model(&self.session.document, usd));
                }
                if entry(ui, "Export MaterialX…", "", true) {
                    self.chrome.dialog = Some(Dialog::export_materialx(&self.session.document));
                }
                if entry(ui, "Export maps…", "", true) {
                    self.chrome.dialog = Some(Dialog::export_maps(&self.session.document));
                }
            });
            ui.menu_button("Edit", |ui| {
                if shortcut_entry(ui, "Undo", &UNDO, self.session.document.history.can_undo()) {
                    self.undo();
                }
                if shortcut_entry(ui, "Redo", &REDO, self.session.document.history.can_redo()) {
                    self.redo();
                }
                if entry(ui, "Add node…", "Space", true) {
                    self.open_add_node(ui.ctx(), None, None);
                }
                if shortcut_entry(ui, "Duplicate", &DUPLICATE, true) {
                    self.duplicate_at_mouse(ui.ctx());
                }
                if entry(ui, "View all", "Home, F", true) {
                    self.canvas.navigation.frame(Framing::All);
                }
                if entry(ui, "View selected", ".", !self.canvas.selection.is_empty()) {
                    self.canvas.navigation.frame(Framing::Selection);
                }
                if shortcut_entry(
                    ui,
                    "Frame selected nodes",
                    &FRAME_SELECTION,
                    !self.canvas.selection.is_empty(),
                ) {
                    self.frame_selection();
                }
                ui.separator();
                let group_selected = self.canvas.selection.iter().any(|id| {
                    self.canvas
                        .snarl
                        .get_node(*id)
                        .is_some_and(crate::app::canvas::boundary::is_instance)
                });
                if shortcut_entry(
                    ui,
                    "Group selected nodes",
                    &GROUP,
                    !self.canvas.selection.is_empty(),
                ) {
                    self.group_selection();
                }
                if shortcut_entry(ui, "Ungroup", &UNGROUP, group_selected) {
                    self.ungroup_selection();
                }
                let inside = !self.canvas.scope.levels.is_empty();
                if entry(
                    ui,
                    "Edit group / leave group",
                    "Tab",
                    group_selected || inside,
                ) {
                    self.tab();
                }
                ui.separator();
                if ui.button("Arrange nodes").clicked() {
                    let level = self.canvas.scope.level();
                    self.edit(crate::graph::edit::GraphEdit::Arrange { level });
                    self.canvas.navigation.frame(Framing::All);
                }
            });
            ui.menu_button("View", |ui| {
                let shown = self.thumbnails.enabled;
                if entry(
                    ui,
                    &format!("{} Node thumbnails", if shown { "☑" } else { "☐" }),
                    "T",
                    true,
                ) {
                    self.thumbnails.enabled = !shown;
                }
                let rate = self.chrome.show_frame_rate;
                let label = format!("{} Frame rate", if rate { "☑" } else { "☐" });
                if entry(ui, &label, "", true) {
                    self.chrome.show_frame_rate = !rate;
                }
            });
        });
    }

    pub(in crate::app) fn status_bar(&mut self, ui: &mut Ui) {
        let mut stale = false;
        ui.horizontal(|ui| {
            let compiling = self.preview.live.is_compiling();
            match self.preview.live.status(&self.session.document.graph) {
                _ if compiling => {
                    ui.spinner();
                    ui.label("compiling the material…");
                }
                Some(error) => {
                    ui.colored_label(egui::Color32::from_rgb(240, 80, 60), format!("⚠ {error}"));
                }
                None if self.preview.live.warnings.top.is_empty() => {
                    ui.label("✔ material compiles");
                }
                None => {
                    let count = self
                        .preview
                        .live
                        .warnings
                        .top
                        .values()
                        .map(|w| w.lines().count())
                        .sum::<usize>();
                    ui.label("✔ material compiles");
                    ui.colored_label(
                        egui::Color32::from_rgb(230, 180, 60),
                        format!(
                            "⚠ {} (see the marked nodes)",
                            counted(count, "numerical warning")
                        ),
                    );
                }
            }
            if let Some(message) = &self.chrome.message {
                // A message fades out after a few seconds (a new one starts again).
                let id = egui::Id::new("status message");
                let now = ui.input(|input| input.time);
                let since = match ui.data(|data| data.get_temp::<(String, f64)>(id)) {
                    Some((shown, since)) if shown == *message => since,
                    _ => {
                        ui.data_mut(|data| data.insert_temp(id, (message.clone(), now)));
                        now
                    }
                };
                let left = MESSAGE_SECONDS - (now - since);
                if left <= 0.0 {
                    stale = true;
                } else {
                    let opacity = left.min(1.0) as f32;
                    ui.separator();
                    ui.label(
                        egui::RichText::new(message)
                            .color(ui.visuals().text_color().gamma_multiply(opacity)),
                    );
                    // Repaint to fade (no faster than twice the frame time), then to go.
                    let frame = 2.0 * f64::from(ui.input(|input| input.predicted_dt));
                    let wait = if left > 1.0 { left - 1.0 } else { 0.05 };
                    ui.ctx()
                        .request_repaint_after(std::time::Duration::from_secs_f64(
                            wait.max(frame).min(left + 0.01),
                        ));
                }
            }
            if self.canvas.grab.is_moving() {
                ui.separator();
                ui.label("moving the copies with the mouse: click to put them down, Escape to leave them beside the originals");
            }
            if let Some(job) = &self.session.export {
                ui.separator();
                let bar = egui::ProgressBar::new(job.fraction().unwrap_or(0.0))
                    .desired_width(160.0)
                    .text(format!("exporting {}", job.what));
                ui.add(bar.animate(job.fraction().is_none()));
                if ui
                    .add_enabled(!job.cancelled(), egui::Button::new("Cancel"))
                    .on_hover_text("stops the export; nothing is written")
                    .clicked()
                {
                    job.cancel();
                }
            }
            ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                // The nodes of the level shown, as the graph view has them now (the
                // document takes its edits in at the end of the frame).
                let count = self
                    .canvas
                    .snarl
                    .nodes()
                    .filter(|node| crate::app::canvas::boundary::boundary(node).is_none())
                    .count();
                let nodes = match self.canvas.scope.current() {
                    Some(name) => format!("{} in {name}", counted(count, "node")),
                    None => counted(count, "node"),
                };
                ui.weak(format!(
                    "{nodes} · {}",
                    counted(self.preview.live.compiles as usize, "compile")
                ));
                if let Some(rate) = self
                    .chrome
                    .frame_clock
                    .rate()
                    .filter(|_| self.chrome.show_frame_rate)
                {
                    let main = rate.main_thread.as_secs_f64() * 1e3;
                    ui.weak(format!(
                        "{:.0} fps · main thread {main:.1} ms ·",
                        rate.per_second
                    ))
                    .on_hover_text(
                        "over the last second of continuous redrawing: frames a second, \
                             and the time the main thread spends on each (the rest is \
                             painting the window and waiting)",
                    );
                }
            });
        });
        if stale {
            self.chrome.message = None;
        }
    }
}
