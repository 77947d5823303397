//! Keeping the followers of the document in step after each frame's panels, and
//! measuring where the main thread's time goes. Every change is an edit
//! ([`crate::graph::edit::GraphEdit`], `session::commands`) that bumps the revision and
//! says what it changed: a structure change recompiles, a value does not, and the lint,
//! the thumbnails, the dirty mark and the title follow the revision. No frame compares
//! or copies the whole graph to find out whether something changed.

use crate::app::VeneerApp;
use crate::app::chrome::frame_clock::FrameProfile;
use crate::app::preview::background::Snapshot;
use crate::graph::edit::{Change, Level};
use crate::graph::{Graph, NodeId, NodeKind};
use std::time::{Duration, Instant};

/// The graph's revision: bumped on every change, and what the followers (the compile,
/// the lint, the dirty mark) last took in.
#[derive(Default)]
pub(in crate::app) struct Revision {
    pub number: u64,
    /// Bumped with `number` whenever a change may change the code (a node, a wire, a
    /// setting, the material's constants) and when the document is replaced: what a
    /// follower keyed by the graph's structure compares instead of the graph.
    pub structure: u64,
    /// Frames that took edits in from the graph view (for tests: idle frames never do).
    pub reads: u64,
    /// The document was changed from outside the editor's own panels (a script or a
    /// test, through `document_mut`): the graph as it was before, to make the change
    /// one undoable step on the next frame.
    pub outside: Option<Graph>,
    /// Whether a change since the last compile changed the structure (compile), or
    /// may change the code (compare the structure first).
    recompile: Recompile,
    /// The noise detail compiled with (a setting of the preview's), `None` before the
    /// first compile.
    detail: Option<bool>,
    /// The revision last linted (`None` before the first: a graph opened with a hazard
    /// shows it at once).
    linted: Option<u64>,
    /// The revision whose dirty mark was worked out (`None`: work it out again, after
    /// a save or a load).
    dirty_known: Option<u64>,
    /// Whether a gesture (a drag, a grab) is under way: its edits are one undo step.
    pub gesture: bool,
}

impl Revision {
    /// Takes in `changes` of one edit to `graph`: a new revision, compiled again when
    /// the code may change (a structure or setting, a constant of the material node,
    /// which decides what its pipeline does, or of an image node, which its passes may
    /// hold).
    pub fn changed(&mut self, changes: &[Change], graph: &Graph) {
        if changes.is_empty() {
            return;
        }
        self.number += 1;
        let mut needed_now = Recompile::No;
        for change in changes {
            let needed = match change {
                Change::Structure => Recompile::Compile,
                Change::Settings => Recompile::Compare,
                Change::Value {
                    level: Level::Top,
                    node,
                    ..
                } if is_material(graph, *node) => Recompile::Compare,
                Change::Value { level, node, .. } if samples(graph, level, *node) => {
                    Recompile::Compare
                }
                Change::Value { .. } | Change::Layout => Recompile::No,
            };
            needed_now = needed_now.max(needed);
        }
        self.recompile = self.recompile.max(needed_now);
        if needed_now != Recompile::No {
            self.structure += 1;
        }
    }

    /// The document was replaced (opened, new, recovered): every follower starts over.
    pub fn replaced(&mut self) {
        self.number += 1;
        self.structure += 1;
        self.recheck();
    }

    /// The document was saved or replaced: its dirty mark is worked out again.
    pub fn recheck(&mut self) {
        self.dirty_known = None;
    }
}

/// What the material needs after the changes since its last compile.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord)]
pub(in crate::app) enum Recompile {
    /// Nothing: values and layout only.
    #[default]
    No,
    /// Compared with the structure compiled, compiled if that changed (settings, the
    /// material's constants).
    Compare,
    /// Compiled (nodes, wires or node settings changed).
    Compile,
}

/// Whether node `id` of the top level is the material node.
fn is_material(graph: &Graph, id: NodeId) -> bool {
    graph
        .node(id)
        .is_some_and(|node| node.kind == NodeKind::Material)
}

/// Whether node `id` of `level` reads an input as a buffer (an image node).
fn samples(graph: &Graph, level: &Level, id: NodeId) -> bool {
    let nodes = match level {
        Level::Top => &graph.nodes,
        Level::Group(name) => match graph.groups.get(name) {
            Some(group) => &group.nodes,
            None => return false,
        },
    };
    (nodes.iter()).any(|node| node.id == id && node.kind.samples())
}

impl VeneerApp {
    /// Before the panels: a gesture starts when a button goes down (its edits are one
    /// undo step).
    pub(in crate::app) fn before_edits(&mut self, ctx: &egui::Context) {
        if self.holding(ctx) {
            self.begin_gesture();
        }
    }

    /// After the panels: takes in the graph view's edits, recompiles if needed, ends the
    /// gesture once let go, autosaves (the frame's total is filled in when it ends).
    pub(in crate::app) fn after_edits(&mut self, ctx: &egui::Context) {
        let mut clock = Instant::now();
        let mut lap = || {
            let now = Instant::now();
            std::mem::replace(&mut clock, now).elapsed()
        };
        let held = self.holding(ctx);
        if held {
            // (Ctrl+D's copies start following the mouse after the frame's start.)
            self.begin_gesture();
        }
        let before = self.session.revision.number;
        self.take_in_outside_change();
        self.take_in_view_edits();
        if !held && self.session.revision.gesture {
            self.session.revision.gesture = false;
            self.session.document.history.end_gesture();
        }
        if self.session.revision.number != before {
            // What was drawn before the graph view (the status bar, the inspector)
            // shows the change in the next frame.
            ctx.request_repaint();
        }
        let revision = self.session.revision.number;
        let sync = lap();
        // A big graph's compile, done on its thread: the preview, drawn before, shows
        // it in the next frame.
        if self.preview.live.receive() {
            ctx.request_repaint();
        }
        let detail = Some(self.preview.live.full_detail);
        let recompile = std::mem::take(&mut self.session.revision.recompile);
        let snapshot = Snapshot::new(&self.session.document.graph);
        if recompile == Recompile::Compile {
            self.preview.live.recompile(&snapshot);
        } else if recompile == Recompile::Compare || self.session.revision.detail != detail {
            self.preview.live.update(snapshot.graph);
        }
        self.session.revision.detail = detail;
        let compile = lap();
        // The lint and the dirty mark wait for a drag to end (they read every node).
        if self.session.revision.linted != Some(revision) && !held {
            self.session.revision.linted = Some(revision);
            self.preview.live.lint(&snapshot);
        }
        // (The autosave writes a big graph from the same copy.)
        let copy = snapshot.into_copy();
        let lint = lap();
        let time = self.preview.state.view.time;
        let hovered = self.canvas.hovered_wire.as_ref();
        // Asked only of graphs with more nodes than tiles: the nodes on screen, none
        // when they are outlines, and while the view moves the same as before.
        let navigation = &self.canvas.navigation;
        let visible = std::cell::OnceCell::new();
        let on_screen = |node: NodeId| {
            visible
                .get_or_init(|| {
                    if navigation.outlines(self.canvas.snarl.node_ids().count()) {
                        return Default::default();
                    }
                    let shown = navigation.on_screen();
                    let ids = shown.filter_map(|id| self.canvas.snarl.get_node(id).map(|n| n.id));
                    ids.collect::<rustc_hash::FxHashSet<NodeId>>()
                })
                .contains(&node)
        };
        let view = (!navigation.moving()).then_some(&on_screen as &dyn Fn(NodeId) -> bool);
        let graph = &self.session.document.graph;
        let stamp = crate::app::thumbnails::Stamp {
            revision,
            structure: self.session.revision.structure,
            unit_tile: self.preview.live.renders_passes(),
            held,
        };
        self.thumbnails
            .update(ctx, graph, stamp, hovered, time, view);
        let thumbnails = lap();
        let known = self.session.revision.dirty_known;
        if known != Some(revision) {
            if held && known.is_some() {
                // Edited during the drag; whether back to what was saved, once let go
                // (or saved meanwhile).
                self.session.dirty = true;
            } else {
                self.session.revision.dirty_known = Some(revision);
                self.session.dirty = self.session.document.is_dirty();
            }
        }
        let title = self.session.document.title(self.session.dirty);
        if title != self.session.title {
            ctx.send_viewport_cmd(egui::ViewportCommand::Title(title.clone()));
            self.session.title = title;
        }
        self.autosave_tick(ctx, copy);
        let history = lap();
        self.chrome.profile = FrameProfile {
            total: Duration::ZERO,
            cpu: Duration::ZERO,
            sync,
            compile,
            lint,
            thumbnails,
            history,
        };
    }

    /// Whether a button is held, nodes follow the mouse or a field has the keyboard:
    /// edits then belong to a gesture (a drag, a grab, a name or number typed is one
    /// undo step).
    fn holding(&self, ctx: &egui::Context) -> bool {
        ctx.input(|input| input.pointer.any_down())
            || self.canvas.grab.is_moving()
            || ctx.memory(|memory| memory.focused().is_some())
    }

    /// Starts a gesture unless one is under way.
    fn begin_gesture(&mut self) {
        if !self.session.revision.gesture {
            self.session.revision.gesture = true;
            self.session.document.history.begin_gesture();
        }
    }
}
