//! A node's footprint: the rectangle the editor draws it in, in canvas units, reckoned
//! from what the node shows (its title, a row per pin with the label and, for an input
//! left unwired, its value fields, the colour ramp's bar, the thumbnail under the pins)
//! at the sizes egui draws them at the editor's usual zoom. Never smaller than what is
//! drawn (the editor's tests measure it), so footprints that do not intersect are nodes
//! that do not overlap on screen.

use crate::graph::{Node, NodeId, NodeKind, PinDefault, Shading, Value, Wire};
use crate::nodes::Body;
use std::collections::HashSet;

/// Widths of the printable ASCII characters (space to `~`) in egui's proportional font
/// (Ubuntu Light), in ems to three decimals; any other character is reckoned an em wide.
const ADVANCE: [f32; 95] = [
    0.228, 0.274, 0.392, 0.653, 0.564, 0.831, 0.648, 0.240, 0.310, 0.310, 0.472, 0.564, 0.246,
    0.282, 0.246, 0.359, 0.564, 0.564, 0.564, 0.564, 0.564, 0.564, 0.564, 0.564, 0.564, 0.564,
    0.246, 0.246, 0.564, 0.564, 0.564, 0.380, 0.940, 0.671, 0.630, 0.601, 0.702, 0.555, 0.520,
    0.658, 0.692, 0.248, 0.487, 0.599, 0.502, 0.865, 0.709, 0.774, 0.592, 0.774, 0.618, 0.517,
    0.570, 0.680, 0.652, 0.932, 0.624, 0.600, 0.560, 0.310, 0.359, 0.310, 0.564, 0.490, 0.376,
    0.509, 0.583, 0.460, 0.583, 0.548, 0.376, 0.573, 0.569, 0.237, 0.245, 0.495, 0.255, 0.863,
    0.569, 0.582, 0.583, 0.583, 0.374, 0.428, 0.387, 0.569, 0.496, 0.790, 0.514, 0.489, 0.455,
    0.319, 0.262, 0.319, 0.564,
];

/// The size of node titles, and of pin labels and values (egui's body text).
const TITLE_SIZE: f32 = 24.0;
const TEXT_SIZE: f32 = 14.0;
/// The node's frame around its contents, on each side (margin and stroke).
const FRAME: f32 = 7.0;
/// Before the title: the collapse button, the drag handle and the spaces after them.
const TITLE_LEAD: f32 = 44.0;
/// A warning or error sign after the title, with its space.
const SIGN: f32 = 23.0;
/// The title's row, and the space between it and the pins.
const TITLE_ROW: f32 = 28.0;
const BELOW_TITLE: f32 = 10.0;
/// Space between widgets side by side, and between rows.
const SPACE: f32 = 8.0;
const ROW_SPACE: f32 = 3.0;
/// A pin row's height (that of a value field).
const ROW: f32 = 18.0;
/// The room a pin takes beside its row.
const PIN: f32 = 11.0;
/// The narrowest value field, its padding around the number, and a colour swatch.
const FIELD: f32 = 40.0;
const FIELD_PADDING: f32 = 8.0;
const SWATCH: f32 = 40.0;
/// The thumbnail under the pins of a node with an output.
const THUMBNAIL: f32 = 64.0;

/// A rectangle of the canvas, in canvas units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    pub min: (f32, f32),
    pub max: (f32, f32),
}

impl Bounds {
    /// Whether the two share more than an edge.
    pub fn intersects(&self, other: &Bounds) -> bool {
        self.min.0 < other.max.0
            && other.min.0 < self.max.0
            && self.min.1 < other.max.1
            && other.min.1 < self.max.1
    }

    /// The rectangle grown by `by` on every side.
    pub fn expand(&self, by: f32) -> Bounds {
        Bounds {
            min: (self.min.0 - by, self.min.1 - by),
            max: (self.max.0 + by, self.max.1 + by),
        }
    }

    /// The smallest rectangle holding both.
    pub fn union(&self, other: &Bounds) -> Bounds {
        Bounds {
            min: (self.min.0.min(other.min.0), self.min.1.min(other.min.1)),
            max: (self.max.0.max(other.max.0), self.max.1.max(other.max.1)),
        }
    }
}

/// The size of the rectangle the editor draws a node in, in whole canvas units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Footprint {
    pub width: f32,
    pub height: f32,
}

impl Footprint {
    /// The footprint of `node` whose inputs named by `wired` are connected (a wired
    /// input shows no value field).
    pub fn of(node: &Node, wired: impl Fn(&str) -> bool) -> Footprint {
        let signature = node.kind.signature();
        let input_rows = signature.inputs.iter().map(|pin| {
            let shown = match pin.default {
                _ if wired(pin.name) => 0.0,
                PinDefault::Const(default) => {
                    let value = node.inputs.get(pin.name).copied().unwrap_or(default);
                    SPACE + fields_width(value.convert(pin.ty))
                }
                PinDefault::Position => SPACE + text_width("position", TEXT_SIZE),
                PinDefault::Required => SPACE + text_width("connect", TEXT_SIZE),
                PinDefault::Builtin(shape) => SPACE + text_width(shape, TEXT_SIZE),
            };
            PIN + SPACE + text_width(pin.name, TEXT_SIZE) + shown
        });
        let output_rows = signature
            .outputs
            .iter()
            .map(|pin| text_width(pin.name, TEXT_SIZE) + SPACE + PIN);
        let (inputs, outputs) = (
            input_rows.fold(0.0, f32::max),
            output_rows.fold(0.0, f32::max),
        );
        // A body picture (the colour ramp's bar) sits between the inputs and outputs.
        let (bar_width, bar_height) = match node.kind.definition().body() {
            Some(_) => (Body::SIZE.0 + SPACE, Body::SIZE.1),
            None => (0.0, 0.0),
        };
        let pins_width = inputs + SPACE + bar_width + outputs;
        let mut title = TITLE_LEAD + text_width(&node.title(), TITLE_SIZE) + SIGN;
        if node.kind == NodeKind::Material {
            // The shading's name after the title, whichever it is.
            let widest = Shading::ALL.map(|shading| text_width(shading.name(), TEXT_SIZE));
            title += SPACE + widest.into_iter().fold(0.0, f32::max);
        }
        let rows = signature.inputs.len().max(signature.outputs.len()) as f32;
        let pins_height = (rows * (ROW + ROW_SPACE)).max(bar_height);
        let footer = if signature.outputs.is_empty() {
            0.0
        } else {
            ROW_SPACE + THUMBNAIL
        };
        Footprint {
            width: (2.0 * FRAME + title.max(pins_width)).ceil(),
            height: (2.0 * FRAME + TITLE_ROW + BELOW_TITLE + pins_height + footer).ceil(),
        }
    }

    /// The rectangle it covers with its node at `position` (the editor draws a node's
    /// frame around the point it is placed at).
    pub fn at(&self, position: (f32, f32)) -> Bounds {
        let min = (position.0 - FRAME, position.1 - FRAME);
        Bounds {
            min,
            max: (min.0 + self.width, min.1 + self.height),
        }
    }
}

/// The footprint of each of `nodes`, joined by `wires`, in their order.
pub fn footprints(nodes: &[Node], wires: &[Wire]) -> Vec<Footprint> {
    let wired: HashSet<(NodeId, &str)> = wires
        .iter()
        .map(|wire| (wire.to.node, wire.to.pin.as_str()))
        .collect();
    nodes
        .iter()
        .map(|node| Footprint::of(node, |pin| wired.contains(&(node.id, pin))))
        .collect()
}

/// Where each of `nodes`, joined by `wires`, is drawn, in their order.
pub fn bounds(nodes: &[Node], wires: &[Wire]) -> Vec<Bounds> {
    footprints(nodes, wires)
        .iter()
        .zip(nodes)
        .map(|(footprint, node)| footprint.at(node.position))
        .collect()
}

/// Two of `nodes` (joined by `wires`) whose footprints intersect, if any: the first
/// found sweeping from left to right.
pub fn overlapping(nodes: &[Node], wires: &[Wire]) -> Option<(NodeId, NodeId)> {
    let drawn = bounds(nodes, wires);
    let mut order: Vec<usize> = (0..nodes.len()).collect();
    order.sort_by(|a, b| drawn[*a].min.0.total_cmp(&drawn[*b].min.0));
    // Only nodes whose spans in x meet are compared.
    for (k, &a) in order.iter().enumerate() {
        for &b in &order[k + 1..] {
            if drawn[b].min.0 >= drawn[a].max.0 {
                break;
            }
            if drawn[a].intersects(&drawn[b]) {
                return Some((nodes[a].id, nodes[b].id));
            }
        }
    }
    None
}

/// How wide `text` is drawn at `size`.
fn text_width(text: &str, size: f32) -> f32 {
    let ems: f32 = text
        .chars()
        .map(|c| match c {
            ' '..='~' => ADVANCE[c as usize - ' ' as usize],
            _ => 1.0,
        })
        .sum();
    ems * size
}

/// How wide the fields editing `value` are: a number field per component (its number
/// with up to four decimals), or one colour swatch.
fn fields_width(value: Value) -> f32 {
    let number = |x: f64| {
        let text = format!("{x:.4}");
        (text_width(&text, TEXT_SIZE) + FIELD_PADDING).max(FIELD)
    };
    let numbers =
        |xs: &[f64]| xs.iter().map(|x| number(*x)).sum::<f32>() + SPACE * (xs.len() - 1) as f32;
    match value {
        Value::Float(x) => number(x),
        Value::Vec2(x, y) => numbers(&[x, y]),
        Value::Vec3(x, y, z) => numbers(&[x, y, z]),
        Value::Color(..) => SWATCH,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::graph::{Graph, NodeKind};

    fn alone(graph: &Graph, index: usize) -> Footprint {
        footprints(&graph.nodes, &graph.wires)[index]
    }

    #[test]
    fn a_transform_with_three_vectors_is_wider_than_its_title() {
        let mut graph = Graph::default();
        let a = graph.add("t", NodeKind::Transform);
        let width = alone(&graph, 0).width;
        assert!(width > 3.0 * FIELD + PIN, "{width}");
        // Wired inputs show no fields.
        let p = graph.add("p", NodeKind::Position);
        for pin in ["scale", "rotation", "offset"] {
            graph.connect(p, "position", a, pin);
        }
        assert!(alone(&graph, 0).width < width);
    }

    #[test]
    fn a_colour_ramp_holds_its_bar_beside_its_pins() {
        let ramp = NodeKind::examples()
            .into_iter()
            .find(|kind| matches!(kind, NodeKind::ColorRamp(_)))
            .unwrap();
        let mut graph = Graph::default();
        graph.add("", ramp);
        let pins = text_width("factor", TEXT_SIZE) + text_width("color", TEXT_SIZE);
        assert!(alone(&graph, 0).width > Body::SIZE.0 + pins + 2.0 * PIN);
    }

    #[test]
    fn long_titles_and_large_values_widen_a_node() {
        let mut graph = Graph::default();
        graph.add("a", NodeKind::Position);
        graph.add(&"W".repeat(30), NodeKind::Position);
        graph.add("s", NodeKind::Smoothstep);
        let large = graph.add("s", NodeKind::Smoothstep);
        graph.set_input(large, "edge0", Value::Float(-123_456.5));
        let sizes = footprints(&graph.nodes, &graph.wires);
        assert!(sizes[1].width > 30.0 * 0.9 * TITLE_SIZE, "{:?}", sizes[1]);
        assert!(sizes[1].width > sizes[0].width);
        assert!(sizes[3].width > sizes[2].width);
        // Nodes with an output show a thumbnail under their pins; the material does not.
        graph.add("m", NodeKind::Material);
        let material = footprints(&graph.nodes, &graph.wires)[4];
        let rows = NodeKind::Material.signature().inputs.len() as f32;
        let expected = 2.0 * FRAME + TITLE_ROW + BELOW_TITLE + rows * (ROW + ROW_SPACE);
        assert_eq!(material.height, expected.ceil());
    }

    #[test]
    fn a_footprint_starts_its_frame_up_and_left_of_the_node() {
        let size = Footprint {
            width: 100.0,
            height: 50.0,
        };
        let at = size.at((10.0, 20.0));
        assert_eq!(at.min, (10.0 - FRAME, 20.0 - FRAME));
        assert_eq!(at.max, (110.0 - FRAME, 70.0 - FRAME));
        assert!(!at.intersects(&size.at((110.0, 20.0))), "edges touch");
        assert!(at.intersects(&size.at((109.0, 69.0))));
    }
}
