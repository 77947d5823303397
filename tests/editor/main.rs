//! The editor driven for real through egui_kittest, rendering through wgpu on the
//! machine's adapter (lavapipe or llvmpipe on CI).

mod add_node;
#[path = "../engine/big_graphs.rs"]
#[allow(dead_code)]
mod big_graphs;
mod dialogs;
mod editing;
mod files;
mod fitting;
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
