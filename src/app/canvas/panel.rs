//! The graph panel, each frame: a grab moves its nodes, the view moves, egui-snarl is
//! told the selection and shows the level, then the pointer's clicks and box change the
//! selection, new nodes are placed, and the add-node search opens or shows.

use crate::app::VeneerApp;
use crate::app::canvas::viewer::{Asked, Viewer};
use crate::app::canvas::{Canvas, navigation, painting};
use egui::{Context, Modifiers, Ui};
use egui_snarl::ui::SnarlWidget;

impl VeneerApp {
    /// Shows the graph view of the level shown and takes in what was done on it.
    pub(in crate::app) fn graph_panel(&mut self, ui: &mut Ui) {
        let ctx = ui.ctx().clone();
        self.canvas.add.set_graph_rect(ui.max_rect());
        // Node titles and pin names are not text to select: a click on a title selects
        // the node, and Ctrl+C copies the node, not the title.
        ui.style_mut().interaction.selectable_labels = false;
        let to_graph = self.canvas.navigation.transform.inverse();
        let grabbed = self
            .canvas
            .grab
            .update(&ctx, &mut self.canvas.snarl, to_graph);
        let canvas = &mut self.canvas;
        canvas.selection.retain_existing(&canvas.snarl);
        let modifiers = canvas.navigation.before(
            &ctx,
            ui.max_rect(),
            &canvas.snarl,
            &canvas.selection,
            !grabbed,
        );
        // Inside a group, the top level's errors and frames do not apply: its nodes' ids
        // are the definition's own. Its warnings and thumbnails are its own.
        let in_group = canvas.scope.current().is_some();
        self.thumbnails.show_level(canvas.scope.current());
        let no_errors = Default::default();
        let mut asked = Asked::default();
        let graph = &self.session.document.graph;
        let mut viewer = Viewer {
            errors: if in_group {
                &no_errors
            } else {
                &self.preview.live.errors
            },
            warnings: self.preview.live.warnings.of_level(canvas.scope.current()),
            asked: &mut asked,
            active: canvas.selection.active(),
            navigation: &mut canvas.navigation,
            frames: if in_group { &[] } else { &graph.frames },
            thumbnails: &mut self.thumbnails,
            spots: canvas.spots.clone(),
            in_group,
            groups: &graph.groups,
            shading: graph.shading,
        };
        *canvas.spots.borrow_mut() = Default::default();
        // In big graphs nodes off screen are not laid out at all, and zoomed out they are
        // outlines (our egui-snarl patch).
        let big = navigation::is_big(canvas.snarl.node_ids().count());
        let widget = SnarlWidget::new()
            .id_salt(("graph", canvas.view_generation))
            .style(painting::graph_style(ui.style()))
            .cull_offscreen(big)
            .outline_below(navigation::OUTLINE_ZOOM);
        widget.set_selected_nodes(ui, &canvas.selection);
        widget.show(&mut canvas.snarl, &mut viewer, ui);
        self.wire_pointer(ui);
        self.canvas.navigation.after(&ctx, modifiers);
        if self.chrome.dialog.is_none() && !grabbed {
            // (A click on a dialog is not for the node under it.)
            self.canvas
                .select_by_pointer(&ctx, asked.clicked, modifiers);
        }
        if let Some(area) = self.canvas.navigation.selection_box(&ctx) {
            painting::paint_selection_box(ui, area);
        }
        if asked.hint.is_some() {
            self.chrome.message = asked.hint;
        }
        if let Some(copies) = asked.duplicated {
            self.grab_new(&ctx, copies);
        }
        let exposed = asked.expose.and_then(|pin| self.expose_input(pin));
        asked.declared.extend(exposed);
        self.declare(asked.declared);
        if let Some(action) = asked.group_action {
            self.group_action(action);
        }
        self.breadcrumb(&ctx, ui.max_rect());
        // A right click on empty canvas, or a wire dropped there, opens the add-node search.
        let right_click = self.canvas.navigation.right_clicked_empty_canvas() && !grabbed;
        if asked.dropped.is_some() || right_click {
            self.open_add_node(&ctx, asked.dropped, None);
        }
        self.add_node_popup(&ctx);
    }

    /// Duplicates: placed clear of the others, selected, and following the mouse.
    pub(in crate::app) fn grab_new(&mut self, ctx: &Context, copies: Vec<egui_snarl::NodeId>) {
        let to_graph = self.canvas.navigation.transform.inverse();
        let mouse = match ctx.pointer_latest_pos() {
            Some(pointer) => to_graph * pointer,
            None => self.placement(ctx).1,
        };
        self.canvas.placed(copies.clone());
        self.canvas.grab.start(&self.canvas.snarl, &copies, mouse);
    }
}

impl Canvas {
    /// After the graph is shown: a click on a node, a box let go of (a click on empty
    /// canvas is an empty one), or a drag of an unselected node changes the selection.
    fn select_by_pointer(
        &mut self,
        ctx: &Context,
        clicked: Option<egui_snarl::NodeId>,
        modifiers: Modifiers,
    ) {
        let before = self.selection.clone();
        if let Some(node) = clicked {
            self.selection.click(node, modifiers);
        } else if let Some(area) = self.navigation.released_box() {
            self.selection
                .boxed(self.navigation.nodes_in(area), modifiers);
        }
        // A node dragged that was not selected is the selection (it moved alone).
        let dragged = self.node_drag.filter(|(id, start)| {
            self.snarl
                .get_node_info(*id)
                .is_some_and(|info| info.pos != *start)
        });
        if let Some((node, _)) = dragged
            && !self.selection.contains(&node)
        {
            self.selection.set([node]);
        }
        if self.selection != before {
            // The inspector, drawn before the graph, shows the new active node.
            ctx.request_repaint();
        }
    }
}
