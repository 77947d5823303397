//! Shader exports: every preset to every target, baked and with a uniform block, accepted
//! by naga and by the independent validators (glslangValidator, spirv-val) that .ci/run
//! installs; identifiers that are keywords somewhere stay valid everywhere.

use crate::support::presets;
use std::path::Path;
use std::process::Command;
use veneer::codegen::ParamMode;
use veneer::codegen::export::{Target, export};
use veneer::graph::{Graph, NodeKind};
use veneer::nodes::{Noise, Unary};

fn run_validator(tool: &str, file: &Path) {
    let output = Command::new(tool)
        .arg(file)
        .output()
        .unwrap_or_else(|error| {
            panic!("{tool} is needed (Debian glslang-tools / spirv-tools; `.ci/run` installs them): {error}")
        });
    assert!(
        output.status.success(),
        "{tool} rejects {}:\n{}{}",
        file.display(),
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
}

/// Exports `graph` to every target in every parameter mode (baked, every constant a
/// slot, the exposed parameters by name) and checks each output.
fn export_everywhere(graph: &Graph, name: &str, dir: &Path) {
    for (target, target_name, _) in Target::ALL {
        for params in [ParamMode::Baked, ParamMode::Uniform, ParamMode::Named] {
            let bytes = export(graph, target, params)
                .unwrap_or_else(|e| panic!("{name} → {target_name}: {e}"));
            assert!(!bytes.is_empty());
            // glslangValidator picks the stage from the extension.
            let file = dir.join(format!(
                "{name}-{target_name}-{params:?}.{}",
                target.extension()
            ));
            std::fs::write(&file, &bytes).expect("export written");
            match target {
                Target::Glsl | Target::GlslEs => run_validator("glslangValidator", &file),
                Target::Spirv => run_validator("spirv-val", &file),
                Target::Wgsl => assert!(
                    String::from_utf8(bytes)
                        .unwrap()
                        .contains("fn veneer_material(")
                ),
                Target::Hlsl | Target::Msl => {
                    let text = String::from_utf8(bytes).expect("text");
                    assert!(
                        text.contains("veneer_material(") && text.contains("veneer_fragment"),
                        "{name} {target_name}"
                    );
                }
            }
        }
    }
}

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("veneer-export-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir
}

#[test]
fn every_preset_exports_to_every_target_and_validates() {
    let dir = scratch("presets");
    for path in presets() {
        let graph = veneer::graph::load(&path).expect("preset loads");
        export_everywhere(&graph, &crate::support::stem(&path), &dir);
    }
}

#[test]
fn every_periodic_noise_exports_to_every_target_and_validates() {
    let graph = crate::tiles::all_periodic_noises();
    export_everywhere(&graph, "periodic", &scratch("periodic"));
    let graph = crate::tiles::warped_and_bumped(3);
    export_everywhere(&graph, "periodic-warp", &scratch("periodic"));
}

#[test]
fn labels_that_are_keywords_in_the_target_languages_stay_valid() {
    let mut graph = Graph::default();
    let mut previous = None;
    for keyword in [
        "float", "half", "texture", "device", "constant", "cbuffer", "kernel", "main", "input",
        "output",
    ] {
        let node = graph.add(
            keyword,
            NodeKind::Unary(Unary {
                op: veneer::graph::UnaryOp::Fract,
                ty: veneer::graph::ValueType::Float,
            }),
        );
        match previous {
            Some(before) => graph.connect(before, "result", node, "x"),
            None => {
                let noise = graph.add(
                    "sampler",
                    NodeKind::Noise(Noise {
                        basis: veneer::graph::Basis::Simplex,
                        period: 0,
                    }),
                );
                graph.connect(noise, "value", node, "x");
            }
        }
        previous = Some(node);
    }
    let material = graph.add("discard", NodeKind::Material);
    graph.connect(previous.unwrap(), "result", material, "albedo");
    export_everywhere(&graph, "keywords", &scratch("keywords"));
}

#[test]
fn the_uniform_block_has_one_slot_per_parameter_at_a_documented_binding() {
    let graph = veneer::graph::load(&crate::support::root("graphs/marble.ron")).expect("marble");
    let options = veneer::codegen::CompileOptions::with_params(ParamMode::Uniform);
    let slots = veneer::codegen::compile(&graph, &options)
        .expect("compiles")
        .module
        .params
        .len();
    let glsl =
        String::from_utf8(export(&graph, Target::Glsl, ParamMode::Uniform).unwrap()).unwrap();
    assert!(glsl.contains(&format!("vec4 values[{slots}];")), "{glsl}");
    assert!(glsl.contains("layout(std140, binding = 1) uniform veneer_parameters"));
    assert!(glsl.contains("layout(std140, binding = 0) uniform VeneerFrame"));
    let baked = String::from_utf8(export(&graph, Target::Glsl, ParamMode::Baked).unwrap()).unwrap();
    assert!(!baked.contains("veneer_parameters"));
}
