//! Hostile groups, names and declarations (issue 32): groups nested thousands deep or
//! multiplying past a million nodes, groups with too many pins, preset and group names
//! that would lead out of their folders, and everything `check` must refuse in what a
//! graph declares. Graphs are generated here as text, as a hostile file would be.

use crate::hostile_scale::{refused, run_within};
use crate::support::{root, temp_dir, veneer};
use std::path::Path;
use std::time::Duration;

/// How long any one command may take before the test calls it a hang.
const HANG: Duration = Duration::from_secs(120);

/// The deepest nesting accepted.
const DEPTH: usize = veneer::graph::group::MAX_GROUP_DEPTH;

/// The most inputs a group shows.
const PINS: usize = veneer::graph::group::MAX_GROUP_PINS;

/// A graph whose albedo comes through groups `g0` › `g1` › … nested `depth` deep, each
/// holding `copies` nodes of the next (their results added); the innermost multiplies
/// x by its input `gain` (0.5 by default), which every level inherits, or with several
/// copies by 0.5 (inherited, the inputs would multiply too).
fn nested(depth: usize, copies: usize) -> String {
    let mut text = String::from(
        "(\n    version: 2,\n    nodes: [\n        (id: 1, label: \"top\", kind: Group(name: \"g0\")),\n        (id: 2, kind: Material),\n    ],\n    wires: [\n        (from: (node: 1, pin: \"result\"), to: (node: 2, pin: \"albedo\")),\n    ],\n    groups: {\n",
    );
    for level in 0..depth {
        let body = if level + 1 == depth {
            let inner = "outputs: [(name: \"result\", ty: Float)], nodes: [(id: 1, kind: Position), (id: 2, kind: Split(ty: Vec3)), (id: 3, kind: Math(op: Multiply, ty: Float), inputs: {\"b\": Float(0.5)})], wires: [(from: (node: 1, pin: \"position\"), to: (node: 2, pin: \"v\")), (from: (node: 2, pin: \"x\"), to: (node: 3, pin: \"a\")), (from: (node: 3, pin: \"result\"), to: (node: 0, pin: \"result\"))";
            let gain = "inputs: [(name: \"gain\", ty: Float, default: Float(0.5), range: Some((0.0, 4.0)))], ";
            let wire = ", (from: (node: 0, pin: \"gain\"), to: (node: 3, pin: \"b\"))";
            match copies {
                1 => format!("{gain}{inner}{wire}]"),
                _ => format!("{inner}]"),
            }
        } else {
            let next = level + 1;
            let mut nodes = Vec::new();
            let mut wires = Vec::new();
            for copy in 0..copies {
                nodes.push(format!(
                    "(id: {}, kind: Group(name: \"g{next}\"))",
                    copy + 1
                ));
            }
            // The copies' results summed by a chain of additions, ids after theirs.
            let mut last = (1, "result");
            for copy in 1..copies {
                let add = copies + copy;
                nodes.push(format!("(id: {add}, kind: Math(op: Add, ty: Float))"));
                wires.push(format!(
                    "(from: (node: {}, pin: \"{}\"), to: (node: {add}, pin: \"a\"))",
                    last.0, last.1
                ));
                wires.push(format!(
                    "(from: (node: {}, pin: \"result\"), to: (node: {add}, pin: \"b\"))",
                    copy + 1
                ));
                last = (add, "result");
            }
            wires.push(format!(
                "(from: (node: {}, pin: \"{}\"), to: (node: 0, pin: \"result\"))",
                last.0, last.1
            ));
            format!(
                "outputs: [(name: \"result\", ty: Float)], nodes: [{}], wires: [{}]",
                nodes.join(", "),
                wires.join(", ")
            )
        };
        text.push_str(&format!("        \"g{level}\": ({body}),\n"));
    }
    text.push_str("    },\n)\n");
    text
}

/// A graph whose albedo is group `wide`'s result, `wide` declaring `inputs` float
/// inputs (`i0`, `i1`, …) of which the first scales x, and whose `extra` text goes into
/// the graph's top level (presets, parameters).
fn wide(inputs: usize, extra: &str) -> String {
    let declared: Vec<String> = (0..inputs)
        .map(|k| {
            format!("(name: \"i{k}\", ty: Float, default: Float(0.5), range: Some((0.0, 1.0)))")
        })
        .collect();
    format!(
        "(\n    version: 2,\n    nodes: [\n        (id: 1, kind: Group(name: \"wide\")),\n        (id: 2, kind: Material),\n    ],\n    wires: [\n        (from: (node: 1, pin: \"result\"), to: (node: 2, pin: \"albedo\")),\n    ],\n    groups: {{\n        \"wide\": (inputs: [{}], outputs: [(name: \"result\", ty: Float)], nodes: [(id: 1, kind: Math(op: Multiply, ty: Float))], wires: [(from: (node: 0, pin: \"i0\"), to: (node: 1, pin: \"a\")), (from: (node: 1, pin: \"result\"), to: (node: 0, pin: \"result\"))]),\n    }},\n{extra})\n",
        declared.join(", ")
    )
}

/// Writes `text` to `dir/name` and returns the path as a string.
fn write(dir: &Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).expect("the graph is written");
    path.display().to_string()
}

/// `veneer args`, killed past [`HANG`].
fn run(dir: &Path, args: &[&str]) -> std::process::Output {
    run_within(dir, args, HANG).0
}

#[test]
fn groups_nested_past_the_limit_are_refused_naming_the_path_at_any_depth() {
    // 16,000 levels overflowed the stack of `check` (and 50,000 that of `fmt`), 1,000
    // took the driver 0.97 GB to render.
    let dir = temp_dir("groups-deep");
    for depth in [DEPTH + 1, 1_000, 20_000, 60_000] {
        let graph = write(&dir, &format!("deep-{depth}.ron"), &nested(depth, 1));
        let out = dir.join("deep.wgsl").display().to_string();
        for args in [vec!["check", &graph], vec!["compile", &graph, "-o", &out]] {
            let message = refused(
                &run(&dir, &args),
                &format!("groups nest {}", thousands(depth)),
            );
            assert!(
                message.contains(&format!("more than {DEPTH}: 'g0' › 'g1' › 'g2' › 'g3' › …")),
                "{message}"
            );
            assert!(message.contains(&format!("'g{}'", depth - 1)), "{message}");
        }
        assert!(!Path::new(&out).exists());
        // The file still loads and is rewritten as it is: only the check refuses it.
        let before = std::fs::read_to_string(&graph).unwrap();
        let output = run(&dir, &["fmt", &graph]);
        assert!(
            output.status.success(),
            "{}",
            String::from_utf8_lossy(&output.stderr)
        );
        let after = std::fs::read_to_string(&graph).unwrap();
        assert_eq!(
            after.matches("Group(name:").count(),
            before.matches("Group(name:").count()
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `n` with a comma every three digits, as messages write it.
fn thousands(n: usize) -> String {
    veneer::messages::thousands(n)
}

#[test]
fn groups_nested_to_the_limit_check_set_and_render() {
    let dir = temp_dir("groups-deepest");
    let graph = write(&dir, "deepest.ron", &nested(DEPTH, 1));
    let output = run(&dir, &["check", &graph]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let png = dir.join("deepest.png").display().to_string();
    let output = run(
        &dir,
        &[
            "render", &graph, "--size", "32", "--set", "gain=2", "-o", &png,
        ],
    );
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(std::fs::metadata(&png).is_ok_and(|m| m.len() > 0));
    // The inherited input is exposed once, through every level, with its group path.
    let loaded = veneer::graph::from_ron(&std::fs::read_to_string(&graph).unwrap()).unwrap();
    let exposed = veneer::graph::parameters::exposed(&loaded);
    assert_eq!(exposed.len(), 1);
    assert_eq!(exposed[0].group_path.len(), DEPTH);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn groups_that_multiply_past_a_million_nodes_are_refused() {
    // Two nodes of the next group at each of 24 levels stand for 2²⁴ nodes: 16 million
    // from a file of 6 kB, which inlining took without end (nor could a driver take it).
    let dir = temp_dir("groups-multiplying");
    let graph = write(&dir, "doubling.ron", &nested(24, 2));
    let limit = veneer::graph::group::MAX_INLINED_NODES as usize;
    let expected = format!("group nodes stand for more than {} nodes", thousands(limit));
    let message = refused(&run(&dir, &["check", &graph]), &expected);
    assert!(
        message.contains("group node stands for every node"),
        "{message}"
    );
    // Under the limit it inlines: 2¹⁶ copies of the innermost group's three nodes, an
    // addition in each of the 2¹⁶ - 1 others, and the material.
    let graph = write(&dir, "under.ron", &nested(17, 2));
    let flat = veneer::graph::group::flatten(
        &veneer::graph::from_ron(&std::fs::read_to_string(&graph).unwrap()).unwrap(),
    )
    .expect("inlines")
    .into_owned();
    assert_eq!(flat.nodes.len(), 3 * 65_536 + 65_535 + 1);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn groups_with_more_pins_than_the_limit_are_refused_naming_the_group() {
    let dir = temp_dir("groups-wide");
    for inputs in [PINS + 1, 100_000] {
        let graph = write(&dir, "wide.ron", &wide(inputs, ""));
        let message = refused(&run(&dir, &["check", &graph]), "group 'wide' has");
        let expected = format!(
            "{} inputs, more than the 1,024 a group may show",
            thousands(inputs)
        );
        assert!(message.contains(&expected), "{message}");
    }
    // Inherited inputs count too: two nodes of a 600-input group expose 1,200.
    let text = wide(600, "").replace(
        "    groups: {\n",
        "    groups: {\n        \"twice\": (outputs: [(name: \"result\", ty: Float)], nodes: [(id: 1, label: \"a\", kind: Group(name: \"wide\")), (id: 2, label: \"b\", kind: Group(name: \"wide\"))], wires: [(from: (node: 1, pin: \"result\"), to: (node: 0, pin: \"result\"))]),\n",
    );
    let graph = write(&dir, "twice.ron", &text);
    refused(
        &run(&dir, &["check", &graph]),
        "group 'twice' has more inputs",
    );
    // At the limit, the inputs are parameters like any others.
    let graph = write(&dir, "widest.ron", &wide(PINS, ""));
    let out = dir.join("widest.wgsl").display().to_string();
    let output = run(
        &dir,
        &["compile", &graph, "--params", "uniform", "-o", &out],
    );
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let description = std::fs::read_to_string(dir.join("widest.parameters.json")).unwrap();
    assert!(description.contains("\"i1023\""), "{description}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A graph of group `wide` with two inputs and `presets` (RON text of the map).
fn with_presets(presets: &str) -> String {
    wide(2, &format!("    presets: {presets},\n"))
}

#[test]
fn a_preset_name_never_reaches_a_path_outside_the_golden_folder() {
    let dir = temp_dir("groups-preset-name");
    let graph = write(
        &dir,
        "g.ron",
        &with_presets("{\"x/../../escape\": {\"i0\": Float(0.25)}}"),
    );
    refused(
        &run(&dir, &["check", &graph]),
        "preset name 'x/../../escape'",
    );
    let gold = dir.join("gold");
    std::fs::create_dir_all(gold.join("g.x")).unwrap();
    let gold_arg = gold.display().to_string();
    let args = [
        "snapshot",
        &graph,
        "--golden",
        &gold_arg,
        "--preset",
        "x/../../escape",
        "--update",
        "--flat",
        "preview",
        "--size",
        "8",
    ];
    let output = run(&dir, &args);
    let message = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{message}");
    assert!(
        message.contains("preset name 'x/../../escape'"),
        "{message}"
    );
    assert!(!dir.join("escape.png").exists());
    assert!(!gold.join("escape.png").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `veneer args` in the repository root, with the user library in `library`.
fn with_library(library: &Path, args: &[&str]) -> std::process::Output {
    veneer()
        .current_dir(root(""))
        .args(args)
        .env("VENEER_LIBRARY", library)
        .output()
        .expect("the veneer binary runs")
}

#[test]
fn a_linked_group_named_out_of_the_library_keeps_the_graphs_copy_and_is_refused() {
    let dir = temp_dir("groups-library-name");
    let library = dir.join("library");
    std::fs::create_dir_all(&library).unwrap();
    std::fs::create_dir_all(dir.join("victim")).unwrap();
    // The file outside the library the name leads to: a group of another output.
    let evil = "(version: 1, name: \"../victim/libevil\", group: (outputs: [(name: \"planted\", ty: Float)], nodes: [(id: 1, kind: Time)], wires: [(from: (node: 1, pin: \"time\"), to: (node: 0, pin: \"planted\"))]))\n";
    std::fs::write(dir.join("victim/libevil.ron"), evil).unwrap();
    let text = wide(2, "")
        .replace(
            "Group(name: \"wide\")",
            "Group(name: \"../victim/libevil\")",
        )
        .replace(
            "\"wide\": (inputs",
            "\"../victim/libevil\": (linked: true, inputs",
        );
    let graph = write(&dir, "g.ron", &text);
    let output = with_library(&library, &["check", &graph]);
    let message = refused(&output, "group name '../victim/libevil'");
    assert!(!message.contains("planted"), "{message}");
    // Loading keeps the graph's own copy: the name is not looked up at all.
    let loaded = veneer::graph::load(Path::new(&graph)).expect("loads");
    assert_eq!(loaded.groups["../victim/libevil"].outputs[0].name, "result");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn unreadable_library_files_are_named_in_a_warning() {
    let dir = temp_dir("groups-library-files");
    let library = dir.join("library");
    std::fs::create_dir_all(&library).unwrap();
    // The wood preset links ring_wood: a corrupt file of that name is not used, and
    // said so.
    std::fs::write(
        library.join("ring_wood.ron"),
        "(version: 1, name: \"ring_wood\", grou",
    )
    .unwrap();
    let check = |graph: &str| {
        let output = with_library(&library, &["check", graph]);
        assert!(
            output.status.success(),
            "{}",
            String::from_utf8_lossy(&output.stderr)
        );
        String::from_utf8_lossy(&output.stderr).into_owned()
    };
    let warning = check("graphs/wood.ron");
    let file = library.join("ring_wood.ron").display().to_string();
    assert!(
        warning.contains(&format!("warning: graphs/wood.ron: {file}:")),
        "{warning}"
    );
    assert!(warning.contains("keeps the graph's copy"), "{warning}");
    // A FIFO, or a link to /dev/zero, is refused at once, and said so too.
    let fifo = library.join("veined_marble.ron");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .expect("mkfifo runs");
    assert!(made.success());
    let warning = check("graphs/marble.ron");
    assert!(warning.contains(&fifo.display().to_string()), "{warning}");
    std::fs::remove_file(&library.join("ring_wood.ron")).unwrap();
    std::os::unix::fs::symlink("/dev/zero", library.join("ring_wood.ron")).unwrap();
    let warning = check("graphs/wood.ron");
    assert!(warning.contains(&file), "{warning}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The errors `check` gives `text` (a graph), joined by lines.
fn check_errors(text: &str) -> String {
    let graph = veneer::graph::from_ron(text).expect("the file loads");
    crate::support::refusal(&graph)
}

#[test]
fn check_refuses_presets_that_set_what_the_graph_does_not_take() {
    let cases = [
        (
            "{\"oak\": {\"nonsense\": Float(1.0)}}",
            "preset 'oak': no parameter named 'nonsense'",
        ),
        (
            "{\"oak\": {\"i0\": Float(7.0)}}",
            "preset 'oak': parameter 'i0' takes values from 0 to 1; 7 is outside",
        ),
        (
            "{\"oak\": {\"i1\": Vec3(0.1, 0.2, 0.3)}}",
            "preset 'oak': parameter 'i1' takes a float: 3 numbers given",
        ),
    ];
    for (presets, expected) in cases {
        let message = check_errors(&with_presets(presets));
        assert!(message.contains(expected), "{presets}: {message}");
    }
}

#[test]
fn check_refuses_ranges_defaults_and_names_a_group_cannot_have() {
    let input = "(name: \"i0\", ty: Float, default: Float(0.5), range: Some((0.0, 1.0)))";
    let long = "g".repeat(1_000_000);
    let cases: Vec<(String, &str)> = vec![
        (
            wide(1, "").replace("range: Some((0.0, 1.0))", "range: Some((5.0, 1.0))"),
            "group 'wide' input 'i0': the range (5, 1) has its minimum above its maximum",
        ),
        (
            wide(1, "").replace("range: Some((0.0, 1.0))", "range: Some((NaN, 1.0))"),
            "group 'wide' input 'i0': the range (NaN, 1) is not finite",
        ),
        (
            wide(1, "").replace("default: Float(0.5)", "default: Vec3(0.5, 0.25, 1.0)"),
            "group 'wide' input 'i0' is a float but its default is a vec3",
        ),
        (
            wide(1, "").replace("default: Float(0.5)", "default: Float(3.0)"),
            "group 'wide' input 'i0': the default 3 is outside its range, 0 to 1",
        ),
        (
            wide(1, "").replace(input, &format!("{input}, {input}")),
            "group 'wide' has two inputs named 'i0'",
        ),
        (
            wide(1, "").replace(
                "outputs: [(name: \"result\", ty: Float)]",
                "outputs: [(name: \"result\", ty: Float), (name: \"result\", ty: Color)]",
            ),
            "group 'wide' has two outputs named 'result'",
        ),
        (
            wide(1, "").replace("\"wide\"", &format!("\"{long}\"")),
            "group name 'gggg",
        ),
        (
            wide(
                1,
                "    parameters: [(name: \"gain\", node: 2, pin: \"alpha\", range: Some((1.0, 0.0)))],\n",
            ),
            "parameter 'gain': the range (1, 0) has its minimum above its maximum",
        ),
    ];
    for (text, expected) in cases {
        let message = check_errors(&text);
        assert!(message.contains(expected), "{expected}: {message}");
        assert!(message.len() < 4_096, "{} bytes of message", message.len());
    }
}

#[test]
fn files_that_give_a_name_twice_are_refused() {
    let dir = temp_dir("groups-twice");
    let graph = write(&dir, "g.ron", &wide(2, ""));
    let out = dir.join("g.wgsl").display().to_string();
    for (name, text) in [
        ("values.json", "{\"i0\": 0.25, \"i1\": 0.5, \"i0\": 0.75}"),
        ("values.ron", "{\"i0\": 0.25, \"i1\": 0.5, \"i0\": 0.75}"),
    ] {
        let values = write(&dir, name, text);
        let output = run(
            &dir,
            &["compile", &graph, "--params-file", &values, "-o", &out],
        );
        let message = refused(&output, "'i0' is given twice");
        assert!(message.contains(name), "{message}");
    }
    // In a graph file too: a group or preset named twice, a parameter twice in a preset.
    let group = "\"wide\": (inputs";
    let twice = wide(2, "").replacen(
        group,
        &format!("\"wide\": (outputs: [], nodes: []),\n        {group}"),
        1,
    );
    for text in [
        twice,
        with_presets("{\"oak\": {\"i0\": Float(0.1)}, \"oak\": {\"i0\": Float(0.2)}}"),
        with_presets("{\"oak\": {\"i0\": Float(0.1), \"i0\": Float(0.2)}}"),
    ] {
        let error = veneer::graph::from_ron(&text).expect_err("refused");
        assert!(error.to_string().contains("is given twice"), "{error}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
