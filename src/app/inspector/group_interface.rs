//! The inspector of a group's boundary nodes: the group's inputs (name, default, range,
//! widget) and outputs (name), each renamable and removable. Edits go through
//! `graph::group_interface`, which follows them into every instance, inherited input,
//! exposed parameter and parameter preset.

use crate::app::canvas::boundary::Boundary;
use crate::app::widgets::value_editor;
use crate::graph::group::{GroupDef, GroupInput, Hint};
use crate::graph::group_interface::Side;
use egui::{DragValue, RichText, Ui};

/// One change to a group's interface asked for in the inspector.
#[derive(Clone, Debug, PartialEq)]
pub enum InterfaceEdit {
    Rename {
        side: Side,
        old: String,
        new: String,
    },
    Remove {
        side: Side,
        name: String,
    },
    /// Input `name`'s default, range or widget set to those of `input`.
    Input {
        name: String,
        input: GroupInput,
    },
}

/// The section for boundary node `side` of group `definition`.
pub fn show(ui: &mut Ui, side: Boundary, definition: &GroupDef) -> Option<InterfaceEdit> {
    let mut edit = None;
    if side != Boundary::Output {
        ui.label(RichText::new("Group inputs").strong());
        ui.label(
            RichText::new(
                "Drop a wire from an inner input on the + pin (or right-click the input's \
                 name) to add one.",
            )
            .weak(),
        );
        for input in &definition.inputs {
            ui.separator();
            edit = edit.or(input_rows(ui, input));
        }
    }
    if side != Boundary::Input {
        ui.label(RichText::new("Group outputs").strong());
        ui.label(RichText::new("Drop a wire from an inner output on the + pin to add one.").weak());
        for output in &definition.outputs {
            ui.horizontal(|ui| {
                edit = edit.take().or(name_row(ui, Side::Output, &output.name));
                ui.label(RichText::new(output.ty.to_string()).weak());
            });
        }
    }
    edit
}

/// The rows of one input: name, type and remove; default; range; widget.
fn input_rows(ui: &mut Ui, input: &GroupInput) -> Option<InterfaceEdit> {
    let mut edit = None;
    ui.horizontal(|ui| {
        edit = name_row(ui, Side::Input, &input.name);
        ui.label(RichText::new(input.ty.to_string()).weak());
    });
    let mut changed = input.clone();
    ui.horizontal(|ui| {
        ui.label("default");
        value_editor(ui, &mut changed.default, input.pin_range());
    });
    ui.horizontal(|ui| {
        let mut limited = changed.range.is_some();
        ui.checkbox(&mut limited, "range");
        changed.range = limited.then(|| changed.range.unwrap_or((0.0, 1.0)));
        if let Some((min, max)) = &mut changed.range {
            ui.add(DragValue::new(min).speed(0.01).max_decimals(4));
            ui.label("to");
            ui.add(DragValue::new(max).speed(0.01).max_decimals(4));
        }
    });
    ui.horizontal(|ui| {
        ui.label("widget");
        egui::ComboBox::from_id_salt(("hint", &input.name))
            .selected_text(hint_name(&changed.hint))
            .show_ui(ui, |ui| {
                let options = [
                    Hint::Slider,
                    Hint::Colour,
                    Hint::Toggle,
                    Hint::Choice(vec!["first".into(), "second".into()]),
                ];
                for option in options {
                    let same =
                        std::mem::discriminant(&option) == std::mem::discriminant(&changed.hint);
                    if ui.selectable_label(same, hint_name(&option)).clicked() && !same {
                        changed.hint = option;
                    }
                }
            });
    });
    if let Hint::Choice(options) = &mut changed.hint {
        ui.horizontal(|ui| {
            ui.label("options");
            let id = ui.id().with(("options", &input.name));
            let text = options.join(", ");
            if let Some(typed) = committed_text(ui, id, &text, "comma-separated names")
                && let Ok(list) = choice_options(&typed)
            {
                *options = list;
            }
        });
    }
    if edit.is_none() && changed != *input {
        edit = Some(InterfaceEdit::Input {
            name: input.name.clone(),
            input: changed,
        });
    }
    edit
}

/// A name field (renaming on Enter or when it loses focus) and a remove button.
fn name_row(ui: &mut Ui, side: Side, name: &str) -> Option<InterfaceEdit> {
    let id = ui.id().with(("pin name", side == Side::Input, name));
    let renamed = committed_text(ui, id, name, "name").filter(|new| new != name);
    let removed = ui
        .small_button("×")
        .on_hover_text("remove it, and every wire to or from it")
        .clicked();
    match (renamed, removed) {
        (_, true) => Some(InterfaceEdit::Remove {
            side,
            name: name.to_string(),
        }),
        (Some(new), false) => Some(InterfaceEdit::Rename {
            side,
            old: name.to_string(),
            new,
        }),
        (None, false) => None,
    }
}

/// A one-line text field showing `text`, kept in egui's memory under `id` while it is
/// edited; returns what was typed when Enter is pressed or the field loses focus.
fn committed_text(ui: &mut Ui, id: egui::Id, text: &str, hint: &str) -> Option<String> {
    let mut typed: String = ui
        .data_mut(|d| d.get_temp(id))
        .unwrap_or_else(|| text.to_string());
    let response = ui.add(
        egui::TextEdit::singleline(&mut typed)
            .id(id.with("field"))
            .hint_text(hint)
            .desired_width(140.0),
    );
    if response.lost_focus() {
        ui.data_mut(|d| d.remove::<String>(id));
        return Some(typed.trim().to_string());
    }
    if response.has_focus() {
        ui.data_mut(|d| d.insert_temp(id, typed));
    }
    None
}

/// The options of a choice from comma-separated text: at least two, none empty.
fn choice_options(text: &str) -> Result<Vec<String>, String> {
    let options: Vec<String> = text
        .split(',')
        .map(|part| part.trim().to_string())
        .collect();
    if options.len() < 2 || options.iter().any(String::is_empty) {
        return Err("a choice needs two or more names, separated by commas".into());
    }
    Ok(options)
}

fn hint_name(hint: &Hint) -> &'static str {
    match hint {
        Hint::Slider => "slider",
        Hint::Colour => "colour",
        Hint::Toggle => "toggle",
        Hint::Choice(_) => "choice",
    }
}
