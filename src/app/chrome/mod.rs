//! The window's chrome: menus, dialogs, the file browser and the frame clock.

pub(in crate::app) mod dialogs;
pub(in crate::app) mod file_browser;
pub(in crate::app) mod frame_clock;
pub(in crate::app) mod menus;

/// The window's chrome: the status bar's message, the open dialog, the file browser,
/// and the frame clock with what it shows and writes down.
#[derive(Default)]
pub(in crate::app) struct Chrome {
    /// A message for the status bar (saved, exported, refused wire…).
    pub message: Option<String>,
    pub dialog: Option<dialogs::Dialog>,
    /// The file browser a path dialog opened.
    pub browser: file_browser::Browser,
    /// The node whose file setting the open file browser chooses for.
    pub choosing_file_for: Option<egui_snarl::NodeId>,
    /// Whether the status bar shows the frame rate (View → Frame rate).
    pub show_frame_rate: bool,
    /// Where the main thread's time went in the last frame.
    pub profile: frame_clock::FrameProfile,
    /// Frames a second and main-thread time over the last second.
    pub frame_clock: frame_clock::FrameClock,
    /// Where each frame is written down, when asked (`veneer edit --frame-log`).
    pub frame_log: Option<frame_clock::FrameLog>,
}
