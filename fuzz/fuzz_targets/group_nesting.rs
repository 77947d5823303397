//! Group nesting on arbitrary graphs of groups (structure-aware): chains of groups
//! thousands deep, groups that contain themselves, that multiply their inner groups or
//! name groups that do not exist, pins and wires at random, on both sides of every
//! boundary. Resolving, exposing parameters, inlining, the check and the compiler never
//! panic (nor overflow the stack); the check accepts exactly what inlines; what loads
//! saves to text that loads back the same; what checks compiles to WGSL naga accepts.

#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use veneer::codegen::{CompileError, CompileOptions, ParamMode, compile};
use veneer::graph::group::{self, BOUNDARY, GroupDef, GroupInput, GroupOutput, Hint};
use veneer::graph::{Graph, Node, NodeId, NodeKind, PinRef, ValueType, Wire};
use veneer::nodes::Group;

/// Pin names the generated groups and wires choose from.
const PINS: [&str; 5] = ["result", "a", "b", "gain", "x"];

/// A node: of a kind (group nodes of `kind` name groups that may not exist), or a
/// node of the group with this index among the generated ones.
#[derive(Arbitrary, Debug)]
enum FuzzNode {
    Kind(NodeKind),
    Instance(u16),
}

/// A wire: from node, output pin, to node, input pin; nodes by index (0: the group's
/// boundary inside a definition), pins by index into [`PINS`].
type FuzzWire = [u8; 4];

#[derive(Arbitrary, Debug)]
struct FuzzGroup {
    inputs: Vec<(u8, ValueType, Option<(f64, f64)>)>,
    outputs: Vec<(u8, ValueType)>,
    nodes: Vec<FuzzNode>,
    wires: Vec<FuzzWire>,
    linked: bool,
}

#[derive(Arbitrary, Debug)]
struct FuzzGraph {
    /// Groups `chain0` › `chain1` › … nested this deep (255: 20,000 deep), a node of
    /// `chain0` at the top level.
    chain: u8,
    groups: Vec<FuzzGroup>,
    top: Vec<FuzzNode>,
    wires: Vec<FuzzWire>,
    preset: Vec<(u8, f64)>,
}

fn pin(k: u8) -> String {
    PINS[k as usize % PINS.len()].to_string()
}

/// The nodes of `nodes` (ids from 1), group nodes naming `names`.
fn nodes(fuzz: &[FuzzNode], names: &[String]) -> Vec<Node> {
    fuzz.iter()
        .enumerate()
        .map(|(k, node)| {
            let kind = match node {
                FuzzNode::Kind(kind) => kind.clone(),
                FuzzNode::Instance(_) if names.is_empty() => NodeKind::Time,
                FuzzNode::Instance(g) => {
                    NodeKind::Group(Group::named(names[*g as usize % names.len()].clone()))
                }
            };
            Node::new(NodeId(k as u32 + 1), kind)
        })
        .collect()
}

/// The wires of `fuzz` between `count` nodes (ids from 1; 0 the boundary).
fn wires(fuzz: &[FuzzWire], count: usize) -> Vec<Wire> {
    fuzz.iter()
        .map(|&[from, output, to, input]| {
            let node = |k: u8| NodeId(k as u32 % (count as u32 + 1));
            Wire {
                from: PinRef::new(node(from), &pin(output)),
                to: PinRef::new(node(to), &pin(input)),
            }
        })
        .collect()
}

fn build(fuzz: &FuzzGraph) -> Graph {
    let chain = match fuzz.chain {
        u8::MAX => 20_000,
        depth => depth as usize,
    };
    let mut names: Vec<String> = (0..fuzz.groups.len()).map(|k| format!("g{k}")).collect();
    names.extend((0..chain).map(|k| format!("chain{k}")));
    let mut graph = Graph::default();
    for (k, group) in fuzz.groups.iter().enumerate() {
        let inner = nodes(&group.nodes, &names);
        let definition = GroupDef {
            linked: group.linked,
            inputs: group
                .inputs
                .iter()
                .map(|(name, ty, range)| GroupInput {
                    name: pin(*name),
                    ty: *ty,
                    default: veneer::graph::Value::Float(0.5).convert(*ty),
                    range: *range,
                    hint: Hint::Slider,
                })
                .collect(),
            outputs: group
                .outputs
                .iter()
                .map(|(name, ty)| GroupOutput {
                    name: pin(*name),
                    ty: *ty,
                })
                .collect(),
            wires: wires(&group.wires, inner.len()),
            nodes: inner,
        };
        graph.groups.insert(names[k].clone(), definition);
    }
    for level in 0..chain {
        let kind = if level + 1 < chain {
            NodeKind::Group(Group::named(format!("chain{}", level + 1)))
        } else {
            NodeKind::Time
        };
        let definition = GroupDef {
            linked: false,
            inputs: Vec::new(),
            outputs: vec![GroupOutput {
                name: "result".into(),
                ty: ValueType::Float,
            }],
            nodes: vec![Node::new(NodeId(1), kind)],
            wires: vec![Wire {
                from: PinRef::new(NodeId(1), if level + 1 < chain { "result" } else { "time" }),
                to: PinRef::new(BOUNDARY, "result"),
            }],
        };
        graph.groups.insert(format!("chain{level}"), definition);
    }
    let mut top = nodes(&fuzz.top, &names);
    if chain > 0 {
        let id = NodeId(top.len() as u32 + 1);
        top.push(Node::new(
            id,
            NodeKind::Group(Group::named("chain0".into())),
        ));
    }
    top.push(Node::new(NodeId(top.len() as u32 + 1), NodeKind::Material));
    graph.wires = wires(&fuzz.wires, top.len());
    graph.nodes = top;
    if !fuzz.preset.is_empty() {
        let values = fuzz
            .preset
            .iter()
            .map(|(name, x)| (pin(*name), veneer::graph::Value::Float(*x)))
            .collect();
        graph.presets.insert("fuzzed".into(), values);
    }
    group::resolve(&mut graph);
    graph
}

fuzz_target!(|fuzz: FuzzGraph| {
    let graph = build(&fuzz);
    let _ = group::interfaces(&graph.groups);
    let exposed = veneer::graph::parameters::exposed(&graph);
    assert!(exposed.len() <= veneer::graph::parameters::MAX_PARAMETERS + 1);
    let flat = group::flatten(&graph);
    let checked = veneer::graph::check(&graph);
    assert!(
        checked.is_err() || flat.is_ok(),
        "the check accepted a graph that does not inline"
    );
    let saved = veneer::graph::to_ron(&graph);
    let reloaded =
        veneer::graph::from_ron(&saved).unwrap_or_else(|error| panic!("{error}\n{saved}"));
    assert_eq!(
        veneer::graph::to_ron(&reloaded),
        saved,
        "save → load → save changed the text"
    );
    if checked.is_ok() {
        for params in [ParamMode::Baked, ParamMode::Named] {
            let options = CompileOptions {
                params,
                ..Default::default()
            };
            if let Err(CompileError::Validation(error)) = compile(&graph, &options) {
                panic!("naga rejected a checked graph: {error}\n{saved}");
            }
        }
    }
});
