//! Pin signatures: the inputs and outputs of a node kind, with the defaults and the
//! ranges the inspector offers, and the small builders the family files use.

use super::value::{Value, ValueType};

/// What an unconnected input uses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PinDefault {
    /// A constant, overridable per node in the graph file.
    Const(Value),
    /// The surface position (texture-space coordinate), like Blender's implicit vector input.
    Position,
    /// The input must be wired.
    Required,
    /// Unwired, the node draws a pattern of its own (a re-evaluated input's fallback,
    /// described in these words: "a dome").
    Builtin(&'static str),
}

/// Points of pointer travel a drag takes to change a value by its own size (or, near
/// zero, by a twentieth of its pin's soft span).
pub const DRAG_POINTS: f64 = 200.0;

/// How the inspector offers a constant input: hard limits for dragging, and the span
/// artists usually work in (its width sets the drag step).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PinRange {
    pub min: f64,
    pub max: f64,
    pub soft_min: f64,
    pub soft_max: f64,
}

impl PinRange {
    /// Any finite value, usually within [-1, 1].
    pub const ANY: PinRange = PinRange {
        min: f64::NEG_INFINITY,
        max: f64::INFINITY,
        soft_min: -1.0,
        soft_max: 1.0,
    };

    /// The drag step (change per point of pointer travel) for a value of `magnitude`:
    /// a drag of [`DRAG_POINTS`] changes the value by its own size, so that 1 drags as
    /// finely as 1,000 does coarsely; near zero, by a twentieth of the soft span. Shift
    /// drags ten times finer, Ctrl snaps to [`PinRange::snap`].
    pub fn step(&self, magnitude: f64) -> f64 {
        let span = self.soft_max - self.soft_min;
        (magnitude.abs().max(span / 20.0) / DRAG_POINTS).min(1.0e6)
    }

    /// What a drag with Ctrl held snaps to: a round step (1, 2 or 5 × 10ⁿ) no larger
    /// than a twentieth of the soft span.
    pub fn snap(&self) -> f64 {
        let span = (self.soft_max - self.soft_min).clamp(1e-9, 1e12);
        let target = span / 20.0;
        let decade = 10f64.powf(target.log10().floor());
        [5.0, 2.0, 1.0]
            .into_iter()
            .map(|factor| factor * decade)
            .find(|step| *step <= target)
            .unwrap_or(decade)
    }
}

/// One input pin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InputPin {
    pub name: &'static str,
    pub ty: ValueType,
    pub default: PinDefault,
    pub range: PinRange,
    /// Whether the node reads its upstream at other points than the one being shaded:
    /// the compiler renders the upstream into a buffer (a pass) and the node samples it.
    pub sampled: bool,
    /// Whether the node evaluates its upstream itself, once per instance it places, at
    /// points of its own choosing (a local frame, or an instance's centre): the compiler
    /// emits the upstream as a function of the surface and the instance (see
    /// `graph::frames`).
    pub re_evaluated: bool,
}

impl InputPin {
    /// The same pin offered within `soft` (any value allowed).
    pub const fn soft(self, soft_min: f64, soft_max: f64) -> InputPin {
        InputPin {
            range: PinRange {
                soft_min,
                soft_max,
                ..self.range
            },
            ..self
        }
    }

    /// The same pin read as a buffer (see [`InputPin::sampled`]); it must be wired.
    pub const fn sampled(self) -> InputPin {
        InputPin {
            sampled: true,
            default: PinDefault::Required,
            ..self
        }
    }

    /// The same pin re-evaluated by its node (see [`InputPin::re_evaluated`]).
    pub const fn re_evaluated(self) -> InputPin {
        InputPin {
            re_evaluated: true,
            ..self
        }
    }

    /// The same pin stopped at `min` in the inspector, offered within its soft span.
    pub const fn at_least(self, min: f64) -> InputPin {
        InputPin {
            range: PinRange { min, ..self.range },
            ..self
        }
    }

    /// The same pin limited to [min, max] in the inspector, offered within that span.
    pub const fn limits(self, min: f64, max: f64) -> InputPin {
        InputPin {
            range: PinRange {
                min,
                max,
                soft_min: min,
                soft_max: max,
            },
            ..self
        }
    }
}

/// One output pin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OutputPin {
    pub name: &'static str,
    pub ty: ValueType,
    /// Whether its whole-number values name things (an instance's number): thumbnails
    /// show each value as a colour of its own rather than as a grey.
    pub identity: bool,
}

impl OutputPin {
    /// The same pin naming things (see [`OutputPin::identity`]).
    pub const fn identity(self) -> OutputPin {
        OutputPin {
            identity: true,
            ..self
        }
    }
}

/// The pins of a node kind.
#[derive(Clone, Debug, Default)]
pub struct Signature {
    pub inputs: Vec<InputPin>,
    pub outputs: Vec<OutputPin>,
    /// The first pin of each name, on signatures with many pins (a group's): looking
    /// a pin up by name stays cheap however many there are. A lookup the index does
    /// not confirm (pins edited in place) scans the pins.
    index: Option<std::sync::Arc<PinIndex>>,
}

impl PartialEq for Signature {
    fn eq(&self, other: &Signature) -> bool {
        self.inputs == other.inputs && self.outputs == other.outputs
    }
}

/// Pin positions by name.
#[derive(Debug, Default)]
struct PinIndex {
    inputs: std::collections::HashMap<&'static str, usize>,
    outputs: std::collections::HashMap<&'static str, usize>,
}

impl Signature {
    /// Pins a signature has before it indexes them by name.
    const SCANNED: usize = 16;

    /// A signature of these inputs and outputs.
    pub fn new(inputs: Vec<InputPin>, outputs: Vec<OutputPin>) -> Signature {
        let index = (inputs.len() + outputs.len() > Self::SCANNED).then(|| {
            let mut index = PinIndex::default();
            for (k, pin) in inputs.iter().enumerate() {
                index.inputs.entry(pin.name).or_insert(k);
            }
            for (k, pin) in outputs.iter().enumerate() {
                index.outputs.entry(pin.name).or_insert(k);
            }
            std::sync::Arc::new(index)
        });
        Signature {
            inputs,
            outputs,
            index,
        }
    }

    /// The input pin called `name` and its index.
    pub fn input(&self, name: &str) -> Option<(usize, &InputPin)> {
        let index = self.index.as_ref().map(|index| &index.inputs);
        find(&self.inputs, index, name, |pin| pin.name)
    }

    /// The output pin called `name` and its index.
    pub fn output(&self, name: &str) -> Option<(usize, &OutputPin)> {
        let index = self.index.as_ref().map(|index| &index.outputs);
        find(&self.outputs, index, name, |pin| pin.name)
    }
}

/// The first pin called `name` among `pins` and its index: where `index` says, when
/// that pin has the name, else found by a scan.
fn find<'p, P>(
    pins: &'p [P],
    index: Option<&std::collections::HashMap<&'static str, usize>>,
    name: &str,
    name_of: impl Fn(&P) -> &str,
) -> Option<(usize, &'p P)> {
    let indexed = index
        .and_then(|index| index.get(name))
        .and_then(|&k| Some((k, pins.get(k)?)));
    match indexed {
        Some((k, pin)) if name_of(pin) == name => Some((k, pin)),
        _ => pins
            .iter()
            .enumerate()
            .find(|(_, pin)| name_of(pin) == name),
    }
}

/// The index of input pin `name` among `pins`. A name the kind does not have is a bug
/// in its definition (the registry test exercises every part of every kind).
pub fn pin_index(pins: &[InputPin], name: &str) -> usize {
    pins.iter()
        .position(|pin| pin.name == name)
        .unwrap_or_else(|| panic!("the node kind has no input '{name}'"))
}

/// A float default.
pub const fn f(x: f64) -> PinDefault {
    PinDefault::Const(Value::Float(x))
}
/// A vec2 default.
pub const fn v2(x: f64, y: f64) -> PinDefault {
    PinDefault::Const(Value::Vec2(x, y))
}
/// A vec3 default.
pub const fn v3(x: f64, y: f64, z: f64) -> PinDefault {
    PinDefault::Const(Value::Vec3(x, y, z))
}
/// A colour default.
pub const fn rgb(r: f64, g: f64, b: f64) -> PinDefault {
    PinDefault::Const(Value::Color(r, g, b))
}
/// `x` in every component of a `ty` default.
pub fn splat(ty: ValueType, x: f64) -> PinDefault {
    PinDefault::Const(Value::Float(x).convert(ty))
}
/// An input pin offered within [-1, 1] (see [`InputPin::soft`] and [`InputPin::limits`]).
pub const fn input(name: &'static str, ty: ValueType, default: PinDefault) -> InputPin {
    InputPin {
        name,
        ty,
        default,
        range: PinRange::ANY,
        sampled: false,
        re_evaluated: false,
    }
}
/// An output pin.
pub const fn output(name: &'static str, ty: ValueType) -> OutputPin {
    OutputPin {
        name,
        ty,
        identity: false,
    }
}

pub const FLOAT: ValueType = ValueType::Float;
pub const VEC2: ValueType = ValueType::Vec2;
pub const VEC3: ValueType = ValueType::Vec3;
pub const COLOR: ValueType = ValueType::Color;
pub const REQUIRED: PinDefault = PinDefault::Required;
pub const POSITION: PinDefault = PinDefault::Position;

/// The point a pattern samples: the surface position unless wired.
pub const POINT: InputPin = input("p", VEC3, POSITION);

/// How many lattice cells a noise spans per unit: its frequency.
pub const SCALE: InputPin = input("scale", FLOAT, f(1.0)).soft(0.0, 50.0);

/// Names of vector components, in order.
pub const COMPONENTS: [&str; 3] = ["x", "y", "z"];

/// `name` as a `'static` string, for pins whose names come from a file (a group's
/// inputs and outputs): each distinct name is stored once for the life of the process,
/// so memory grows with the names seen, not with the graphs loaded.
pub fn intern(name: &str) -> &'static str {
    use std::collections::HashSet;
    use std::sync::{Mutex, OnceLock};
    static NAMES: OnceLock<Mutex<HashSet<&'static str>>> = OnceLock::new();
    let mut names = NAMES
        .get_or_init(Default::default)
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner());
    if let Some(known) = names.get(name) {
        return known;
    }
    let stored: &'static str = Box::leak(name.to_owned().into_boxed_str());
    names.insert(stored);
    stored
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_drag_moves_a_scale_of_one_by_about_itself_in_two_hundred_points() {
        // Worley's scale (soft 0 to 50) once went from 1 to 52 in 200 points.
        let step = SCALE.range.step(1.0);
        assert!((200.0 * step - 2.5).abs() < 1e-9, "{}", 200.0 * step);
        // Large values drag as fast, relatively.
        assert_eq!(SCALE.range.step(400.0), 2.0);
        // A span of 0 to 1 (roughness) takes 4,000 points near zero.
        let unit = PinRange {
            min: 0.0,
            max: 1.0,
            soft_min: 0.0,
            soft_max: 1.0,
        };
        assert_eq!(unit.step(0.0), 0.05 / DRAG_POINTS);
    }

    #[test]
    fn ctrl_snaps_to_a_round_twentieth_of_the_soft_span() {
        let range = |soft_min, soft_max| PinRange {
            soft_min,
            soft_max,
            ..PinRange::ANY
        };
        assert_eq!(range(0.0, 50.0).snap(), 2.0);
        assert_eq!(range(0.0, 1.0).snap(), 0.05);
        assert_eq!(range(-1.0, 1.0).snap(), 0.1);
        assert_eq!(range(0.0, 360.0).snap(), 10.0);
        // No span: a tiny step, not zero (nothing divides by it).
        let degenerate = range(3.0, 3.0).snap();
        assert!((degenerate - 5e-11).abs() < 1e-20, "{degenerate}");
    }
}
