//! The lint pass: each numerical hazard is found on the right node from propagated
//! ranges, clean graphs stay clean, and `veneer check` prints warnings but passes.

use veneer::graph::{Basis, Graph, MathOp, NodeId, NodeKind, Value, ValueType};
use veneer::lint::{lint, preview_positions};
use veneer::nodes::{Fbm, Math, Noise, Normalize};

/// Lints of `graph`, as (node, message) pairs.
fn lints(graph: &Graph) -> Vec<(NodeId, String)> {
    let checked = veneer::graph::check(graph).expect("the graph checks");
    lint(&checked, preview_positions(graph))
        .into_iter()
        .map(|l| (l.node, l.message))
        .collect()
}

/// A graph with `kind` feeding the material's albedo, and its node id.
fn with_node(kind: NodeKind) -> (Graph, NodeId) {
    let mut graph = Graph::default();
    let node = graph.add("under test", kind.clone());
    let material = graph.add("material", NodeKind::Material);
    let output = kind.signature().outputs[0].name;
    graph.connect(node, output, material, "albedo");
    (graph, node)
}

fn assert_lint(graph: &Graph, node: NodeId, expected: &str) {
    let found = lints(graph);
    assert!(
        found
            .iter()
            .any(|(n, m)| *n == node && m.contains(expected)),
        "no '{expected}' on {node}: {found:?}"
    );
}

#[test]
fn degenerate_smoothstep_and_remap_parameters() {
    let (mut graph, node) = with_node(NodeKind::Smoothstep);
    let x = graph.add("x", NodeKind::Project);
    graph.connect(x, "x", node, "x");
    graph.set_input(node, "edge0", Value::Float(0.5));
    graph.set_input(node, "edge1", Value::Float(0.5));
    assert_lint(&graph, node, "a hard step");
    graph.set_input(node, "edge1", Value::Float(0.2));
    assert_lint(&graph, node, "falls instead of rising");
    let (mut graph, node) = with_node(NodeKind::Remap);
    let x = graph.add("x", NodeKind::Project);
    graph.connect(x, "x", node, "x");
    graph.set_input(node, "from_max", Value::Float(0.0));
    assert_lint(&graph, node, "to_min everywhere");
}

#[test]
fn fractal_parameters_and_octave_budgets() {
    let (mut graph, node) = with_node(NodeKind::Fbm(Fbm {
        basis: Basis::ValuePcg,
        octaves: 6,
        normalize: false,
        rotate: false,
        period: 0,
    }));
    graph.set_input(node, "gain", Value::Float(1.2));
    assert_lint(&graph, node, "does not converge");
    graph.set_input(node, "gain", Value::Float(0.5));
    graph.set_input(node, "lacunarity", Value::Float(0.9));
    assert_lint(&graph, node, "do not get finer");
    let (graph, node) = with_node(NodeKind::Fbm(Fbm {
        basis: Basis::Gradient,
        octaves: 64,
        normalize: true,
        rotate: false,
        period: 0,
    }));
    assert_lint(&graph, node, "past f32's integer precision");
    let (graph, _) = with_node(NodeKind::Fbm(Fbm {
        basis: Basis::Gradient,
        octaves: 16,
        normalize: true,
        rotate: false,
        period: 0,
    }));
    assert!(
        lints(&graph).is_empty(),
        "16 octaves at lacunarity 2 stay within f32: {:?}",
        lints(&graph)
    );
}

#[test]
fn the_sine_hash_far_from_the_origin() {
    let (mut graph, node) = with_node(NodeKind::Noise(Noise {
        basis: Basis::ValueSine,
        period: 0,
    }));
    graph.preview.size = 5.0e6;
    assert_lint(&graph, node, "sine hash");
    graph.nodes[0].kind = NodeKind::Noise(Noise {
        basis: Basis::ValuePcg,
        period: 0,
    });
    assert!(lints(&graph).is_empty(), "the PCG hash is fine there");
}

#[test]
fn divisions_powers_and_normalisations_that_may_hit_zero_or_negatives() {
    // x spans the preview (-1..1), so it crosses zero.
    for (op, expected) in [
        (MathOp::Divide, "divisor may be 0"),
        (MathOp::Power, "base may be negative"),
    ] {
        let (mut graph, node) = with_node(NodeKind::Math(Math {
            op,
            ty: ValueType::Float,
        }));
        let x = graph.add("x", NodeKind::Project);
        let (input, other) = if op == MathOp::Divide {
            ("b", "a")
        } else {
            ("a", "b")
        };
        graph.connect(x, "x", node, input);
        graph.set_input(node, other, Value::Float(2.0));
        assert_lint(&graph, node, expected);
    }
    let (mut graph, node) = with_node(NodeKind::Normalize(Normalize {
        ty: ValueType::Vec3,
    }));
    let position = graph.add("position", NodeKind::Position);
    graph.connect(position, "position", node, "v");
    assert_lint(&graph, node, "may be zero");
    graph.preview.center = (10.0, 0.0, 0.0);
    assert!(
        lints(&graph).is_empty(),
        "away from the origin the vector is never zero"
    );
}

#[test]
fn presets_are_clean_and_check_prints_warnings_but_passes() {
    for path in crate::support::presets() {
        let graph = veneer::graph::load(&path).expect("preset");
        assert!(
            lints(&graph).is_empty(),
            "{}: {:?}",
            path.display(),
            lints(&graph)
        );
    }
    let (mut graph, _) = with_node(NodeKind::Smoothstep);
    let x = graph.add("x", NodeKind::Project);
    let smooth = graph.nodes[0].id;
    graph.connect(x, "x", smooth, "x");
    graph.set_input(smooth, "edge1", Value::Float(0.0));
    let dir = std::env::temp_dir().join(format!("veneer-lint-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("folder");
    let file = dir.join("step.ron");
    veneer::graph::save(&graph, &file).expect("saved");
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_veneer"))
        .arg("check")
        .arg(&file)
        .output()
        .expect("runs");
    assert!(output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("warning: node 'under test' (#1): edge0 = edge1 = 0: a hard step"),
        "{stderr}"
    );
}
