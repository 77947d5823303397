//! Graph → WGSL: emits `veneer_material` for a checked graph with only the library
//! items it uses, then validates the module with naga.
//!
//! One entry point: [`compile`] checks a graph and emits its module once, as a
//! [`Compiled`] value that renders, bakes, snapshots, reports and the editor hand on;
//! [`compile_checked`] emits the same module for a graph some caller has checked already
//! (`veneer check`, which lints it meanwhile).

mod body;
pub mod export;
mod functions;
pub mod library;
pub mod manifest;
mod naming;
mod parts;
pub mod passes;
mod validate;

pub use crate::nodes::emit::{Detail, float_literal, value_literal};
pub use validate::{ValidationError, validate};

use crate::graph::check::{CheckedGraph, InputSource};
use crate::graph::{self, AlphaMode, CheckError, Graph, NodeId, NodeKind, Preview};
use crate::nodes::emit;
use naming::Namer;
use parts::Block;
use rustc_hash::FxHashMap;
use std::ops::Range;

/// How unconnected inputs appear in generated WGSL.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ParamMode {
    /// As literal constants: a self-contained module with no bindings (exports, renders).
    #[default]
    Baked,
    /// As slots of one uniform block, `veneer_params` at `@group(1) @binding(0)`: every
    /// parameter is one `vec4f` (a float in `.x`, a vec2 in `.xy`, a vec3 or colour in
    /// `.xyz`), in the order of [`WgslModule::params`]. Editing a value then only means
    /// rewriting the buffer.
    Uniform,
    /// The slots of [`ParamMode::Uniform`], laid out the same way, in a read-only storage
    /// buffer at the same binding: no size limit (a uniform block holds 4,096 slots at the
    /// least a device must offer), so the editor's live preview takes graphs of any size.
    Storage,
    /// The graph's exposed parameters (see `graph::parameters`) as named members of one
    /// uniform struct, `veneer_params: VeneerParameters` at `@group(1) @binding(0)`,
    /// every other constant baked: what engines set by name (`--params uniform`).
    Named,
}

impl ParamMode {
    /// Whether every constant is a slot of a buffer rather than a literal.
    pub fn has_slots(self) -> bool {
        matches!(self, ParamMode::Uniform | ParamMode::Storage)
    }
}

/// One parameter slot of a uniform-mode module.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamSlot {
    pub node: NodeId,
    pub pin: &'static str,
    pub ty: graph::ValueType,
}

/// The values of a uniform-mode module's parameters for `graph`, one `vec4f` per slot:
/// the node's constant for the pin, or the pin's default. The slots of a graph with
/// groups name the nodes of its flattened form, which inlining numbers the same way
/// for the same structure, so an edited value lands in the slots it reaches.
pub fn param_values(graph: &Graph, slots: &[ParamSlot]) -> Vec<[f32; 4]> {
    let flat = graph::group::flatten(graph).unwrap_or(std::borrow::Cow::Borrowed(graph));
    let graph = flat.as_ref();
    // Looked up by id: graphs of thousands of nodes have thousands of slots.
    let nodes: FxHashMap<NodeId, &graph::Node> =
        graph.nodes.iter().map(|node| (node.id, node)).collect();
    slots
        .iter()
        .map(|slot| {
            let value = nodes.get(&slot.node).and_then(|node| {
                let pin = node.kind.signature().input(slot.pin).map(|(_, pin)| *pin)?;
                match (node.inputs.get(slot.pin), pin.default) {
                    (Some(value), _) => Some(value.convert(slot.ty)),
                    (None, graph::PinDefault::Const(value)) => Some(value),
                    (None, _) => None,
                }
            });
            let [x, y, z] = value.map(|v| v.components()).unwrap_or([0.0; 3]);
            [x as f32, y as f32, z as f32, 0.0]
        })
        .collect()
}

/// A generated WGSL module and where each node's code sits in it.
#[derive(Clone, Debug)]
pub struct WgslModule {
    pub source: String,
    /// Byte ranges of the source and the node whose code they hold.
    pub node_spans: Vec<(Range<usize>, NodeId)>,
    /// Names of the library items the module contains, in emission order.
    pub library: Vec<String>,
    /// The validated naga module.
    pub module: naga::Module,
    /// Parameter slots (uniform mode only; empty when baked). A multi-pass material's
    /// modules share one numbering: each holds the slots of the modules before it too,
    /// and the material's (the last) holds every slot.
    pub params: Vec<ParamSlot>,
    /// Whether the module reads a parameter block at group 1 (a renderer binds it).
    pub binds_params: bool,
    /// The members of `VeneerParameters`, one per exposed parameter in the order of
    /// the checked graph's `parameters` (named mode only).
    pub members: Vec<crate::graph::parameters::Member>,
    /// Which surface inputs the material reads, so renderers compute only those.
    pub uses: SurfaceUse,
}

/// What a mesh pipeline does with a material's alpha.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum AlphaUse {
    /// The surface is opaque everywhere (the alpha is 1 or ignored): back faces are
    /// culled.
    #[default]
    Opaque,
    /// Fragments with alpha below the cutoff are cut out; back faces are drawn.
    Mask(f32),
    /// Opaque fragments are drawn first, then the see-through ones blended back to
    /// front; back faces are drawn.
    Blend,
}

/// What of the surface a material needs beyond position, normal and uv.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SurfaceUse {
    /// Which of the four distance fields some node reads.
    pub fields: [bool; 4],
    /// Which mesh field each lane of `VeneerSurface.fields` holds, in the lanes the
    /// distance fields leave free (every mesh field the whole material reads, its
    /// passes' nodes included), so renderers compute those.
    pub mesh_fields: crate::nodes::mesh_field::MeshLanes,
    /// Whether the height output can be non-zero (the mesh is displaced).
    pub displacement: bool,
    /// Whether the bump output can be non-zero (the shading normal is perturbed).
    pub bump: bool,
    /// What the alpha output asks of the pipeline.
    pub alpha: AlphaUse,
    /// Whether the tangent-space normal can differ from (0, 0, 1) (the shading normal
    /// is tilted in the surface's tangent frame).
    pub normal: bool,
    /// The lighting model (the graph's setting).
    pub shading: graph::Shading,
}

/// The lanes of `VeneerSurface.fields` holding the mesh fields the nodes of `graph`
/// read: those its distance fields leave free.
pub fn mesh_lanes(graph: &CheckedGraph) -> crate::nodes::mesh_field::MeshLanes {
    use crate::nodes::mesh_field;
    let kinds = || graph.order.iter().map(|checked| &checked.node.kind);
    mesh_field::lanes(&mesh_field::fields_read(kinds()), distance_slots(kinds()))
}

/// The module's `VENEER_FLAT_FIELDS`: the `fields` flat views pass, as
/// [`crate::nodes::mesh_field::flat_fields`] gives them for `lanes`.
fn flat_fields_constant(lanes: &crate::nodes::mesh_field::MeshLanes) -> String {
    let values = crate::nodes::mesh_field::flat_fields(lanes)
        .map(|value| crate::nodes::emit::float_literal(f64::from(value)));
    format!(
        "\n// The fields flat views pass (no mesh): 0 for distance fields, an unbounded flat plane's value for mesh fields.\nconst VENEER_FLAT_FIELDS = vec4f({});\n",
        values.join(", ")
    )
}

/// Which of the four slots of `VeneerSurface.fields` the Distance field nodes among
/// `kinds` read.
pub fn distance_slots<'a>(kinds: impl IntoIterator<Item = &'a NodeKind>) -> [bool; 4] {
    let mut slots = [false; 4];
    for kind in kinds {
        if let NodeKind::Field(field) = kind {
            slots[field.slot as usize % 4] = true;
        }
    }
    slots
}

impl SurfaceUse {
    /// The detail a module compiles with: every octave when the mesh is displaced
    /// (vertex stage), else `asked`.
    fn detail(&self, asked: Detail) -> Detail {
        if self.displacement {
            Detail::Full
        } else {
            asked
        }
    }

    /// Whether the shading normal can differ from the mesh's: a bump, a height or a
    /// tilted tangent-space normal.
    pub fn perturbs_normal(&self) -> bool {
        self.displacement || self.bump || self.normal
    }

    fn of(graph: &CheckedGraph) -> SurfaceUse {
        let mut uses = SurfaceUse {
            fields: distance_slots(graph.order.iter().map(|checked| &checked.node.kind)),
            ..SurfaceUse::default()
        };
        uses.mesh_fields = mesh_lanes(graph);
        let material = graph.material();
        // A wired input can take any value.
        let shows = |pin: &str| match material.input(pin) {
            Some(InputSource::Const(value)) => {
                SurfaceUse::input_shows(pin, value, graph.alpha).unwrap_or(true)
            }
            _ => true,
        };
        uses.bump = shows("bump");
        uses.displacement = shows("height");
        uses.normal = shows("normal");
        uses.shading = graph.shading;
        let alpha_shows = shows("alpha");
        uses.alpha = match graph.alpha {
            AlphaMode::Mask { cutoff } if alpha_shows => AlphaUse::Mask(cutoff as f32),
            AlphaMode::Blend if alpha_shows => AlphaUse::Blend,
            AlphaMode::Mask { .. } | AlphaMode::Blend | AlphaMode::Opaque => AlphaUse::Opaque,
        };
        uses
    }

    /// Whether an unwired input of the material node, at `value`, makes mesh pipelines
    /// do work: a bump or height other than zero, a tilted tangent-space normal, an alpha that shows under the graph's
    /// `alpha` mode (below the cutoff, or below 1 when blended); `None` for the inputs
    /// that do not change the pipeline. The editor recompiles when an edit changes it.
    pub fn input_shows(pin: &str, value: &graph::Value, alpha: AlphaMode) -> Option<bool> {
        match pin {
            "bump" | "height" => Some(value.components() != [0.0; 3]),
            "normal" => Some(value.components() != [0.0, 0.0, 1.0]),
            "alpha" => Some(match alpha {
                AlphaMode::Mask { cutoff } => value.components()[0] < cutoff,
                AlphaMode::Blend => value.components()[0] < 1.0,
                AlphaMode::Opaque => false,
            }),
            _ => None,
        }
    }
}

impl WgslModule {
    /// The node whose code contains byte `offset`, if any.
    pub fn node_at(&self, offset: usize) -> Option<NodeId> {
        self.node_spans
            .iter()
            .find(|(range, _)| range.contains(&offset))
            .map(|(_, id)| *id)
    }
}

/// Why a graph could not be compiled.
#[derive(Debug, thiserror::Error)]
pub enum CompileError {
    /// The graph failed its checks (one message per line, repeats summarised).
    #[error("{}", crate::messages::summarise(.0.iter().map(|e| e.to_string())).join("\n"))]
    Check(Vec<CheckError>),
    /// The generated WGSL did not validate (a bug in Veneer or an out-of-range constant).
    #[error(transparent)]
    Validation(ValidationError),
}

/// How to compile a graph. The default — parameters baked, every octave — is what
/// renders, bakes, snapshots and exports use.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CompileOptions {
    /// Parameters as literals or as slots of a uniform block.
    pub params: ParamMode,
    /// How much detail noise and fractal nodes compute.
    pub detail: Detail,
}

impl CompileOptions {
    /// The default options with parameters in `params`.
    pub fn with_params(params: ParamMode) -> CompileOptions {
        CompileOptions {
            params,
            ..CompileOptions::default()
        }
    }

    /// The default options with noise detail `detail`.
    pub fn with_detail(detail: Detail) -> CompileOptions {
        CompileOptions {
            detail,
            ..CompileOptions::default()
        }
    }
}

/// A graph checked and compiled once, with what the stages after the compiler need of
/// it: renders, bakes, snapshots, reports and the editor's preview take this instead of
/// the graph.
#[derive(Clone, Debug)]
pub struct Compiled {
    /// The checked graph the module was emitted from (needed nodes in order).
    pub checked: CheckedGraph,
    /// The validated WGSL module, with its parameter slots and surface uses.
    pub module: WgslModule,
    /// The graph's preview settings: the mesh, its distance fields and the placement
    /// renders and bakes use.
    pub preview: Preview,
    /// The options the module was compiled with.
    pub options: CompileOptions,
    /// The folder of the graph's file, which its Image nodes' paths are relative to.
    pub folder: graph::Folder,
    /// The graph's named sets of parameter values (exports that keep parameters keep
    /// them too).
    pub presets:
        std::collections::BTreeMap<String, std::collections::BTreeMap<String, graph::Value>>,
    /// The passes that render the buffers the module reads, in order (none for a
    /// graph without sampled inputs).
    pub passes: passes::Passes,
    /// The graph's groups as they were before inlining (a MaterialX export keeps them).
    pub groups: std::sync::Arc<graph::group::GroupSource>,
}

impl Compiled {
    /// The WGSL source of the module.
    pub fn source(&self) -> &str {
        &self.module.source
    }

    /// Which surface inputs the material reads.
    pub fn uses(&self) -> SurfaceUse {
        self.module.uses
    }
}

/// Checks `graph` and compiles it to a validated WGSL module: the one way from a graph
/// to its code.
pub fn compile(graph: &Graph, options: &CompileOptions) -> Result<Compiled, CompileError> {
    counts::checked();
    let checked = graph::check(graph).map_err(CompileError::Check)?;
    let (module, passes) = compile_checked(graph, &checked, options)?;
    Ok(Compiled {
        checked,
        module,
        preview: graph.preview.clone(),
        options: *options,
        folder: graph.folder.clone(),
        presets: graph.presets.clone(),
        passes,
        groups: std::sync::Arc::new(graph::group::GroupSource::of(graph)),
    })
}

/// How many graphs this thread has checked and emitted through the compiler, for tests
/// that hold a command to checking and emitting each graph once.
#[doc(hidden)]
pub mod counts {
    use std::cell::Cell;

    thread_local! {
        static COUNTS: Cell<CompileCounts> = const { Cell::new(CompileCounts { checks: 0, emissions: 0 }) };
    }

    /// Checks and emissions so far on the calling thread.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
    pub struct CompileCounts {
        /// Graphs checked by [`super::compile`].
        pub checks: u64,
        /// Modules emitted by [`super::compile_checked`] (and so by [`super::compile`]).
        pub emissions: u64,
    }

    impl std::ops::Sub for CompileCounts {
        type Output = CompileCounts;
        fn sub(self, earlier: CompileCounts) -> CompileCounts {
            CompileCounts {
                checks: self.checks - earlier.checks,
                emissions: self.emissions - earlier.emissions,
            }
        }
    }

    /// The calling thread's counts.
    pub fn current() -> CompileCounts {
        COUNTS.with(Cell::get)
    }

    pub(super) fn checked() {
        COUNTS.with(|c| {
            c.set(CompileCounts {
                checks: c.get().checks + 1,
                ..c.get()
            })
        });
    }

    pub(super) fn emitted() {
        COUNTS.with(|c| {
            c.set(CompileCounts {
                emissions: c.get().emissions + 1,
                ..c.get()
            })
        });
    }
}

/// What a node left for the nodes that read it, by its position in the checked order.
#[derive(Default)]
struct Emitted {
    /// One WGSL expression per output.
    outputs: Vec<String>,
    /// The output values, when the node folded into constants.
    folded: Option<Vec<[f32; 3]>>,
    /// The node's code in the body, when it has some.
    block: Option<usize>,
}

/// The WGSL expression for one input: `from` is the node a wired input reads.
fn input_expression(
    source: &InputSource,
    pin: &graph::InputPin,
    node: NodeId,
    from: Option<&Emitted>,
    params: Option<&mut Vec<ParamSlot>>,
) -> String {
    match (source, params) {
        (InputSource::Wire { output, ty, .. }, _) => {
            let expression = from.and_then(|from| from.outputs.get(*output));
            emit::convert(expression.cloned().unwrap_or_default(), *ty, pin.ty)
        }
        (InputSource::Const(_), Some(params)) => {
            let swizzle = ["x", "xy", "xyz"][pin.ty.width() - 1];
            params.push(ParamSlot {
                node,
                pin: pin.name,
                ty: pin.ty,
            });
            format!("veneer_params.values[{}].{swizzle}", params.len() - 1)
        }
        (InputSource::Const(value), None) => value_literal(value),
        (InputSource::Position, _) => "s.position".into(),
    }
}

/// The outputs of `checked` when all its inputs are constants (literals or outputs of
/// folded nodes) and it reads nothing of the surface: a constant subgraph folds into
/// literals. `None` when it cannot fold (or folds to a non-finite value).
fn fold(
    checked: &graph::check::CheckedNode,
    from: &[Option<&Emitted>],
    bound: &[Option<String>],
) -> Option<Vec<[f32; 3]>> {
    if checked.node.kind.definition().reads_surface() {
        return None;
    }
    let inputs = checked
        .inputs
        .iter()
        .zip(from)
        .zip(bound)
        .map(|((source, from), bound)| match *source {
            InputSource::Const(_) if bound.is_some() => None,
            InputSource::Const(ref value) => Some(value.components().map(|c| c as f32)),
            InputSource::Wire { output, .. } => (*from)?.folded.as_ref()?.get(output).copied(),
            InputSource::Position => None,
        })
        .collect::<Option<Vec<_>>>()?;
    let values = crate::eval::constant_outputs(checked, &inputs);
    values
        .iter()
        .all(|lanes| lanes.iter().all(|x| x.is_finite()))
        .then_some(values)
}

/// The parameter block of a module with slots (uniform or storage), its layout spelled out.
fn params_block(graph: &CheckedGraph, params: &[ParamSlot], mode: ParamMode) -> String {
    let mut text = String::from(
        "\n// Parameters: one vec4f per slot (float in .x, vec2 in .xy, vec3/colour in .xyz).\n",
    );
    for (slot, param) in params.iter().enumerate() {
        let node = graph
            .index_of(param.node)
            .map(|i| graph.order[i].node.to_string())
            .unwrap_or_default();
        text.push_str(&format!(
            "//   slot {slot}: {} input '{}' ({})\n",
            naming::comment(&node),
            param.pin,
            param.ty
        ));
    }
    text.push_str(&format!(
        "struct veneer_parameters {{\n    values: array<vec4f, {}>,\n}}\n\n@group(1) @binding(0) var<{}> veneer_params: veneer_parameters;\n",
        params.len(),
        if mode == ParamMode::Storage { "storage, read" } else { "uniform" }
    ));
    text
}

/// The members of the `VeneerParameters` struct for `parameters`: WGSL identifiers
/// made from their names, laid out in order.
pub fn parameter_members(
    parameters: &[crate::graph::parameters::Exposed],
) -> Vec<crate::graph::parameters::Member> {
    let mut names = Namer::default();
    crate::graph::parameters::members(parameters, |name, k| names.name(name, k))
}

/// The JSON description of the compiled graph's exposed parameters, written beside
/// exports: names, `VeneerParameters` members and layout, types, defaults, ranges,
/// hints and group paths.
pub fn describe_parameters(compiled: &Compiled) -> String {
    let parameters = &compiled.checked.parameters;
    crate::graph::parameters::describe(parameters, &parameter_members(parameters))
}

/// The WGSL reading member `member` (of type `from`) as an input of type `to`.
fn member_expression(member: &str, from: graph::ValueType, to: graph::ValueType) -> String {
    let expression = format!("veneer_params.{member}");
    match (from.width(), to.width()) {
        (from_width, to_width) if from_width > to_width => {
            format!("{expression}.{}", ["x", "xy"][to_width - 1])
        }
        _ => emit::convert(expression, from, to),
    }
}

/// The `VeneerParameters` struct of a named-mode module, each member's parameter,
/// byte offset and size spelled out (WGSL's uniform layout: f32 aligned to 4 bytes,
/// vec2f to 8, vec3f to 16, the struct's size a multiple of 16, as in std140).
fn named_block(graph: &CheckedGraph, members: &[crate::graph::parameters::Member]) -> String {
    let mut text = String::from(
        "\n// Exposed parameters, set by name: a uniform buffer at group 1, binding 0.\n",
    );
    let mut fields = String::new();
    for (member, parameter) in members.iter().zip(&graph.parameters) {
        text.push_str(&format!(
            "//   {} '{}' ({}): bytes {}..{}\n",
            member.name,
            naming::comment(&parameter.name),
            parameter.ty,
            member.offset,
            member.offset + member.size
        ));
        fields.push_str(&format!("    {}: {},\n", member.name, member.ty.wgsl()));
    }
    let size = members
        .last()
        .map_or(0, |m| (m.offset + m.size).div_ceil(16) * 16);
    text.push_str(&format!(
        "//   struct size: {size} bytes\nstruct VeneerParameters {{\n{fields}}}\n\n@group(1) @binding(0) var<uniform> veneer_params: VeneerParameters;\n"
    ));
    text
}

/// The module (and passes) [`compile`] emits for `graph`, checked already as `checked`
/// by [`graph::check`]: `veneer check` validates exactly this, the module `veneer
/// compile` exports (a group as one function where the graph allows it, else inlined;
/// a multi-pass material's passes planned and validated too).
pub fn compile_checked(
    graph: &Graph,
    checked: &CheckedGraph,
    options: &CompileOptions,
) -> Result<(WgslModule, passes::Passes), CompileError> {
    Ok(match passes::plan(checked, options)? {
        Some(planned) => planned,
        None => match functions::compile(graph, checked, options) {
            Some(module) => (module?, passes::Passes::default()),
            None => (single_pass(checked, options)?, passes::Passes::default()),
        },
    })
}

/// The module of a checked graph without sampled inputs, groups inlined.
fn single_pass(graph: &CheckedGraph, options: &CompileOptions) -> Result<WgslModule, CompileError> {
    counts::emitted();
    let uses = SurfaceUse::of(graph);
    let members = if options.params == ParamMode::Named {
        parameter_members(&graph.parameters)
    } else {
        Vec::new()
    };
    let mut emitter = body::Emitter::new(
        options.params,
        uses.detail(options.detail),
        &graph.parameters,
        &members,
    );
    emitter.mesh_lanes = uses.mesh_fields;
    let (blocks, _) = emitter.body(graph, &graph.bindings, &Default::default());
    let around = Around {
        functions: "",
        buffers: "",
        entry: parts::Entry::MATERIAL,
    };
    assemble(graph, emitter, around, &blocks, uses)
}

/// What a module holds around its body: group functions, the buffers it reads, and the
/// function the body becomes.
struct Around<'a> {
    /// The group functions the body calls.
    functions: &'a str,
    /// The declarations of the buffers the body reads (multi-pass materials).
    buffers: &'a str,
    entry: parts::Entry,
}

/// The module around the material's `blocks`: the header, the contract structs, the
/// parameter block, the buffers read, the library items the bodies called, the group
/// functions and the entry function, validated. `graph` (flattened) names the nodes in
/// errors.
fn assemble(
    graph: &CheckedGraph,
    emitter: body::Emitter,
    around: Around,
    blocks: &[Block],
    uses: SurfaceUse,
) -> Result<WgslModule, CompileError> {
    let mode = emitter.mode;
    let members = emitter.members.to_vec();
    let params = emitter.params;
    let declares_slots = params.len() > emitter.first_slot;
    let items = library::closure(emitter.roots.iter().map(String::as_str));
    let mut source = String::new();
    let title = if graph.name.is_empty() {
        "a Veneer graph".to_string()
    } else {
        format!("\"{}\"", naming::comment(&graph.name))
    };
    source.push_str(&format!(
        "// Material {title}, generated by Veneer {}.\n",
        env!("CARGO_PKG_VERSION")
    ));
    source.push_str(&format!(
        "// Entry point: {}(s: VeneerSurface) -> {}.\n",
        around.entry.name, around.entry.returns
    ));
    for (lane, field) in uses.mesh_fields.iter().enumerate() {
        if let Some(field) = field {
            source.push_str(&format!(
                "// VeneerSurface.fields.{} carries a mesh field, not a distance field: {field}.\n",
                ["x", "y", "z", "w"][lane]
            ));
        }
    }
    source.push('\n');
    for line in library::SURFACE
        .lines()
        .filter(|line| !line.starts_with("//!"))
        .skip_while(|line| line.is_empty())
    {
        source.push_str(line);
        source.push('\n');
    }
    source.push_str(&flat_fields_constant(&uses.mesh_fields));
    if declares_slots {
        source.push_str(&params_block(graph, &params, mode));
    }
    if !members.is_empty() {
        source.push_str(&named_block(graph, &members));
    }
    source.push_str(around.buffers);
    let mut family = "";
    for item in &items {
        if item.family != family {
            family = item.family;
            source.push_str(&format!("\n// ---- shaders/{family}.wgsl\n"));
        }
        source.push('\n');
        source.push_str(&item.text);
    }
    source.push_str(around.functions);
    if !emitter.local_functions.is_empty() {
        source.push_str("\n// ---- local frames\n");
        source.push_str(&emitter.local_functions);
    }
    let node_spans = parts::write_entry(&mut source, blocks, around.entry);

    let library = items.into_iter().map(|item| item.name).collect();
    // A module may hold slots it never reads (a blur's radius, baked into its stages):
    // a pipeline's layout then has no parameter binding, so the module binds none.
    let reads_params = source.contains("veneer_params.");
    let mut module = WgslModule {
        source,
        node_spans,
        library,
        module: naga::Module::default(),
        binds_params: (declares_slots || !members.is_empty()) && reads_params,
        params,
        members,
        uses,
    };
    module.module = validate(&module.source).map_err(|mut error| {
        if let Some(offset) = error.offset {
            error.node = module.node_at(offset);
            error.node_name = error
                .node
                .and_then(|id| graph.index_of(id))
                .map(|i| graph.order[i].node.to_string());
        }
        CompileError::Validation(error)
    })?;
    Ok(module)
}
