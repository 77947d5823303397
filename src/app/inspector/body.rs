//! The picture a node's definition declares for its body ([`crate::nodes::Body`]),
//! drawn in the node and in the inspector.

use crate::nodes::Body;
use egui::{Color32, Rgba, Sense, Ui, vec2};

/// Slices a gradient is drawn in (enough for constant ramps' edges to look sharp).
const SLICES: usize = 128;

/// Draws `body` `width` wide.
pub fn show_body(ui: &mut Ui, body: &Body<'_>, width: f32) {
    match body {
        Body::Gradient { colour, ticks } => gradient(ui, colour, ticks, width),
    }
}

/// A bar of `colour` from 0 to 1, with a tick at each of `ticks`.
fn gradient(ui: &mut Ui, colour: &dyn Fn(f64) -> [f64; 3], ticks: &[f64], width: f32) {
    let (rect, _) = ui.allocate_exact_size(vec2(width, Body::SIZE.1), Sense::hover());
    let painter = ui.painter();
    for slice in 0..SLICES {
        let (from, to) = (
            slice as f32 / SLICES as f32,
            (slice + 1) as f32 / SLICES as f32,
        );
        let [r, g, b] = colour(f64::from((from + to) * 0.5)).map(|c| c as f32);
        let slice_rect = egui::Rect::from_x_y_ranges(
            rect.lerp_inside(vec2(from, 0.0)).x..=rect.lerp_inside(vec2(to, 0.0)).x + 0.5,
            rect.y_range(),
        );
        painter.rect_filled(slice_rect, 0.0, Color32::from(Rgba::from_rgb(r, g, b)));
    }
    let stroke = ui.visuals().widgets.noninteractive.fg_stroke;
    painter.rect_stroke(rect, 2.0, stroke, egui::StrokeKind::Outside);
    for tick in ticks {
        let x = rect.lerp_inside(vec2(*tick as f32, 0.0)).x;
        painter.vline(x, rect.bottom() - 5.0..=rect.bottom() + 3.0, stroke);
    }
}
