//! Veneer's patch: a level of detail for far zoom. Below the widget's outline scale, a
//! node that has been drawn in full once is drawn as an outline — a box in the node's
//! fill with an edge a point wide, its title only where it fits, straight wires — from
//! the rectangle and pins it had when last drawn in full (moved with the node). It is
//! still clicked, dragged and box-selected as a node; its pins take no wires until
//! zoomed in.

use egui::{
    Color32, FontId, Id, Modifiers, PointerButton, Pos2, Rect, Sense, Shape, Stroke, StrokeKind,
    Ui, Vec2,
};

use super::{DrawNodeResponse, DrawnNode, PinResponse, SnarlStyle, SnarlViewer, state::SnarlState};
use crate::{InPinId, NodeId, OutPinId, Snarl};

/// The sizes (graph units) an outline's title may be drawn at: the smallest that is at
/// least [`TITLE_PIXELS`] on screen, where the title fits inside the box.
const TITLE_SIZES: [f32; 3] = [28.0, 48.0, 80.0];
/// The smallest a title is drawn on screen, in points.
const TITLE_PIXELS: f32 = 8.0;
/// Room left between an outline's edge and its title (graph units).
const TITLE_MARGIN: f32 = 8.0;

/// What one frame's outlines share.
pub(super) struct Outlines<'a> {
    pub style: &'a SnarlStyle,
    pub snarl_id: Id,
    pub modifiers: Modifiers,
    /// The part of the graph on screen (graph units).
    pub viewport: Rect,
    /// The view's zoom.
    pub scale: f32,
}

impl DrawnNode {
    /// Whether this drawing still shows `node`: as many pins as it has now.
    pub(super) fn shows<T, V: SnarlViewer<T>>(&self, viewer: &mut V, node: &T) -> bool {
        self.input_count == viewer.inputs(node) && self.output_count == viewer.outputs(node)
    }
}

impl Outlines<'_> {
    /// Draws `node` as an outline of `last` moved to where the node is now, records its
    /// pins for the wires, and answers clicks and drags on it as on a node.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn draw<T, V: SnarlViewer<T>>(
        &self,
        snarl: &mut Snarl<T>,
        ui: &mut Ui,
        node: NodeId,
        last: &DrawnNode,
        viewer: &mut V,
        snarl_state: &mut SnarlState,
        input_positions: &mut ahash::HashMap<InPinId, PinResponse>,
        output_positions: &mut ahash::HashMap<OutPinId, PinResponse>,
    ) -> DrawNodeResponse {
        let moved = snarl.nodes[node.0].pos - last.pos;
        let rect = last.rect.translate(moved);
        // The pins of an outline not moved are looked up in `last` by the wires; only a
        // moved one's are written down, where they are now.
        if moved != Vec2::ZERO {
            let shifted = |response: &PinResponse| PinResponse {
                pos: response.pos + moved,
                ..*response
            };
            input_positions.extend(last.inputs.iter().map(|(pin, at)| (*pin, shifted(at))));
            output_positions.extend(last.outputs.iter().map(|(pin, at)| (*pin, shifted(at))));
        }
        let mut response = DrawNodeResponse {
            node_moved: None,
            node_to_top: None,
            drag_released: false,
            pin_hovered: None,
            final_rect: rect,
        };
        if !self.viewport.intersects(rect) {
            return response;
        }
        let selected = snarl_state.selected_nodes().contains(&node);
        self.paint(ui, rect, selected, || viewer.title(&snarl.nodes[node.0].value));

        // The same interaction as a node drawn in full (the same id, so that a drag goes
        // on across the change of detail).
        let frame = ui.interact(
            rect,
            self.snarl_id.with(("snarl-node", node)).with("frame"),
            Sense::click_and_drag(),
        );
        let modifiers = self.modifiers;
        if !modifiers.shift && !modifiers.command && frame.dragged_by(PointerButton::Primary) {
            response.node_moved = Some((node, frame.drag_delta()));
        }
        if frame.clicked_by(PointerButton::Primary) || frame.dragged_by(PointerButton::Primary) {
            if modifiers.shift {
                snarl_state.select_one_node(modifiers.command, node);
            } else if modifiers.command {
                snarl_state.deselect_one_node(node);
            }
        }
        if frame.clicked() || frame.dragged() {
            response.node_to_top = Some(node);
        }
        if viewer.has_node_menu(&snarl.nodes[node.0].value) {
            frame.context_menu(|ui| {
                let inputs = (0..last.input_count)
                    .map(|input| crate::InPin::new(snarl, InPinId { node, input }))
                    .collect::<Vec<_>>();
                let outputs = (0..last.output_count)
                    .map(|output| crate::OutPin::new(snarl, OutPinId { node, output }))
                    .collect::<Vec<_>>();
                viewer.show_node_menu(node, &inputs, &outputs, ui, snarl);
            });
        }
        if snarl.nodes.contains(node.0) {
            viewer.final_node_rect(node, rect, ui, snarl);
        }
        response
    }

    /// Paints the box: the selection's margin, the node's frame colours, and the title
    /// (asked for only when some title size could fit).
    fn paint(&self, ui: &Ui, rect: Rect, selected: bool, title: impl FnOnce() -> String) {
        let visuals = ui.style();
        let frame = self.style.get_node_frame(visuals);
        if selected {
            let select = self.style.get_select_style(visuals);
            ui.painter().rect(
                rect + select.margin,
                select.rounding,
                select.fill,
                select.stroke,
                StrokeKind::Inside,
            );
        }
        // The edge one point wide on screen, in the text's weak colour: a frame's own
        // stroke, a fraction of a point at this zoom, would not show.
        let edge = Stroke::new(1.0 / self.scale, visuals.visuals.weak_text_color());
        ui.painter()
            .rect(rect, frame.corner_radius, frame.fill, edge, StrokeKind::Inside);
        let room = rect.shrink(TITLE_MARGIN);
        let Some(size) = TITLE_SIZES
            .into_iter()
            .find(|size| size * self.scale >= TITLE_PIXELS)
            .filter(|size| *size <= room.height())
        else {
            return;
        };
        let color = visuals.visuals.strong_text_color();
        let galley = ui
            .painter()
            .layout_no_wrap(title(), FontId::proportional(size), color);
        if galley.size().x <= room.width() {
            ui.painter()
                .galley(room.left_top(), galley, Color32::PLACEHOLDER);
        }
    }
}

/// A wire between outlines: a straight line, where it crosses the part on screen.
pub(super) fn wire(viewport: Rect, from: Pos2, to: Pos2, stroke: Stroke) -> Option<Shape> {
    let bounds = Rect::from_two_pos(from, to).expand(stroke.width);
    viewport
        .intersects(bounds)
        .then(|| Shape::line_segment([from, to], stroke))
}
