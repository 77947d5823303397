//! Moving around the graph as in Blender and Material Maker: the wheel zooms about the
//! cursor, middle-drag (or Alt-drag, wherever it starts) pans, a left-drag on empty
//! canvas draws a selection box, Home/F frame every node and '.' the selection. The
//! view's transform is ours: egui-snarl's own pan and zoom (wheel pans, any drag on the
//! canvas pans) are overridden each frame, and a pan takes the pointer from the nodes.

use crate::graph::Node;
use egui::emath::TSTransform;
use egui::{Context, PointerButton, Pos2, Rect, Vec2};
use egui_snarl::Snarl;

/// The size of node titles, in graph units, at zooms where that is at least
/// [`TITLE_PIXELS`] on screen.
pub const TITLE_SIZE: f32 = 24.0;
/// The smallest size of node titles on screen: zoomed out further, titles grow in graph
/// units so that they stay readable.
pub const TITLE_PIXELS: f32 = 12.0;
/// The smallest zoom a graph opens at (titles are then drawn 40 units tall); a graph
/// that does not fit at it opens at its top-left corner.
const OPEN_ZOOM: f32 = 0.3;

/// The size node titles are drawn at, in graph units, at `zoom`.
pub fn title_size(zoom: f32) -> f32 {
    TITLE_SIZE.max(TITLE_PIXELS / zoom)
}

/// The zoom range the wheel and framing keep to.
const ZOOM_RANGE: std::ops::RangeInclusive<f32> = 0.1..=2.0;
/// Natural log of the zoom per point of wheel scroll (a wheel notch, 50 points, ≈ ×1.2).
const ZOOM_PER_POINT: f32 = 0.0036;
/// The part of the zoom still to come that each frame applies (the rest eases in).
const ZOOM_EASE: f32 = 0.35;
/// Room left around framed nodes, in graph units.
const MARGIN: f32 = 30.0;
/// A node's size before it has been drawn once (in graph units).
const UNMEASURED: Vec2 = egui::vec2(240.0, 160.0);
/// Pins stick out of a node's rectangle by about this much (graph units).
const PIN_REACH: f32 = 10.0;
/// Graphs of more nodes than this skip the nodes off screen (egui-snarl's
/// `cull_offscreen`, our patch).
const BIG_GRAPH: usize = 200;

/// Whether a graph of `nodes` nodes is big: its nodes off screen are skipped, and
/// zoomed out below [`OUTLINE_ZOOM`] they are outlines.
pub fn is_big(nodes: usize) -> bool {
    nodes > BIG_GRAPH
}

/// Zoomed out below this, big graphs draw their nodes as outlines: a box, the title
/// where it fits, straight wires (egui-snarl's `outline_below`, our patch). Their pins'
/// names would be under 4 points tall. Graphs open at it or closer, in full.
pub const OUTLINE_ZOOM: f32 = OPEN_ZOOM;

/// Frames a framing follows the nodes' sizes for: egui settles a node's size over its
/// first frames, and thumbnails arrive after it.
const FRAMING_FRAMES: u8 = 12;

/// How to place the view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Framing {
    /// Fit every node (Home, F).
    All,
    /// Fit the selected nodes ('.').
    Selection,
    /// Fit every node but never below [`OPEN_ZOOM`], the top-left first if they do
    /// not fit (a graph just opened).
    Open,
}

/// The graph view's transform and the gestures moving it.
#[derive(Default)]
pub struct Navigation {
    /// From graph to screen coordinates.
    pub transform: TSTransform,
    /// A framing to apply, the bounds it was last applied to and how many more frames
    /// it may follow the nodes' sizes as they settle.
    framing: Option<(Framing, Rect, u8)>,
    /// Natural log of the zoom still to apply (the wheel eases in over a few frames).
    zoom_to_come: f32,
    /// A pan drag is in progress.
    panning: bool,
    /// Where a left-drag that began on empty canvas began (graph coordinates): it draws
    /// a selection box. A click there is an empty box.
    boxing: Option<Pos2>,
    /// The box let go of this frame (graph coordinates).
    box_released: Option<Rect>,
    /// A right click on empty canvas came this frame.
    right_click: bool,
    /// Every node's rectangle when last drawn, in graph coordinates.
    rects: std::collections::HashMap<egui_snarl::NodeId, Rect>,
    /// Where the graph is on screen (`None` before the first frame).
    viewport: Option<Rect>,
}

impl Navigation {
    /// Asks for the view to be placed as `framing` says (applied in the next frames).
    pub fn frame(&mut self, framing: Framing) {
        self.framing = Some((framing, Rect::NOTHING, FRAMING_FRAMES));
    }

    /// Records where a node was drawn this frame (graph coordinates).
    pub fn measured(&mut self, node: egui_snarl::NodeId, rect: Rect) {
        self.rects.insert(node, rect);
    }

    /// Before the graph is shown: moves the view as the input and any framing ask, and
    /// starts or ends a selection box (not while `boxes` is false). egui-snarl selects
    /// by its own rectangle while Shift is held, and deselects on a Ctrl click: over
    /// empty canvas it is told neither is held. Returns the modifiers held, to restore
    /// once the graph has been shown.
    pub fn before(
        &mut self,
        ctx: &Context,
        viewport: Rect,
        snarl: &Snarl<Node>,
        selection: &[egui_snarl::NodeId],
        boxes: bool,
    ) -> egui::Modifiers {
        self.rects.retain(|id, _| snarl.get_node(*id).is_some());
        self.viewport = Some(viewport);
        self.apply_framing(viewport, snarl, selection);
        let (pointer, modifiers) = ctx.input(|input| (input.pointer.latest_pos(), input.modifiers));
        let on_canvas = pointer.filter(|pos| {
            viewport.contains(*pos)
                && ctx
                    .layer_id_at(*pos)
                    .is_none_or(|layer| layer.order == egui::Order::Background)
        });
        let over_node = on_canvas.is_some_and(|pos| self.node_at(pos));
        self.zoom(ctx, on_canvas);
        self.pan(ctx, on_canvas.is_some(), modifiers.alt);
        let (pressed, released, secondary) = ctx.input(|input| {
            let pointer = &input.pointer;
            (
                pointer.button_pressed(PointerButton::Primary),
                pointer.button_released(PointerButton::Primary),
                pointer.button_clicked(PointerButton::Secondary),
            )
        });
        let empty = on_canvas.is_some() && !over_node && !self.panning;
        let to_graph = self.transform.inverse();
        if pressed && empty && boxes {
            let origin = ctx.input(|input| input.pointer.press_origin()).or(pointer);
            self.boxing = origin.map(|pos| to_graph * pos);
        }
        self.right_click = secondary && empty;
        self.box_released = None;
        if released && let Some(origin) = self.boxing.take() {
            let end = pointer.map_or(origin, |pos| to_graph * pos);
            self.box_released = Some(Rect::from_two_pos(origin, end));
        }
        if (empty && !ctx.input(|input| input.pointer.any_down())) || self.boxing.is_some() {
            ctx.input_mut(|input| {
                input.modifiers.shift = false;
                input.modifiers.command = false;
                input.modifiers.ctrl = false;
            });
        }
        modifiers
    }

    /// The selection box let go of this frame, in graph coordinates (a click on empty
    /// canvas is an empty one).
    pub fn released_box(&self) -> Option<Rect> {
        self.box_released
    }

    /// Whether a right click on empty canvas came this frame.
    pub fn right_clicked_empty_canvas(&self) -> bool {
        self.right_click
    }

    /// The selection box being drawn, on screen.
    pub fn selection_box(&self, ctx: &Context) -> Option<Rect> {
        let pointer = ctx.input(|input| input.pointer.latest_pos())?;
        Some(Rect::from_two_pos(self.transform * self.boxing?, pointer))
    }

    /// The nodes whose rectangle, when last drawn, meets `area` (graph coordinates).
    pub fn nodes_in(&self, area: Rect) -> Vec<egui_snarl::NodeId> {
        let meets = |rect: &Rect| rect.intersects(area) && area.is_finite();
        let nodes = self.rects.iter().filter(|(_, rect)| meets(rect));
        nodes.map(|(id, _)| *id).collect()
    }

    /// After the graph is shown: puts back the modifiers [`Navigation::before`] changed.
    pub fn after(&self, ctx: &Context, modifiers: egui::Modifiers) {
        ctx.input_mut(|input| input.modifiers = modifiers);
    }

    /// Whether a graph of `nodes` nodes is drawn as outlines at the current zoom (then no
    /// node shows its thumbnail).
    pub fn outlines(&self, nodes: usize) -> bool {
        is_big(nodes) && self.transform.scaling < OUTLINE_ZOOM
    }

    /// Whether the view is moving: a pan held, a zoom easing in, or a framing settling.
    pub fn moving(&self) -> bool {
        self.panning || self.zoom_to_come != 0.0 || self.framing.is_some()
    }

    /// The nodes whose rectangle, when last drawn, was at least partly on screen.
    pub fn on_screen(&self) -> impl Iterator<Item = egui_snarl::NodeId> + '_ {
        self.rects
            .iter()
            .filter(|(_, rect)| {
                self.viewport
                    .is_some_and(|viewport| viewport.intersects(self.transform * **rect))
            })
            .map(|(id, _)| *id)
    }

    /// Whether the screen point `pos` is on a node (or one of its pins).
    fn node_at(&self, pos: Pos2) -> bool {
        let graph_pos = self.transform.inverse() * pos;
        self.rects
            .values()
            .any(|rect| rect.expand(PIN_REACH).contains(graph_pos))
    }

    /// The wheel (and Ctrl+wheel, pinch) zooms about the cursor, easing in.
    fn zoom(&mut self, ctx: &Context, on_canvas: Option<Pos2>) {
        if let Some(pos) = on_canvas {
            let (scroll, pinch) =
                ctx.input(|input| (input.smooth_scroll_delta, input.zoom_delta()));
            self.zoom_to_come += scroll.y * ZOOM_PER_POINT + pinch.ln();
            self.transform =
                TSTransform::from_translation(Vec2::new(scroll.x, 0.0)) * self.transform;
            if self.zoom_to_come.abs() > 1e-4 {
                let step = self.zoom_to_come * ZOOM_EASE;
                self.zoom_to_come -= step;
                self.zoom_about(pos, step.exp());
                ctx.request_repaint();
            } else {
                self.zoom_to_come = 0.0;
            }
        } else {
            self.zoom_to_come = 0.0;
        }
    }

    /// Multiplies the zoom by `factor` (within the zoom range), keeping the graph point
    /// under the screen point `pos` where it is.
    fn zoom_about(&mut self, pos: Pos2, factor: f32) {
        let scaling =
            (self.transform.scaling * factor).clamp(*ZOOM_RANGE.start(), *ZOOM_RANGE.end());
        let anchor = self.transform.inverse() * pos;
        self.transform.scaling = scaling;
        self.transform.translation = pos.to_vec2() - anchor.to_vec2() * scaling;
    }

    /// Middle-drag, or a left-drag with Alt held, begun on the canvas, pans (Space is
    /// the add-node search's: its popup opens under the pointer on the press).
    fn pan(&mut self, ctx: &Context, on_canvas: bool, pan_modifier: bool) {
        let (middle, primary, delta) = ctx.input(|input| {
            let pointer = &input.pointer;
            (
                pointer.button_pressed(PointerButton::Middle),
                pointer.button_pressed(PointerButton::Primary),
                pointer.delta(),
            )
        });
        if on_canvas && (middle || (primary && pan_modifier)) {
            self.panning = true;
        }
        if self.panning {
            let down = ctx.input(|input| {
                input.pointer.button_down(PointerButton::Middle)
                    || input.pointer.button_down(PointerButton::Primary)
            });
            if down {
                self.transform.translation += delta;
                // The drag is the pan's: no node under the pointer moves with it.
                ctx.set_dragged_id(egui::Id::new("veneer pan"));
            } else {
                self.panning = false;
            }
        }
    }

    /// Applies the framing asked for: straight away (with sizes estimated for nodes not
    /// drawn yet), then again whenever the nodes' measured bounds change, for
    /// [`FRAMING_FRAMES`] frames.
    fn apply_framing(
        &mut self,
        viewport: Rect,
        snarl: &Snarl<Node>,
        selection: &[egui_snarl::NodeId],
    ) {
        let Some((framing, last_bounds, frames_left)) = self.framing else {
            return;
        };
        let nodes: Vec<egui_snarl::NodeId> = match framing {
            Framing::Selection => selection.to_vec(),
            Framing::All | Framing::Open => snarl.node_ids().map(|(id, _)| id).collect(),
        };
        let bounds = nodes
            .iter()
            .filter_map(|id| self.node_rect(snarl, *id))
            .fold(Rect::NOTHING, Rect::union);
        // Applied again only while the nodes' sizes change (by a unit or more), so that
        // a pan or zoom right after opening is not undone; done once they stop.
        let settled = last_bounds.is_positive()
            && (bounds.min - last_bounds.min).length() < 1.0
            && (bounds.max - last_bounds.max).length() < 1.0;
        if settled {
            self.framing = None;
            return;
        }
        if bounds.is_positive() {
            let framed = bounds.expand(MARGIN);
            let fit = (viewport.width() / framed.width()).min(viewport.height() / framed.height());
            let (scaling, focus) = match framing {
                Framing::All | Framing::Selection => (fit.min(1.0), framed.center()),
                Framing::Open if fit >= OPEN_ZOOM => (fit.min(1.0), framed.center()),
                // Too big to read whole: the top-left corner at the legible zoom.
                Framing::Open => (OPEN_ZOOM, framed.min + viewport.size() / (2.0 * OPEN_ZOOM)),
            };
            let scaling = scaling.clamp(*ZOOM_RANGE.start(), *ZOOM_RANGE.end());
            self.transform = TSTransform {
                scaling,
                translation: viewport.center().to_vec2() - focus.to_vec2() * scaling,
            };
            self.zoom_to_come = 0.0;
        }
        self.framing = (frames_left > 1).then_some((framing, bounds, frames_left - 1));
    }

    /// Where node `id` is in graph coordinates: as last drawn, or estimated.
    fn node_rect(&self, snarl: &Snarl<Node>, id: egui_snarl::NodeId) -> Option<Rect> {
        let estimated = || {
            let info = snarl.get_node_info(id)?;
            Some(Rect::from_min_size(info.pos, UNMEASURED))
        };
        self.rects.get(&id).copied().or_else(estimated)
    }
}
