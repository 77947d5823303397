//! Editors for pin values, shared by the node bodies and the inspector.

use crate::graph::{Node, PinDefault, PinRange, Value, ValueType};
use egui::{Color32, DragValue, Ui};

/// The colour of a pin (and its wires) by type.
pub fn type_color(ty: ValueType) -> Color32 {
    match ty {
        ValueType::Float => Color32::from_rgb(160, 160, 160),
        ValueType::Vec2 => Color32::from_rgb(90, 200, 120),
        ValueType::Vec3 => Color32::from_rgb(100, 140, 230),
        ValueType::Color => Color32::from_rgb(230, 200, 60),
    }
}

/// Reads a typed number as egui does (spaces ignored, `−` taken for a minus), refusing
/// what a shader cannot compute with (`inf`, `nan`): the field then keeps its value, as
/// it does for any text that is not a number. Every field that edits a graph's values
/// parses with it.
pub fn finite_number(text: &str) -> Option<f64> {
    let text: String = (text.chars())
        .filter(|c| !c.is_whitespace())
        .map(|c| if c == '−' { '-' } else { c })
        .collect();
    text.parse::<f64>().ok().filter(|x| x.is_finite())
}

/// An editor for one value offered within `range`: dragging steps by the range's step
/// for the value (Shift ten times finer, Ctrl snapping to [`PinRange::snap`]), dragged
/// and typed values stop at the hard limits (a value from a file outside them is kept
/// until edited); returns whether it changed.
pub fn value_editor(ui: &mut Ui, value: &mut Value, range: PinRange) -> bool {
    let drag = |ui: &mut Ui, x: &mut f64| {
        let before = *x;
        let step = range.step(*x);
        let response = ui.add(
            DragValue::new(x)
                .custom_parser(finite_number)
                .speed(step)
                .range(range.min..=range.max)
                .clamp_existing_to_range(false)
                .min_decimals(1)
                .max_decimals(3),
        );
        if response.dragged() && response.changed() && ui.input(|i| i.modifiers.ctrl) {
            let snap = range.snap();
            *x = ((*x / snap).round() * snap).clamp(range.min, range.max);
        }
        // A field left with text that is no number reports a change but keeps its value.
        response.changed() && *x != before
    };
    match value {
        Value::Float(x) => drag(ui, x),
        Value::Vec2(x, y) => drag(ui, x) | drag(ui, y),
        Value::Vec3(x, y, z) => drag(ui, x) | drag(ui, y) | drag(ui, z),
        Value::Color(r, g, b) => {
            let mut rgb = [*r as f32, *g as f32, *b as f32];
            let changed = ui.color_edit_button_rgb(&mut rgb).changed();
            if changed {
                (*r, *g, *b) = (f64::from(rgb[0]), f64::from(rgb[1]), f64::from(rgb[2]));
            }
            changed
        }
    }
}

/// The constant an unconnected input of `node` currently has (its own or the default),
/// and the range the kind offers it in.
pub fn input_value(node: &Node, pin: &str) -> Option<(Value, PinRange)> {
    let (_, spec) = node.kind.signature().input(pin).map(|(i, p)| (i, *p))?;
    let value = match (node.inputs.get(pin), spec.default) {
        (Some(value), _) => value.convert(spec.ty),
        (None, PinDefault::Const(value)) => value,
        _ => return None,
    };
    Some((value, spec.range))
}

/// An editor for the constant of input `pin` of `node`: the value, when edited.
pub fn input_editor(ui: &mut Ui, node: &Node, pin: &str) -> Option<Value> {
    let (mut value, range) = input_value(node, pin)?;
    value_editor(ui, &mut value, range).then_some(value)
}

/// Stores `value`, edited by [`input_editor`], as the constant of input `pin` of node
/// `id` of `snarl` (the view's journal takes the edit to the document).
pub fn store_input(
    snarl: &mut egui_snarl::Snarl<Node>,
    id: egui_snarl::NodeId,
    pin: &str,
    value: Option<Value>,
) {
    if let Some(value) = value {
        snarl[id].inputs.insert(pin.to_string(), value);
    }
}

#[cfg(test)]
mod tests {
    use super::finite_number;

    #[test]
    fn typed_numbers_read_as_egui_reads_them_but_only_finite_ones() {
        assert_eq!(finite_number(" 1 000.5 "), Some(1000.5));
        assert_eq!(finite_number("−2"), Some(-2.0));
        for refused in ["inf", "-inf", "NaN", "1e400", "abc", ""] {
            assert_eq!(finite_number(refused), None, "{refused:?}");
        }
    }
}
