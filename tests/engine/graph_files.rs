//! Graph checks, pruning and codegen through the library API.

use veneer::codegen::{CompileError, CompileOptions, ParamMode, compile};
use veneer::graph::{Graph, Metric, NodeKind, Value, WorleyFeature};
use veneer::nodes::{Fbm, Math, Mix, Noise, Worley};

fn small_graph() -> (Graph, veneer::graph::NodeId) {
    let mut graph = Graph::default();
    let noise = graph.add(
        "grain",
        NodeKind::Noise(Noise {
            basis: veneer::graph::Basis::ValuePcg,
            period: 0,
        }),
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
        NodeKind::Worley(Worley {
            feature: WorleyFeature::F1,
            metric: Metric::Euclidean,
            octaves: 1,
            period: 0,
            points: veneer::graph::FeaturePoints::Hashed,
        }),
    );
    let module = compile(&graph, &Default::default())
        .expect("compiles")
        .module;
    assert!(!module.source.contains("worley"), "{}", module.source);
    assert!(!module.library.iter().any(|name| name.contains("worley")));
}

#[test]
fn only_used_library_functions_are_emitted() {
    let (graph, _) = small_graph();
    let module = compile(&graph, &Default::default())
        .expect("compiles")
        .module;
    assert_eq!(
        module.library,
        [
            "veneer_lattice_domain",
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
fn a_constant_beyond_f32_is_rejected_by_the_check_naming_its_node() {
    let (mut graph, noise) = small_graph();
    graph.set_input(noise, "scale", Value::Float(1e39));
    match compile(&graph, &Default::default()) {
        Err(CompileError::Check(errors)) => {
            let message = errors[0].to_string();
            assert!(message.starts_with("node 'grain' (#1)"), "{message}");
            assert!(message.contains("beyond the f32 range"), "{message}");
        }
        other => panic!("expected a check error, got {other:?}"),
    }
}

#[test]
fn generated_code_maps_back_to_its_node() {
    // What a naga error, should one slip past the check, is blamed on.
    let (graph, noise) = small_graph();
    let module = compile(&graph, &Default::default())
        .expect("compiles")
        .module;
    let offset = module.source.find("let grain").expect("the node's line");
    assert_eq!(module.node_at(offset), Some(noise));
    assert_eq!(module.node_at(0), None);
}

#[test]
fn generated_wgsl_is_deterministic_and_named_after_labels() {
    let (graph, _) = small_graph();
    let (a, b) = (
        compile(&graph, &Default::default())
            .expect("compiles")
            .module,
        compile(&graph, &Default::default())
            .expect("compiles")
            .module,
    );
    assert_eq!(a.source, b.source);
    assert!(
        a.source
            .contains("let grain: f32 = veneer_noise_value_pcg(s.position * 1.0f);"),
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
        NodeKind::Fbm(Fbm {
            basis: veneer::graph::Basis::Gradient,
            octaves: 65,
            normalize: false,
            rotate: false,
            period: 0,
        }),
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

#[test]
fn every_preset_module_defines_exactly_the_contract_and_prefixes_the_rest() {
    for path in crate::support::presets() {
        let graph = veneer::graph::load(&path).expect("preset loads");
        let module = compile(&graph, &Default::default())
            .expect("preset compiles")
            .module
            .module;
        let types: Vec<&str> = module
            .types
            .iter()
            .filter_map(|(_, ty)| ty.name.as_deref())
            .collect();
        for contract in ["VeneerSurface", "VeneerMaterial"] {
            assert_eq!(
                types.iter().filter(|name| **name == contract).count(),
                1,
                "{}: {contract}",
                path.display()
            );
        }
        let named = types.iter().copied().chain(
            module
                .functions
                .iter()
                .filter_map(|(_, f)| f.name.as_deref()),
        );
        for name in named {
            let allowed =
                name.starts_with("veneer_") || name == "VeneerSurface" || name == "VeneerMaterial";
            assert!(
                allowed,
                "{}: '{name}' is not prefixed veneer_",
                path.display()
            );
        }
        let entry = module
            .functions
            .iter()
            .find(|(_, f)| f.name.as_deref() == Some("veneer_material"));
        let (_, entry) = entry.unwrap_or_else(|| panic!("{}: no veneer_material", path.display()));
        assert_eq!(entry.arguments.len(), 1);
        let result = entry
            .result
            .as_ref()
            .expect("veneer_material returns a value");
        assert_eq!(
            module.types[result.ty].name.as_deref(),
            Some("VeneerMaterial")
        );
        assert_eq!(
            module.types[entry.arguments[0].ty].name.as_deref(),
            Some("VeneerSurface")
        );
        assert_eq!(
            struct_fields(&module, "VeneerSurface"),
            ["position", "normal", "uv", "fields", "time"]
        );
        let material = struct_fields(&module, "VeneerMaterial");
        assert_eq!(
            material,
            [
                "albedo",
                "alpha",
                "specular",
                "shininess",
                "bump",
                "height",
                "emission",
                // Appended for metallic-roughness materials.
                "metallic",
                "roughness",
                "normal",
                "emission_strength",
                "occlusion"
            ]
        );
    }
}

/// Member names of the struct called `name`, in order.
fn struct_fields(module: &naga::Module, name: &str) -> Vec<String> {
    let (_, ty) = module
        .types
        .iter()
        .find(|(_, ty)| ty.name.as_deref() == Some(name))
        .expect("struct defined");
    match &ty.inner {
        naga::TypeInner::Struct { members, .. } => {
            members.iter().filter_map(|m| m.name.clone()).collect()
        }
        other => panic!("{name} is not a struct: {other:?}"),
    }
}

#[test]
fn uniform_mode_turns_every_constant_into_a_slot_and_validates() {
    for path in crate::support::presets() {
        let graph = veneer::graph::load(&path).expect("preset loads");
        let module = compile(&graph, &CompileOptions::with_params(ParamMode::Uniform))
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
            .module;
        assert!(!module.params.is_empty());
        assert!(
            module
                .source
                .contains(&format!("values: array<vec4f, {}>", module.params.len()))
        );
        let values = veneer::codegen::param_values(&graph, &module.params);
        assert_eq!(values.len(), module.params.len());
    }
    let graph = veneer::graph::load(&crate::support::root("graphs/marble.ron")).expect("marble");
    let module = compile(&graph, &CompileOptions::with_params(ParamMode::Uniform))
        .expect("compiles")
        .module;
    let slot = module
        .params
        .iter()
        .position(|p| p.pin == "frequency")
        .expect("the bands' frequency is a slot");
    assert_eq!(
        veneer::codegen::param_values(&graph, &module.params)[slot][0],
        3.0
    );
}

#[test]
fn storage_mode_has_the_uniform_modes_slots_in_a_storage_buffer() {
    for path in crate::support::presets() {
        let graph = veneer::graph::load(&path).expect("preset loads");
        let compiled = |mode| {
            compile(&graph, &CompileOptions::with_params(mode))
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
                .module
        };
        let (uniform, storage) = (compiled(ParamMode::Uniform), compiled(ParamMode::Storage));
        assert_eq!(storage.params, uniform.params, "{}", path.display());
        let declaration =
            "@group(1) @binding(0) var<storage, read> veneer_params: veneer_parameters;";
        assert!(storage.source.contains(declaration));
        assert_eq!(
            storage.source.replace("var<storage, read>", "var<uniform>"),
            uniform.source,
            "{}: only the declaration differs",
            path.display()
        );
    }
}

#[test]
fn constant_subgraphs_fold_to_literals_and_surface_reads_do_not() {
    let mut graph = Graph::default();
    let sum = graph.add(
        "quarter plus half",
        NodeKind::Math(Math {
            op: veneer::graph::MathOp::Add,
            ty: veneer::graph::ValueType::Float,
        }),
    );
    graph.set_input(sum, "a", Value::Float(0.25));
    graph.set_input(sum, "b", Value::Float(0.5));
    let noise = graph.add(
        "noise",
        NodeKind::Noise(Noise {
            basis: veneer::graph::Basis::Gradient,
            period: 0,
        }),
    );
    let mix = graph.add(
        "shade",
        NodeKind::Mix(Mix {
            ty: veneer::graph::ValueType::Color,
        }),
    );
    graph.connect(sum, "result", mix, "factor");
    let material = graph.add("material", NodeKind::Material);
    graph.connect(mix, "result", material, "albedo");
    graph.connect(noise, "value", material, "shininess");
    let source = compile(&graph, &Default::default()).unwrap().module.source;
    assert!(
        !source.contains("quarter_plus_half"),
        "the sum folded away:\n{source}"
    );
    assert!(source.contains("0.75f"), "its value is a literal");
    assert!(
        source.contains("veneer_noise_gradient(s.position"),
        "noise of the position stays"
    );
    let uniform = compile(&graph, &CompileOptions::with_params(ParamMode::Uniform))
        .unwrap()
        .module
        .source;
    assert!(
        uniform.contains("quarter_plus_half"),
        "editor parameters stay live: no folding"
    );
}
