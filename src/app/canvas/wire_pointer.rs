//! What the pointer does with wires in the graph panel: hovering one shows the value it
//! carries (its output's thumbnail, beside the pointer); dragging a node over one
//! highlights it, and releasing the node there inserts the node into it (one undo step:
//! the history commits once the button is up).

use crate::app::canvas::wires;
use crate::app::canvas::wires::{carried, insert_into_wire};
use crate::app::*;

/// Side of the thumbnail in a wire's tooltip, in points.
const WIRE_THUMBNAIL: f32 = 96.0;

impl VeneerApp {
    /// After the graph is drawn: finds the wire under the pointer, shows its value or
    /// inserts a node dropped on it.
    pub(in crate::app) fn wire_pointer(&mut self, ui: &Ui) {
        let ctx = ui.ctx().clone();
        let pointer = ctx.pointer_latest_pos();
        let on_graph = pointer.is_some_and(|pos| {
            ui.max_rect().contains(pos)
                && ctx
                    .layer_id_at(pos)
                    .is_none_or(|layer| layer.order == egui::Order::Background)
        });
        let (pressed, down, released) = ctx.input(|input| {
            let pointer = &input.pointer;
            (
                pointer.primary_pressed(),
                pointer.primary_down(),
                pointer.primary_released(),
            )
        });
        self.canvas.hovered_wire = None;
        let (Some(pointer), true) = (pointer, on_graph) else {
            if released {
                self.canvas.node_drag = None;
            }
            return;
        };
        let at = self.canvas.navigation.transform.inverse() * pointer;
        let spots = self.canvas.spots.clone();
        let spots = spots.borrow();
        if pressed {
            self.canvas.node_drag = spots
                .nodes
                .iter()
                .find(|(_, rect)| rect.contains(at))
                .and_then(|(id, _)| Some((*id, self.canvas.snarl.get_node_info(*id)?.pos)));
        }
        let dragged = self
            .canvas
            .node_drag
            .filter(|(id, start)| {
                self.canvas
                    .snarl
                    .get_node_info(*id)
                    .is_some_and(|info| info.pos != *start)
            })
            .map(|(id, _)| id)
            // A group's boundary nodes are never inserted into a wire.
            .filter(|id| crate::app::canvas::boundary::boundary(&self.canvas.snarl[*id]).is_none());
        if let Some(node) = dragged {
            if let Some(wire) = spots.wire_at(&self.canvas.snarl, at, Some(node)) {
                if released {
                    drop(spots);
                    if !insert_into_wire(&mut self.canvas.snarl, node, wire) {
                        self.chrome.message =
                            Some("this node has no free pins that fit the wire".into());
                    }
                    self.canvas.node_drag = None;
                    return;
                }
                self.highlight_wire(&ctx, &spots, wire);
            }
        } else if !down
            && self.canvas.scope.current().is_none()
            && !spots.nodes.values().any(|rect| rect.contains(at))
        {
            // (Inside a group the wires' values are not the top level's to show.)
            self.canvas.hovered_wire = spots
                .wire_at(&self.canvas.snarl, at, None)
                .and_then(|(from, _)| carried(&self.canvas.snarl, from));
        }
        if released {
            self.canvas.node_drag = None;
        }
        drop(spots);
        if let Some(pin) = self.canvas.hovered_wire.clone() {
            self.wire_tooltip(&ctx, pointer, &pin);
        }
    }

    /// Draws the wire a dragged node would be inserted into, thick and bright.
    fn highlight_wire(
        &self,
        ctx: &egui::Context,
        spots: &wires::Spots,
        (from, to): (egui_snarl::OutPinId, egui_snarl::InPinId),
    ) {
        let (Some(a), Some(b)) = (spots.output(from), spots.input(to)) else {
            return;
        };
        let points: Vec<egui::Pos2> = spots
            .curve(a, b)
            .into_iter()
            .map(|point| self.canvas.navigation.transform * point)
            .collect();
        let layer = egui::LayerId::new(egui::Order::Foreground, egui::Id::new("wire drop"));
        let stroke = egui::Stroke::new(5.0, egui::Color32::from_rgb(255, 190, 80));
        ctx.layer_painter(layer)
            .add(egui::Shape::line(points, stroke));
    }

    /// The value on the wire from `pin`: its name and its thumbnail, beside the pointer.
    fn wire_tooltip(&self, ctx: &egui::Context, pointer: egui::Pos2, pin: &crate::graph::PinRef) {
        let name = self
            .session
            .document
            .graph
            .node(pin.node)
            .map(|node| node.display_name().to_string())
            .unwrap_or_default();
        egui::Area::new(egui::Id::new("wire value"))
            .order(egui::Order::Tooltip)
            .fixed_pos(pointer + egui::vec2(16.0, 16.0))
            .interactable(false)
            .show(ctx, |ui| {
                egui::Frame::popup(ui.style()).show(ui, |ui| {
                    ui.label(format!("{name} · {}", pin.pin));
                    let size = egui::Vec2::splat(WIRE_THUMBNAIL);
                    match self.thumbnails.tile(pin) {
                        Some((texture, uv)) => {
                            ui.add(egui::Image::new((texture, size)).uv(uv));
                        }
                        None => {
                            ui.allocate_exact_size(size, egui::Sense::hover());
                        }
                    }
                });
            });
    }
}
