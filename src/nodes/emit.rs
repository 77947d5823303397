//! WGSL literals and the interface through which a node kind emits its code: inputs
//! by pin name, the identifier reserved for the node, and what it adds to
//! `veneer_material` and the library.

use super::mesh_field::MeshLanes;
use super::pins::{InputPin, OutputPin};
use super::value::{Value, ValueType};

/// A WGSL f32 literal for `x` (`0.35f`): typed, so that expressions of constants only
/// are never abstract (naga rejects builtins of abstract arguments outside constants).
pub fn float_literal(x: f64) -> String {
    let text = format!("{x:?}");
    let text = if text.contains(['.', 'e', 'E']) {
        text
    } else {
        format!("{text}.0")
    };
    format!("{text}f")
}

/// A WGSL literal for a constant.
pub fn value_literal(value: &Value) -> String {
    match *value {
        Value::Float(x) => float_literal(x),
        Value::Vec2(x, y) => format!("vec2f({}, {})", float_literal(x), float_literal(y)),
        Value::Vec3(x, y, z) | Value::Color(x, y, z) => {
            format!(
                "vec3f({}, {}, {})",
                float_literal(x),
                float_literal(y),
                float_literal(z)
            )
        }
    }
}

/// A literal of type `ty` from three f32 lanes (a folded constant), each written as the
/// shortest decimal that reads back as the same f32.
pub fn lanes_literal(ty: ValueType, lanes: [f32; 3]) -> String {
    let [x, y, z] = lanes.map(|lane| {
        let text = format!("{lane:?}");
        if text.contains(['.', 'e', 'E']) {
            format!("{text}f")
        } else {
            format!("{text}.0f")
        }
    });
    match ty {
        ValueType::Float => x,
        ValueType::Vec2 => format!("vec2f({x}, {y})"),
        ValueType::Vec3 | ValueType::Color => format!("vec3f({x}, {y}, {z})"),
    }
}

/// How much detail noise and fractal nodes compute.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Detail {
    /// Every octave everywhere: the same numbers as the CPU evaluator (exports, renders,
    /// snapshots).
    #[default]
    Full,
    /// Fractal nodes leave out octaves finer than the pixel footprint (from screen-space
    /// derivatives of their input), fading the last one; periodic and thresholding
    /// patterns (bands, waves, rings, tiles, steps, smoothsteps, stepped ranges) are
    /// box-filtered over it analytically, fading to their mean past Nyquist: less
    /// aliasing and less work in the distance. Fragment stage only, so materials that
    /// displace vertices keep full detail, and only at the shaded point (see
    /// [`Emit::filters_footprint`]).
    Footprint,
}

/// What one node contributes to the material function.
#[derive(Default)]
pub struct NodeCode {
    /// Statements, one per line, without indentation.
    pub statements: Vec<String>,
    /// One WGSL expression per output pin.
    pub outputs: Vec<String>,
    /// Library items the statements call.
    pub library: Vec<String>,
    /// The WGSL type of the identifier the statements bind (the node's name), if any.
    pub binding: Option<&'static str>,
}

/// A node's view of code generation: its inputs as WGSL expressions (already converted
/// to each pin's type), the name reserved for it, and the code it writes.
pub struct Emit<'a> {
    pins: &'a [InputPin],
    inputs: &'a [String],
    outputs: &'a [OutputPin],
    name: &'a str,
    /// The arguments (`texture, edge`) of the bitmap the node reads (an Image node).
    source: Option<&'a str>,
    /// How much detail fractal nodes compute.
    pub detail: Detail,
    /// Which mesh field each lane of `VeneerSurface.fields` holds.
    mesh_lanes: MeshLanes,
    /// Per input pin, the function of the local frame a wired re-evaluated input reads.
    locals: &'a [Option<&'a str>],
    /// The identifier of the instance, inside a local frame's function.
    instance: Option<&'static str>,
    code: NodeCode,
}

impl<'a> Emit<'a> {
    /// A node with these input pins and expressions, output pins and reserved name.
    pub fn new(
        pins: &'a [InputPin],
        inputs: &'a [String],
        outputs: &'a [OutputPin],
        name: &'a str,
        detail: Detail,
    ) -> Emit<'a> {
        Emit {
            pins,
            inputs,
            outputs,
            name,
            source: None,
            detail,
            mesh_lanes: MeshLanes::default(),
            locals: &[],
            instance: None,
            code: NodeCode::default(),
        }
    }

    /// The same node in a frame: `locals` holds, per input pin, the function a wired
    /// re-evaluated input reads; `instance` names the instance inside a local frame.
    pub fn in_frame(
        self,
        locals: &'a [Option<&'a str>],
        instance: Option<&'static str>,
    ) -> Emit<'a> {
        Emit {
            locals,
            instance,
            ..self
        }
    }

    /// The function `fn(s: VeneerSurface, instance: VeneerInstance) -> T` that evaluates
    /// re-evaluated input `pin`'s upstream, when the pin is wired (unwired, its value is
    /// [`Emit::input`], or for a builtin default the node's own pattern).
    pub fn local(&self, pin: &str) -> Option<&'a str> {
        self.locals
            .get(super::pins::pin_index(self.pins, pin))
            .copied()
            .flatten()
    }

    /// Whether the node filters over the pixel footprint: footprint detail, at the shaded
    /// point. A local frame's function runs once per instance, in non-uniform control
    /// flow where screen-space derivatives are undefined, so nodes there draw in full
    /// (a sampler filters the edges it places over the instance's own footprint).
    pub fn filters_footprint(&self) -> bool {
        self.detail == Detail::Footprint && self.instance.is_none()
    }

    /// The identifier of the instance being placed, when the node is emitted inside a
    /// local frame's function (`None` at the shaded point).
    pub fn instance(&self) -> Option<&'static str> {
        self.instance
    }

    /// The same node in a module whose mesh fields sit in `lanes`.
    pub fn with_mesh_lanes(self, lanes: MeshLanes) -> Emit<'a> {
        Emit {
            mesh_lanes: lanes,
            ..self
        }
    }

    /// Which mesh field each lane of `VeneerSurface.fields` holds.
    pub fn mesh_lanes(&self) -> MeshLanes {
        self.mesh_lanes
    }

    /// The same node reading the bitmap at `arguments` (`texture, edge`).
    pub fn with_source(self, arguments: Option<&'a str>) -> Emit<'a> {
        Emit {
            source: arguments,
            ..self
        }
    }

    /// The arguments (`texture, edge`) of the bitmap the node reads. The compiler uploads
    /// every Image node's file before it emits the node: a missing one is a bug.
    pub fn source(&self) -> &'a str {
        self.source
            .expect("a node reading a bitmap is emitted with its buffer")
    }

    /// The expression of input pin `pin`. A name the kind does not have is a bug in its
    /// definition (the registry test emits every kind).
    pub fn input(&self, pin: &str) -> &'a str {
        &self.inputs[super::pins::pin_index(self.pins, pin)]
    }

    /// Every input expression, in pin order.
    pub fn inputs(&self) -> &'a [String] {
        self.inputs
    }

    /// The input pins, in order.
    pub fn pins(&self) -> &'a [InputPin] {
        self.pins
    }

    /// The identifier reserved for the node.
    pub fn name(&self) -> &'a str {
        self.name
    }

    /// The WGSL type of the first output (f32 when there is none).
    fn output_type(&self) -> &'static str {
        self.outputs
            .first()
            .map(|pin| pin.ty.wgsl())
            .unwrap_or("f32")
    }

    /// One output: `let name: T = expression;`, typed so that an expression of constants
    /// only (abstract in WGSL) becomes f32.
    pub fn single(&mut self, expression: String) {
        let ty = self.output_type();
        self.code
            .statements
            .push(format!("let {}: {ty} = {expression};", self.name));
        self.code.outputs = vec![self.name.to_string()];
        self.code.binding = Some(ty);
    }

    /// One output: library function `function` of every input in pin order.
    pub fn call(&mut self, function: &str) {
        self.single(format!("{function}({})", self.inputs.join(", ")));
        self.uses(function);
    }

    /// The library function a band-limited pattern calls: `function`, or its twin
    /// `<function>_filtered` (shaders/band_limit.wgsl), which takes the same arguments and
    /// filters over the pixel footprint, where the node [filters](Emit::filters_footprint).
    pub fn band_limited(&self, function: &str) -> String {
        if self.filters_footprint() {
            format!("{function}_filtered")
        } else {
            function.to_string()
        }
    }

    /// `let name = expression;` of type `ty`, whose parts the outputs then name.
    pub fn bind(&mut self, ty: &'static str, expression: String) {
        self.code
            .statements
            .push(format!("let {} = {expression};", self.name));
        self.code.binding = Some(ty);
    }

    /// A `var` of type `ty` the following statements update; it is the one output.
    pub fn var(&mut self, ty: &'static str, expression: String) {
        self.code
            .statements
            .push(format!("var {} = {expression};", self.name));
        self.code.binding = Some(ty);
        self.code.outputs = vec![self.name.to_string()];
    }

    /// A statement after the node's binding.
    pub fn statement(&mut self, statement: String) {
        self.code.statements.push(statement);
    }

    /// The outputs' expressions, in pin order (when `single` does not set them).
    pub fn outputs(&mut self, outputs: Vec<String>) {
        self.code.outputs = outputs;
    }

    /// Library item `item` is called.
    pub fn uses(&mut self, item: &str) {
        self.code.library.push(item.to_string());
    }

    /// The code written.
    pub fn finish(self) -> NodeCode {
        self.code
    }
}

/// `expression` of type `from` converted to `to` (a float broadcasts).
pub fn convert(expression: String, from: ValueType, to: ValueType) -> String {
    if from == ValueType::Float && to != ValueType::Float {
        format!("{}({expression})", to.wgsl())
    } else {
        expression
    }
}
