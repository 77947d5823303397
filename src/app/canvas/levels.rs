//! The level of the graph the view shows: the top level, or the definition of a group
//! entered with Tab (groups nest; Tab or the breadcrumb goes back up). The document
//! always holds the whole graph: while a group is shown, every frame's edits are
//! written into its definition, so the preview, undo and saving see them at once.

use crate::app::VeneerApp;
use crate::app::canvas::navigation::{Framing, Navigation};
use crate::app::canvas::scope::{self, Level};
use crate::app::canvas::snarl_model::{graph_from_snarl, snarl_from_graph};
use crate::graph::{Graph, NodeId, group};
use egui::Rect;

impl VeneerApp {
    /// The whole graph as the graph view shows it now (the level shown written into
    /// its place).
    pub(in crate::app) fn shown_graph(&mut self) -> Graph {
        let Some(name) = self.canvas.scope.current().map(str::to_string) else {
            return graph_from_snarl(&self.canvas.snarl, &self.session.document.graph);
        };
        let mut graph = self.session.document.graph.clone();
        if scope::write_back(&mut graph, &name, &self.canvas.snarl) {
            self.unlink_edited(&mut graph, &name);
            group::resolve(&mut graph);
        }
        graph
    }

    /// Reads the graph view back into the document.
    pub(in crate::app) fn sync_document(&mut self) {
        let graph = self.shown_graph();
        if graph != self.session.document.graph {
            self.session.document.graph = graph;
        }
    }

    /// A linked group takes the library's version when its graph is loaded: one edited
    /// here stops following the library, so that the edits are kept.
    pub(in crate::app) fn unlink_edited(&mut self, graph: &mut Graph, name: &str) {
        if let Some(definition) = graph.groups.get_mut(name)
            && definition.linked
        {
            definition.linked = false;
            self.chrome.message = Some(format!(
                "group '{name}' is local to this graph now (edited): library updates no \
                 longer apply; Save to library shares the edits"
            ));
        }
    }

    /// Shows the document at the level shown (the top level when that group is gone),
    /// the nodes selected before still selected.
    pub(in crate::app) fn rebuild_snarl(&mut self) {
        let selected: Vec<NodeId> = self
            .canvas
            .selection
            .iter()
            .filter_map(|id| Some(self.canvas.snarl.get_node(*id)?.id))
            .collect();
        self.canvas.grab.forget();
        if self
            .canvas
            .scope
            .keep_existing(&self.session.document.graph)
        {
            self.new_view();
            self.canvas.navigation.frame(Framing::All);
        }
        self.canvas.snarl = match self.canvas.scope.current() {
            Some(name) => {
                scope::snarl_for_group(&self.session.document.graph, name).unwrap_or_default()
            }
            None => snarl_from_graph(&self.session.document.graph),
        };
        let ids: std::collections::HashMap<NodeId, egui_snarl::NodeId> = self
            .canvas
            .snarl
            .node_ids()
            .map(|(id, node)| (node.id, id))
            .collect();
        let kept = selected.iter().filter_map(|node| ids.get(node).copied());
        self.canvas.selection.set(kept);
    }

    /// Starts the graph view afresh (its selection is for other nodes now).
    pub(in crate::app) fn new_view(&mut self) {
        self.canvas.view_generation += 1;
        self.canvas.selection.clear();
    }

    /// Selects the node `node` of the level shown.
    pub(in crate::app) fn select(&mut self, node: NodeId) {
        let shown = self.canvas.snarl.node_ids().find(|(_, shown)| {
            shown.id == node && crate::app::canvas::boundary::boundary(shown).is_none()
        });
        self.canvas.selection.set(shown.map(|(id, _)| id));
    }

    /// Tab: enters the selected group node, else leaves the group shown. Returns
    /// `false` when it did neither (at the top level, no group node selected).
    pub(in crate::app) fn tab(&mut self) -> bool {
        let selected = self.canvas.selection.active().filter(|id| {
            self.canvas
                .snarl
                .get_node(*id)
                .is_some_and(crate::app::canvas::boundary::is_instance)
        });
        if let Some(node) = selected {
            self.enter_group(node);
        } else if let Some(depth) = self.canvas.scope.levels.len().checked_sub(1) {
            self.leave_to(depth);
        } else {
            return false;
        }
        true
    }

    /// Shows the definition of group node `node` of the level shown.
    pub(in crate::app) fn enter_group(&mut self, node: egui_snarl::NodeId) {
        let Some(instance) = self
            .canvas
            .snarl
            .get_node(node)
            .filter(|n| crate::app::canvas::boundary::is_instance(n))
        else {
            return;
        };
        let name = group::group_name(instance).unwrap_or_default().to_string();
        if !self.session.document.graph.groups.contains_key(&name) {
            self.chrome.message = Some(format!("no group named '{name}' in the graph"));
            return;
        }
        let level = Level {
            group: name,
            instance: instance.id,
            view: self.canvas.navigation.transform,
        };
        self.sync_document();
        self.canvas.scope.levels.push(level);
        self.rebuild_snarl();
        self.new_view();
        self.canvas.navigation = Navigation::default();
        self.canvas.navigation.frame(Framing::All);
    }

    /// Leaves the groups entered below `depth` levels (0: back to the top level),
    /// putting back the view there and selecting the group node they were entered by.
    pub(in crate::app) fn leave_to(&mut self, depth: usize) {
        if depth >= self.canvas.scope.levels.len() {
            return;
        }
        self.sync_document();
        let left = self.canvas.scope.levels.split_off(depth);
        self.rebuild_snarl();
        self.new_view();
        self.canvas.navigation = Navigation::default();
        self.canvas.navigation.transform = left[0].view;
        self.select(left[0].instance);
    }

    /// The breadcrumb over the graph while a group is shown, "Graph › ring_wood": each
    /// level above the one shown goes back to it when clicked.
    pub(in crate::app) fn breadcrumb(&mut self, ctx: &egui::Context, canvas: Rect) {
        if self.canvas.scope.levels.is_empty() {
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
                        let last = self.canvas.scope.levels.len() - 1;
                        for (depth, level) in self.canvas.scope.levels.iter().enumerate() {
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
