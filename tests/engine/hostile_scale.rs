//! Hostile input at scale (issue 18): huge graphs check in linear time, huge colour ramps,
//! long texts and floods of errors are refused or summarised at once, and primitives
//! stop at a detail that fits the machine. Big inputs are generated here, in a temporary
//! folder.

use crate::big_graphs::{chain, ramp};
use crate::support::{cpu_flat_rgb8, difference, flat_rgb8, root, temp_dir, veneer};
use std::path::Path;
use std::process::{Output, Stdio};
use std::time::{Duration, Instant};
use veneer::codegen::export::Target;
use veneer::codegen::{Detail, ParamMode};
use veneer::graph::{Graph, MathOp, NodeKind, PinRef, Value, ValueType, Wire};
use veneer::nodes::{Math, Noise};

/// Runs `veneer args` (output to files, so a flood of lines cannot block it), killing it
/// past `limit`; returns what it did and how long it took.
pub(crate) fn run_within(dir: &Path, args: &[&str], limit: Duration) -> (Output, Duration) {
    let file = |name: &str| std::fs::File::create(dir.join(name)).expect("output file");
    let start = Instant::now();
    let mut child = veneer()
        .args(args)
        .current_dir(root(""))
        .stdout(Stdio::from(file("stdout")))
        .stderr(Stdio::from(file("stderr")))
        .spawn()
        .expect("the veneer binary runs");
    let status = loop {
        if let Some(status) = child.try_wait().expect("waits") {
            break status;
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            panic!("veneer {} ran past {limit:?}", args.join(" "));
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let read = |name: &str| std::fs::read(dir.join(name)).expect("output read back");
    let output = Output {
        status,
        stdout: read("stdout"),
        stderr: read("stderr"),
    };
    (output, start.elapsed())
}

/// `veneer check` of `graph` written to `dir/name`, within `limit`.
fn check(dir: &Path, name: &str, graph: &Graph, limit: Duration) -> (Output, Duration) {
    let path = dir.join(name);
    veneer::graph::save(graph, &path).expect("graph written");
    run_within(dir, &["check", path.to_str().expect("utf-8 path")], limit)
}

/// Asserts exit code 1, no panic and a short message containing `expected`.
pub(crate) fn refused(output: &Output, expected: &str) -> String {
    let message = String::from_utf8_lossy(&output.stderr).into_owned();
    assert_eq!(output.status.code(), Some(1), "{message}");
    assert!(!message.contains("panicked"), "{message}");
    assert!(message.contains(expected), "'{expected}' not in: {message}");
    assert!(message.len() < 16_384, "{} bytes of message", message.len());
    message
}

#[test]
fn a_chain_of_100k_nodes_checks_in_linear_time() {
    // It took 58 s (10k: 1.6 s): the check looked every wire up by a linear scan and
    // naga slows down more than linearly on one long function.
    let dir = temp_dir("chain-100k");
    let (output, took) = check(&dir, "chain.ron", &chain(100_000), Duration::from_secs(120));
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{message}");
    assert!(took < Duration::from_secs(20), "took {took:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn large_materials_compile_to_part_functions_every_target_accepts() {
    let graph = chain(2_000);
    for (mode, detail) in [
        (ParamMode::Baked, Detail::Full),
        (ParamMode::Uniform, Detail::Footprint),
        (ParamMode::Storage, Detail::Footprint),
    ] {
        let options = veneer::codegen::CompileOptions {
            params: mode,
            detail,
        };
        let module = veneer::codegen::compile(&graph, &options)
            .expect("compiles and validates")
            .module;
        assert!(module.source.contains("in 8 parts of at most 256 nodes"));
        assert!(
            module
                .source
                .contains("fn veneer_material_part_8(s: VeneerSurface, ")
        );
        assert!(
            module
                .source
                .contains("struct veneer_part_7 {\n    noise_1791: f32,\n}")
        );
        assert_eq!(module.node_spans.len(), 2_000);
    }
    for (target, name, _) in Target::ALL {
        veneer::codegen::export::export(&graph, target, ParamMode::Baked)
            .unwrap_or_else(|error| panic!("{name}: {error}"));
    }
}

#[test]
fn a_material_in_parts_renders_as_the_cpu_evaluates_it() {
    // 600 additions of 0.0005 to a noise (f32 adds round the same on both sides), in
    // three functions handing the running sum on.
    let mut graph = Graph::default();
    let noise = graph.add(
        "noise",
        NodeKind::Noise(Noise {
            basis: veneer::graph::Basis::ValuePcg,
            period: 0,
        }),
    );
    let mut previous = (noise, "value");
    for k in 0..600 {
        let add = graph.add(
            &format!("add {k}"),
            NodeKind::Math(Math {
                op: MathOp::Add,
                ty: ValueType::Float,
            }),
        );
        graph.connect(previous.0, previous.1, add, "a");
        graph.set_input(add, "b", Value::Float(0.0005));
        previous = (add, "result");
    }
    let material = graph.add("material", NodeKind::Material);
    graph.connect(previous.0, previous.1, material, "albedo");
    let module = veneer::codegen::compile(&graph, &Default::default())
        .expect("compiles")
        .module;
    assert!(module.source.contains("in 3 parts"));
    let rect = veneer::render::preview_rect(&graph.preview);
    let gpu = flat_rgb8(&module.source, rect, 32);
    let cpu = cpu_flat_rgb8(&graph, rect, 32);
    let comparison = difference(&gpu, &cpu, 3, 1);
    assert_eq!(comparison.share_outside, 0.0, "{comparison:?}");
}

#[test]
fn a_ramp_of_a_million_stops_is_refused_at_once() {
    // It took 53 s at 30k stops (one line of shader code per stop) and hours at 10⁶.
    let dir = temp_dir("ramp-1m");
    let (output, took) = check(&dir, "ramp.ron", &ramp(1_000_000), Duration::from_secs(60));
    refused(
        &output,
        "node 'ramp' (#2): the colour ramp has 1,000,000 stops (at most 256)",
    );
    assert!(took < Duration::from_secs(10), "took {took:?}");
    let most = veneer::codegen::compile(&ramp(veneer::graph::MAX_RAMP_STOPS), &Default::default());
    assert!(most.is_ok(), "{:?}", most.err());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn long_texts_are_refused_naming_their_node() {
    // A 200 MB label cost 3–4 GB and a 1 GB shader: the label named every variable and
    // comment. 10⁷ characters show the same.
    let dir = temp_dir("long-texts");
    let long = "ab".repeat(5_000_000);
    let mut graph = ramp(2);
    graph.nodes[1].label = long.clone();
    let (output, _) = check(&dir, "label.ron", &graph, Duration::from_secs(60));
    let message = refused(
        &output,
        "…' (#2): the label is 10,000,000 characters long (at most 256)",
    );
    assert!(message.contains(&format!("node '{}…'", &long[..256])));

    let mut graph = ramp(2);
    graph.name = long.clone();
    graph.preview.mesh = long.clone();
    graph.frames.push(veneer::graph::Frame {
        title: long.clone(),
        min: (0.0, 0.0),
        max: (1.0, 1.0),
        color: (0.5, 0.5, 0.5),
    });
    graph.wires[1].to.pin = long.clone();
    graph.nodes[0].inputs.insert(long, Value::Float(1.0));
    let (output, _) = check(&dir, "texts.ron", &graph, Duration::from_secs(60));
    let message = refused(
        &output,
        "the graph name is 10,000,000 characters long (at most 256)",
    );
    for expected in [
        "the preview mesh name is 10,000,000 characters long (at most 4096)",
        "a frame title is 10,000,000 characters long (at most 256)",
        "node 'noise' (#1): no input named 'abab",
        "node 'material' (#3): no input named 'abab",
    ] {
        assert!(message.contains(expected), "'{expected}' not in: {message}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_million_duplicate_wires_are_summarised() {
    let dir = temp_dir("duplicate-wires");
    let mut graph = ramp(2);
    let wire = graph.wires[1].clone();
    graph.wires.extend(std::iter::repeat_n(wire, 1_000_000));
    let path = dir.join("wires.ron");
    // Saving sorts and removes duplicates, so the file is written as text.
    let text = veneer::graph::to_ron(&ramp(2));
    let line = "        (from: (node: 2, pin: \"color\"), to: (node: 3, pin: \"albedo\")),\n";
    let at = text.find(line).expect("the ramp's wire") + line.len();
    let text = format!("{}{}{}", &text[..at], line.repeat(1_000_000), &text[at..]);
    std::fs::write(&path, text).expect("graph written");
    let (output, _) = run_within(
        &dir,
        &["check", path.to_str().unwrap()],
        Duration::from_secs(120),
    );
    let message = refused(
        &output,
        "node 'material' (#3): input 'albedo' has more than one wire\n",
    );
    assert!(
        message.ends_with("wires.ron: … and 999,999 more like this\n"),
        "{message}"
    );
    assert_eq!(message.lines().count(), 2, "{message}");
    drop(graph);

    // Different errors stop after 100 lines, with a count of the rest.
    let mut graph = ramp(2);
    graph.wires.extend((0..1000).map(|k| Wire {
        from: PinRef::new(veneer::graph::NodeId(100 + k), "value"),
        to: PinRef::new(veneer::graph::NodeId(3), "alpha"),
    }));
    let (output, _) = check(&dir, "missing.ron", &graph, Duration::from_secs(60));
    let message = refused(&output, "a wire refers to node #100, which does not exist");
    assert!(
        message.ends_with("missing.ron: … and 900 more\n"),
        "{message}"
    );

    // So do warnings: 1,000 smoothsteps with equal edges.
    let mut graph = Graph::default();
    let mut previous = (graph.add("time", NodeKind::Time), "time");
    for k in 0..1000 {
        let step = graph.add(&format!("step {k}"), NodeKind::Smoothstep);
        graph.set_input(step, "edge0", Value::Float(0.5));
        graph.set_input(step, "edge1", Value::Float(0.5));
        graph.connect(previous.0, previous.1, step, "x");
        previous = (step, "result");
    }
    let material = graph.add("material", NodeKind::Material);
    graph.connect(previous.0, previous.1, material, "alpha");
    let (output, _) = check(&dir, "steps.ron", &graph, Duration::from_secs(60));
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{message}");
    assert_eq!(message.lines().count(), 101, "{message}");
    assert!(
        message.ends_with("steps.ron: … and 900 more\n"),
        "{message}"
    );
    assert!(String::from_utf8_lossy(&output.stdout).contains("ok (1000 warnings)"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_long_cycle_is_named_by_its_ends() {
    // A cycle through 100,000 nodes: one line, its ends named, the middle counted.
    let mut graph = chain(100_000);
    let last = graph.wires.len() - 1;
    graph.wires[last].to = PinRef::new(veneer::graph::NodeId(1), "scale");
    graph.wires.push(Wire {
        from: PinRef::new(veneer::graph::NodeId(99_999), "result"),
        to: PinRef::new(veneer::graph::NodeId(100_000), "alpha"),
    });
    let started = Instant::now();
    let errors = veneer::graph::check(&graph).expect_err("a cycle");
    assert!(started.elapsed() < Duration::from_secs(5));
    assert_eq!(errors.len(), 1, "{errors:?}");
    let message = errors[0].to_string();
    let ends = "cycle: 'step 99998' -> 'step 99997' -> 'noise 99996' -> 'step 99995' -> \
                … 99,991 more … -> 'noise 3' -> 'step 2' -> 'step 1' -> 'start' -> 'step 99998'";
    assert!(message.ends_with(ends), "{message}");
    assert!(message.len() < 400, "{message}");
}

#[test]
fn primitive_detail_stops_where_it_fits_this_machine() {
    // `torus:4096` (67 million triangles) ran past 60 s and 5–6 GB in `veneer mesh`.
    let dir = temp_dir("detail-cap");
    for args in [
        &["mesh", "torus:4096"][..],
        &[
            "geodesic",
            "torus:4096",
            "--sources",
            "0",
            "-o",
            "never.csv",
        ],
        &["mesh", "sphere:513"],
    ] {
        let (output, took) = run_within(&dir, args, Duration::from_secs(60));
        let message = refused(&output, "level of detail out of range");
        assert!(message.contains("1 to 512"), "{message}");
        assert!(
            message.contains("torus:512 is a million triangles: about"),
            "{message}"
        );
        assert!(took < Duration::from_secs(5), "{args:?} took {took:?}");
    }
    let help = veneer()
        .args(["geodesic", "--help"])
        .output()
        .expect("runs");
    assert!(String::from_utf8_lossy(&help.stdout).contains("level of detail up to 512"));
    std::fs::remove_dir_all(&dir).unwrap();
}
