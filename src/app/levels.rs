//! The level of the graph the view shows: the top level, or the definition of a group
//! entered with Tab (groups nest; Tab or the breadcrumb goes back up). The document
//! always holds the whole graph: while a group is shown, every frame's edits are
//! written into its definition, so the preview, undo and saving see them at once.

use super::VeneerApp;
use super::graph_view::{graph_from_snarl, snarl_from_graph};
use super::navigation::{Framing, Navigation};
use super::scope::{self, Level};
use crate::graph::{Graph, NodeId, group};
use egui::Rect;

impl VeneerApp {
    /// The whole graph as the graph view shows it now (the level shown written into
    /// its place).
    pub(super) fn shown_graph(&mut self) -> Graph {
        let Some(name) = self.scope.current().map(str::to_string) else {
            return graph_from_snarl(&self.snarl, &self.document.graph);
        };
        let mut graph = self.document.graph.clone();
        if scope::write_back(&mut graph, &name, &self.snarl) {
            self.unlink_edited(&mut graph, &name);
            group::resolve(&mut graph);
        }
        graph
    }

    /// Reads the graph view back into the document.
    pub(super) fn sync_document(&mut self) {
        let graph = self.shown_graph();
        if graph != self.document.graph {
            self.document.graph = graph;
        }
    }

    /// A linked group takes the library's version when its graph is loaded: one edited
    /// here stops following the library, so that the edits are kept.
    pub(super) fn unlink_edited(&mut self, graph: &mut Graph, name: &str) {
        if let Some(definition) = graph.groups.get_mut(name)
            && definition.linked
        {
            definition.linked = false;
            self.message = Some(format!(
                "group '{name}' is local to this graph now (edited): library updates no \
                 longer apply; Save to library shares the edits"
            ));
        }
    }

    /// Shows the document at the level shown (the top level when that group is gone).
    pub(super) fn rebuild_snarl(&mut self) {
        if self.scope.keep_existing(&self.document.graph) {
            self.new_view();
            self.navigation.frame(Framing::All);
        }
        self.snarl = match self.scope.current() {
            Some(name) => scope::snarl_for_group(&self.document.graph, name).unwrap_or_default(),
            None => snarl_from_graph(&self.document.graph),
        };
    }

    /// Starts the graph view afresh (its selection is for other nodes now).
    pub(super) fn new_view(&mut self) {
        self.view_generation += 1;
        self.selection.clear();
        self.clicked = None;
    }

    /// Selects the node `node` of the level shown.
    pub(super) fn select(&mut self, node: NodeId) {
        self.clicked = self
            .snarl
            .node_ids()
            .find(|(_, shown)| shown.id == node && scope::boundary(shown).is_none())
            .map(|(id, _)| id);
        self.selection = self.clicked.into_iter().collect();
    }

    /// Tab: enters the selected group node, else leaves the group shown. Returns
    /// `false` when it did neither (at the top level, no group node selected).
    pub(super) fn tab(&mut self) -> bool {
        let selected = self
            .selection
            .first()
            .copied()
            .filter(|id| self.snarl.get_node(*id).is_some_and(scope::is_instance));
        if let Some(node) = selected {
            self.enter_group(node);
        } else if let Some(depth) = self.scope.levels.len().checked_sub(1) {
            self.leave_to(depth);
        } else {
            return false;
        }
        true
    }

    /// Shows the definition of group node `node` of the level shown.
    pub(super) fn enter_group(&mut self, node: egui_snarl::NodeId) {
        let Some(instance) = self.snarl.get_node(node).filter(|n| scope::is_instance(n)) else {
            return;
        };
        let name = group::group_name(instance).unwrap_or_default().to_string();
        if !self.document.graph.groups.contains_key(&name) {
            self.message = Some(format!("no group named '{name}' in the graph"));
            return;
        }
        let level = Level {
            group: name,
            instance: instance.id,
            view: self.navigation.transform,
        };
        self.sync_document();
        self.scope.levels.push(level);
        self.rebuild_snarl();
        self.new_view();
        self.navigation = Navigation::default();
        self.navigation.frame(Framing::All);
    }

    /// Leaves the groups entered below `depth` levels (0: back to the top level),
    /// putting back the view there and selecting the group node they were entered by.
    pub(super) fn leave_to(&mut self, depth: usize) {
        if depth >= self.scope.levels.len() {
            return;
        }
        self.sync_document();
        let left = self.scope.levels.split_off(depth);
        self.rebuild_snarl();
        self.new_view();
        self.navigation = Navigation::default();
        self.navigation.transform = left[0].view;
        self.select(left[0].instance);
    }

    /// The breadcrumb over the graph while a group is shown, "Graph › ring_wood": each
    /// level above the one shown goes back to it when clicked.
    pub(super) fn breadcrumb(&mut self, ctx: &egui::Context, canvas: Rect) {
        if self.scope.levels.is_empty() {
            return;
        }
        let mut go = None;
        egui::Area::new(egui::Id::new("veneer-breadcrumb"))
            .fixed_pos(canvas.min + egui::vec2(10.0, 10.0))
            .show(ctx, |ui| {
                egui::Frame::popup(ui.style()).show(ui, |ui| {
                    ui.horizontal(|ui| {
                        if ui.link("Graph").clicked() {
                            go = Some(0);
                        }
                        let last = self.scope.levels.len() - 1;
                        for (depth, level) in self.scope.levels.iter().enumerate() {
                            ui.label("›");
                            if depth == last {
                                ui.strong(&level.group);
                            } else if ui.link(&level.group).clicked() {
                                go = Some(depth + 1);
                            }
                        }
                        ui.weak("· Tab goes up");
                    });
                });
            });
        if let Some(depth) = go {
            self.leave_to(depth);
        }
    }
}
