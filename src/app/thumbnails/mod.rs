//! Thumbnails of node outputs in the graph: which outputs get a tile, the atlas graph
//! compiled once per structure (parameters are uniforms), which tiles changed since they
//! were drawn, and the egui texture the drawn atlas lands in.
//!
//! A tile shows one output pin over the preview square (see `probe.rs` for how each
//! type maps to a colour). Tiles go to the drawing thread only when something upstream
//! of their pin changed: a node's kind, settings or constants, a wire, the placement, the
//! code, or the time for tiles that read it.

pub(in crate::app) mod keys;
pub(in crate::app) mod level;
pub(in crate::app) mod tiles;
pub(in crate::app) mod worker;

use crate::app::preview::live::LiveMaterial;
use crate::app::preview::probe::atlas_graph_reading;
pub use crate::app::thumbnails::tiles::TILE_PIXELS;
use crate::app::thumbnails::tiles::Tiles;
use crate::app::thumbnails::worker::{Done, Job, Worker};
use crate::graph::{Graph, Node, NodeId, PinRef};
use crate::render::FlatRect;
use std::collections::BTreeSet;
use std::hash::{Hash, Hasher};
use std::sync::Arc;

/// The most tiles drawn: past it only nodes on screen get one.
pub const MAX_TILES: usize = 256;

/// The most graph nodes the atlas compiles: a tile that would take it past this is left
/// out (see [`keys::within_atlas`]).
pub const ATLAS_NODES: usize = 1_000;

/// The thumbnails' state, kept by the app between frames.
pub struct Thumbnails {
    /// Thumbnails on nodes at all (View menu, T).
    pub enabled: bool,
    /// Nodes whose thumbnail is switched off (node menu).
    pub hidden: BTreeSet<NodeId>,
    /// The atlas graph's compiles (a parameter edit never adds one).
    pub atlas: LiveMaterial,
    /// The tiles: which pins, where in the atlas, what was sent and what is drawn.
    tiles: Tiles,
    /// The Mix node selecting each tile (see `probe::AtlasGraph`).
    selectors: Vec<NodeId>,
    /// Nodes left out of the atlas, and why.
    left_out: LeftOut,
    /// The drawing thread and the job sent to it.
    drawing: Drawing,
    /// Tiles drawn so far (a tile drawn twice counts twice).
    pub tiles_drawn: u64,
    /// The pins drawn by the last job to come back.
    pub last_drawn: Vec<PinRef>,
    /// Why the last draw failed, if it did.
    pub error: Option<String>,
    /// What the tiles were last brought in step with; nothing is done again until it
    /// changes or a job comes back.
    seen: Option<Seen>,
    /// The level shown (the top level or a group), and the graph its tiles come from.
    level: level::Level,
}

/// The thread that draws the tiles, and what it was sent.
#[derive(Default)]
struct Drawing {
    worker: Option<Worker>,
    /// A job is out.
    in_flight: bool,
    /// Tiles changed while a job was out: sent once it comes back.
    waiting: bool,
}

/// Nodes whose tiles the atlas leaves out.
#[derive(Default)]
struct LeftOut {
    /// The structure `broken` was found in ([`Stamp::structure`]): it is forgotten when
    /// that changes.
    structure: u64,
    /// Nodes whose code fails to compile: left out with what reads them.
    broken: BTreeSet<NodeId>,
    /// Nodes with too much upstream for the atlas (more than [`ATLAS_NODES`] with the
    /// tiles before them).
    too_deep: rustc_hash::FxHashSet<NodeId>,
}

/// Where the edited graph stands: its revision, bumped on every change, and its
/// structure's, bumped when a change may change the code (the app's `Revision`); and
/// whether its material renders passes (see [`LiveMaterial::renders_passes`]): then the
/// tiles show the unit tile rather than the preview square; and whether a pointer
/// button is held (a drag), when the tiles of an atlas with rendered passes wait, so that
/// the preview's drafts have the cores.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stamp {
    pub revision: u64,
    pub structure: u64,
    pub unit_tile: bool,
    pub held: bool,
}

/// What the tiles depend on besides the drawing thread: the graph's revision, the
/// time and which pins would get a tile.
#[derive(Clone, PartialEq)]
struct Seen {
    revision: u64,
    time: u32,
    unit_tile: bool,
    held: bool,
    pins: Vec<PinRef>,
}

impl Default for Thumbnails {
    fn default() -> Thumbnails {
        Thumbnails {
            enabled: true,
            hidden: BTreeSet::new(),
            atlas: LiveMaterial::default(),
            tiles: Tiles::default(),
            selectors: Vec::new(),
            left_out: LeftOut::default(),
            drawing: Drawing::default(),
            tiles_drawn: 0,
            last_drawn: Vec::new(),
            error: None,
            seen: None,
            level: level::Level::default(),
        }
    }
}

impl Thumbnails {
    /// Whether `node` shows its thumbnail.
    pub fn shows(&self, node: NodeId) -> bool {
        self.enabled && !self.hidden.contains(&node)
    }

    /// The graph view shows the top level (`None`) or group `group`: tiles are asked
    /// for by its nodes from now on (inside a group, each drawn as it works in the
    /// group's first instance).
    pub fn show_level(&mut self, group: Option<&str>) {
        self.level.show(group);
    }

    /// The pins (of the tiles' graph) that would get a tile: the first output of every
    /// node of the level shown that shows its thumbnail and, in graphs with more of them
    /// than [`MAX_TILES`], only of those on screen (`on_screen`; `None` while the view
    /// moves: those of the last call), up to that many; and `hovered` (the wire under
    /// the pointer).
    fn candidates(
        &self,
        graph: &Graph,
        hovered: Option<&PinRef>,
        on_screen: Option<&dyn Fn(NodeId) -> bool>,
    ) -> Vec<PinRef> {
        // Pins are made (a name each) only for the nodes that get one: while the view of
        // a big graph moves, this runs every frame.
        let shown = |node: &Node| self.level.shown_node(node.id);
        let showing = |node: &&Node| {
            shown(node).is_some_and(|id| self.shows(id))
                && !node.kind.signature().outputs.is_empty()
        };
        let first_output =
            |node: &Node| PinRef::new(node.id, node.kind.signature().outputs[0].name);
        let nodes = graph.nodes.iter().filter(showing);
        let mut pins: BTreeSet<PinRef> = if nodes.clone().nth(MAX_TILES).is_some() {
            let Some(on_screen) = on_screen else {
                let last = self.seen.as_ref().map(|seen| seen.pins.clone());
                return last.unwrap_or_default();
            };
            // (Whether a node is on screen is asked first: it is the cheaper question.)
            let nodes = graph.nodes.iter();
            let on_screen = nodes.filter(|node| shown(node).is_some_and(on_screen));
            let on_screen = on_screen.filter(showing).take(MAX_TILES);
            on_screen.map(first_output).collect()
        } else {
            nodes.map(first_output).collect()
        };
        pins.extend(hovered.and_then(|pin| self.level.drawn_pin(pin)));
        pins.into_iter().collect()
    }

    /// The candidates that get a tile: those not reading a node that fails to compile,
    /// as many as the atlas takes (the others are noted as too deep); and the nodes
    /// they read.
    fn wanted(
        &mut self,
        graph: &Graph,
        candidates: &[PinRef],
    ) -> (Vec<PinRef>, rustc_hash::FxHashSet<NodeId>) {
        let mut pins = candidates.to_vec();
        if !self.left_out.broken.is_empty() {
            let tainted = graph.downstream(self.left_out.broken.iter().copied());
            pins.retain(|pin| !tainted.contains(&pin.node));
        }
        let fit = keys::within_atlas(graph, &pins, ATLAS_NODES);
        self.left_out.too_deep = fit.too_deep;
        (fit.pins, fit.upstream)
    }

    /// Whether `node`'s tile is left out for having more upstream than the atlas takes.
    pub fn too_deep(&self, node: NodeId) -> bool {
        let drawn = self.level.drawn_node(node);
        drawn.is_some_and(|node| self.left_out.too_deep.contains(&node))
    }

    /// Brings the tiles in step with `graph` at `stamp` (whose revision changes whenever
    /// the graph does): recompiles the atlas if its structure changed, sends the tiles
    /// whose inputs changed to the drawing thread, and takes in what it drew. The work
    /// grows with the tiles' upstream, not with the graph (see [`Graph::part`]). `hovered` is the
    /// output pin of the wire under the pointer; `on_screen` which nodes are on screen
    /// (`None` while the view moves). Does nothing when neither these nor the thread's
    /// work changed since the last call.
    pub fn update(
        &mut self,
        ctx: &egui::Context,
        graph: &Graph,
        stamp: Stamp,
        hovered: Option<&PinRef>,
        time: f32,
        on_screen: Option<&dyn Fn(NodeId) -> bool>,
    ) {
        // A job come back matters here only when tiles wait to be sent.
        let received = self.receive(ctx) && std::mem::take(&mut self.drawing.waiting);
        // A big graph's atlas compiles on a thread of its own.
        self.atlas.work_in_background(ctx);
        self.atlas
            .small_too(crate::app::preview::background::is_big(graph));
        let compiled = self.atlas.receive();
        // Inside a group, the tiles come from the graph flattened.
        let flat = self.level.flattened(graph, stamp.revision);
        if self.level.in_group() && flat.is_none() {
            self.tiles.clear();
            return;
        }
        let graph: &Graph = flat.as_deref().unwrap_or(graph);
        let seen = Seen {
            revision: stamp.revision,
            time: time.to_bits(),
            unit_tile: stamp.unit_tile,
            held: stamp.held,
            pins: self.candidates(graph, hovered, on_screen),
        };
        if !received && !compiled && self.seen.as_ref() == Some(&seen) {
            return;
        }
        let candidates = seen.pins.clone();
        self.seen = Some(seen);
        if self.left_out.structure != stamp.structure {
            self.left_out.structure = stamp.structure;
            self.left_out.broken.clear();
        }
        // A node that fails to compile is left out (with what reads it) and the rest
        // compiled again; each round leaves out at least one more node.
        let atlas = loop {
            let (pins, upstream) = self.wanted(graph, &candidates);
            let Some(atlas) = atlas_graph_reading(graph, &pins, upstream) else {
                self.tiles.clear();
                return;
            };
            self.atlas.update(&atlas.graph);
            if self.atlas.is_compiling() {
                // Tiles are drawn once the code for them is in.
                return;
            }
            let failed: Vec<NodeId> = self.atlas.errors.keys().flatten().copied().collect();
            if failed.is_empty()
                || failed
                    .iter()
                    .all(|node| self.left_out.broken.contains(node))
            {
                break atlas;
            }
            self.left_out.broken.extend(failed);
        };
        let Some(compiled) = &self.atlas.compiled else {
            return;
        };
        if !self.atlas.errors.is_empty() {
            return;
        }
        let passes = &compiled.passes;
        if stamp.held && !passes.is_empty() && !passes.uploads_only() {
            // Drawn when the drag ends (`Seen::held` changes then).
            return;
        }
        // Each tile's key hashes what is upstream of the node its colour comes from.
        let sources: rustc_hash::FxHashMap<PinRef, NodeId> =
            atlas.pins.iter().cloned().zip(atlas.sources).collect();
        self.tiles.lay_out(atlas.pins);
        self.selectors = atlas.selectors;
        if self.drawing.in_flight {
            self.drawing.waiting = true;
            return;
        }
        // (The atlas holds everything upstream of its pins, wires included.)
        let upstream = crate::app::thumbnails::keys::upstream_hashes(&atlas.graph, time);
        let rect = if stamp.unit_tile {
            crate::bake::UNIT_TILE
        } else {
            placement(graph)
        };
        let slots = &compiled.module.params;
        let values = crate::app::preview::live::slot_values(&atlas.graph, slots);
        let generation = self.atlas.generation;
        let changed = self
            .tiles
            .take_changed(|pin| tile_key(&upstream, pin, sources.get(pin), generation, rect));
        let tiles: Vec<_> = changed
            .into_iter()
            .map(|index| (index, tile_params(&values, slots, &self.selectors, index)))
            .collect();
        if tiles.is_empty() {
            return;
        }
        let wake = ctx.clone();
        let worker = self
            .drawing
            .worker
            .get_or_insert_with(|| Worker::start(move || wake.request_repaint()));
        worker.send(Job {
            generation: self.atlas.generation,
            wgsl: Arc::from(compiled.source()),
            slots: slots.len(),
            passes: (!passes.is_empty()).then(|| Arc::new(passes.clone())),
            layout: self.tiles.layout(),
            rect,
            time,
            shared: values.clone(),
            tiles,
        });
        self.drawing.in_flight = true;
    }

    /// Takes in a finished job (its tiles' pixels go into the texture); returns whether
    /// one came back.
    fn receive(&mut self, ctx: &egui::Context) -> bool {
        let Some(worker) = &self.drawing.worker else {
            return false;
        };
        let done = match worker.try_done() {
            Ok(Some(done)) => done,
            Ok(None) => return false,
            Err(()) => {
                self.drawing.worker = None;
                self.drawing.in_flight = false;
                self.drawing.waiting = true;
                return true;
            }
        };
        self.drawing.in_flight = false;
        let Done {
            layout,
            tiles,
            pixels,
        } = done;
        let pixels = match pixels {
            Ok(pixels) => pixels,
            Err(error) => {
                self.error = Some(error);
                return true;
            }
        };
        self.error = None;
        self.tiles_drawn += tiles.len() as u64;
        self.last_drawn = tiles
            .iter()
            .filter_map(|index| self.tiles.pins().get(*index).cloned())
            .collect();
        self.tiles.take_in(ctx, layout, &tiles, pixels);
        true
    }

    /// The output pins that have a tile, in tile order.
    pub fn pins(&self) -> &[PinRef] {
        self.tiles.pins()
    }

    /// Whether every tile has been drawn as it is now (nothing sent or waiting).
    pub fn settled(&self) -> bool {
        !self.drawing.in_flight && !self.atlas.is_compiling() && self.tiles.all_ready()
    }

    /// The texture and the part of it showing `pin` (of a node of the level shown),
    /// once drawn.
    pub fn tile(&self, pin: &PinRef) -> Option<(egui::TextureId, egui::Rect)> {
        self.tiles.tile(&self.level.drawn_pin(pin)?)
    }

    /// The RGBA8 pixels of `pin`'s tile (of a node of the level shown), rows from the
    /// top, once drawn.
    pub fn tile_pixels(&self, pin: &PinRef) -> Option<Vec<[u8; 4]>> {
        self.tiles.tile_pixels(&self.level.drawn_pin(pin)?)
    }
}

/// The parameter values that make the atlas module show tile `index`: `values` (the
/// atlas graph's, see [`crate::codegen::param_values`]) with every selector's factor 0 but tile
/// `index`'s, which is 1.
pub fn tile_params(
    values: &[[f32; 4]],
    slots: &[crate::codegen::ParamSlot],
    selectors: &[NodeId],
    index: usize,
) -> Vec<[f32; 4]> {
    let mut tile = values.to_vec();
    let selected = selectors.get(index);
    let selectors: rustc_hash::FxHashSet<&NodeId> = selectors.iter().collect();
    for (slot, param) in slots.iter().enumerate() {
        if selectors.contains(&param.node) {
            tile[slot][0] = if selected == Some(&param.node) {
                1.0
            } else {
                0.0
            };
        }
    }
    tile
}

/// The square the tiles sample in a graph without rendered passes (with them, the unit
/// tile: see [`Stamp::unit_tile`]): the preview's placement (centre ± size in x
/// and z, at the centre's y), as the inspector's thumbnail shows it.
pub fn placement(graph: &Graph) -> FlatRect {
    let (x, y, z) = graph.preview.center;
    let size = graph.preview.size;
    FlatRect {
        x0: x - size,
        z0: z - size,
        x1: x + size,
        z1: z + size,
        y,
    }
}

/// What a tile shows depends on: its pin, the nodes upstream of its colour's `source`
/// (the pin's node, or the sampler copy placing it; kinds, settings, constants) and the
/// wires between them, the code, the placement, and the time when some node upstream
/// reads it — `upstream` holds all but the pin, code and placement.
fn tile_key(
    upstream: &rustc_hash::FxHashMap<NodeId, u64>,
    pin: &PinRef,
    source: Option<&NodeId>,
    generation: u64,
    rect: FlatRect,
) -> u64 {
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    pin.hash(&mut hasher);
    generation.hash(&mut hasher);
    format!("{rect:?}").hash(&mut hasher);
    upstream.get(source.unwrap_or(&pin.node)).hash(&mut hasher);
    hasher.finish()
}

/// The thumbnail of `node` as a node body shows it: its tile, or an empty square of the
/// same size until the tile is first drawn (saying why on hover when it never will be).
pub fn show_tile(ui: &mut egui::Ui, thumbnails: &Thumbnails, node: &crate::graph::Node) {
    let size = egui::Vec2::splat(TILE_PIXELS as f32);
    let output = node.kind.signature().outputs.first().map(|o| o.name);
    let tile = output.and_then(|output| thumbnails.tile(&PinRef::new(node.id, output)));
    // Named for screen readers (and the editor's tests), drawn or not yet.
    let name = format!("{} thumbnail", node.title());
    match tile {
        Some((texture, uv)) => {
            ui.add(egui::Image::new((texture, size)).uv(uv).alt_text(name));
        }
        None => {
            let (_, square) = ui.allocate_exact_size(size, egui::Sense::hover());
            square.widget_info(|| {
                egui::WidgetInfo::labeled(egui::WidgetType::Image, true, name.clone())
            });
            if thumbnails.too_deep(node.id) {
                square.on_hover_text(format!(
                    "No thumbnail: with the thumbnails before it, it needs more than \
                     {ATLAS_NODES} nodes upstream, more than the thumbnails' shader takes"
                ));
            }
        }
    }
}
