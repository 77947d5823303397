//! What the window paints, kept to what shows. On a software rasteriser (llvmpipe,
//! lavapipe) the window's cost is the pixels its shapes cover, overdraw included: egui's
//! defaults fill the graph's area twice (the central panel, then the canvas on it) and
//! each node three times (its shadow, its frame, its header on the frame). Here the
//! canvas colour is the window's clear colour, so neither the panel nor the canvas
//! fills, and nodes fill once.

use egui::{Color32, Frame, Rect, Shadow, Style, Ui, Visuals};
use egui_snarl::ui::SnarlStyle;

/// The colour the window is cleared to each frame: the graph canvas's.
pub fn clear_color(visuals: &Visuals) -> [f32; 4] {
    visuals.extreme_bg_color.to_normalized_gamma_f32()
}

/// The central panel's frame: its margins, no fill (the clear colour is the canvas).
pub fn central_panel_frame(style: &Style) -> Frame {
    Frame::central_panel(style).fill(Color32::TRANSPARENT)
}

/// Paints the central panel's margin around the canvas in the panel colour (a ring of
/// thin rectangles, not a fill under the canvas).
pub fn paint_panel_margin(ui: &Ui, panel: Rect, canvas: Rect) {
    let color = ui.visuals().panel_fill;
    let painter = ui.painter();
    let bands = [
        Rect::from_min_max(panel.min, egui::pos2(panel.max.x, canvas.min.y)),
        Rect::from_min_max(egui::pos2(panel.min.x, canvas.max.y), panel.max),
        Rect::from_min_max(
            egui::pos2(panel.min.x, canvas.min.y),
            egui::pos2(canvas.min.x, canvas.max.y),
        ),
        Rect::from_min_max(
            egui::pos2(canvas.max.x, canvas.min.y),
            egui::pos2(panel.max.x, canvas.max.y),
        ),
    ];
    for band in bands.into_iter().filter(|band| band.is_positive()) {
        painter.rect_filled(band, 0.0, color);
    }
}

/// The graph's look: the canvas outlined but not filled, nodes with a short shadow and
/// headers that do not fill over their node.
pub fn graph_style(style: &Style) -> SnarlStyle {
    let mut graph = SnarlStyle::new();
    graph.bg_frame = Some(Frame::canvas(style).fill(Color32::TRANSPARENT));
    let node = Frame::window(style).shadow(Shadow::NONE);
    graph.node_frame = Some(node);
    graph.header_frame = Some(node.fill(Color32::TRANSPARENT));
    graph
}

/// Paints the selection box `area` (on screen) over the graph, as egui-snarl draws its own.
pub fn paint_selection_box(ui: &Ui, area: Rect) {
    let layer = egui::LayerId::new(egui::Order::Foreground, egui::Id::new("selection box"));
    let painter = ui.ctx().layer_painter(layer).with_clip_rect(ui.max_rect());
    let selection = &ui.visuals().selection;
    let stroke = egui::Stroke::new(
        selection.stroke.width,
        selection.stroke.color.gamma_multiply(0.5),
    );
    painter.rect(
        area,
        0.0,
        selection.bg_fill.gamma_multiply(0.3),
        stroke,
        egui::StrokeKind::Inside,
    );
}
