//! Every node kind the registry lists, every input and every numeric setting at extreme
//! values (±3.4e38, ±1e30, ±1e20, ±0, ±1e-40, negative sizes): either `check` refuses the
//! graph with an error naming the node, or every output is finite — on the CPU in f32 and
//! f64, in the compiled WGSL (constants fold, and naga validates what it is given), and on
//! the GPU.

use crate::node_kinds::{graph_driving, show_outputs};
use veneer::eval::{Real, Surface};
use veneer::graph::{Graph, InputPin, NodeId, NodeKind, PinDefault, Value, ValueType};
use veneer::nodes::Combine;
use veneer::nodes::cpu::Eval;
use veneer::nodes::settings::Setting;
use veneer::render::{FlatChannels, FlatRect, FlatRenderer};

/// The values every input and numeric setting takes in turn.
const EXTREMES: [f64; 12] = [
    3.4e38, -3.4e38, 1.0e30, -1.0e30, 1.0e20, -1.0e20, 0.0, -0.0, 1.0e-40, -1.0e-40, -1.0, -0.5,
];

/// Ordinary points, which the inputs not under test take (or keep their defaults).
const ORDINARY: [[f64; 3]; 3] = [[0.3, 0.7, -0.2], [-1.7, 2.5, 0.9], [12.5, -3.25, 40.0]];

/// The material inputs a node's output lanes are shown in, three lanes each.
pub const TARGETS: [&str; 3] = ["albedo", "specular", "emission"];

/// The label of the node under test (the one `check` must name when it refuses).
const UNDER_TEST: &str = "under test";

/// Every kind with outputs, with the settings its tests cover, and each of those again
/// (with `every` false: the first of each kind only) with each numeric setting at its
/// extremes: counts at and past their ends, every ramp stop's position and colour at
/// each extreme value and past the f32 range.
fn variants(every: bool) -> Vec<NodeKind> {
    let mut kinds: Vec<NodeKind> = Vec::new();
    for kind in NodeKind::examples() {
        // Image nodes read buffers: tests/engine/passes.rs drives them to extremes.
        if kind.signature().outputs.is_empty() || kind.samples() {
            continue;
        }
        let first = !kinds.iter().any(|k| k.name() == kind.name());
        let count = if every || first {
            kind.clone().settings().len()
        } else {
            0
        };
        for index in 0..count {
            for value in setting_extremes(&kind, index) {
                let mut variant = kind.clone();
                value(&mut variant.settings()[index]);
                kinds.push(variant);
            }
        }
        kinds.push(kind);
    }
    kinds
}

/// A way to set setting `index` of a kind.
type SetTo = Box<dyn Fn(&mut Setting<'_>)>;

/// The extreme values of setting `index` of `kind` (none for choices and toggles, whose
/// every value the examples cover).
fn setting_extremes(kind: &NodeKind, index: usize) -> Vec<SetTo> {
    let mut kind = kind.clone();
    let settings = kind.settings();
    match &settings[index] {
        Setting::Count { range, .. } => {
            let (low, high) = (*range.start(), *range.end());
            [0, low, high, veneer::graph::MAX_OCTAVES, u32::MAX]
                .into_iter()
                .map(|n| -> SetTo {
                    Box::new(move |setting| {
                        if let Setting::Count { value, .. } = setting {
                            **value = n;
                        }
                    })
                })
                .collect()
        }
        Setting::Ramp { .. } => EXTREMES
            .into_iter()
            .chain([1.0e308, -1.0e308, 3.5e38])
            .flat_map(|x| {
                let position: SetTo = Box::new(move |setting| {
                    if let Setting::Ramp { stops, .. } = setting {
                        stops.iter_mut().for_each(|stop| stop.position = x);
                    }
                });
                let color: SetTo = Box::new(move |setting| {
                    if let Setting::Ramp { stops, .. } = setting {
                        stops.iter_mut().for_each(|stop| stop.color = (x, -x, x));
                    }
                });
                [position, color]
            })
            .collect(),
        // Files: tests/engine/bitmaps.rs and the CLI contract suite.
        Setting::Choice { .. } | Setting::Toggle { .. } | Setting::File { .. } => Vec::new(),
    }
}

/// A constant of `pin`'s type with `lanes` (a float takes the first).
fn constant(pin: &InputPin, lanes: [f64; 3]) -> Value {
    Value::Vec3(lanes[0], lanes[1], lanes[2]).convert(pin.ty)
}

/// The inputs of `kind` at ordinary point `point`: each pin's default where it has one,
/// else the point.
fn ordinary_inputs(kind: &NodeKind, point: [f64; 3]) -> Vec<[f64; 3]> {
    kind.signature()
        .inputs
        .iter()
        .map(|pin| match pin.default {
            PinDefault::Const(value) => value.components(),
            PinDefault::Position | PinDefault::Required | PinDefault::Builtin(_) => {
                constant(pin, point).components()
            }
        })
        .collect()
}

/// The cases of one kind: the inputs with one pin (all its lanes, or its first lane only)
/// or every pin at an extreme value, the others ordinary.
fn input_cases(kind: &NodeKind) -> Vec<(String, Vec<[f64; 3]>)> {
    let pins = kind.signature().inputs;
    let mut cases = Vec::new();
    for x in EXTREMES {
        for point in ORDINARY {
            let ordinary = ordinary_inputs(kind, point);
            for (k, pin) in pins.iter().enumerate() {
                let mut all = ordinary.clone();
                all[k] = constant(pin, [x; 3]).components();
                cases.push((format!("input '{}' = {x:e}", pin.name), all));
                if pin.ty != ValueType::Float {
                    let mut first = ordinary.clone();
                    first[k][0] = x;
                    cases.push((format!("input '{}'.x = {x:e}", pin.name), first));
                }
            }
        }
        let every = pins
            .iter()
            .map(|pin| constant(pin, [x; 3]).components())
            .collect();
        cases.push((format!("every input = {x:e}"), every));
    }
    cases
}

/// The outputs of `kind` for these inputs in precision `R`, at a surface point `at`.
fn outputs<R: Real>(kind: &NodeKind, inputs: &[[f64; 3]], at: [f64; 3]) -> Vec<[R; 3]> {
    let signature = kind.signature();
    let values: Vec<[R; 3]> = inputs.iter().map(|v| v.map(R::c)).collect();
    let surface = Surface::<R>::at(at);
    kind.eval(&Eval::new(&signature.inputs, &values, &surface))
}

/// A graph of `kind` alone with every input a constant (required ones through a
/// Constant node), shown as the albedo: the whole graph folds to literals.
fn constant_graph(kind: &NodeKind, inputs: &[[f64; 3]]) -> Graph {
    let mut graph = Graph::default();
    let signature = kind.signature();
    let node = graph.add(UNDER_TEST, kind.clone());
    for (pin, lanes) in signature.inputs.iter().zip(inputs) {
        let value = constant(pin, *lanes);
        if pin.default == PinDefault::Required {
            let source = graph.add(
                "source",
                NodeKind::Constant(veneer::nodes::Constant { ty: pin.ty }),
            );
            graph.set_input(source, "value", value);
            graph.connect(source, "value", node, pin.name);
        } else {
            graph.set_input(node, pin.name, value);
        }
    }
    let material = graph.add("material", NodeKind::Material);
    show_outputs(&mut graph, node, &signature.outputs, material, &TARGETS);
    graph
}

/// What is wrong with `kind` at these inputs, if anything: `check` refuses it without
/// naming the node, or it checks and an output is not finite on the CPU (f32 or f64),
/// or its compiled WGSL does not validate.
fn cpu_failure(kind: &NodeKind, inputs: &[[f64; 3]]) -> Option<String> {
    let graph = constant_graph(kind, inputs);
    if let Err(errors) = veneer::graph::check(&graph) {
        let named = errors.iter().any(|e| {
            e.node_name
                .as_deref()
                .is_some_and(|n| n.contains(UNDER_TEST))
        });
        return (!named).then(|| format!("refused without naming the node: {errors:?}"));
    }
    for at in ORDINARY {
        let wide = outputs::<f64>(kind, inputs, at);
        let narrow = outputs::<f32>(kind, inputs, at);
        // Within the f32 range in f64 too: the clamps are the same in both.
        let finite = wide
            .iter()
            .flatten()
            .all(|x| x.abs() <= f64::from(f32::MAX))
            && narrow.iter().flatten().all(|x| x.is_finite());
        if !finite {
            return Some(format!("at {at:?}: {wide:?} (f64) / {narrow:?} (f32)"));
        }
    }
    veneer::codegen::compile(&graph, &Default::default())
        .err()
        .map(|e| format!("does not compile: {e}"))
}

/// Every kind, every setting and every input at extreme values, on the CPU and through
/// the compiler: finite outputs, or a refusal naming the node.
#[test]
fn every_node_kind_stays_finite_at_extreme_settings_on_the_cpu() {
    let mut failures = Vec::new();
    for kind in variants(true) {
        for (case, inputs) in input_cases(&kind) {
            if let Some(failure) = cpu_failure(&kind, &inputs) {
                failures.push(format!("{kind:?} with {case}: {failure}"));
                break;
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} kinds fail at extreme settings:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// Feeds `pin` of `node` from the surface's time (a vector from three times the time).
fn drive_by_time(graph: &mut Graph, node: NodeId, pin: &InputPin) {
    let time = graph.add("time", NodeKind::Time);
    if pin.ty == ValueType::Float {
        graph.connect(time, "time", node, pin.name);
        return;
    }
    let combine = graph.add("times", NodeKind::Combine(Combine { ty: pin.ty }));
    for lane in ["x", "y", "z"].iter().take(pin.ty.width()) {
        graph.connect(time, "time", combine, lane);
    }
    graph.connect(combine, "v", node, pin.name);
}

/// Every kind and setting (the extremes of settings for one example of each kind) on the
/// GPU, each input in turn fed the extreme values at run time (through the time uniform),
/// the others driven by position as in the CPU–GPU comparison: every output lane finite
/// at every pixel.
#[test]
fn every_node_kind_stays_finite_at_extreme_inputs_on_the_gpu() {
    let gpu = crate::support::gpu();
    let rect = FlatRect {
        x0: -3.0,
        z0: -2.0,
        x1: 5.0,
        z1: 6.0,
        y: 0.25,
    };
    // The flat render's outputs that show the material inputs of TARGETS.
    let channels = [
        FlatChannels::AlbedoAlpha,
        FlatChannels::SpecularShininess,
        FlatChannels::Emission,
    ];
    let mut failures = Vec::new();
    for kind in variants(false) {
        let signature = kind.signature();
        for pin in &signature.inputs {
            let (graph, shown) = graph_driving(&kind, &TARGETS, |graph, node, candidate| {
                let hit = candidate.name == pin.name;
                if hit {
                    drive_by_time(graph, node, candidate);
                }
                hit
            });
            // Settings `check` refuses are the CPU test's (it checks the refusal names the node).
            let Ok(compiled) = veneer::codegen::compile(&graph, &Default::default()) else {
                continue;
            };
            let source = compiled.module.source;
            let renderer = FlatRenderer::new(gpu, &source).expect("pipeline");
            for x in EXTREMES {
                for channel in channels.iter().take(shown) {
                    let pixels = renderer
                        .render_channels(gpu, rect, 4, x as f32, *channel, |_, _| {})
                        .expect("renders");
                    if !pixels.iter().flatten().all(|v| v.is_finite()) {
                        failures.push(format!("{kind:?} with input '{}' = {x:e}", pin.name));
                    }
                }
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} cases are not finite on the GPU:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// A graph with a two-stop colour ramp over time, from 0 to a stop at `position` (in
/// order, whatever its sign): past the f32 range, `check` refuses it.
pub fn ramp_graph(position: f64) -> Graph {
    use veneer::graph::RampStop;
    let mut stops = vec![
        RampStop {
            position: 0.0,
            color: (0.0, 0.0, 0.0),
        },
        RampStop {
            position,
            color: (1.0, 1.0, 1.0),
        },
    ];
    if position < 0.0 {
        stops.reverse();
    }
    let ramp = veneer::nodes::ColorRamp {
        stops,
        interpolation: Default::default(),
    };
    let mut graph = Graph::default();
    let time = graph.add("time", NodeKind::Time);
    let node = graph.add("ramp", NodeKind::ColorRamp(ramp));
    let material = graph.add("material", NodeKind::Material);
    graph.connect(time, "time", node, "factor");
    graph.connect(node, "color", material, "albedo");
    graph
}

/// Constants at the ends of the f32 range fold through Length, Dot and Normalize into
/// finite literals that naga accepts (before: "length operation overflowed", a raw
/// validator error); colour-ramp stops past the f32 range are refused by `check`, naming
/// the node and the value (before: "numeric literal not representable").
#[test]
fn f32_extreme_constants_compile_and_ramp_stops_past_f32_are_refused_by_name() {
    use veneer::nodes::{Dot, Length, Normalize};
    let mut graph = Graph::default();
    let big = graph.add(
        "big",
        NodeKind::Combine(Combine {
            ty: ValueType::Vec3,
        }),
    );
    for (lane, x) in [("x", 3.4e38), ("y", -3.4e38), ("z", 3.4e38)] {
        graph.set_input(big, lane, Value::Float(x));
    }
    let ty = ValueType::Vec3;
    let length = graph.add("length", NodeKind::Length(Length { ty }));
    let dot = graph.add("dot", NodeKind::Dot(Dot { ty }));
    let unit = graph.add("unit", NodeKind::Normalize(Normalize { ty }));
    let material = graph.add("material", NodeKind::Material);
    graph.connect(big, "v", length, "v");
    graph.connect(big, "v", dot, "a");
    graph.connect(big, "v", dot, "b");
    graph.connect(big, "v", unit, "v");
    graph.connect(length, "length", material, "alpha");
    graph.connect(dot, "dot", material, "height");
    graph.connect(unit, "unit", material, "albedo");
    let module = veneer::codegen::compile(&graph, &Default::default())
        .unwrap_or_else(|e| panic!("extreme constants compile: {e}"))
        .module
        .source;
    let folded = veneer::eval::Evaluator::new(&graph)
        .expect("checks")
        .eval(&Surface::<f32>::at([0.0; 3]));
    assert_eq!(
        folded.alpha, 3.0e38,
        "the length clamps to the finite range"
    );
    assert_eq!(folded.height, 3.0e38, "so does the dot product");
    let third = 1.0 / 3.0f32.sqrt();
    assert!(
        (folded.albedo[0] - third).abs() < 1.0e-6,
        "{:?}",
        folded.albedo
    );
    assert!(module.contains("3e38f"), "folded into literals:\n{module}");

    for (position, shown) in [(1.0e308, "1e308"), (-1.0e308, "-1e308"), (3.5e38, "3.5e38")] {
        let graph = ramp_graph(position);
        let errors = veneer::graph::check(&graph).expect_err("refused");
        let named = |e: &veneer::graph::CheckError| {
            let text = e.to_string();
            text.contains("node 'ramp'") && text.contains(shown) && !text.contains("WGSL")
        };
        assert!(
            errors.iter().any(named),
            "not refused by name and value: {errors:?}"
        );
    }
}
