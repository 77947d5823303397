//! The editor driven for real through egui_kittest, rendering through wgpu on the
//! machine's adapter (lavapipe or llvmpipe on CI).

mod add_node;
mod dialogs;
mod editing;
mod files;
mod footprints;
mod geotextures;
mod groups;
mod navigation;
mod painting;
mod real_window;
mod responsiveness;
mod selection;
mod support;
mod thumbnails;
