//! Graph checks, pruning and codegen through the library API.

use veneer::codegen::{CompileError, compile_graph};
use veneer::graph::{Graph, Metric, NodeKind, Value, WorleyFeature};

fn small_graph() -> (Graph, veneer::graph::NodeId) {
    let mut graph = Graph::default();
    let noise = graph.add(
        "grain",
        NodeKind::Noise {
            basis: veneer::graph::Basis::ValuePcg,
        },
    );
    let material = graph.add("material", NodeKind::Material);
    graph.connect(noise, "value", material, "albedo");
    (graph, noise)
}

#[test]
fn unconnected_worley_emits_no_worley_code() {
    let (mut graph, _) = small_graph();
    graph.add(
        "unused cells",
        NodeKind::Worley {
            feature: WorleyFeature::F1,
            metric: Metric::Euclidean,
            octaves: 1,
        },
    );
    let module = compile_graph(&graph).expect("compiles");
    assert!(!module.source.contains("worley"), "{}", module.source);
    assert!(!module.library.iter().any(|name| name.contains("worley")));
}

#[test]
fn only_used_library_functions_are_emitted() {
    let (graph, _) = small_graph();
    let module = compile_graph(&graph).expect("compiles");
    assert_eq!(
        module.library,
        [
            "veneer_cell_bits",
            "veneer_pcg3d",
            "veneer_unit_floats",
            "veneer_lattice_pcg",
            "veneer_noise_value_pcg"
        ]
    );
    assert!(!module.source.contains("veneer_lattice_sine"));
}

#[test]
fn a_naga_error_is_mapped_to_the_node_that_caused_it() {
    let (mut graph, noise) = small_graph();
    graph.set_input(noise, "scale", Value::Float(1e39));
    match compile_graph(&graph) {
        Err(CompileError::Validation(error)) => {
            assert_eq!(error.node, Some(noise), "{error}");
            assert!(
                error.to_string().starts_with("node 'grain' (#1)"),
                "{error}"
            );
        }
        other => panic!("expected a validation error, got {other:?}"),
    }
}

#[test]
fn generated_wgsl_is_deterministic_and_named_after_labels() {
    let (graph, _) = small_graph();
    let (a, b) = (
        compile_graph(&graph).expect("compiles"),
        compile_graph(&graph).expect("compiles"),
    );
    assert_eq!(a.source, b.source);
    assert!(
        a.source
            .contains("let grain = veneer_noise_value_pcg(s.position * 1.0);"),
        "{}",
        a.source
    );
}

#[test]
fn missing_required_input_is_reported_by_node_name() {
    let mut graph = Graph::default();
    let smooth = graph.add("edge", NodeKind::Smoothstep);
    let material = graph.add("material", NodeKind::Material);
    graph.connect(smooth, "result", material, "alpha");
    let errors = veneer::graph::check(&graph).expect_err("x is required");
    assert_eq!(
        errors[0].to_string(),
        "node 'edge' (#1): input 'x' (float) must be connected"
    );
}

#[test]
fn out_of_range_settings_and_unknown_pins_are_errors() {
    let (mut graph, noise) = small_graph();
    graph.set_input(noise, "frequency", Value::Float(2.0));
    graph.add(
        "too fine",
        NodeKind::Fbm {
            basis: veneer::graph::Basis::Gradient,
            octaves: 65,
            normalize: false,
        },
    );
    let messages: Vec<String> = veneer::graph::check(&graph)
        .expect_err("two errors")
        .iter()
        .map(|e| e.to_string())
        .collect();
    assert!(
        messages
            .iter()
            .any(|m| m.contains("no input named 'frequency' (inputs: p, scale)")),
        "{messages:?}"
    );
    assert!(
        messages
            .iter()
            .any(|m| m.contains("octaves 65 is out of range (expected 1 to 64)")),
        "{messages:?}"
    );
}

#[test]
fn future_versions_are_rejected_with_a_position() {
    let text = "(\n    version: 9,\n    nodes: [],\n)\n";
    let error = veneer::graph::from_ron(text).expect_err("version 9 is unknown");
    assert_eq!(error.position, Some((2, 5)));
    assert!(
        error.message.contains("unsupported graph version 9"),
        "{}",
        error.message
    );
}
