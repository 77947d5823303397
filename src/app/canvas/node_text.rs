//! What the graph view says about a node beyond its pins and title: the tooltips of its
//! header and pins, all read from the node kind's single definition.

use crate::graph::{NodeKind, PinDefault};
use crate::nodes::pins::{InputPin, OutputPin, PinRange};
use crate::nodes::value::Value;

/// The header's tooltip: the kind, its category and the names peers give it.
pub fn kind_tip(kind: &NodeKind) -> String {
    let mut tip = format!("{} ({})", kind.title(), kind.category().name());
    let keywords = kind.definition().keywords();
    if !keywords.is_empty() {
        tip.push_str("\nalso known as: ");
        tip.push_str(&keywords.join(", "));
    }
    tip
}

/// An input pin's tooltip: name, type, what it uses unconnected and its range.
pub fn input_tip(pin: &InputPin) -> String {
    let default = match pin.default {
        PinDefault::Const(value) => format!("default {}", value_text(value)),
        PinDefault::Position => "unconnected: the surface position".to_string(),
        PinDefault::Required => "must be connected".to_string(),
        PinDefault::Builtin(shape) => format!("unconnected: {shape}"),
    };
    let mut tip = format!("{} · {}\n{default}", pin.name, pin.ty);
    if matches!(pin.default, PinDefault::Const(_)) {
        tip.push('\n');
        tip.push_str(&range_text(&pin.range));
    }
    tip
}

/// An output pin's tooltip: name and type.
pub fn output_tip(pin: &OutputPin) -> String {
    format!("{} · {}", pin.name, pin.ty)
}

fn value_text(value: Value) -> String {
    match value {
        Value::Float(x) => format!("{x}"),
        Value::Vec2(x, y) => format!("({x}, {y})"),
        Value::Vec3(x, y, z) | Value::Color(x, y, z) => format!("({x}, {y}, {z})"),
    }
}

fn range_text(range: &PinRange) -> String {
    let usual = format!("usually {} to {}", range.soft_min, range.soft_max);
    match (range.min.is_finite(), range.max.is_finite()) {
        (true, true) => format!("{usual}, limited to {} to {}", range.min, range.max),
        (true, false) => format!("{usual}, at least {}", range.min),
        (false, true) => format!("{usual}, at most {}", range.max),
        (false, false) => usual,
    }
}
