//! Node groups and exposed parameters: grouping and ungrouping random graphs changes
//! nothing, nested exposure, recursion, the library, file determinism, `--set` on every
//! command, the named uniform export read by a wgpu program, and sharded batches.

use crate::properties::random_graph;
use crate::support::{compiled_rgb8, cpu_flat_rgb8, flat_rgb8, root, run_veneer, temp_dir, veneer};
use proptest::prelude::*;
use std::collections::BTreeSet;
use veneer::codegen::{CompileOptions, ParamMode, compile};
use veneer::graph::group::{
    BOUNDARY, GroupDef, GroupInput, GroupOutput, Hint, group_nodes, ungroup,
};
use veneer::graph::parameters::{Given, exposed, set};
use veneer::graph::{Graph, NodeId, NodeKind, PinRef, Value, ValueType, Wire};
use veneer::nodes::{Group, Math};
use veneer::render::FlatRect;

/// The rectangle the group tests render over.
const RECT: FlatRect = FlatRect {
    x0: -2.0,
    z0: -1.5,
    x1: 3.0,
    z1: 2.5,
    y: 0.3,
};

/// A connected selection of `graph`'s nodes (the material left out): up to `size`
/// nodes reached over wires from the `start`-th node.
fn connected_selection(graph: &Graph, start: usize, size: usize) -> BTreeSet<NodeId> {
    let candidates: Vec<NodeId> = graph
        .nodes
        .iter()
        .filter(|node| node.kind != NodeKind::Material)
        .map(|node| node.id)
        .collect();
    let mut selection = BTreeSet::new();
    let Some(first) = candidates.get(start % candidates.len().max(1)) else {
        return selection;
    };
    let mut frontier = vec![*first];
    while let Some(id) = frontier.pop() {
        if selection.len() >= size || !candidates.contains(&id) || !selection.insert(id) {
            continue;
        }
        for wire in &graph.wires {
            if wire.from.node == id {
                frontier.push(wire.to.node);
            }
            if wire.to.node == id {
                frontier.push(wire.from.node);
            }
        }
    }
    selection
}

/// `graph` with a connected selection of up to `size` nodes from `start` grouped as
/// "part", and the group node; `None` when there is nothing to select.
fn grouped_part(graph: &Graph, start: usize, size: usize) -> Option<(Graph, NodeId)> {
    let selection = connected_selection(graph, start, size);
    if selection.is_empty() {
        return None;
    }
    let mut grouped = graph.clone();
    let instance = group_nodes(&mut grouped, &selection, "part").expect("groups");
    Some((grouped, instance))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 240, ..ProptestConfig::default() })]

    /// Grouping any connected selection gives the same image (CPU, f32); ungrouping it
    /// again gives the same file and the same WGSL as before.
    #[test]
    fn grouping_then_ungrouping_changes_nothing(
        kinds in prop::collection::vec(0u32..8192, 2..16),
        choices in prop::collection::vec(any::<u32>(), 1..48),
        start in any::<usize>(),
        size in 1usize..8,
    ) {
        let graph = random_graph(&kinds, &choices, true);
        let Ok(original) = compile(&graph, &Default::default()) else { return Ok(()) };
        let part = grouped_part(&graph, start, size);
        prop_assume!(part.is_some());
        let (mut grouped, instance) = part.expect("assumed");
        prop_assert!(grouped.nodes.len() <= graph.nodes.len());
        let compiled = compile(&grouped, &Default::default());
        prop_assert!(compiled.is_ok(), "{:?}\n{}", compiled.err(), veneer::graph::to_ron(&grouped));
        prop_assert_eq!(cpu_flat_rgb8(&grouped, RECT, 8), cpu_flat_rgb8(&graph, RECT, 8));
        // The grouped file reads back as itself.
        let text = veneer::graph::to_ron(&grouped);
        prop_assert_eq!(veneer::graph::to_ron(&veneer::graph::from_ron(&text).expect("loads")), text);

        ungroup(&mut grouped, instance).expect("ungroups");
        prop_assert_eq!(veneer::graph::to_ron(&grouped), veneer::graph::to_ron(&graph));
        let again = compile(&grouped, &Default::default()).expect("compiles");
        prop_assert_eq!(again.source(), original.source());
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    /// `veneer check` validates exactly the module `veneer compile` exports: for any
    /// grouped graph both pass with the same WGSL (a group as one function where the
    /// graph allows it) or both fail with the same message.
    #[test]
    fn check_validates_the_module_compile_exports(
        kinds in prop::collection::vec(0u32..8192, 2..16),
        choices in prop::collection::vec(any::<u32>(), 1..48),
        start in any::<usize>(),
        size in 1usize..8,
    ) {
        let graph = random_graph(&kinds, &choices, true);
        let part = grouped_part(&graph, start, size);
        prop_assume!(part.is_some());
        let (grouped, _) = part.expect("assumed");
        let exported = compile(&grouped, &Default::default());
        let checked = veneer::graph::check(&grouped);
        match (checked, exported) {
            (Ok(checked), Ok(exported)) => {
                let (module, _) = veneer::codegen::compile_checked(&grouped, &checked, &Default::default())
                    .expect("the check passes where the export does");
                prop_assert_eq!(&module.source, exported.source());
            }
            (Ok(checked), Err(error)) => {
                let checked = veneer::codegen::compile_checked(&grouped, &checked, &Default::default());
                prop_assert_eq!(checked.err().map(|e| e.to_string()), Some(error.to_string()));
            }
            (Err(errors), exported) => {
                let message = veneer::codegen::CompileError::Check(errors).to_string();
                prop_assert_eq!(exported.err().map(|e| e.to_string()), Some(message));
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 32, ..ProptestConfig::default() })]

    /// The GPU draws a grouped graph (its group as a WGSL function) exactly as the
    /// graph it came from.
    #[test]
    fn grouped_graphs_render_the_same_on_the_gpu(
        kinds in prop::collection::vec(0u32..8192, 2..10),
        choices in prop::collection::vec(any::<u32>(), 1..32),
        start in any::<usize>(),
    ) {
        let graph = random_graph(&kinds, &choices, false);
        let Ok(original) = compile(&graph, &Default::default()) else { return Ok(()) };
        let part = grouped_part(&graph, start, 4);
        prop_assume!(part.is_some());
        let (grouped, _) = part.expect("assumed");
        let compiled = compile(&grouped, &Default::default()).expect("compiles");
        prop_assert_eq!(compiled_rgb8(&compiled, RECT, 16), compiled_rgb8(&original, RECT, 16));
    }
}

/// A group `name` computing `x * gain` of the surface's x (gain a declared input, 2 by
/// default), or, with `inner`, the same through an instance of group `inner` whose
/// inputs it leaves unwired.
fn scaling_group(inner: Option<&str>) -> GroupDef {
    let mut definition = GroupDef {
        linked: false,
        inputs: Vec::new(),
        outputs: vec![GroupOutput {
            name: "result".into(),
            ty: ValueType::Float,
        }],
        nodes: Vec::new(),
        wires: Vec::new(),
    };
    let mut holder = Graph::default();
    let position = holder.add("position", NodeKind::Position);
    let split = holder.add(
        "split",
        NodeKind::Split(veneer::nodes::Split {
            ty: ValueType::Vec3,
        }),
    );
    holder.connect(position, "position", split, "v");
    let last = match inner {
        Some(inner) => {
            let id = holder.add("scaled", NodeKind::Group(Group::named(inner.into())));
            holder.connect(split, "x", id, "x");
            (id, "result")
        }
        None => {
            let multiply = holder.add(
                "gain",
                NodeKind::Math(Math {
                    op: veneer::graph::MathOp::Multiply,
                    ty: ValueType::Float,
                }),
            );
            holder.connect(split, "x", multiply, "a");
            definition.inputs = vec![
                GroupInput {
                    name: "gain".into(),
                    ty: ValueType::Float,
                    default: Value::Float(2.0),
                    range: Some((0.0, 10.0)),
                    hint: Hint::Slider,
                },
                GroupInput {
                    name: "x".into(),
                    ty: ValueType::Float,
                    default: Value::Float(0.0),
                    range: None,
                    hint: Hint::Slider,
                },
            ];
            holder.wires.retain(|wire| wire.to.node != multiply);
            definition.wires.push(Wire {
                from: PinRef::new(BOUNDARY, "x"),
                to: PinRef::new(multiply, "a"),
            });
            definition.wires.push(Wire {
                from: PinRef::new(BOUNDARY, "gain"),
                to: PinRef::new(multiply, "b"),
            });
            (multiply, "result")
        }
    };
    definition.wires.extend(holder.wires.clone());
    definition.wires.push(Wire {
        from: PinRef::new(last.0, last.1),
        to: PinRef::new(BOUNDARY, "result"),
    });
    definition.nodes = holder.nodes;
    definition
}

/// A graph whose albedo is `outer`'s result, `outer` using `inner` (x * gain).
fn nested_graph() -> Graph {
    let mut graph = Graph::default();
    graph.groups.insert("inner".into(), scaling_group(None));
    graph
        .groups
        .insert("outer".into(), scaling_group(Some("inner")));
    let outer = graph.add("outer", NodeKind::Group(Group::named("outer".into())));
    let material = graph.add("material", NodeKind::Material);
    graph.connect(outer, "result", material, "albedo");
    veneer::graph::group::resolve(&mut graph);
    graph
}

/// The CPU albedo's red channel at x = 0.25 (which the nested groups scale).
fn red_at_quarter(graph: &Graph) -> f64 {
    let evaluator = veneer::eval::Evaluator::new(graph).expect("checks");
    let surface = veneer::eval::Surface::<f64>::at([0.25, 0.0, 0.0]);
    evaluator.eval(&surface).albedo[0]
}

#[test]
fn renaming_and_removing_a_group_input_follows_it_through_nesting_and_presets() {
    use veneer::graph::group_interface::{Side, remove, rename};
    let mut graph = nested_graph();
    set(&mut graph, "gain", &Given::Number(3.0)).expect("sets");
    graph.presets.insert(
        "strong".into(),
        [("gain".to_string(), Value::Float(4.0))].into(),
    );
    rename(&mut graph, "inner", Side::Input, "gain", "amount").expect("renames");
    let names: Vec<String> = exposed(&graph)
        .into_iter()
        .map(|entry| entry.name)
        .collect();
    assert!(
        names.contains(&"amount".to_string()) && !names.contains(&"gain".to_string()),
        "{names:?}"
    );
    assert!(
        (red_at_quarter(&graph) - 0.75).abs() < 1e-9,
        "the value set stays"
    );
    assert!(
        graph.presets["strong"].contains_key("amount"),
        "the preset follows"
    );
    veneer::graph::parameters::apply_preset(&mut graph, "strong").expect("applies");
    assert!((red_at_quarter(&graph) - 1.0).abs() < 1e-9);
    // Bad and taken names are refused, the graph untouched.
    let before = veneer::graph::to_ron(&graph);
    assert!(rename(&mut graph, "inner", Side::Input, "amount", "x").is_err());
    assert!(rename(&mut graph, "inner", Side::Input, "amount", "2 much").is_err());
    assert_eq!(veneer::graph::to_ron(&graph), before);

    // Removing the input: the pin it fed keeps its default (gain 2), fixed now.
    remove(&mut graph, "inner", Side::Input, "amount").expect("removes");
    assert!(exposed(&graph).iter().all(|entry| entry.name != "amount"));
    assert!(!graph.presets["strong"].contains_key("amount"));
    assert!((red_at_quarter(&graph) - 0.5).abs() < 1e-9);
    compile(&graph, &Default::default()).expect("compiles");

    // An output renamed keeps its wires; removed, the wires from it go.
    rename(&mut graph, "outer", Side::Output, "result", "scaled_x").expect("renames");
    assert!(graph.wires.iter().any(|wire| wire.from.pin == "scaled_x"));
    assert!((red_at_quarter(&graph) - 0.5).abs() < 1e-9);
    remove(&mut graph, "outer", Side::Output, "scaled_x").expect("removes");
    assert!(graph.wires.is_empty());
}

#[test]
fn nested_parameters_stay_exposed_through_their_parents_until_wired() {
    let mut graph = nested_graph();
    let names: Vec<(String, Vec<String>)> = exposed(&graph)
        .into_iter()
        .map(|entry| (entry.name, entry.group_path))
        .collect();
    assert!(
        names.contains(&("gain".into(), vec!["outer".into(), "inner".into()])),
        "{names:?}"
    );
    assert!(
        (red_at_quarter(&graph) - 0.5).abs() < 1e-9,
        "the default gain is 2"
    );
    set(&mut graph, "gain", &Given::Number(3.0)).expect("sets");
    assert!((red_at_quarter(&graph) - 0.75).abs() < 1e-9);
    // The change is also what the compiled shader and its parameter list say.
    let compiled =
        compile(&graph, &CompileOptions::with_params(ParamMode::Named)).expect("compiles");
    assert!(
        compiled.source().contains("gain: f32"),
        "{}",
        compiled.source()
    );
    assert!(
        set(&mut graph, "gain", &Given::Number(11.0)).is_err(),
        "outside its range"
    );

    // Wiring the inner instance's gain inside `outer` binds it: no longer exposed.
    let outer = graph.groups.get_mut("outer").expect("outer");
    let inner_id = outer
        .nodes
        .iter()
        .find(|node| node.label == "scaled")
        .expect("inner instance")
        .id;
    let constant = NodeId(99);
    let mut node = veneer::graph::Node::new(
        constant,
        NodeKind::Constant(veneer::nodes::Constant {
            ty: ValueType::Float,
        }),
    );
    node.inputs.insert("value".into(), Value::Float(4.0));
    outer.nodes.push(node);
    outer.wires.push(Wire {
        from: PinRef::new(constant, "value"),
        to: PinRef::new(inner_id, "gain"),
    });
    veneer::graph::group::resolve(&mut graph);
    assert!(exposed(&graph).iter().all(|entry| entry.name != "gain"));
    assert!((red_at_quarter(&graph) - 1.0).abs() < 1e-9);
}

/// Two instances of the `inner` group (x * gain) side by side, gains `a` and `b`, x the
/// surface's x; the first feeds the albedo, the second the alpha.
fn twin_graph(a: f64, b: f64) -> Graph {
    let mut graph = Graph::default();
    graph.groups.insert("inner".into(), scaling_group(None));
    let position = graph.add("position", NodeKind::Position);
    let split = graph.add(
        "split",
        NodeKind::Split(veneer::nodes::Split {
            ty: ValueType::Vec3,
        }),
    );
    graph.connect(position, "position", split, "v");
    let material = graph.add("material", NodeKind::Material);
    for (gain, pin) in [(a, "albedo"), (b, "alpha")] {
        let twin = graph.add("twin", NodeKind::Group(Group::named("inner".into())));
        graph.set_input(twin, "gain", Value::Float(gain));
        graph.connect(split, "x", twin, "x");
        graph.connect(twin, "result", material, pin);
    }
    veneer::graph::group::resolve(&mut graph);
    graph
}

#[test]
fn a_group_is_one_function_with_only_the_arguments_its_instances_differ_in() {
    let source = |graph: &Graph| {
        compile(graph, &Default::default())
            .expect("compiles")
            .source()
            .to_string()
    };
    let differing = source(&twin_graph(2.0, 3.0));
    assert_eq!(
        differing.matches("fn veneer_group_inner(").count(),
        1,
        "{differing}"
    );
    assert_eq!(differing.matches("= veneer_group_inner(s, ").count(), 2);
    assert!(
        differing.contains("fn veneer_group_inner(s: VeneerSurface, gain: f32, x: f32)"),
        "{differing}"
    );
    // The same gain everywhere is no argument: it folds inside the function.
    let same = source(&twin_graph(2.5, 2.5));
    assert!(
        same.contains("fn veneer_group_inner(s: VeneerSurface, x: f32)"),
        "{same}"
    );
    assert!(same.contains("* 2.5f"), "{same}");
    // A group whose outputs nobody reads emits nothing.
    let mut unused = twin_graph(2.0, 3.0);
    unused.wires.retain(|wire| wire.from.node.0 < 4);
    assert!(!source(&unused).contains("veneer_group_inner"));
    // The functions draw what the inlined graph draws.
    let graph = twin_graph(2.0, 3.0);
    let flat = veneer::graph::group::flatten(&graph)
        .expect("flattens")
        .into_owned();
    let flat_source = source(&flat);
    assert!(!flat_source.contains("veneer_group"));
    assert_eq!(
        flat_rgb8(&differing, RECT, 16),
        flat_rgb8(&flat_source, RECT, 16)
    );
}

#[test]
fn a_group_that_contains_itself_is_refused_naming_the_groups() {
    let mut graph = Graph::default();
    graph
        .groups
        .insert("bark".into(), scaling_group(Some("grain")));
    graph
        .groups
        .insert("grain".into(), scaling_group(Some("bark")));
    let bark = graph.add("bark", NodeKind::Group(Group::named("bark".into())));
    let material = graph.add("material", NodeKind::Material);
    graph.connect(bark, "result", material, "albedo");
    let message = crate::support::refusal(&graph);
    assert!(message.contains("'bark' › 'grain' › 'bark'"), "{message}");
    // The file still loads and saves: the error is the check's.
    let text = veneer::graph::to_ron(&graph);
    assert_eq!(
        veneer::graph::to_ron(&veneer::graph::from_ron(&text).unwrap()),
        text
    );
}

#[test]
fn errors_inside_groups_name_the_group_path() {
    let mut graph = nested_graph();
    let inner = graph.groups.get_mut("inner").expect("inner");
    let multiply = inner
        .nodes
        .iter_mut()
        .find(|n| n.label == "gain")
        .expect("gain");
    multiply.inputs.insert("nonsense".into(), Value::Float(1.0));
    let errors = veneer::graph::check(&graph).expect_err("unknown pin");
    let message = errors
        .iter()
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join("\n");
    assert!(
        message.contains("group 'outer' › group 'scaled' › node 'gain' (#"),
        "{message}"
    );
}

#[test]
fn group_files_are_deterministic_and_plain_graphs_stay_version_one() {
    let graph = nested_graph();
    let text = veneer::graph::to_ron(&graph);
    assert!(text.contains("version: 2"), "{text}");
    let reloaded = veneer::graph::from_ron(&text).expect("loads");
    assert_eq!(veneer::graph::to_ron(&reloaded), text);
    let mut plain = veneer::graph::load(&root("graphs/thesis_brick.ron")).expect("loads");
    plain.parameters.clear();
    plain.presets.clear();
    assert!(veneer::graph::to_ron(&plain).contains("version: 1"));
    // The shipped presets are in canonical form.
    for name in ["wood", "marble", "wood_polished", "marble_polished"] {
        let path = root(&format!("graphs/{name}.ron"));
        let on_disk = std::fs::read_to_string(&path).expect("reads");
        assert_eq!(
            veneer::graph::to_ron(&veneer::graph::load(&path).unwrap()),
            on_disk,
            "{name}"
        );
    }
}

#[test]
fn fmt_arranges_library_groups_and_the_insides_of_graphs_groups() {
    // The shipped files are laid out as `fmt --arrange` lays them out: running it on
    // copies changes nothing, library group files included.
    let dir = temp_dir("fmt-groups");
    let files = [
        "graphs/lib/ring_wood.ron",
        "graphs/lib/veined_marble.ron",
        "graphs/wood.ron",
        "graphs/marble_polished.ron",
    ];
    let mut args = vec!["fmt", "--arrange", "--width", "1620", "--height", "1000"];
    let copies: Vec<String> = files
        .iter()
        .enumerate()
        .map(|(k, file)| {
            let copy = dir.join(format!("{k}.ron"));
            std::fs::copy(root(file), &copy).unwrap();
            copy.display().to_string()
        })
        .collect();
    args.extend(copies.iter().map(String::as_str));
    let output = run_veneer(&args);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    for (file, copy) in files.iter().zip(&copies) {
        let shipped = std::fs::read_to_string(root(file)).unwrap();
        assert_eq!(std::fs::read_to_string(copy).unwrap(), shipped, "{file}");
    }
    // A group laid out anew: its nodes move, the file stays a library group.
    let scrambled = copies[0].replace(".ron", "-scrambled.ron");
    std::fs::write(
        &scrambled,
        std::fs::read_to_string(root(files[0]))
            .unwrap()
            .replace("position: (0.0, 0.0)", "position: (5000.0, 5000.0)"),
    )
    .unwrap();
    let output = run_veneer(&[
        "fmt",
        "--arrange",
        "--width",
        "1620",
        "--height",
        "1000",
        &scrambled,
    ]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let arranged = std::fs::read_to_string(&scrambled).unwrap();
    assert!(!arranged.contains("5000.0"), "{arranged}");
    let group = veneer::graph::library::from_ron(&arranged).expect("still a library group");
    assert_eq!(group.group.nodes.len(), 32);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `veneer render graphs/wood.ron` at 96 px with `extra` arguments, as PNG bytes.
fn wood_render(extra: &[&str], library: Option<&std::path::Path>) -> Vec<u8> {
    let dir = temp_dir("groups-wood");
    let out = dir.join(format!(
        "wood-{}.png",
        extra.join("_").replace(['/', '='], "-")
    ));
    let mut command = veneer();
    command
        .current_dir(root(""))
        .args(["render", "graphs/wood.ron", "--size", "96", "-o"])
        .arg(&out)
        .args(extra)
        .env("VENEER_LIBRARY", library.unwrap_or(&dir.join("no-library")));
    let output = command.output().expect("runs");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    std::fs::read(&out).expect("written")
}

#[test]
fn editing_a_library_group_updates_the_graphs_that_link_it() {
    let default = wood_render(&[], None);
    let changed = wood_render(&["--set", "ring_frequency=0.9"], None);
    assert_ne!(default, changed);
    // The user's library has a ring_wood whose ring frequency defaults to 0.9.
    let library = temp_dir("groups-library");
    let shipped = std::fs::read_to_string(root("graphs/lib/ring_wood.ron")).expect("reads");
    let edited = shipped.replace(
        "(name: \"ring_frequency\", ty: Float, default: Float(0.5)",
        "(name: \"ring_frequency\", ty: Float, default: Float(0.9)",
    );
    assert_ne!(edited, shipped);
    std::fs::write(library.join("ring_wood.ron"), edited).expect("writes");
    assert_eq!(wood_render(&[], Some(&library)), changed);

    // A local copy (Make local) keeps its own definition.
    let local = temp_dir("groups-local").join("wood_local.ron");
    let mut graph = veneer::graph::load(&root("graphs/wood.ron")).expect("loads");
    graph.groups.get_mut("ring_wood").expect("ring_wood").linked = false;
    veneer::graph::save(&graph, &local).expect("saves");
    let out = local.with_extension("png");
    let output = veneer()
        .args(["render", "--size", "96", "-o"])
        .arg(&out)
        .arg(&local)
        .env("VENEER_LIBRARY", &library)
        .output()
        .expect("runs");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert_eq!(std::fs::read(&out).unwrap(), default);
}

/// A hand edit of a linked group's copy inside a graph file is replaced by the library's
/// version on load: said, naming the group and which version is used.
#[test]
fn a_linked_copy_that_differs_from_the_library_is_reported_on_load() {
    let dir = temp_dir("groups-linked-copy");
    let text = std::fs::read_to_string(root("graphs/wood.ron")).expect("reads");
    let edited = text.replacen(
        "(name: \"ring_frequency\", ty: Float, default: Float(0.5)",
        "(name: \"ring_frequency\", ty: Float, default: Float(0.9)",
        1,
    );
    assert_ne!(edited, text);
    let path = dir.join("wood_edited.ron");
    std::fs::write(&path, edited).expect("writes");
    let output = run_veneer(&["check", &path.to_string_lossy()]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    assert!(
        stderr.contains("the graph's copy of linked group 'ring_wood' differs from the library's")
            && stderr.contains("the library's is used"),
        "{stderr}"
    );
    // The shipped graph's copy is the library's: nothing to say.
    let shipped = run_veneer(&["check", "graphs/wood.ron"]);
    assert!(!String::from_utf8_lossy(&shipped.stderr).contains("differs"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn set_works_on_every_command() {
    let dir = temp_dir("groups-set");
    let path = |name: &str| dir.join(name).to_string_lossy().into_owned();
    // render: covered with the library test; compile: the literal changes.
    let default = run_veneer(&["compile", "graphs/wood.ron"]);
    let set = run_veneer(&["compile", "graphs/wood.ron", "--set", "ring_frequency=0.7"]);
    assert!(set.status.success());
    assert!(String::from_utf8_lossy(&set.stdout).contains("* 0.7f)"));
    assert_ne!(default.stdout, set.stdout);
    // bake: the albedo map changes.
    for (folder, extra) in [
        ("plain", vec![]),
        ("set", vec!["--set", "ring_frequency=0.7"]),
    ] {
        let mut args = vec![
            "bake",
            "graphs/wood.ron",
            "--size",
            "32",
            "--maps",
            "albedo",
            "--out-dir",
        ];
        let out = path(folder);
        std::fs::create_dir_all(&out).unwrap();
        args.push(&out);
        args.extend(extra);
        let output = run_veneer(&args);
        assert!(
            output.status.success(),
            "{}",
            String::from_utf8_lossy(&output.stderr)
        );
    }
    assert_ne!(
        std::fs::read(dir.join("plain/wood_albedo.png")).unwrap(),
        std::fs::read(dir.join("set/wood_albedo.png")).unwrap()
    );
    // snapshot: goldens approved with a preset are named after it; a different value
    // then differs from them (exit 1).
    let golden = path("golden");
    let snapshot = |extra: &[&str]| {
        let mut args = vec![
            "snapshot",
            "graphs/wood.ron",
            "--size",
            "48",
            "--golden",
            &golden,
            "--preset",
            "oak",
        ];
        args.extend(extra);
        let output = run_veneer(&args);
        let said = format!(
            "{}{}",
            String::from_utf8_lossy(&output.stdout),
            String::from_utf8_lossy(&output.stderr)
        );
        (output.status.code(), said)
    };
    let (approved, said) = snapshot(&["--update"]);
    assert_eq!(approved, Some(0), "{said}");
    assert!(dir.join("golden/wood.oak.png").is_file());
    let (same, said) = snapshot(&[]);
    assert_eq!(same, Some(0), "{said}");
    let (other, said) = snapshot(&["--set", "ring_frequency=2"]);
    assert_eq!(other, Some(1), "{said}");
    // A bad name or value is refused naming the file, with nothing written.
    let out = path("bad.png");
    let bad = run_veneer(&[
        "render",
        "graphs/wood.ron",
        "-o",
        &out,
        "--set",
        "ring_frequncy=1",
    ]);
    assert_eq!(bad.status.code(), Some(1));
    let message = String::from_utf8_lossy(&bad.stderr);
    assert!(
        message.contains("graphs/wood.ron: no parameter named 'ring_frequncy'"),
        "{message}"
    );
    assert!(!dir.join("bad.png").exists());
    let file = dir.join("params.json");
    std::fs::write(&file, r#"{"ring_frequency": 0.7}"#).unwrap();
    let from_file = run_veneer(&[
        "compile",
        "graphs/wood.ron",
        "--params-file",
        &file.to_string_lossy(),
    ]);
    assert_eq!(from_file.stdout, set.stdout);
}

#[test]
fn choices_and_toggles_take_their_words() {
    let mut graph = nested_graph();
    let inner = graph.groups.get_mut("inner").expect("inner");
    inner.inputs[0].hint = Hint::Choice(vec!["off".into(), "single".into(), "2x".into()]);
    veneer::graph::group::resolve(&mut graph);
    // An option may start with a digit.
    set(&mut graph, "gain", &Given::parse("2x").unwrap()).expect("an option");
    assert!(
        (red_at_quarter(&graph) - 0.5).abs() < 1e-9,
        "option 2 is a gain of 2"
    );
    let error = set(&mut graph, "gain", &Given::Word("triple".into())).unwrap_err();
    assert!(
        error
            .to_string()
            .contains("'triple' is not one of its options (off, single, 2x)"),
        "{error}"
    );
    let inner = graph.groups.get_mut("inner").expect("inner");
    inner.inputs[0].hint = Hint::Toggle;
    veneer::graph::group::resolve(&mut graph);
    set(&mut graph, "gain", &Given::parse("on").unwrap()).expect("a toggle");
    assert!((red_at_quarter(&graph) - 0.25).abs() < 1e-9);
    let inner = graph.groups.get_mut("inner").expect("inner");
    inner.inputs[0].hint = Hint::Slider;
    veneer::graph::group::resolve(&mut graph);
    let error = set(&mut graph, "gain", &Given::parse("0.5x").unwrap()).unwrap_err();
    assert!(
        error.to_string().contains("'0.5x' is not a number"),
        "{error}"
    );
    assert!(Given::parse("0.1,x").is_err(), "a list is of numbers");
}

#[test]
fn a_parameter_preset_looks_the_same_whatever_was_set_before() {
    let fresh = veneer::graph::load(&root("graphs/wood.ron")).expect("loads");
    let mut oak = fresh.clone();
    veneer::graph::parameters::apply_preset(&mut oak, "oak").expect("applies");
    let mut tweaked = fresh;
    veneer::graph::parameters::apply_preset(&mut tweaked, "walnut").expect("applies");
    set(&mut tweaked, "taper", &Given::Number(0.9)).expect("sets");
    veneer::graph::parameters::apply_preset(&mut tweaked, "oak").expect("applies");
    assert_eq!(veneer::graph::to_ron(&tweaked), veneer::graph::to_ron(&oak));
    let coarse = exposed(&oak)
        .into_iter()
        .find(|e| e.name == "coarse_warp")
        .unwrap();
    assert_eq!(
        coarse.value,
        Value::Float(0.35),
        "the group's default, not walnut's"
    );
}

#[test]
fn ungrouping_drops_the_preset_values_of_the_parameters_it_dissolves() {
    // A preset naming a parameter the graph does not expose does not check: ungrouping
    // the wood's group node leaves presets that still check (and still apply).
    let mut graph = veneer::graph::load(&root("graphs/wood.ron")).expect("loads");
    assert!(graph.presets.values().any(|values| !values.is_empty()));
    let group = graph
        .nodes
        .iter()
        .find(|node| matches!(node.kind, NodeKind::Group(_)))
        .expect("the wood is built on a group")
        .id;
    ungroup(&mut graph, group).expect("dissolves");
    assert!(graph.presets.values().all(|values| values.is_empty()));
    veneer::graph::check(&graph).expect("checks");
    let preset = graph.presets.keys().next().cloned().expect("a preset");
    veneer::graph::parameters::apply_preset(&mut graph, &preset).expect("applies");
}
