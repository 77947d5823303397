//! Wires under the pointer: where each pin was drawn this frame, which wire the pointer
//! is on (to show its value, or to drop a dragged node onto it), and inserting a node
//! into a wire.
//!
//! egui-snarl keeps its wire hit-testing to itself, so pins report where they were
//! drawn and the wires are traced here as snarl draws them by default (5th-degree
//! Bézier curves, left to right; a wire running backwards is traced more roughly).

use crate::graph::{Node, PinRef};
use egui::{Pos2, Rect};
use egui_snarl::ui::{PinInfo, PinWireInfo, SnarlPin, SnarlStyle};
use egui_snarl::{InPinId, OutPinId, Snarl};
use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;

/// How near a wire the pointer must be to be on it, in points of the graph.
const HIT_DISTANCE: f32 = 6.0;

/// Where pins and nodes were drawn in the last frame, in graph coordinates.
#[derive(Default)]
pub struct Spots {
    outputs: HashMap<OutPinId, Pos2>,
    inputs: HashMap<InPinId, Pos2>,
    /// Nodes' rectangles.
    pub nodes: HashMap<egui_snarl::NodeId, Rect>,
    /// The pin size snarl draws with (it sets how far wires leave their pins straight).
    pin_size: f32,
}

/// Spots shared between the viewer's pins (which fill them while snarl draws) and the app.
pub type SharedSpots = Rc<RefCell<Spots>>;

/// Which pin a [`SpottedPin`] is.
#[derive(Clone, Copy)]
pub enum PinSide {
    In(InPinId),
    Out(OutPinId),
}

/// A pin drawn as `info` that records where it was drawn.
pub struct SpottedPin {
    pub info: PinInfo,
    pub pin: PinSide,
    pub spots: SharedSpots,
}

impl SnarlPin for SpottedPin {
    fn draw(
        self,
        snarl_style: &SnarlStyle,
        style: &egui::Style,
        rect: Rect,
        painter: &egui::Painter,
    ) -> PinWireInfo {
        let mut spots = self.spots.borrow_mut();
        match self.pin {
            PinSide::In(pin) => spots.inputs.insert(pin, rect.center()),
            PinSide::Out(pin) => spots.outputs.insert(pin, rect.center()),
        };
        spots.pin_size = rect.width().max(rect.height());
        self.info.draw(snarl_style, style, rect, painter)
    }
}

impl Spots {
    /// The wire whose curve passes within [`HIT_DISTANCE`] of `pointer` (graph
    /// coordinates), leaving out wires that touch `except`.
    pub fn wire_at(
        &self,
        snarl: &Snarl<Node>,
        pointer: Pos2,
        except: Option<egui_snarl::NodeId>,
    ) -> Option<(OutPinId, InPinId)> {
        snarl
            .wires()
            .filter(|(from, to)| except.is_none_or(|node| from.node != node && to.node != node))
            .find(|(from, to)| {
                let (Some(a), Some(b)) = (self.outputs.get(from), self.inputs.get(to)) else {
                    return false;
                };
                distance_to_polyline(&self.curve(*a, *b), pointer) <= HIT_DISTANCE
            })
    }

    /// Points along the wire from `from` to `to`, as snarl draws it.
    pub fn curve(&self, from: Pos2, to: Pos2) -> Vec<Pos2> {
        // snarl's default frame: three pin sizes, at most a sixth of the wire's length.
        let frame = (self.pin_size * 3.0).min((to - from).length() / 6.0);
        let from_2 = from + egui::vec2(frame, 0.0);
        let to_2 = to - egui::vec2(frame, 0.0);
        let towards = (to_2 - from_2).normalized();
        let controls = [
            from,
            from_2,
            from_2 + towards * frame,
            to_2 - towards * frame,
            to_2,
            to,
        ];
        (0..=48)
            .map(|k| bezier(&controls, k as f32 / 48.0))
            .collect()
    }

    /// Where `pin` (of `node`) was drawn.
    pub fn output(&self, pin: OutPinId) -> Option<Pos2> {
        self.outputs.get(&pin).copied()
    }

    /// Where `pin` was drawn.
    pub fn input(&self, pin: InPinId) -> Option<Pos2> {
        self.inputs.get(&pin).copied()
    }
}

/// The point at `t` of the Bézier curve with `controls` (de Casteljau).
fn bezier(controls: &[Pos2; 6], t: f32) -> Pos2 {
    let mut points = *controls;
    for level in (1..points.len()).rev() {
        for k in 0..level {
            points[k] = points[k].lerp(points[k + 1], t);
        }
    }
    points[0]
}

fn distance_to_polyline(points: &[Pos2], pointer: Pos2) -> f32 {
    points
        .windows(2)
        .map(|segment| {
            let (a, b) = (segment[0], segment[1]);
            let along = b - a;
            let t = ((pointer - a).dot(along) / along.length_sq().max(1e-6)).clamp(0.0, 1.0);
            (a + along * t).distance(pointer)
        })
        .fold(f32::INFINITY, f32::min)
}

/// The output pin a wire carries, as the graph names it.
pub fn carried(snarl: &Snarl<Node>, from: OutPinId) -> Option<PinRef> {
    let node = snarl.get_node(from.node)?;
    let output = node.kind.signature().outputs.get(from.output)?.name;
    Some(PinRef::new(node.id, output))
}

/// Puts `node` into the wire `from` → `to`: `from` into the node's first free input
/// that takes its type, the node's first free output that `to` takes into `to`.
/// Returns whether it did (nothing changes when the node has no such pins, or when
/// either new wire would close a cycle).
pub fn insert_into_wire(
    snarl: &mut Snarl<Node>,
    node: egui_snarl::NodeId,
    (from, to): (OutPinId, InPinId),
) -> bool {
    let signature = snarl[node].kind.signature();
    let given = snarl[from.node].kind.signature().outputs[from.output].ty;
    let wanted = snarl[to.node].kind.signature().inputs[to.input].ty;
    let wired_in = |input: usize| {
        snarl
            .wires()
            .any(|(_, target)| target == InPinId { node, input })
    };
    let wired_out = |output: usize| {
        snarl
            .wires()
            .any(|(source, _)| source == OutPinId { node, output })
    };
    let input = (0..signature.inputs.len())
        .find(|&k| given.converts_to(signature.inputs[k].ty) && !wired_in(k));
    let output = (0..signature.outputs.len())
        .find(|&k| signature.outputs[k].ty.converts_to(wanted) && !wired_out(k));
    let (Some(input), Some(output)) = (input, output) else {
        return false;
    };
    if crate::app::canvas::snarl_model::would_cycle(snarl, from.node, node)
        || crate::app::canvas::snarl_model::would_cycle(snarl, node, to.node)
    {
        return false;
    }
    snarl.disconnect(from, to);
    snarl.connect(from, InPinId { node, input });
    snarl.connect(OutPinId { node, output }, to);
    true
}
