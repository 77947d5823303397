//! The graphs behind thumbnails: the same graph with one node's output shown as the
//! material's albedo (the inspector's thumbnail), or with many outputs side by side, a
//! parameter picking which (the node thumbnails' atlas).
//!
//! How an output shows as a colour: a colour as itself, a float as grey, a vec2 as red
//! and green (blue 0), a vec3 remapped from [-1, 1] to [0, 1] (`v * 0.5 + 0.5`), each
//! clamped to [0, 1] when drawn; a number naming things (an instance's id) as a colour
//! per value. An output a sampler places per instance (upstream of a
//! re-evaluated input) shows as placed: in every instance, as that instance sees it, so
//! an Instance node's random numbers and ids show one per instance.

use crate::graph::{Graph, MathOp, NodeId, NodeKind, PinRef, Value, ValueType, Wire};
use crate::nodes::{Combine, Math, Mix, Split};
use rustc_hash::{FxHashMap, FxHashSet};

/// The part of `graph` that `node` reads, its first output wired into the material's
/// albedo (see [`Graph::part`]), or `None` for the material node itself and nodes
/// without outputs.
pub fn probe_graph(graph: &Graph, node: NodeId) -> Option<Graph> {
    let output = *graph.node(node)?.kind.signature().outputs.first()?;
    let material = graph.material()?.id;
    let pin = PinRef::new(node, output.name);
    let sampler = Placing::of(graph).sampler(node);
    let upstream = graph.upstream(sampler.into_iter().chain([node]));
    let mut probe = part_with(graph, upstream, material);
    // Flat: the material's other inputs (a height, a bump) would light or move it.
    cut_material(&mut probe, material);
    let (colour, pin) = shown_colour(&mut probe, &pin, output.ty, sampler);
    probe.connect(colour, pin, material, "albedo");
    Some(probe)
}

/// Which sampler places a node per instance, over an index of each node's readers made
/// once per graph (an atlas asks for every tile).
struct Placing<'g> {
    graph: &'g Graph,
    readers: FxHashMap<NodeId, Vec<&'g Wire>>,
}

impl<'g> Placing<'g> {
    fn of(graph: &'g Graph) -> Placing<'g> {
        let mut readers: FxHashMap<NodeId, Vec<&Wire>> = FxHashMap::default();
        for wire in &graph.wires {
            readers.entry(wire.from.node).or_default().push(wire);
        }
        Placing { graph, readers }
    }

    /// The sampler that places `node` per instance: the first node found downstream of
    /// it that reads it through a re-evaluated input (nodes are looked at nearest first).
    fn sampler(&self, node: NodeId) -> Option<NodeId> {
        let mut seen = FxHashSet::default();
        let mut queue = std::collections::VecDeque::from([node]);
        while let Some(at) = queue.pop_front() {
            for wire in self.readers.get(&at).into_iter().flatten() {
                let reader = self.graph.node(wire.to.node)?;
                let re_evaluated = (reader.kind.signature().input(&wire.to.pin))
                    .is_some_and(|(_, pin)| pin.re_evaluated);
                if re_evaluated {
                    return Some(reader.id);
                }
                if seen.insert(reader.id) {
                    queue.push_back(reader.id);
                }
            }
        }
        None
    }
}

/// Adds to `graph` what shows `pin` (of type `ty`) as a colour (see the module's
/// comment): as it is, or as placed by `sampler` (the one placing it, in `graph` with its
/// upstream), through a copy of that sampler drawing it in every instance untinted.
fn shown_colour(
    graph: &mut Graph,
    pin: &PinRef,
    ty: ValueType,
    sampler: Option<NodeId>,
) -> (NodeId, &'static str) {
    let (colour, colour_pin) = as_colour(graph, pin, ty);
    let Some(sampler) = sampler else {
        return (colour, colour_pin);
    };
    let Some(original) = graph.node(sampler).cloned() else {
        return (colour, colour_pin);
    };
    let placed = graph.add("probe placed", original.kind.clone());
    let untinted = Value::Color(1.0, 1.0, 1.0);
    if let Some(node) = graph.node_mut(placed) {
        node.inputs = original.inputs.clone();
        node.inputs.insert("colour_low".into(), untinted);
        node.inputs.insert("colour_high".into(), untinted);
        node.inputs
            .insert("luminance_random".into(), Value::Float(0.0));
    }
    let wires: Vec<_> = (graph.wires.iter())
        .filter(|wire| wire.to.node == sampler && wire.to.pin != "pattern_colour")
        .cloned()
        .collect();
    for wire in wires {
        graph.connect(wire.from.node, &wire.from.pin, placed, &wire.to.pin);
    }
    graph.connect(colour, colour_pin, placed, "pattern_colour");
    (placed, "colour")
}

/// Places `probe`'s preview square on the unit tile (x and z from 0 to 1), where a
/// texture graph's flat view and thumbnails show it.
pub fn over_the_unit_tile(probe: &mut Graph) {
    probe.preview.center = (0.5, 0.0, 0.5);
    probe.preview.size = 0.5;
}

/// The part of `graph` made of `keep` (the nodes some outputs read) and its `material`
/// node (see [`Graph::part`]): what a thumbnail needs, however big the graph is.
fn part_with(graph: &Graph, mut keep: FxHashSet<NodeId>, material: NodeId) -> Graph {
    keep.insert(material);
    graph.part(&keep)
}

/// Cuts every wire into node `material` of `graph` and clears its constants, so that
/// only what is wired to it afterwards shows (and gets code).
fn cut_material(graph: &mut Graph, material: NodeId) {
    graph.wires.retain(|wire| wire.to.node != material);
    if let Some(node) = graph.node_mut(material) {
        node.inputs.clear();
    }
}

/// The graph behind the thumbnail atlas (see [`atlas_graph`]).
pub struct AtlasGraph {
    /// The material shows tile k's pin where the factor of `selectors[k]` is 1 and every
    /// other selector's is 0.
    pub graph: Graph,
    /// The output each tile shows, in tile order.
    pub pins: Vec<PinRef>,
    /// The Mix node whose `factor` selects each tile.
    pub selectors: Vec<NodeId>,
    /// The node each tile's colour comes from, in tile order: everything the tile shows
    /// is upstream of it.
    pub sources: Vec<NodeId>,
}

/// `graph` with the material's albedo showing one of `pins` (outputs of its nodes),
/// chosen by uniform parameters: a chain of colour Mix nodes, one per pin, each mixing
/// the chain so far with its pin's colour by a factor left as a parameter. The
/// material's other inputs are cut, and only the nodes the pins read are copied.
/// `None` when the graph has no material or no pin is an output of its nodes.
pub fn atlas_graph(graph: &Graph, pins: &[PinRef]) -> Option<AtlasGraph> {
    atlas_graph_reading(graph, pins, graph.upstream(pins.iter().map(|pin| pin.node)))
}

/// [`atlas_graph`] when the nodes the pins read, `upstream`, are known already.
pub fn atlas_graph_reading(
    graph: &Graph,
    pins: &[PinRef],
    upstream: FxHashSet<NodeId>,
) -> Option<AtlasGraph> {
    let material = graph.material()?.id;
    let placing = Placing::of(graph);
    let samplers: Vec<Option<NodeId>> = pins.iter().map(|pin| placing.sampler(pin.node)).collect();
    let mut upstream = upstream;
    upstream.extend(graph.upstream(samplers.iter().flatten().copied()));
    let mut atlas = part_with(graph, upstream, material);
    cut_material(&mut atlas, material);
    let (mut shown, mut selectors, mut chain) = (Vec::new(), Vec::new(), None);
    let mut sources = Vec::new();
    for (pin, sampler) in pins.iter().zip(samplers) {
        let Some(output) = graph
            .node(pin.node)
            .and_then(|node| node.kind.signature().output(&pin.pin).map(|(_, o)| *o))
        else {
            continue;
        };
        let (colour, colour_pin) = shown_colour(&mut atlas, pin, output.ty, sampler);
        sources.push(colour);
        let tile = atlas.add(
            "thumbnail tile",
            NodeKind::Mix(Mix {
                ty: ValueType::Color,
            }),
        );
        atlas.connect(colour, colour_pin, tile, "b");
        if let Some(previous) = chain {
            atlas.connect(previous, "result", tile, "a");
        }
        chain = Some(tile);
        shown.push(pin.clone());
        selectors.push(tile);
    }
    atlas.connect(chain?, "result", material, "albedo");
    Some(AtlasGraph {
        graph: atlas,
        pins: shown,
        selectors,
        sources,
    })
}

/// Adds to `graph` what shows `pin` (of type `ty`) as a colour (see the module's
/// comment); returns the node and output pin that give the colour.
fn as_colour(graph: &mut Graph, pin: &PinRef, ty: ValueType) -> (NodeId, &'static str) {
    let output = graph
        .node(pin.node)
        .and_then(|node| node.kind.signature().output(&pin.pin).map(|(_, o)| *o));
    let source = output.map_or("value", |output| output.name);
    if output.is_some_and(|output| output.identity) {
        // A colour per whole number: white noise's colour of the lattice cell it names.
        let colours = graph.add("probe colour per value", NodeKind::WhiteNoise);
        graph.connect(pin.node, source, colours, "p");
        return (colours, "color");
    }
    match ty {
        ValueType::Float | ValueType::Color => (pin.node, source),
        ValueType::Vec2 => {
            let split = graph.add(
                "probe split",
                NodeKind::Split(Split {
                    ty: ValueType::Vec2,
                }),
            );
            let combine = graph.add(
                "probe colour",
                NodeKind::Combine(Combine {
                    ty: ValueType::Color,
                }),
            );
            graph.connect(pin.node, source, split, "v");
            graph.connect(split, "x", combine, "x");
            graph.connect(split, "y", combine, "y");
            (combine, "v")
        }
        ValueType::Vec3 => {
            let half = Value::Vec3(0.5, 0.5, 0.5);
            let scale = graph.add(
                "probe half",
                NodeKind::Math(Math {
                    op: MathOp::Multiply,
                    ty: ValueType::Vec3,
                }),
            );
            let shift = graph.add(
                "probe colour",
                NodeKind::Math(Math {
                    op: MathOp::Add,
                    ty: ValueType::Vec3,
                }),
            );
            graph.connect(pin.node, source, scale, "a");
            graph.set_input(scale, "b", half);
            graph.connect(scale, "result", shift, "a");
            graph.set_input(shift, "b", half);
            (shift, "result")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::codegen::compile;

    #[test]
    fn every_node_of_the_presets_can_be_probed() {
        for (name, _) in crate::app::PRESETS {
            let graph = crate::app::preset(name).unwrap();
            for node in &graph.nodes {
                match probe_graph(&graph, node.id) {
                    Some(probe) => {
                        compile(&probe, &Default::default())
                            .unwrap_or_else(|e| panic!("{name} {node}: {e}"));
                    }
                    None => assert_eq!(node.kind, NodeKind::Material),
                }
            }
        }
    }

    #[test]
    fn every_output_of_the_presets_compiles_in_one_atlas() {
        for (name, _) in crate::app::PRESETS {
            let graph = crate::app::preset(name).unwrap();
            let pins: Vec<PinRef> = graph
                .nodes
                .iter()
                .flat_map(|node| {
                    let outputs = node.kind.signature().outputs;
                    outputs
                        .iter()
                        .map(|output| PinRef::new(node.id, output.name))
                        .collect::<Vec<_>>()
                })
                .collect();
            let atlas = atlas_graph(&graph, &pins).unwrap();
            assert_eq!(atlas.pins, pins);
            compile(&atlas.graph, &Default::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
        }
    }

    #[test]
    fn a_probe_shows_the_node_flat_even_when_it_feeds_the_materials_height() {
        let mut graph = crate::app::preset("wood").unwrap();
        let material = graph.material().unwrap().id;
        let group = graph.nodes.iter().find(|n| n.id != material).unwrap().id;
        let output = graph.node(group).unwrap().kind.signature().outputs[0].name;
        graph.connect(group, output, material, "height");
        let probe = probe_graph(&graph, group).unwrap();
        let into_material: Vec<&str> = probe
            .wires
            .iter()
            .filter(|wire| wire.to.node == material)
            .map(|wire| wire.to.pin.as_str())
            .collect();
        assert_eq!(
            into_material,
            ["albedo"],
            "only the probed output reaches it"
        );
    }

    #[test]
    fn a_placed_instance_node_shows_one_grey_and_one_colour_per_instance() {
        use crate::nodes::formulas::instances::TileBlend;
        let mut graph = Graph::default();
        let instance = graph.add("instance", NodeKind::Instance);
        let sampler = graph.add(
            "sampler",
            NodeKind::TileSampler(crate::nodes::TileSampler {
                blend: TileBlend::Max,
            }),
        );
        graph.set_input(sampler, "columns", Value::Float(4.0));
        graph.set_input(sampler, "rows", Value::Float(4.0));
        graph.connect(instance, "random", sampler, "pattern_colour");
        let material = graph.add("material", NodeKind::Material);
        graph.connect(sampler, "colour", material, "albedo");
        for output in ["random", "id"] {
            let pins = [PinRef::new(instance, output)];
            let mut atlas = atlas_graph(&graph, &pins).unwrap();
            assert_ne!(atlas.sources, [instance], "shown through a sampler");
            let selector = atlas.selectors[0];
            atlas.graph.set_input(selector, "factor", Value::Float(1.0));
            let evaluator = crate::eval::Evaluator::new(&atlas.graph).unwrap();
            // The centres of the sixteen cells: each instance's own grey or colour.
            let mut seen = std::collections::BTreeSet::new();
            for k in 0..16 {
                let (column, row) = (f64::from(k % 4), f64::from(k / 4));
                let centre = [0.25 * (column + 0.5), 0.0, 0.25 * (row + 0.5)];
                let surface = evaluator.flat_surface(centre);
                let albedo = evaluator.eval::<f64>(&surface).albedo;
                assert!(albedo.iter().all(|c| (0.0..1.0).contains(c)), "{albedo:?}");
                seen.insert(albedo.map(f64::to_bits));
            }
            assert_eq!(seen.len(), 16, "{output}: one value per instance");
        }
        let pins = [PinRef::new(instance, "random")];
        // Not placed, an Instance node is zero at the shaded point.
        let mut unplaced = graph.clone();
        unplaced.wires.retain(|wire| wire.from.node != instance);
        let plain = atlas_graph(&unplaced, &pins).unwrap();
        assert_eq!(plain.sources, [instance]);
    }
}
