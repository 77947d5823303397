//! The inspector: every setting and input of the selected node, with sliders, drag
//! values, colour pickers, enum choices, colour-ramp stops, and a "connect from" choice
//! per input.

use crate::app::widgets::{finite_number, input_editor, store_input, type_color};
use crate::graph::{Node, PinDefault, RampInterpolation, RampStop, ValueType};
use crate::nodes::settings::{RAMP_INTERPOLATIONS, Setting};
use egui::{ComboBox, RichText, Ui};
use egui_snarl::{InPinId, OutPinId, Snarl};

/// A combo box choosing among `names`; whether the choice changed.
fn combo(ui: &mut Ui, label: &str, names: &[String], selected: &mut usize) -> bool {
    let before = *selected;
    ComboBox::from_label(label)
        .selected_text(names.get(*selected).cloned().unwrap_or_default())
        .show_ui(ui, |ui| {
            for (index, name) in names.iter().enumerate() {
                ui.selectable_value(selected, index, name);
            }
        });
    *selected != before
}

/// A file the user asked to choose in the file browser for a node's file setting.
#[derive(Clone, Debug, PartialEq)]
pub struct FileRequest {
    /// What the browser offers (lower-case extensions).
    pub extensions: &'static [&'static str],
    /// The path the setting holds now, relative to the graph's folder.
    pub current: String,
}

/// Editors for the structural settings the node's kind lists; a file setting's
/// *Choose…* button asks for the file browser.
fn settings(ui: &mut Ui, node: &mut Node) -> Option<FileRequest> {
    let mut request = None;
    for setting in node.kind.settings() {
        match setting {
            Setting::Choice { label, mut value } => {
                let mut selected = value.selected();
                if combo(ui, label, &value.names(), &mut selected) {
                    value.select(selected);
                }
            }
            Setting::Count {
                label,
                value,
                range,
            } => {
                ui.add(egui::Slider::new(value, range).text(label));
            }
            Setting::Toggle { label, value } => {
                ui.checkbox(value, label);
            }
            Setting::File {
                label,
                value,
                extensions,
            } => {
                ui.horizontal(|ui| {
                    ui.label(label);
                    let choose = ui
                        .button("Choose…")
                        .on_hover_text("choose the file in the file browser");
                    if choose.clicked() {
                        request = Some(FileRequest {
                            extensions,
                            current: value.clone(),
                        });
                    }
                });
                // A stable id: the check's message above it comes and goes as the
                // path is typed, and must not take the focus away.
                ui.add(
                    egui::TextEdit::singleline(value)
                        .id(ui.make_persistent_id(("file setting", label)))
                        .hint_text("path relative to the graph's folder")
                        .desired_width(f32::INFINITY),
                );
            }
            Setting::Ramp {
                stops,
                interpolation,
            } => ramp_editor(ui, stops, interpolation),
        }
    }
    request
}

fn ramp_editor(ui: &mut Ui, stops: &mut Vec<RampStop>, interpolation: &mut RampInterpolation) {
    let names: Vec<String> = RAMP_INTERPOLATIONS
        .iter()
        .map(|i| format!("{i:?}"))
        .collect();
    let mut selected = RAMP_INTERPOLATIONS
        .iter()
        .position(|i| i == interpolation)
        .unwrap_or(0);
    if combo(ui, "interpolation", &names, &mut selected) {
        *interpolation = RAMP_INTERPOLATIONS[selected];
    }
    let ramp = crate::nodes::ColorRamp {
        stops: stops.clone(),
        interpolation: *interpolation,
    };
    if let Some(body) = crate::nodes::Definition::body(&ramp) {
        crate::app::inspector::body::show_body(ui, &body, ui.available_width().max(80.0));
    }
    let mut remove = None;
    for (index, stop) in stops.iter_mut().enumerate() {
        ui.horizontal(|ui| {
            ui.add(
                egui::DragValue::new(&mut stop.position)
                    .custom_parser(finite_number)
                    .range(0.0..=1.0)
                    .speed(0.005)
                    .max_decimals(3),
            );
            let mut rgb = [
                stop.color.0 as f32,
                stop.color.1 as f32,
                stop.color.2 as f32,
            ];
            if ui.color_edit_button_rgb(&mut rgb).changed() {
                stop.color = (f64::from(rgb[0]), f64::from(rgb[1]), f64::from(rgb[2]));
            }
            if ui.small_button("×").on_hover_text("remove stop").clicked() {
                remove = Some(index);
            }
        });
    }
    if let Some(index) = remove.filter(|_| stops.len() > 1) {
        stops.remove(index);
    }
    let room = stops.len() < crate::graph::MAX_RAMP_STOPS;
    let add = ui.add_enabled(room, egui::Button::new("Add stop"));
    if add
        .on_disabled_hover_text(format!(
            "a ramp has at most {} stops",
            crate::graph::MAX_RAMP_STOPS
        ))
        .clicked()
    {
        let last = stops.last().copied().unwrap_or(RampStop {
            position: 0.0,
            color: (0.5, 0.5, 0.5),
        });
        stops.push(RampStop {
            position: (last.position + 0.1).min(1.0),
            ..last
        });
    }
    stops.sort_by(|a, b| a.position.total_cmp(&b.position));
}

/// Outputs of other nodes that could feed an input of type `ty` of `target` (never
/// closing a cycle: nodes that read `target`, directly or not, are left out). Linear in
/// the graph: asked only while the choice is open.
fn candidates(
    snarl: &Snarl<Node>,
    target: egui_snarl::NodeId,
    ty: ValueType,
) -> Vec<(OutPinId, String)> {
    let readers = readers_of(snarl, target);
    let mut found = Vec::new();
    for (id, node) in snarl.node_ids() {
        if readers.contains(&id) {
            continue;
        }
        for (index, pin) in node.kind.signature().outputs.iter().enumerate() {
            // (A boundary node's "+" takes wires only to declare a new group input.)
            if pin.ty.converts_to(ty) && !crate::app::canvas::boundary::is_add_pin(node, pin.name) {
                found.push((
                    OutPinId {
                        node: id,
                        output: index,
                    },
                    source_name(node, pin.name),
                ));
            }
        }
    }
    found
}

/// How a choice names the output `pin` of `node`.
fn source_name(node: &Node, pin: &str) -> String {
    format!("{} · {}", node.display_name(), pin)
}

/// `source` and every node that reads it, directly or not.
fn readers_of(
    snarl: &Snarl<Node>,
    source: egui_snarl::NodeId,
) -> std::collections::HashSet<egui_snarl::NodeId> {
    let mut readers: std::collections::HashMap<_, Vec<_>> = std::collections::HashMap::new();
    for (from, to) in snarl.wires() {
        readers
            .entry(from.node)
            .or_insert_with(Vec::new)
            .push(to.node);
    }
    let mut reached = std::collections::HashSet::new();
    let mut stack = vec![source];
    while let Some(node) = stack.pop() {
        if reached.insert(node) {
            stack.extend(readers.get(&node).into_iter().flatten().copied());
        }
    }
    reached
}

/// Shows the inspector for node `id` of `snarl`; a file the user asked to choose.
pub fn show(
    ui: &mut Ui,
    snarl: &mut Snarl<Node>,
    id: egui_snarl::NodeId,
    error: Option<&String>,
    warning: Option<&String>,
) -> Option<FileRequest> {
    // Edited as a copy, put back when changed: the view's journal then lists it.
    let Some(mut node) = snarl.get_node(id).cloned() else {
        return None;
    };
    ui.horizontal(|ui| {
        ui.label(RichText::new(node.kind.title()).strong());
        ui.weak(format!("{}", node.id));
    });
    ui.horizontal(|ui| {
        ui.label("label");
        ui.text_edit_singleline(&mut node.label);
    });
    if let Some(error) = error {
        ui.colored_label(egui::Color32::from_rgb(240, 80, 60), error);
    }
    if let Some(warning) = warning {
        ui.colored_label(
            egui::Color32::from_rgb(230, 180, 60),
            format!("⚠ {warning}"),
        );
    }
    let request = settings(ui, &mut node);
    let inputs = node.kind.signature().inputs;
    if node != snarl[id] {
        snarl[id] = node;
    }
    ui.separator();
    for (index, pin) in inputs.iter().enumerate() {
        let pin_id = InPinId {
            node: id,
            input: index,
        };
        let source = snarl.in_pin(pin_id).remotes.first().copied();
        ui.horizontal(|ui| {
            ui.colored_label(type_color(pin.ty), pin.name);
            let current = match source {
                Some(from) => snarl
                    .get_node(from.node)
                    .and_then(|node| {
                        let signature = node.kind.signature();
                        let output = signature.outputs.get(from.output)?;
                        Some(source_name(node, output.name))
                    })
                    .unwrap_or_default(),
                None => match pin.default {
                    PinDefault::Const(_) => "constant".to_string(),
                    PinDefault::Position => "position".to_string(),
                    PinDefault::Required => "(not connected)".to_string(),
                    PinDefault::Builtin(shape) => format!("its own: {shape}"),
                },
            };
            let mut chosen = source;
            ComboBox::from_id_salt(("connect", index))
                .selected_text(current)
                .show_ui(ui, |ui| {
                    ui.selectable_value(&mut chosen, None, "no wire");
                    for (option, name) in &candidates(snarl, id, pin.ty) {
                        ui.selectable_value(&mut chosen, Some(*option), name);
                    }
                });
            if chosen != source {
                snarl.drop_inputs(pin_id);
                if let Some(from) = chosen {
                    snarl.connect(from, pin_id);
                }
            }
            if chosen.is_none() && matches!(pin.default, PinDefault::Const(_)) {
                let edited = input_editor(ui, &snarl[id], pin.name);
                store_input(snarl, id, pin.name, edited);
            }
        });
    }
    request
}
