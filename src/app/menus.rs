//! The editor's menu bar, status bar, keyboard shortcuts and clipboard.

use super::*;

impl VeneerApp {
    pub(super) fn shortcuts(&mut self, ctx: &egui::Context) {
        let typing = ctx.memory(|memory| memory.focused().is_some());
        let pressed = |modifiers, key| {
            ctx.input_mut(|input| input.consume_shortcut(&KeyboardShortcut::new(modifiers, key)))
        };
        let command = Modifiers::COMMAND;
        if pressed(command | Modifiers::SHIFT, Key::Z) {
            self.redo();
        } else if pressed(command, Key::Z) {
            self.undo();
        }
        if pressed(command, Key::S) {
            self.save();
        }
        if pressed(command, Key::O) {
            self.dialog = Some(Dialog::Open {
                path: String::new(),
            });
        }
        if pressed(command, Key::N) {
            self.guard(Pending::New);
        }
        if pressed(command, Key::D) {
            self.duplicate_at_mouse(ctx);
        }
        if pressed(command, Key::G) {
            self.frame_selection();
        }
        if typing {
            return;
        }
        if pressed(Modifiers::NONE, Key::Delete) || pressed(Modifiers::NONE, Key::Backspace) {
            for node in self.selection.drain(..) {
                if self.snarl.get_node(node).is_some() {
                    self.snarl.remove_node(node);
                }
            }
        }
        if pressed(Modifiers::NONE, Key::F) {
            self.frame = Some(Framing::All);
        }
        if pressed(Modifiers::NONE, Key::Space) {
            self.open_add_node(ctx, None, Some(" "));
        } else if pressed(Modifiers::NONE, Key::Tab) {
            self.open_add_node(ctx, None, Some("\t"));
        } else if pressed(Modifiers::SHIFT, Key::A) {
            self.open_add_node(ctx, None, Some("A"));
        }
    }

    /// Copy and paste travel as events (the platform clipboard holds RON text).
    pub(super) fn clipboard(&mut self, ctx: &egui::Context) {
        let events = ctx.input(|input| input.events.clone());
        for event in events {
            match event {
                egui::Event::Copy if !self.selection.is_empty() => {
                    ctx.copy_text(clipboard::copy(&self.snarl, &self.selection));
                }
                egui::Event::Paste(text) if ctx.memory(|m| m.focused().is_none()) => {
                    self.paste_at_mouse(ctx, &text);
                }
                _ => {}
            }
        }
    }

    pub(super) fn menu_bar(&mut self, ui: &mut Ui) {
        egui::MenuBar::new().ui(ui, |ui| {
            ui.menu_button("File", |ui| {
                if ui.button("New").clicked() {
                    self.guard(Pending::New);
                }
                if ui.button("Open…").clicked() {
                    self.dialog = Some(Dialog::Open {
                        path: String::new(),
                    });
                }
                ui.menu_button("Open preset", |ui| {
                    for (name, _) in PRESETS {
                        if ui.button(name).clicked() {
                            self.guard(Pending::Preset(name));
                        }
                    }
                });
                ui.menu_button("Open recent", |ui| {
                    for path in self.recent.clone() {
                        if ui.button(path.display().to_string()).clicked() {
                            self.guard(Pending::Open(path));
                        }
                    }
                });
                if ui.button("Save").clicked() {
                    self.save();
                }
                if ui.button("Save as…").clicked() {
                    self.dialog = Some(Dialog::save_as(&self.document));
                }
                ui.separator();
                if ui.button("Export shader…").clicked() {
                    self.dialog = Some(Dialog::export_shader(&self.document));
                }
                if ui.button("Export PNG…").clicked() {
                    self.dialog = Some(Dialog::export_png(&self.document));
                }
            });
            ui.menu_button("Edit", |ui| {
                if ui
                    .add_enabled(self.document.history.can_undo(), egui::Button::new("Undo"))
                    .clicked()
                {
                    self.undo();
                }
                if ui
                    .add_enabled(self.document.history.can_redo(), egui::Button::new("Redo"))
                    .clicked()
                {
                    self.redo();
                }
                if ui.button("Add node…").clicked() {
                    self.open_add_node(ui.ctx(), None, None);
                }
                if ui.button("Duplicate").clicked() {
                    self.duplicate_at_mouse(ui.ctx());
                }
                if ui.button("Frame all").clicked() {
                    self.frame = Some(Framing::All);
                }
                if ui
                    .add_enabled(
                        !self.selection.is_empty(),
                        egui::Button::new("Frame selected nodes"),
                    )
                    .clicked()
                {
                    self.frame_selection();
                }
                if ui.button("Arrange nodes").clicked() {
                    let mut graph = graph_from_snarl(&self.snarl, &self.document.graph);
                    crate::graph::layout::arrange(&mut graph);
                    self.snarl = snarl_from_graph(&graph);
                    self.frame = Some(Framing::All);
                }
            });
        });
    }

    pub(super) fn status_bar(&mut self, ui: &mut Ui) {
        ui.horizontal(|ui| {
            match self.live.status(&self.document.graph) {
                Some(error) => {
                    ui.colored_label(egui::Color32::from_rgb(240, 80, 60), format!("⚠ {error}"));
                }
                None if self.live.warnings.is_empty() => {
                    ui.label("✔ material compiles");
                }
                None => {
                    let count = self
                        .live
                        .warnings
                        .values()
                        .map(|w| w.lines().count())
                        .sum::<usize>();
                    ui.label("✔ material compiles");
                    ui.colored_label(
                        egui::Color32::from_rgb(230, 180, 60),
                        format!("⚠ {count} numerical warnings (see the marked nodes)"),
                    );
                }
            }
            if let Some(message) = &self.message {
                ui.separator();
                ui.label(message);
            }
            ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                ui.weak(format!(
                    "{} · {}",
                    counted(self.document.graph.nodes.len(), "node"),
                    counted(self.live.compiles as usize, "compile")
                ));
            });
        });
    }
}

/// "1 node", "2 nodes".
fn counted(count: usize, noun: &str) -> String {
    if count == 1 {
        format!("1 {noun}")
    } else {
        format!("{count} {noun}s")
    }
}
