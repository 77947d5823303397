//! Keeping the document in step with the graph view after each frame's panels, and
//! measuring where the main thread's time goes. Whole-graph work happens only on frames
//! where the user may have edited (input arrived) and, past the cheap comparison that
//! finds an edit, only when something changed: each change bumps the graph's revision,
//! and the compile, the lint, the thumbnails, the undo history and the title follow it.

use crate::app::VeneerApp;
use crate::app::chrome::frame_clock::FrameProfile;
use crate::graph::{Graph, NodeId};
use std::time::{Duration, Instant};

/// The graph's revision: bumped on every change, and the revision each follower (the
/// compile, the lint, the undo history) last took in.
#[derive(Default)]
pub(in crate::app) struct Revision {
    pub number: u64,
    /// Frames that read the graph view back (for tests: idle frames never do).
    pub reads: u64,
    /// The document was changed from outside the editor's own panels (a script or a
    /// test): the next frame takes it in even without input.
    pub touched: bool,
    /// The graph at `number`, to tell a change from a frame that changed nothing.
    seen: Graph,
    /// The revision compiled, and with which noise detail (a setting of the preview's).
    compiled: Option<(u64, bool)>,
    linted: u64,
    committed: u64,
}

/// Whether the user may have edited this frame: input other than pointer movement
/// arrived, or a button is held or was let go (drags, clicks). Repaints for animation,
/// the previews or thumbnails coming back do no whole-graph work.
fn may_edit(ctx: &egui::Context) -> bool {
    ctx.input(|input| {
        input.pointer.any_down()
            || input.pointer.any_released()
            || input.events.iter().any(|event| {
                !matches!(
                    event,
                    egui::Event::PointerMoved(_) | egui::Event::MouseMoved(_)
                )
            })
    })
}

impl VeneerApp {
    /// After the panels: reads the edited graph back, recompiles if needed, commits undo
    /// steps, autosaves (the frame's total is filled in when it ends).
    pub(in crate::app) fn after_edits(&mut self, ctx: &egui::Context) {
        let mut clock = Instant::now();
        let mut lap = || {
            let now = Instant::now();
            std::mem::replace(&mut clock, now).elapsed()
        };
        // Nodes following the mouse (a grab) are an edit in progress, like a drag: read
        // back as the mouse moves, committed once put down.
        let grabbing = self.canvas.grab.is_moving();
        let pointer_down = ctx.input(|input| input.pointer.any_down()) || grabbing;
        // The first frame takes in the graph the editor opened on.
        let touched = std::mem::take(&mut self.session.revision.touched);
        if self.session.revision.number == 0 || touched || may_edit(ctx) || grabbing {
            self.session.revision.reads += 1;
            let graph = self.shown_graph();
            if graph != self.session.document.graph {
                self.session.document.graph = graph;
            }
            // Edits made to the document directly (fields, frames, picking, undo) too.
            if self.session.document.graph != self.session.revision.seen {
                self.session.revision.seen = self.session.document.graph.clone();
                self.session.revision.number += 1;
                // What was drawn before the graph view (the status bar, the inspector)
                // shows the change in the next frame.
                ctx.request_repaint();
            }
            // Saving (and undoing to what was saved) changes this without an edit.
            self.session.dirty = self.session.document.is_dirty();
        }
        let revision = self.session.revision.number;
        let sync = lap();
        let compile_key = Some((revision, self.preview.live.full_detail));
        if self.session.revision.compiled != compile_key {
            self.session.revision.compiled = compile_key;
            self.preview.live.update(&self.session.document.graph);
        }
        let compile = lap();
        // The lint waits for a drag to end (it reads every constant).
        if self.session.revision.linted != revision && !pointer_down {
            self.session.revision.linted = revision;
            self.preview.live.lint(&self.session.document.graph);
        }
        let lint = lap();
        let time = self.preview.state.view.time;
        let hovered = self.canvas.hovered_wire.as_ref();
        // Asked only of graphs with more nodes than tiles.
        let visible = std::cell::OnceCell::new();
        let on_screen = |node: NodeId| {
            visible
                .get_or_init(|| {
                    let shown = self.canvas.navigation.on_screen();
                    let ids = shown.filter_map(|id| self.canvas.snarl.get_node(id).map(|n| n.id));
                    ids.collect::<rustc_hash::FxHashSet<NodeId>>()
                })
                .contains(&node)
        };
        let graph = &self.session.document.graph;
        self.thumbnails
            .update(ctx, graph, revision, hovered, time, &on_screen);
        let thumbnails = lap();
        if self.session.revision.committed != revision && !pointer_down {
            self.session.revision.committed = revision;
            self.session
                .document
                .history
                .commit(&self.session.document.graph);
        }
        let title = self.session.document.title(self.session.dirty);
        if title != self.session.title {
            ctx.send_viewport_cmd(egui::ViewportCommand::Title(title.clone()));
            self.session.title = title;
        }
        self.autosave_tick(ctx);
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
}
