//! The interface through which a node kind evaluates on the CPU: its inputs by pin
//! name, as three lanes in precision `R`, and the surface point.

use super::formulas::buffers::Image;
use super::formulas::real::{Real, V3};
use super::mesh_field::MeshLanes;
use super::pins::InputPin;

/// The inputs of a material at one point (the CPU side of `VeneerSurface`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface<R> {
    pub position: [R; 3],
    pub normal: [R; 3],
    pub uv: [R; 2],
    pub fields: [R; 4],
    pub time: R,
}

impl<R: Real> Surface<R> {
    /// A point with normal +y, uv 0, fields 0 and time 0 (the flat render's surface).
    pub fn at(position: [f64; 3]) -> Surface<R> {
        let zero = R::c(0.0);
        Surface {
            position: position.map(R::c),
            normal: [zero, R::c(1.0), zero],
            uv: [zero; 2],
            fields: [zero; 4],
            time: zero,
        }
    }
}

/// The instance a local frame is evaluated for (the CPU side of `VeneerInstance`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Instance<R> {
    /// The instance's cell (column, row), wrapped into its tile.
    pub cell: [R; 2],
    /// Its number within the tile: column + row × columns.
    pub id: R,
    /// Its random number in [0, 1), stable while the grid grows or the graph changes.
    pub random: R,
    /// Three more random numbers in [0, 1).
    pub randoms: V3<R>,
    /// The pixel's footprint in the instance's local units (0 when not filtering).
    pub footprint: R,
}

impl<R: Real> Instance<R> {
    /// What the shaded point's frame reads: instance 0 of cell (0, 0), randoms 0.
    pub fn none() -> Instance<R> {
        let zero = R::c(0.0);
        Instance {
            cell: [zero; 2],
            id: zero,
            random: zero,
            randoms: [zero; 3],
            footprint: zero,
        }
    }
}

/// Evaluates the upstream of a node's re-evaluated input `pin` (by index) at a surface
/// for an instance; `None` when the pin is not wired.
pub type Reevaluate<'a, R> = dyn Fn(usize, &Surface<R>, &Instance<R>) -> Option<V3<R>> + 'a;

/// A node's view of CPU evaluation: its input values (three lanes each: a float in all
/// three, a vec2 in the first two) and the surface point.
pub struct Eval<'a, R> {
    pins: &'a [InputPin],
    inputs: &'a [V3<R>],
    /// The buffer of each sampled input, by pin (empty when the node has none).
    images: &'a [Option<&'a Image>],
    /// The bitmap the node reads (an Image node).
    source: Option<&'a Image>,
    /// Which mesh field each lane of the surface's `fields` holds.
    mesh_lanes: MeshLanes,
    /// Evaluates the node's wired re-evaluated inputs elsewhere.
    reevaluate: Option<&'a Reevaluate<'a, R>>,
    /// The instance, inside a local frame.
    instance: Option<&'a Instance<R>>,
    /// The point being shaded.
    pub surface: &'a Surface<R>,
}

impl<'a, R: Real> Eval<'a, R> {
    /// A node with these input pins and values at `surface`.
    pub fn new(pins: &'a [InputPin], inputs: &'a [V3<R>], surface: &'a Surface<R>) -> Self {
        Eval {
            pins,
            inputs,
            images: &[],
            source: None,
            mesh_lanes: MeshLanes::default(),
            reevaluate: None,
            instance: None,
            surface,
        }
    }

    /// The same node in a frame: `reevaluate` evaluates its re-evaluated inputs, and
    /// `instance` is the instance being placed inside a local frame.
    pub fn in_frame(
        self,
        reevaluate: &'a Reevaluate<'a, R>,
        instance: Option<&'a Instance<R>>,
    ) -> Self {
        Eval {
            reevaluate: Some(reevaluate),
            instance,
            ..self
        }
    }

    /// Re-evaluated input `pin`'s upstream at `surface` for `instance`; `None` when the
    /// pin is not wired (its value is then [`Eval::input`], or the node's own pattern).
    pub fn reevaluate(
        &self,
        pin: &str,
        surface: &Surface<R>,
        instance: &Instance<R>,
    ) -> Option<V3<R>> {
        let k = super::pins::pin_index(self.pins, pin);
        (self.reevaluate?)(k, surface, instance)
    }

    /// The instance being placed, inside a local frame (`None` at the shaded point).
    pub fn instance(&self) -> Option<&'a Instance<R>> {
        self.instance
    }

    /// The same node in a material whose mesh fields sit in `lanes`.
    pub fn with_mesh_lanes(self, lanes: MeshLanes) -> Self {
        Eval {
            mesh_lanes: lanes,
            ..self
        }
    }

    /// Which mesh field each lane of the surface's `fields` holds.
    pub fn mesh_lanes(&self) -> MeshLanes {
        self.mesh_lanes
    }

    /// The same node reading `images` for its sampled inputs (one entry per pin).
    pub fn with_images(self, images: &'a [Option<&'a Image>]) -> Self {
        Eval { images, ..self }
    }

    /// The buffer of sampled input pin `pin`. The evaluator renders every sampled
    /// input's buffer before it evaluates the node: a missing one is a bug.
    pub fn image(&self, pin: &str) -> &'a Image {
        self.images
            .get(super::pins::pin_index(self.pins, pin))
            .copied()
            .flatten()
            .unwrap_or_else(|| panic!("sampled input '{pin}' evaluated without its buffer"))
    }

    /// The same node reading bitmap `source` (an Image node).
    pub fn with_source(self, source: Option<&'a Image>) -> Self {
        Eval { source, ..self }
    }

    /// The bitmap the node reads. The evaluator uploads every Image node's file before
    /// it evaluates the node: a missing one is a bug.
    pub fn source(&self) -> &'a Image {
        self.source
            .expect("a node reading a bitmap is evaluated with its image")
    }

    /// The point's domain coordinate (its uv), where buffers are read.
    pub fn domain(&self) -> [f64; 2] {
        self.surface.uv.map(R::to_f64)
    }

    /// The value of input pin `pin`. A name the kind does not have is a bug in its
    /// definition (the registry test evaluates every kind).
    pub fn input(&self, pin: &str) -> V3<R> {
        self.inputs[super::pins::pin_index(self.pins, pin)]
    }

    /// The value of float input pin `pin`.
    pub fn float(&self, pin: &str) -> R {
        self.input(pin)[0]
    }

    /// The value of vec2 input pin `pin`.
    pub fn pair(&self, pin: &str) -> [R; 2] {
        let value = self.input(pin);
        [value[0], value[1]]
    }

    /// Every input value, in pin order.
    pub fn inputs(&self) -> &'a [V3<R>] {
        self.inputs
    }
}
