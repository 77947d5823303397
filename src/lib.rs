//! Veneer: procedural material node graphs compiled to WGSL, checked by naga, evaluated
//! on the CPU as a reference, and rendered through wgpu.

#[cfg(feature = "gui")]
pub mod app;
pub mod bake;
pub mod bitmaps;
pub mod codegen;
pub mod eval;
pub mod fit;
pub mod fsutil;
pub mod geodesic;
pub mod graph;
pub mod lint;
pub mod mesh;
pub mod mesh_fields;
pub mod messages;
pub mod nodes;
pub mod render;
pub mod report;
pub mod snapshot;
