//! The live compile loop: a structural edit recompiles the material (parameters as
//! uniforms), a parameter edit does not; a failed compile keeps the last good material.

use crate::app::preview::background::{Latest, Outcome, Request, Snapshot, is_big};
use crate::codegen::{CompileError, Compiled, SurfaceUse, param_values};
use crate::graph::{Graph, NodeId, Value};
use std::collections::BTreeMap;

/// The material the preview shows, kept in step with the edited graph.
#[derive(Default)]
pub struct LiveMaterial {
    /// Structure of the graph last compiled (nodes, kinds and settings, wires), and the
    /// detail it was compiled with.
    structure: Option<Structure>,
    /// The last graph that compiled, in uniform mode.
    pub compiled: Option<Compiled>,
    /// Errors of the last compile, by node (`None`: not tied to a node).
    pub errors: BTreeMap<Option<NodeId>, String>,
    /// How many times the graph was compiled (parameter edits never count).
    pub compiles: u64,
    /// Bumped whenever the module's code changes, so the preview knows to rebuild its pipeline.
    pub generation: u64,
    /// Numerical hazards of the graph, by node (one message per line).
    pub warnings: Warnings,
    /// Noise detail: footprint-aware unless the user asks for every octave.
    pub full_detail: bool,
    /// Parameters past [`UNIFORM_SLOTS`](crate::app::preview::background::UNIFORM_SLOTS)
    /// in a storage buffer instead of a uniform block.
    storage: bool,
    /// Where big graphs are compiled and linted on a thread of their own: the context
    /// woken when that is done (`None`: every graph at once).
    background: Option<egui::Context>,
    /// Small graphs too go to a thread (the thumbnails' atlas of a big graph: a part of
    /// it, but one that may grow to hundreds of nodes with the next edit).
    small_too: bool,
    /// The compile running on its thread, if one is, and the latest one asked for since
    /// (each with the structure key it works out, when not known when it started).
    compiling: Latest<(Outcome, Option<Structure>)>,
    /// The lint running on its thread, if one is, and the latest one asked for since.
    linting: Latest<Warnings>,
}

/// Numerical hazards by node, one message per line: of the top level's nodes, and of
/// the nodes inside each group definition (whose messages also show on the group node
/// they were inlined from).
#[derive(Clone, Debug, Default)]
pub struct Warnings {
    /// By top-level node; a group node's name the nodes inside it.
    pub top: BTreeMap<NodeId, String>,
    /// By group definition, then by the node's id inside it; each message says which
    /// instance it was found in.
    pub in_groups: BTreeMap<String, BTreeMap<NodeId, String>>,
}

impl Warnings {
    /// The messages of the level shown: the top level, or inside group `group`.
    pub fn of_level(&self, group: Option<&str>) -> &BTreeMap<NodeId, String> {
        static NONE: BTreeMap<NodeId, String> = BTreeMap::new();
        match group {
            None => &self.top,
            Some(name) => self.in_groups.get(name).unwrap_or(&NONE),
        }
    }
}

/// Adds `line` to the lines of `entry`, unless it has it already.
fn add_line(entry: &mut String, line: &str) {
    if entry.lines().any(|known| known == line) {
        return;
    }
    if !entry.is_empty() {
        entry.push('\n');
    }
    entry.push_str(line);
}

/// What decides a graph's code ([`structure`]) and the noise detail asked for.
type Structure = (Graph, bool);

/// What decides the generated code: nodes with their kinds and settings, and the wires.
/// Labels, positions, constant values (inside groups too) except image nodes' (which may
/// be baked into their passes, as a blur's radius is), frames, preview settings and
/// library links are left out: they never need a recompile.
pub(in crate::app) fn structure(graph: &Graph) -> Graph {
    let mut skeleton = graph.clone();
    skeleton.name.clear();
    skeleton.frames.clear();
    skeleton.preview = Default::default();
    for group in skeleton.groups.values_mut() {
        // Following the library or not changes no code.
        group.linked = false;
        for node in &mut group.nodes {
            node.label.clear();
            node.position = (0.0, 0.0);
            if !node.kind.samples() {
                node.inputs.clear();
            }
        }
    }
    for node in &mut skeleton.nodes {
        node.label.clear();
        node.position = (0.0, 0.0);
        if node.kind == crate::graph::NodeKind::Material {
            // What the material's unwired bump, height and alpha are decides what the
            // pipeline does: kept as whether each shows, so that crossing that line
            // recompiles and nothing else does.
            node.inputs.retain(|pin, value| {
                SurfaceUse::input_shows(pin, value, graph.alpha).is_some_and(|shows| {
                    *value = Value::Float(f64::from(u8::from(shows)));
                    true
                })
            });
        } else if !node.kind.samples() {
            node.inputs.clear();
        }
    }
    skeleton
}

/// The numerical hazards of `graph`, by node.
fn warnings_of(graph: &Graph) -> Warnings {
    let mut warnings = Warnings::default();
    let Ok(checked) = crate::graph::check(graph) else {
        return warnings;
    };
    let origins: rustc_hash::FxHashMap<NodeId, &crate::graph::Origin> = checked
        .order
        .iter()
        .filter_map(|inlined| Some((inlined.node.id, inlined.node.origin.as_deref()?)))
        .collect();
    for lint in crate::lint::lint(&checked, crate::lint::preview_positions(graph)) {
        let Some(origin) = origins.get(&lint.node) else {
            add_line(warnings.top.entry(lint.node).or_default(), &lint.message);
            continue;
        };
        add_line(
            warnings.top.entry(origin.top).or_default(),
            &lint.to_string(),
        );
        let inside = warnings.in_groups.entry(origin.definition.clone());
        let line = format!("{} (in {})", lint.message, origin.groups);
        add_line(inside.or_default().entry(origin.id).or_default(), &line);
    }
    warnings
}

/// The values of parameter slots `slots` for `graph`, its groups inlined first as the
/// compile inlined them (the slots name the inlined nodes).
pub(in crate::app) fn slot_values(
    graph: &Graph,
    slots: &[crate::codegen::ParamSlot],
) -> Vec<[f32; 4]> {
    match crate::graph::group::flatten(graph) {
        Ok(flat) => param_values(&flat, slots),
        Err(_) => param_values(graph, slots),
    }
}

impl LiveMaterial {
    /// Whether the last material that compiled renders passes over its domain (not
    /// only uploads): a texture graph, drawn flat over the unit tile (see
    /// [`crate::render::LiveRenderer`]), as its thumbnails are too.
    pub fn renders_passes(&self) -> bool {
        (self.compiled.as_ref())
            .is_some_and(|compiled| !compiled.passes.is_empty() && !compiled.passes.uploads_only())
    }

    /// A live material that moves its parameters to a storage buffer when they pass
    /// what a uniform block holds, so that graphs of any size compile for the preview
    /// ([`ParamMode::Storage`]).
    pub fn in_storage() -> LiveMaterial {
        LiveMaterial {
            storage: true,
            ..LiveMaterial::default()
        }
    }

    /// [`LiveMaterial::in_storage`] that compiles big graphs ([`is_big`]) on a thread
    /// of its own, waking `ctx` when done.
    pub fn in_background(ctx: &egui::Context) -> LiveMaterial {
        let mut live = LiveMaterial::in_storage();
        live.work_in_background(ctx);
        live
    }

    /// From now on, compiles and lints big graphs ([`is_big`]) on a thread of their
    /// own, waking `ctx` when done.
    pub fn work_in_background(&mut self, ctx: &egui::Context) {
        if self.background.is_none() {
            self.background = Some(ctx.clone());
        }
    }

    /// Whether graphs of any size are compiled on a thread of their own (once
    /// [`LiveMaterial::work_in_background`] was called).
    pub fn small_too(&mut self, small_too: bool) {
        self.small_too = small_too;
    }

    /// Recompiles if the graph's structure changed since the last call; returns whether it did
    /// (a big graph's compile may still run: see [`LiveMaterial::receive`]).
    pub fn update(&mut self, graph: &Graph) -> bool {
        let key = (structure(graph), self.full_detail);
        if self.structure.as_ref() == Some(&key) {
            return false;
        }
        self.compile(&Snapshot::new(graph), Some(key));
        true
    }

    /// Forgets the material shown, so that a graph opened in place of another shows its
    /// own material or none, never the other graph's (a failed compile keeps the last
    /// good material only while the same document is edited).
    pub fn forget(&mut self) {
        self.compiling.forget();
        self.structure = None;
        self.compiled = None;
        self.errors.clear();
        self.generation += 1;
    }

    /// Compiles the graph, known to have changed its structure (no comparison made).
    pub fn recompile(&mut self, snapshot: &Snapshot) {
        self.compile(snapshot, None);
    }

    /// Compiles the graph, whose structure key is `key` (worked out here when `None`):
    /// at once, or on a thread of its own when it is big (the key too).
    fn compile(&mut self, snapshot: &Snapshot, key: Option<Structure>) {
        let graph = snapshot.graph;
        self.compiles += 1;
        let detail = self.full_detail;
        let request = Request {
            full_detail: self.full_detail,
            storage: self.storage,
        };
        match &self.background {
            Some(ctx) if self.small_too || is_big(graph) => {
                let graph = snapshot.shared();
                let known = key.is_some();
                self.structure = key;
                let compile = move || {
                    let key = (!known).then(|| (structure(&graph), detail));
                    (request.compile(&graph), key)
                };
                self.compiling.start(compile, ctx.clone());
            }
            _ => {
                self.compiling.forget();
                self.structure = Some(key.unwrap_or_else(|| (structure(graph), detail)));
                self.install(request.compile(graph));
            }
        }
    }

    /// Takes in the compile and the lint finished on their threads, if they are;
    /// returns whether the compile was.
    pub fn receive(&mut self) -> bool {
        if let Some(warnings) = self.linting.outcome() {
            self.warnings = warnings;
        }
        let Some((outcome, key)) = self.compiling.outcome() else {
            return false;
        };
        if key.is_some() {
            self.structure = key;
        }
        self.install(outcome);
        true
    }

    /// Whether a compile runs on its thread (the preview shows the last material).
    pub fn is_compiling(&self) -> bool {
        self.compiling.busy()
    }

    /// Makes a compile's outcome the material shown: a failed compile keeps the last
    /// good material and names the nodes at fault.
    fn install(&mut self, outcome: Outcome) {
        self.errors.clear();
        match outcome {
            Ok(compiled) => {
                // Nodes the output does not reach are pruned: the code may well be
                // unchanged. What the pipeline does with it (alpha mode, relief) may not.
                if self.compiled.as_ref().is_none_or(|old| {
                    old.source() != compiled.source()
                        || old.uses() != compiled.uses()
                        || !old.passes.same_code(&compiled.passes)
                }) {
                    self.generation += 1;
                }
                self.compiled = Some(compiled);
            }
            Err(CompileError::Check(errors)) => {
                for error in errors {
                    let entry = self.errors.entry(error.node).or_default();
                    if !entry.is_empty() {
                        entry.push('\n');
                    }
                    entry.push_str(&error.message);
                }
            }
            Err(CompileError::Validation(error)) => {
                self.errors.insert(error.node, error.message);
            }
        }
    }

    /// Finds the numerical hazards of `graph` (constants matter here, unlike for
    /// compiling); the editor calls it once per revision of the graph. A big graph's
    /// are found on a thread of their own (the last ones stay meanwhile).
    pub fn lint(&mut self, snapshot: &Snapshot) {
        let graph = snapshot.graph;
        match &self.background {
            Some(ctx) if self.small_too || is_big(graph) => {
                let graph = snapshot.shared();
                let lint = move || warnings_of(&graph);
                self.linting.start(lint, ctx.clone());
            }
            _ => {
                self.linting.forget();
                self.warnings = warnings_of(graph);
            }
        }
    }

    /// The uniform values of the current module for `graph`.
    pub fn params(&self, graph: &Graph) -> Vec<[f32; 4]> {
        self.compiled
            .as_ref()
            .map(|compiled| slot_values(graph, &compiled.module.params))
            .unwrap_or_default()
    }

    /// One line for the status bar: the first error, or `None` when the graph compiles.
    pub fn status(&self, graph: &Graph) -> Option<String> {
        let (node, message) = self.errors.iter().next()?;
        let first_line = message.lines().next().unwrap_or_default();
        Some(match (*node).and_then(|id| graph.node(id)) {
            Some(node) => format!("{node}: {first_line}"),
            None => first_line.to_string(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::app::preview::background::BACKGROUND_NODES;
    use crate::graph::{NodeKind, Value};
    use crate::nodes::{Noise, Worley};

    fn graph() -> (Graph, NodeId, NodeId) {
        let mut graph = Graph::default();
        let noise = graph.add(
            "noise",
            NodeKind::Noise(Noise {
                basis: crate::graph::Basis::Gradient,
                period: 0,
            }),
        );
        let material = graph.add("material", NodeKind::Material);
        graph.connect(noise, "value", material, "albedo");
        (graph, noise, material)
    }

    #[test]
    fn parameter_edits_never_recompile_and_structural_edits_do() {
        let (mut graph, noise, material) = graph();
        let mut live = LiveMaterial::default();
        assert!(live.update(&graph));
        let slot = live
            .compiled
            .as_ref()
            .unwrap()
            .module
            .params
            .iter()
            .position(|p| p.pin == "scale")
            .unwrap();
        graph.set_input(noise, "scale", Value::Float(7.5));
        graph.node_mut(noise).unwrap().label = "renamed".into();
        assert!(!live.update(&graph));
        assert_eq!(live.params(&graph)[slot][0], 7.5);
        graph.wires.clear();
        graph.connect(noise, "value", material, "alpha");
        assert!(live.update(&graph));
        assert_eq!(live.compiles, 2);
        let generation = live.generation;
        graph.add(
            "unused",
            NodeKind::Worley(Worley {
                feature: crate::graph::WorleyFeature::F1,
                metric: crate::graph::Metric::Euclidean,
                octaves: 1,
                period: 0,
                points: crate::graph::FeaturePoints::Hashed,
            }),
        );
        assert!(live.update(&graph), "a new node is a structural edit");
        assert_eq!(
            live.generation, generation,
            "but an unconnected one leaves the code, and the pipeline, as they were"
        );
    }

    #[test]
    fn constants_inside_a_group_are_parameters_too() {
        let mut graph = crate::graph::preset("wood").expect("the wood preset");
        let mut live = LiveMaterial::default();
        assert!(live.update(&graph));
        assert!(live.errors.is_empty(), "{:?}", live.errors);
        let before = live.params(&graph);
        let definition = graph.groups.get_mut("ring_wood").expect("ring_wood");
        let shade = definition
            .nodes
            .iter_mut()
            .find(|node| node.label == "tint shade")
            .expect("the tint shade");
        shade.inputs.insert("b".into(), Value::Float(0.25));
        shade.position = (5.0, 5.0);
        assert!(!live.update(&graph), "an inner constant does not recompile");
        let after = live.params(&graph);
        let changed: Vec<_> = before.iter().zip(&after).filter(|(a, b)| a != b).collect();
        assert_eq!(changed.len(), 1, "one slot follows the constant");
        assert_eq!(changed[0].1[0], 0.25);
    }

    #[test]
    fn a_failed_compile_keeps_the_last_good_material_and_names_the_node() {
        let (mut graph, _, material) = graph();
        let mut live = LiveMaterial::default();
        live.update(&graph);
        let good = live.generation;
        let smooth = graph.add("edge", NodeKind::Smoothstep);
        graph.connect(smooth, "result", material, "alpha");
        live.update(&graph);
        assert_eq!(live.generation, good);
        assert!(live.compiled.is_some());
        assert!(live.errors.contains_key(&Some(smooth)));
        assert_eq!(
            live.status(&graph).unwrap(),
            "node 'edge' (#3): input 'x' (float) must be connected"
        );
    }

    #[test]
    fn big_graphs_compile_on_their_own_thread_and_small_ones_at_once() {
        let ctx = egui::Context::default();
        let (small, _, _) = graph();
        let mut live = LiveMaterial::in_background(&ctx);
        assert!(live.update(&small));
        assert!(!live.is_compiling(), "a small graph compiles in the frame");
        assert!(live.compiled.is_some());
        // A chain of Math nodes past the limit.
        let (mut big, noise, material) = graph();
        let mut previous = noise;
        for k in 0..BACKGROUND_NODES {
            let next = big.add(
                &format!("step {k}"),
                NodeKind::Math(crate::nodes::Math {
                    op: crate::graph::MathOp::Add,
                    ty: crate::graph::ValueType::Float,
                }),
            );
            big.connect(previous, if k == 0 { "value" } else { "result" }, next, "a");
            previous = next;
        }
        big.connect(previous, "result", material, "albedo");
        let generation = live.generation;
        assert!(live.update(&big));
        assert!(live.is_compiling(), "a big one on its thread");
        assert_eq!(
            live.generation, generation,
            "the last material stays meanwhile"
        );
        let started = std::time::Instant::now();
        while !live.receive() {
            assert!(
                started.elapsed().as_secs() < 120,
                "the compile never came back"
            );
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
        assert!(!live.is_compiling());
        assert!(live.errors.is_empty(), "{:?}", live.errors);
        assert_eq!(live.generation, generation + 1, "then the new one is in");
    }

    #[test]
    fn a_hazard_inside_a_group_shows_inside_it_and_on_the_group_node() {
        let mut graph = crate::graph::preset("wood").unwrap();
        let definition = graph.groups.get_mut("ring_wood").unwrap();
        let sharp = definition
            .nodes
            .iter_mut()
            .find(|node| node.label == "ring sharp")
            .unwrap();
        // Equal edges: a hard step.
        sharp.inputs.insert("edge0".into(), Value::Float(0.85));
        let sharp = sharp.id;
        let warnings = warnings_of(&graph);
        let inside = warnings.of_level(Some("ring_wood"));
        assert!(
            inside[&sharp].contains("a hard step") && inside[&sharp].contains("group 'wood'"),
            "{warnings:?}"
        );
        let group_node = graph
            .nodes
            .iter()
            .find(|node| node.label == "wood")
            .unwrap();
        let on_group = &warnings.of_level(None)[&group_node.id];
        assert!(
            on_group.contains("ring sharp") && on_group.contains("a hard step"),
            "{on_group}"
        );
        assert!(warnings.of_level(Some("no such group")).is_empty());
    }
}
