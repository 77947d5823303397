//! The file browser behind the path dialogs' *Browse…* button: folders and files listed
//! as in a desktop file chooser (egui-file-dialog, drawn by egui itself, so it needs no
//! desktop portal), filtered by the extensions the dialog expects.

use egui_file_dialog::{DialogState, FileDialog};
use std::path::{Path, PathBuf};

/// What the browser is choosing a file for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Purpose {
    /// An existing file to read, one of `extensions`.
    Pick {
        title: &'static str,
        kind: &'static str,
        extensions: &'static [&'static str],
    },
    /// A file to write, named with `extension` (asks before replacing one).
    Save {
        title: &'static str,
        kind: &'static str,
        extension: &'static str,
    },
}

/// What the browser did this frame.
pub enum Browsed {
    /// It is still open.
    Browsing,
    /// The user closed it without choosing.
    Cancelled,
    /// The user chose this file.
    Picked(PathBuf),
}

/// The file browser, while one is open.
#[derive(Default)]
pub struct Browser {
    dialog: Option<FileDialog>,
}

impl Browser {
    /// Whether a browser is open.
    pub fn is_open(&self) -> bool {
        self.dialog
            .as_ref()
            .is_some_and(|dialog| *dialog.state() == DialogState::Open)
    }

    /// Opens the browser for `purpose`, in the folder of `current` (the path typed so
    /// far, relative to the working folder) and, when saving, suggesting its file name.
    pub fn open(&mut self, purpose: Purpose, current: &str) {
        let current = PathBuf::from(current.trim());
        let folder = if current.is_dir() {
            current.clone()
        } else {
            current
                .parent()
                .filter(|folder| folder.is_dir() && !folder.as_os_str().is_empty())
                .map(Path::to_path_buf)
                .or_else(|| std::env::current_dir().ok())
                .unwrap_or_default()
        };
        let name = current
            .file_name()
            .filter(|_| !current.is_dir())
            .map(|name| name.to_string_lossy().into_owned())
            .unwrap_or_default();
        let dialog = FileDialog::new()
            .id("veneer file browser")
            .initial_directory(folder)
            .default_size([760.0, 480.0])
            .anchor(egui::Align2::CENTER_CENTER, [0.0, 0.0]);
        let dialog = match purpose {
            Purpose::Pick {
                title,
                kind,
                extensions,
            } => {
                let mut dialog = dialog
                    .title(title)
                    .add_file_filter_extensions(kind, extensions.to_vec())
                    .default_file_filter(kind);
                dialog.pick_file();
                dialog
            }
            Purpose::Save {
                title,
                kind,
                extension,
            } => {
                let mut dialog = dialog
                    .title(title)
                    .default_file_name(&name)
                    .add_save_extension(kind, extension)
                    .default_save_extension(kind)
                    .add_file_filter_extensions(kind, vec![extension])
                    .default_file_filter(kind)
                    .allow_file_overwrite(true);
                dialog.save_file();
                dialog
            }
        };
        self.dialog = Some(dialog);
    }

    /// Shows the open browser; what the user did.
    pub fn update(&mut self, ctx: &egui::Context) -> Browsed {
        let Some(dialog) = &mut self.dialog else {
            return Browsed::Cancelled;
        };
        dialog.update(ctx);
        let browsed = match dialog.state() {
            DialogState::Open => return Browsed::Browsing,
            DialogState::Picked(path) => Browsed::Picked(path.clone()),
            DialogState::PickedMultiple(paths) => match paths.first() {
                Some(path) => Browsed::Picked(path.clone()),
                None => Browsed::Cancelled,
            },
            DialogState::Closed | DialogState::Cancelled => Browsed::Cancelled,
        };
        self.dialog = None;
        browsed
    }
}
