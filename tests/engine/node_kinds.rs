//! Every node kind the registry lists, on its own, its main inputs driven by position,
//! evaluated by the CPU evaluator (f32) and by the GPU flat render: the two
//! implementations of each node must agree (within 2/255 on 99.5% of pixels), stay
//! finite at extreme coordinates, and pass the lint's range propagation.

use crate::support::{cpu_flat_rgb8, difference, flat_rgb8};
use veneer::graph::{Basis, Category, Graph, NodeId, NodeKind, PinDefault, Value, ValueType};
use veneer::nodes::{Combine, Fbm, Split};
use veneer::render::FlatRect;

const SIZE: u32 = 48;
const RECT: FlatRect = FlatRect {
    x0: -3.0,
    z0: -2.0,
    x1: 5.0,
    z1: 6.0,
    y: 0.25,
};

/// Every kind the registry lists, with the settings its tests cover, except the output
/// and the image nodes, which read buffers (tests/engine/passes.rs covers them).
fn kinds() -> Vec<NodeKind> {
    NodeKind::examples()
        .into_iter()
        .filter(|kind| !kind.signature().outputs.is_empty() && !kind.samples())
        .collect()
}

/// Varying sources in about [-0.3, 1.3]: a scalar, a second scalar, a vec2 and a point.
struct Sources {
    scalar: NodeId,
    other: NodeId,
    pair: NodeId,
    point: NodeId,
}

fn sources(graph: &mut Graph) -> Sources {
    let point = graph.add("point", NodeKind::Transform);
    graph.set_input(point, "scale", Value::Vec3(0.2, 0.2, 0.2));
    graph.set_input(point, "offset", Value::Vec3(0.3, 0.1, 0.3));
    let scalar = graph.add("scalar", NodeKind::Project);
    graph.connect(point, "p", scalar, "p");
    graph.set_input(scalar, "direction", Value::Vec3(0.6, 0.0, 0.8));
    let other = graph.add("other", NodeKind::Project);
    graph.connect(point, "p", other, "p");
    graph.set_input(other, "direction", Value::Vec3(-0.8, 0.0, 0.6));
    graph.set_input(other, "origin", Value::Vec3(-0.8, 0.0, 0.0));
    let pair = graph.add(
        "pair",
        NodeKind::Combine(Combine {
            ty: ValueType::Vec2,
        }),
    );
    graph.connect(other, "x", pair, "y");
    graph.connect(scalar, "x", pair, "x");
    Sources {
        scalar,
        other,
        pair,
        point,
    }
}

/// A graph showing `kind`'s outputs as the albedo (a lone output as it is, several as
/// their first three channels).
fn graph_for(kind: &NodeKind) -> Graph {
    graph_driving(kind, &["albedo"], |_, _, _| false).0
}

/// The graph of [`graph_for`], except that `drive(graph, node, pin)` may feed an input
/// itself first (returning true when it did) and the outputs are shown in the material
/// inputs `targets` (see [`show_outputs`]); with how many targets it fed.
pub fn graph_driving(
    kind: &NodeKind,
    targets: &[&str],
    mut drive: impl FnMut(&mut Graph, NodeId, &veneer::graph::InputPin) -> bool,
) -> (Graph, usize) {
    let mut graph = Graph::default();
    let sources = sources(&mut graph);
    let signature = kind.signature();
    let node = graph.add("under test", kind.clone());
    if *kind == NodeKind::Transform {
        graph.set_input(node, "rotation", Value::Vec3(30.0, 45.0, 60.0));
    }
    for (index, pin) in signature.inputs.iter().enumerate() {
        if drive(&mut graph, node, pin) {
            continue;
        }
        let driven = matches!(pin.default, PinDefault::Required | PinDefault::Position)
            || ["a", "b", "c", "choice", "factor", "value", "color"].contains(&pin.name)
            || matches!(kind, NodeKind::Combine(Combine { .. }));
        if !driven {
            continue;
        }
        let (source, output) = match pin.ty {
            ValueType::Float if index % 2 == 1 => (sources.other, "x"),
            ValueType::Float => (sources.scalar, "x"),
            ValueType::Vec2 => (sources.pair, "v"),
            ValueType::Vec3 | ValueType::Color => (sources.point, "p"),
        };
        graph.connect(source, output, node, pin.name);
    }
    let material = graph.add("material", NodeKind::Material);
    let shown = show_outputs(&mut graph, node, &signature.outputs, material, targets);
    (graph, shown)
}

/// Wires `node`'s outputs into the material's colour inputs `targets`: a lone output
/// (not a vec2) as it is, several lane by lane, three lanes to each target in turn
/// (lanes past the last target are not shown). Returns how many targets it fed.
pub fn show_outputs(
    graph: &mut Graph,
    node: NodeId,
    outputs: &[veneer::graph::OutputPin],
    material: NodeId,
    targets: &[&str],
) -> usize {
    if outputs.len() == 1 && outputs[0].ty != ValueType::Vec2 {
        graph.connect(node, outputs[0].name, material, targets[0]);
        return 1;
    }
    let mut lanes = Vec::new();
    for output in outputs {
        if output.ty == ValueType::Float {
            lanes.push((node, output.name));
        } else {
            let split = graph.add(
                &format!("{} parts", output.name),
                NodeKind::Split(Split { ty: output.ty }),
            );
            graph.connect(node, output.name, split, "v");
            lanes.extend(
                [(split, "x"), (split, "y"), (split, "z")]
                    .iter()
                    .take(output.ty.width()),
            );
        }
    }
    let chunks: Vec<_> = lanes.chunks(3).zip(targets).collect();
    for (k, (chunk, target)) in chunks.iter().enumerate() {
        let color = graph.add(
            &format!("shown {k}"),
            NodeKind::Combine(Combine {
                ty: ValueType::Color,
            }),
        );
        for (&(from, pin), channel) in chunk.iter().zip(["x", "y", "z"]) {
            graph.connect(from, pin, color, channel);
        }
        graph.connect(color, "v", material, target);
    }
    chunks.len()
}

/// The registry lists every kind in the menu and in the tests, and every part of every
/// kind works together: its settings check, its pins are distinct, and its emission,
/// CPU evaluation and range propagation give one value per output.
#[test]
fn the_registry_lists_every_kind_with_every_part() {
    use std::collections::BTreeSet;
    let named: BTreeSet<&str> = NodeKind::NAMES.iter().copied().collect();
    assert_eq!(named.len(), NodeKind::NAMES.len(), "a kind is listed twice");
    let examples = NodeKind::examples();
    let menu = NodeKind::menu();
    // A group node needs a group definition, a graph bake a file beside its graph:
    // tests/engine/groups.rs and graph_bakes.rs cover them.
    let covered_elsewhere = ["Group", "GraphBake"];
    for name in (NodeKind::NAMES.iter()).filter(|name| !covered_elsewhere.contains(name)) {
        assert!(
            examples.iter().any(|k| k.name() == *name),
            "{name} has no test example"
        );
        assert!(
            menu.iter().any(|(_, k)| k.name() == *name),
            "{name} is not in the menu"
        );
    }
    for kind in &examples {
        let definition = kind.definition();
        assert!(!definition.title().is_empty(), "{kind:?} has no title");
        assert!(
            !definition.keywords().is_empty(),
            "{kind:?} has no search words"
        );
        assert!(Category::ALL.contains(&definition.category()));
        assert_eq!(
            definition.check(),
            None,
            "{kind:?}: its example fails its own check"
        );
        let signature = definition.signature();
        let pins: BTreeSet<&str> = signature.inputs.iter().map(|p| p.name).collect();
        assert_eq!(
            pins.len(),
            signature.inputs.len(),
            "{kind:?} repeats an input name"
        );
        for pin in &signature.inputs {
            let range = pin.range;
            assert!(
                range.min <= range.soft_min
                    && range.soft_min < range.soft_max
                    && range.soft_max <= range.max,
                "{kind:?} input '{}' has a bad range {range:?}",
                pin.name
            );
        }
        if signature.outputs.is_empty() {
            continue;
        }
        let graph = graph_for(kind);
        let checked = veneer::graph::check(&graph).unwrap_or_else(|e| panic!("{kind:?}: {e:?}"));
        let node = checked
            .order
            .iter()
            .find(|c| c.node.label == "under test")
            .expect("the node under test is reachable");
        let inputs = vec![[0.25f64; 3]; signature.inputs.len()];
        let surface = veneer::eval::Surface::<f64>::at([0.5, 0.25, -0.75]);
        let image = veneer::eval::Image {
            width: 2,
            height: 2,
            edge: veneer::nodes::passes::EdgeMode::Wrap,
            texels: vec![[0.25; 4]; 4],
        };
        let images: Vec<_> = (signature.inputs.iter())
            .map(|pin| pin.sampled.then_some(&image))
            .collect();
        let io = veneer::nodes::cpu::Eval::new(&node.signature.inputs, &inputs, &surface)
            .with_images(&images)
            .with_source(definition.bitmap().map(|_| &image));
        assert_eq!(
            kind.eval(&io).len(),
            signature.outputs.len(),
            "{kind:?} evaluates"
        );
        let lanes = vec![[veneer::lint::Interval::UNIT; 3]; signature.inputs.len()];
        let positions = [veneer::lint::Interval::new(-1.0, 1.0); 3];
        let mut ranges =
            veneer::nodes::ranges::Ranges::new(&node.signature.inputs, &lanes, positions);
        assert_eq!(
            definition.ranges(&mut ranges).len(),
            signature.outputs.len(),
            "{kind:?} ranges"
        );
        veneer::lint::lint(&checked, positions);
    }
}

#[test]
fn every_node_kind_agrees_between_cpu_and_gpu() {
    let mut failures = Vec::new();
    // The sine hash differs between adapters (the snapshots mark such graphs too).
    let portable = kinds()
        .into_iter()
        .filter(|kind| kind.basis() != Some(Basis::ValueSine));
    for kind in portable {
        let graph = graph_for(&kind);
        let source = veneer::codegen::compile(&graph, &Default::default())
            .unwrap_or_else(|e| panic!("{kind:?}: {e}"))
            .module
            .source;
        let diff = difference(
            &cpu_flat_rgb8(&graph, RECT, SIZE),
            &flat_rgb8(&source, RECT, SIZE),
            3,
            2,
        );
        if diff.share_outside > 0.005 {
            failures.push(format!("{kind:?}: {diff}"));
        }
    }
    assert!(
        failures.is_empty(),
        "CPU and GPU disagree:\n{}",
        failures.join("\n")
    );
}

/// The switch shows the input its choice picks (rounded to the nearest, clamped), on
/// the GPU as on the CPU: the same image as that input wired straight to the albedo.
#[test]
fn the_switch_picks_the_input_its_choice_names() {
    use veneer::nodes::Switch;
    let wired = |choice: Option<f64>| {
        let mut graph = Graph::default();
        let sources = sources(&mut graph);
        let material = graph.add("material", NodeKind::Material);
        let picked = match choice {
            Some(choice) => {
                let switch = graph.add(
                    "switch",
                    NodeKind::Switch(Switch {
                        ty: ValueType::Float,
                    }),
                );
                graph.connect(sources.scalar, "x", switch, "a");
                graph.connect(sources.other, "x", switch, "b");
                graph.set_input(switch, "c", Value::Float(0.8));
                graph.set_input(switch, "choice", Value::Float(choice));
                (switch, "result")
            }
            None => (sources.scalar, "x"),
        };
        graph.connect(picked.0, picked.1, material, "albedo");
        graph
    };
    let gpu = |graph: &Graph| {
        let module = veneer::codegen::compile(graph, &Default::default()).unwrap();
        flat_rgb8(&module.module.source, RECT, SIZE)
    };
    let only_a = gpu(&wired(None));
    let grey = cpu_flat_rgb8(&wired(Some(2.0)), RECT, SIZE);
    assert!(
        grey.iter().all(|&channel| channel == 204),
        "c is 0.8 everywhere"
    );
    for (choice, expected) in [
        (0.0, &only_a),
        (0.49, &only_a),
        (-3.0, &only_a),
        (2.0, &grey),
        (9.0, &grey),
    ] {
        let graph = wired(Some(choice));
        assert_eq!(&gpu(&graph), expected, "choice {choice} on the GPU");
        assert_eq!(
            &cpu_flat_rgb8(&graph, RECT, SIZE),
            expected,
            "choice {choice} on the CPU"
        );
    }
    let b = gpu(&wired(Some(1.0)));
    assert_ne!(b, only_a, "choice 1 shows b");
    assert_eq!(gpu(&wired(Some(1.49))), b);
}

/// Every node kind at coordinates from 1e-6 to 1e7: the CPU evaluator in f32 and f64 and
/// the GPU give finite results everywhere (precision runs out far out, values do not).
#[test]
fn every_node_kind_stays_finite_at_extreme_coordinates() {
    use veneer::eval::{Evaluator, Surface};
    let mut failures = Vec::new();
    for kind in kinds() {
        let graph = graph_for(&kind);
        let evaluator = Evaluator::new(&graph).expect("graph checks");
        for scale in [1.0e-6, 1.0e-3, 1.0, 1.0e3, 1.0e5, 1.0e7] {
            for p in [
                [scale, 0.0, 0.0],
                [-scale, scale, 0.5 * scale],
                [0.0, 0.0, 0.0],
            ] {
                let wide = evaluator.eval(&Surface::<f64>::at(p)).albedo;
                let narrow = evaluator.eval(&Surface::<f32>::at(p)).albedo;
                if !wide.iter().all(|v| v.is_finite()) || !narrow.iter().all(|v| v.is_finite()) {
                    failures.push(format!("{kind:?} at {p:?}: {wide:?} / {narrow:?}"));
                }
            }
        }
        let source = veneer::codegen::compile(&graph, &Default::default())
            .expect("compiles")
            .module
            .source;
        let renderer =
            veneer::render::FlatRenderer::new(crate::support::gpu(), &source).expect("pipeline");
        let far = FlatRect {
            x0: -1.0e7,
            z0: -1.0e7,
            x1: 1.0e7,
            z1: 1.0e7,
            y: 1.0e7,
        };
        let pixels = renderer
            .render(crate::support::gpu(), far, 8, 0.0)
            .expect("renders");
        if !pixels.iter().flatten().all(|v| v.is_finite()) {
            failures.push(format!("{kind:?} on the GPU near 1e7"));
        }
    }
    assert!(
        failures.is_empty(),
        "non-finite results:\n{}",
        failures.join("\n")
    );
}

/// The cases issue 5 names: points exactly on the wood's axis, an axis parallel to the
/// reference up vector, a zero axis, and a 64-octave fBm, all finite in f32 and f64.
#[test]
fn named_degenerate_cases_stay_finite() {
    use veneer::eval::{Evaluator, Surface};
    let finite = |graph: &Graph, p: [f64; 3]| {
        let evaluator = Evaluator::new(graph).expect("checks");
        let wide = evaluator.eval(&Surface::<f64>::at(p)).albedo;
        let narrow = evaluator.eval(&Surface::<f32>::at(p)).albedo;
        wide.iter().all(|v| v.is_finite()) && narrow.iter().all(|v| v.is_finite())
    };
    let wood = veneer::graph::load(&crate::support::root("graphs/wood.ron")).expect("wood");
    let axis = glam::DVec3::new(0.2, 1.0, -0.1).normalize();
    for t in [-1.0e4, -3.0, 0.0, 7.5, 1.0e4] {
        let p = glam::DVec3::new(25.0, 0.0, 25.0) + axis * t;
        assert!(finite(&wood, p.to_array()), "on the wood's axis at t = {t}");
    }
    for axis in [
        Value::Vec3(0.0, 1.0, 0.0),
        Value::Vec3(0.0, -1.0, 0.0),
        Value::Vec3(0.0, 0.0, 0.0),
        Value::Vec3(1e-30, 0.0, 0.0),
    ] {
        let mut graph = graph_for(&NodeKind::Cylindrical);
        let node = graph
            .nodes
            .iter()
            .find(|n| n.label == "under test")
            .unwrap()
            .id;
        graph.set_input(node, "axis", axis);
        for p in [[0.0, 0.0, 0.0], [0.0, 5.0, 0.0], [1.0, 2.0, 3.0]] {
            assert!(finite(&graph, p), "axis {axis:?} at {p:?}");
        }
    }
    let graph = graph_for(&NodeKind::Fbm(Fbm {
        basis: Basis::Gradient,
        octaves: 64,
        normalize: true,
        rotate: false,
        period: 0,
    }));
    for p in [[0.3, 0.1, 0.7], [1.0e3, 0.0, -1.0e3], [1.0e7, 1.0e7, 1.0e7]] {
        assert!(finite(&graph, p), "64-octave fBm at {p:?}");
    }
}
