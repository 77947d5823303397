//! Graph bake nodes expanded: before a graph is checked, each Graph bake node takes in
//! the nodes of its file's graph that the chosen map reads — the file checked first,
//! its file paths rebased onto this graph's folder, its own groups and bakes expanded
//! — and becomes the Buffer node they feed (same id, label and wires), so the compiler
//! renders the map into a buffer over this material's domain like any other cut. A map
//! the file leaves unwired becomes a Constant of the Material input's value; a bake the
//! material does not read, a Constant of the input's default (its file is not read).

use super::check::CheckError;
use super::{Graph, Node, NodeId, NodeKind, PinRef, Value, Wire};
use crate::nodes::pins::PinDefault;
use crate::nodes::{Constant, GraphBake};
use std::cell::RefCell;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// How deep bakes may reach through bakes (a file baking a file baking …).
pub const MAX_BAKE_DEPTH: usize = 16;

thread_local! {
    /// The files being expanded on this thread, outermost first: a file among them
    /// that is baked again closes a cycle.
    static EXPANDING: RefCell<Vec<PathBuf>> = const { RefCell::new(Vec::new()) };
}

/// Whether `graph` has a Graph bake node.
pub fn has_bakes(graph: &Graph) -> bool {
    (graph.nodes.iter()).any(|node| matches!(node.kind, NodeKind::GraphBake(_)))
}

/// `graph` with every Graph bake node expanded (see the module's documentation); an
/// error names each node whose file cannot be read, does not check, or bakes itself.
pub fn expand(graph: &Graph) -> Result<Graph, Vec<CheckError>> {
    let mut expanded = graph.clone();
    let mut next_id = (graph.nodes.iter())
        .map(|node| node.id.0)
        .max()
        .unwrap_or(0)
        + 1;
    let mut errors = Vec::new();
    // Like an Image node's file, a bake's is read only when the material reads it (a
    // graph without a Material node fails its check anyway).
    let material = graph
        .nodes
        .iter()
        .find(|node| node.kind == NodeKind::Material);
    let read = material.map(|material| upstream_of(graph, material.id));
    for node in &graph.nodes {
        let NodeKind::GraphBake(bake) = &node.kind else {
            continue;
        };
        if read.as_ref().is_some_and(|read| !read.contains(&node.id)) {
            Map::constant(default_of(bake.map.pin())).join(&mut expanded, node, bake, &mut next_id);
            continue;
        }
        match map_of(graph, bake) {
            Ok(map) => map.join(&mut expanded, node, bake, &mut next_id),
            Err(message) => errors.push(CheckError {
                node: Some(node.id),
                node_name: Some(node.to_string()),
                message,
            }),
        }
    }
    if errors.is_empty() {
        Ok(expanded)
    } else {
        Err(errors)
    }
}

/// What a bake brings in: the nodes of the file's (flattened) graph upstream of the map
/// and the wires between them, and where the map comes from; or the value it holds
/// when unwired.
struct Map {
    nodes: Vec<Node>,
    wires: Vec<Wire>,
    source: Result<PinRef, Value>,
}

impl Map {
    /// A map holding `value` everywhere.
    fn constant(value: Value) -> Map {
        Map {
            nodes: Vec::new(),
            wires: Vec::new(),
            source: Err(value),
        }
    }

    /// Adds the map's nodes to `graph` under fresh ids from `next_id`, and turns `node`
    /// (the bake) into the Buffer they feed, or the Constant of the map's value.
    fn join(self, graph: &mut Graph, node: &Node, bake: &GraphBake, next_id: &mut u32) {
        let mut ids = BTreeMap::new();
        for mut inner in self.nodes {
            let id = NodeId(*next_id);
            *next_id += 1;
            ids.insert(inner.id, id);
            inner.id = id;
            inner.label = format!("{} · {}", node.label, inner.label);
            graph.nodes.push(inner);
        }
        let moved = |pin: &PinRef| PinRef::new(ids[&pin.node], &pin.pin);
        for wire in &self.wires {
            graph.wires.push(Wire {
                from: moved(&wire.from),
                to: moved(&wire.to),
            });
        }
        let place = (graph.nodes.iter_mut())
            .find(|n| n.id == node.id)
            .expect("the bake is in the graph");
        match self.source {
            Ok(from) => {
                place.kind = NodeKind::Buffer(bake.buffer());
                graph.wires.push(Wire {
                    from: moved(&from),
                    to: PinRef::new(node.id, "value"),
                });
            }
            Err(value) => {
                place.kind = NodeKind::Constant(Constant { ty: bake.map.ty() });
                place.inputs.insert("value".into(), value);
            }
        }
    }
}

/// The Material node's default for input `pin`.
fn default_of(pin: &str) -> Value {
    let signature = NodeKind::Material.definition().signature();
    let input = signature.inputs.iter().find(|input| input.name == pin);
    match input.expect("a Material input").default {
        PinDefault::Const(value) => value,
        PinDefault::Position | PinDefault::Required | PinDefault::Builtin(_) => {
            unreachable!("every Material input has a constant default")
        }
    }
}

/// The map `bake` takes from its file, read relative to `graph`'s folder.
fn map_of(graph: &Graph, bake: &GraphBake) -> Result<Map, String> {
    let shown = &bake.path;
    if shown.trim().is_empty() {
        return Err("no graph file chosen".into());
    }
    let file = crate::bitmaps::resolve(graph.folder.path(), shown)
        .map_err(|why| format!("graph '{shown}': {why}"))?;
    let inner =
        within(&file, || read(&file, graph)).map_err(|why| format!("graph '{shown}' {why}"))?;
    let material = (inner.nodes.iter())
        .find(|node| node.kind == NodeKind::Material)
        .expect("a graph that checks has a Material node");
    let pin = bake.map.pin();
    let wired = (inner.wires.iter()).find(|wire| wire.to.node == material.id && wire.to.pin == pin);
    let Some(wire) = wired else {
        let value = material.inputs.get(pin).cloned();
        return Ok(Map::constant(value.unwrap_or_else(|| default_of(pin))));
    };
    let upstream = upstream_of(&inner, wire.from.node);
    Ok(Map {
        nodes: (inner.nodes.iter())
            .filter(|node| upstream.contains(&node.id))
            .cloned()
            .collect(),
        wires: (inner.wires.iter())
            .filter(|wire| upstream.contains(&wire.to.node))
            .cloned()
            .collect(),
        source: Ok(wire.from.clone()),
    })
}

/// The graph in `file`, checked, its paths rebased onto `graph`'s folder, flattened
/// (groups inlined, bakes expanded); or what is wrong with it (after the file's name).
fn read(file: &Path, graph: &Graph) -> Result<Graph, String> {
    let mut inner = super::load(file).map_err(|error| match error.position {
        Some((line, column)) => format!("does not load: {line}:{column}: {}", error.message),
        None => format!("does not load: {}", error.message),
    })?;
    inner.move_to(graph.folder.clone());
    if let Err(errors) = super::check(&inner) {
        let first = errors.first().map(ToString::to_string).unwrap_or_default();
        let more = match errors.len() {
            0 | 1 => String::new(),
            n => format!(" (and {} more)", n - 1),
        };
        return Err(format!("does not check: {first}{more}"));
    }
    let flat = super::group::flatten(&inner)
        .map_err(|errors| format!("does not check: {}", errors[0]))?
        .into_owned();
    Ok(flat)
}

/// Runs `expand` with `file` marked as being expanded on this thread; refuses a file
/// already being expanded (a cycle) and bakes past [`MAX_BAKE_DEPTH`].
fn within<T>(file: &Path, expand: impl FnOnce() -> Result<T, String>) -> Result<T, String> {
    let file = file.canonicalize().unwrap_or_else(|_| file.to_path_buf());
    let stack = EXPANDING.with(|stack| stack.borrow().clone());
    if stack.contains(&file) {
        let names: Vec<String> = (stack.iter().chain([&file]))
            .map(|path| {
                format!(
                    "'{}'",
                    path.file_name().unwrap_or_default().to_string_lossy()
                )
            })
            .collect();
        return Err(format!("bakes itself: {}", names.join(" › ")));
    }
    if stack.len() >= MAX_BAKE_DEPTH {
        return Err(format!(
            "is baked {} bakes deep, more than {MAX_BAKE_DEPTH}",
            stack.len() + 1
        ));
    }
    EXPANDING.with(|stack| stack.borrow_mut().push(file));
    let result = expand();
    EXPANDING.with(|stack| stack.borrow_mut().pop());
    result
}

/// The ids of `node` and every node it reads, through `graph`'s wires.
fn upstream_of(graph: &Graph, node: NodeId) -> BTreeSet<NodeId> {
    let mut sources: BTreeMap<NodeId, Vec<NodeId>> = BTreeMap::new();
    for wire in &graph.wires {
        sources
            .entry(wire.to.node)
            .or_default()
            .push(wire.from.node);
    }
    let mut seen = BTreeSet::new();
    let mut stack = vec![node];
    while let Some(at) = stack.pop() {
        if seen.insert(at) {
            stack.extend(sources.get(&at).into_iter().flatten().copied());
        }
    }
    seen
}
