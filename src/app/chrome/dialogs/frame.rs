//! The parts every dialog is built from: what the user chose this frame, and the
//! buttons, check boxes and path fields that collect it (Enter and Escape included).

use crate::app::session::document::Document;
use egui::{Id, Ui};
use std::path::PathBuf;

/// What the user chose in a dialog this frame.
pub(in crate::app) enum Choice {
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
pub(in crate::app) struct Frame {
    /// The dialog's first frame (or the first after the browser closed): focus its field
    /// or default button.
    pub(in crate::app) first: bool,
    /// Destructive buttons respond (the dialog has been up for [`ARM_SECONDS`]).
    pub(in crate::app) armed: bool,
    /// Widgets that act on Enter themselves when focused (buttons, check boxes).
    pub(in crate::app) claims: Vec<Id>,
    pub(in crate::app) choice: Option<Choice>,
}

impl Frame {
    pub(in crate::app) fn choose(&mut self, clicked: bool, choice: Choice) {
        if clicked && self.choice.is_none() {
            self.choice = Some(choice);
        }
    }

    /// A plain button.
    pub(in crate::app) fn button(&mut self, ui: &mut Ui, label: &str, choice: Choice) {
        let response = ui.button(label);
        self.claims.push(response.id);
        self.choose(response.clicked(), choice);
    }

    /// The button Enter presses: focused when the dialog opens.
    pub(in crate::app) fn default_button(&mut self, ui: &mut Ui, label: &str, choice: Choice) {
        let response = ui.button(label);
        if self.first {
            response.request_focus();
        }
        self.claims.push(response.id);
        self.choose(response.clicked(), choice);
    }

    /// A button that loses or overwrites work: enabled once the dialog has been up a moment.
    pub(in crate::app) fn destructive_button(&mut self, ui: &mut Ui, label: &str, choice: Choice) {
        let response = ui.add_enabled(self.armed, egui::Button::new(label));
        self.claims.push(response.id);
        self.choose(response.clicked(), choice);
    }

    /// A check box (Enter toggles it when focused).
    pub(in crate::app) fn checkbox(&mut self, ui: &mut Ui, value: &mut bool, label: &str) {
        let response = ui.checkbox(value, label);
        self.claims.push(response.id);
    }

    /// The path field: full width, focused with its text selected when the dialog opens.
    pub(in crate::app) fn path_field(&mut self, ui: &mut Ui, path: &mut String) {
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
    pub(in crate::app) fn path_buttons(&mut self, ui: &mut Ui, confirm: &str) {
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

pub(in crate::app) fn default_path(document: &Document, extension: &str) -> String {
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
pub(in crate::app) fn typed_path(text: &str) -> PathBuf {
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
pub(in crate::app) fn ago(time: Option<std::time::SystemTime>) -> String {
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
