//! Integration tests of the engine: presets, codegen, CPU evaluator, renders and the CLI.
//! One binary so that wgpu and the rest link once.

mod bake;
mod big_graphs;
mod cli;
mod cli_contract;
mod compile_once;
mod cpu_gpu;
mod detail;
mod emission;
mod errors;
mod export;
mod fuzz_regressions;
mod geodesic;
mod geodesic_files;
mod gltf;
mod graph_files;
mod hostile_cli;
mod hostile_files;
mod hostile_scale;
mod image_based_lighting;
mod limits;
mod lint;
mod meshes;
mod node_kinds;
mod presets;
mod properties;
mod relief;
mod report;
mod seed001_reference;
mod seed003_reference;
mod seed004_reference;
mod seed_reference;
mod snapshots;
mod support;
mod transparency;
