//! The colour ramp drawn as a gradient bar, sampled through the node's own CPU
//! evaluation so that the bar shows exactly what the shader computes.

use crate::nodes::cpu::{Eval, Surface};
use crate::nodes::{ColorRamp, Evaluate};
use egui::{Color32, Rgba, Sense, Ui, vec2};

/// Slices the bar is drawn in (enough for constant ramps' edges to look sharp).
const SLICES: usize = 128;

/// Draws `ramp` as a bar `width` wide, with a tick at each stop.
pub fn ramp_bar(ui: &mut Ui, ramp: &ColorRamp, width: f32) {
    let (rect, _) = ui.allocate_exact_size(vec2(width, 18.0), Sense::hover());
    let pins = crate::nodes::Definition::signature(ramp).inputs;
    let surface = Surface::<f64>::at([0.0; 3]);
    let painter = ui.painter();
    for slice in 0..SLICES {
        let (from, to) = (
            slice as f32 / SLICES as f32,
            (slice + 1) as f32 / SLICES as f32,
        );
        let factor = f64::from((from + to) * 0.5);
        let inputs = [[factor; 3]];
        let [r, g, b] = ramp.eval(&Eval::new(&pins, &inputs, &surface))[0].map(|c| c as f32);
        let slice_rect = egui::Rect::from_x_y_ranges(
            rect.lerp_inside(vec2(from, 0.0)).x..=rect.lerp_inside(vec2(to, 0.0)).x + 0.5,
            rect.y_range(),
        );
        painter.rect_filled(slice_rect, 0.0, Color32::from(Rgba::from_rgb(r, g, b)));
    }
    let stroke = ui.visuals().widgets.noninteractive.fg_stroke;
    painter.rect_stroke(rect, 2.0, stroke, egui::StrokeKind::Outside);
    for stop in &ramp.stops {
        let x = rect.lerp_inside(vec2(stop.position as f32, 0.0)).x;
        painter.vline(x, rect.bottom() - 5.0..=rect.bottom() + 3.0, stroke);
    }
}
