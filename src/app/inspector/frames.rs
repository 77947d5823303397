//! The comment frames' titles, colours and removal, in the inspector when no node is
//! selected.

use egui::Ui;

/// Titles, colours and removal of the graph's comment frames.
pub(in crate::app) fn frames_editor(ui: &mut Ui, frames: &mut Vec<crate::graph::Frame>) {
    if frames.is_empty() {
        return;
    }
    ui.separator();
    ui.label("Frames");
    let mut remove = None;
    for (index, frame) in frames.iter_mut().enumerate() {
        ui.horizontal(|ui| {
            ui.text_edit_singleline(&mut frame.title);
            let mut rgb = [frame.color.0, frame.color.1, frame.color.2];
            if ui.color_edit_button_rgb(&mut rgb).changed() {
                frame.color = (rgb[0], rgb[1], rgb[2]);
            }
            if ui.small_button("×").on_hover_text("remove frame").clicked() {
                remove = Some(index);
            }
        });
    }
    if let Some(index) = remove {
        frames.remove(index);
    }
}
