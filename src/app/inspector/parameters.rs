//! The *Parameters* section of the side panel: the graph's exposed parameters (what
//! `veneer render --set` changes), each with the widget its hint asks for, and its
//! parameter presets. Values go through `graph::parameters`, as the command line's do.

use crate::app::VeneerApp;
use crate::app::widgets::finite_number;
use crate::graph::edit::{GraphEdit, Level};
use crate::graph::group::Hint;
use crate::graph::parameters::{self, Exposed, Given};
use crate::graph::{Value, ValueType};
use egui::Ui;

impl VeneerApp {
    /// The collapsible *Parameters* section (absent when the graph exposes none).
    pub(in crate::app) fn parameters_panel(&mut self, ui: &mut Ui) {
        let exposed = parameters::exposed(&self.session.document.graph);
        let presets: Vec<String> = self
            .session
            .document
            .graph
            .presets
            .keys()
            .cloned()
            .collect();
        if exposed.is_empty() && presets.is_empty() {
            return;
        }
        ui.separator();
        egui::CollapsingHeader::new("Parameters")
            .default_open(true)
            .show(ui, |ui| {
                if !presets.is_empty() {
                    let mut chosen = None;
                    egui::ComboBox::from_label("preset")
                        .selected_text("apply a preset…")
                        .show_ui(ui, |ui| {
                            for name in &presets {
                                if ui.button(name).clicked() {
                                    chosen = Some(name.clone());
                                }
                            }
                        });
                    if let Some(name) = chosen
                        && self.edit(GraphEdit::ApplyPreset { name: name.clone() })
                    {
                        self.chrome.message = Some(format!("applied preset '{name}'"));
                    }
                }
                self.fit_to_image_button(ui, !exposed.is_empty());
                egui::Grid::new("parameters")
                    .num_columns(2)
                    .striped(true)
                    .show(ui, |ui| {
                        for entry in &exposed {
                            ui.label(&entry.name)
                                .on_hover_text(format!("--set {}=…", entry.name));
                            let mut value = entry.value;
                            if parameter_editor(ui, entry, &mut value) {
                                self.set_parameter(entry, &value);
                            }
                            ui.end_row();
                        }
                    });
            });
    }

    /// Sets exposed parameter `entry` to `value`, checked against its type and range
    /// as the command line's `--set` is: an edit of the input it stands for.
    fn set_parameter(&mut self, entry: &Exposed, value: &Value) {
        match entry.value_of(&Given::of(value)) {
            Ok(value) => {
                self.edit(GraphEdit::SetInput {
                    level: Level::Top,
                    node: entry.target.node,
                    pin: entry.target.pin.clone(),
                    value: Some(value),
                });
            }
            Err(error) => self.chrome.message = Some(error.to_string()),
        }
    }
}

/// The widget for exposed parameter `entry` as its hint asks; whether `value` changed.
fn parameter_editor(ui: &mut Ui, entry: &Exposed, value: &mut Value) -> bool {
    if entry.hint == Hint::Colour || entry.ty == ValueType::Color {
        let [r, g, b] = value.components();
        let mut rgb = [r as f32, g as f32, b as f32];
        let changed = ui.color_edit_button_rgb(&mut rgb).changed();
        if changed {
            let [r, g, b] = rgb.map(f64::from);
            *value = Value::Color(r, g, b).convert(entry.ty);
        }
        return changed;
    }
    match (&entry.hint, value) {
        (Hint::Toggle, Value::Float(x)) => {
            let mut on = *x != 0.0;
            let changed = ui.checkbox(&mut on, "").changed();
            *x = if on { 1.0 } else { 0.0 };
            changed
        }
        (Hint::Choice(options), Value::Float(x)) => {
            let before = x.round().max(0.0) as usize;
            let mut selected = before;
            egui::ComboBox::from_id_salt(("parameter", &entry.name))
                .selected_text(options.get(selected).cloned().unwrap_or_default())
                .show_ui(ui, |ui| {
                    for (index, option) in options.iter().enumerate() {
                        ui.selectable_value(&mut selected, index, option);
                    }
                });
            *x = selected as f64;
            selected != before
        }
        (_, value) => {
            let components: Vec<&mut f64> = match value {
                Value::Float(x) => vec![x],
                Value::Vec2(x, y) => vec![x, y],
                Value::Vec3(x, y, z) | Value::Color(x, y, z) => vec![x, y, z],
            };
            let mut changed = false;
            ui.horizontal(|ui| {
                for x in components {
                    let before = *x;
                    let response = match entry.range {
                        Some((min, max)) => {
                            ui.add(egui::Slider::new(x, min..=max).custom_parser(finite_number))
                        }
                        None => ui.add(
                            egui::DragValue::new(x)
                                .custom_parser(finite_number)
                                .speed(0.01),
                        ),
                    };
                    // A field left with text that is no number reports a change but
                    // keeps its value.
                    changed |= response.changed() && *x != before;
                }
            });
            changed
        }
    }
}
