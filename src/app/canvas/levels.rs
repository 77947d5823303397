//! The level of the graph the view shows: the top level, or the definition of a group
//! entered with Tab (groups nest; Tab or the breadcrumb goes back up). The document
//! always holds the whole graph: while a group is shown, the view's edits are edits of
//! its definition, so the preview, undo and saving see them at once.

use crate::app::VeneerApp;
use crate::app::canvas::navigation::{Framing, Navigation};
use crate::app::canvas::scope::{self, Level};
use crate::app::canvas::snarl_model::snarl_from_graph;
use crate::app::canvas::view_edits::Shown;
use crate::graph::{NodeId, group};
use egui::Rect;

impl VeneerApp {
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
        self.canvas.shown = Shown::of(&self.canvas.snarl);
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
        self.take_in_view_edits();
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
        self.take_in_view_edits();
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
