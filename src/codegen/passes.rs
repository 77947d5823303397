//! Multi-pass materials: the graph cut at its sampled inputs. Each cut's upstream part
//! renders once into a buffer over the material's 2D domain (a pass); a node's own
//! texel-space stages (a blur's axes) add passes over its buffer; the material's
//! module, and every pass, reads the buffers it needs at `@group(2)`, one binding each.
//!
//! Passes run in dependency order; one buffer per cut, shared by every reader (the
//! cut's node, output and buffer settings make its key); only cuts some reachable node
//! reads are made. A graph without sampled inputs has no passes and compiles exactly
//! as before.

use super::body::Emitter;
use super::parts::{Block, Entry};
use super::{
    Around, CompileError, CompileOptions, ParamSlot, SurfaceUse, WgslModule, assemble, counts,
};
use crate::bitmaps::Bitmap;
use crate::graph::check::{CheckError, CheckedGraph, InputSource};
use crate::graph::{NodeId, ValueType};
use crate::nodes::passes::{BufferFormat, BufferSpec, Stage};
use rustc_hash::FxHashMap;
use std::collections::{BTreeMap, BTreeSet};
use std::sync::Arc;

/// The entry points a surface pass is rendered with (after its module): the full-screen
/// vertex and `veneer_pass_fragment`, which evaluates `veneer_pass` at a texel centre.
pub const SURFACE_ENTRY_POINTS: &str = concat!(
    include_str!("../../shaders/render_pass_vertex.wgsl"),
    include_str!("../../shaders/render_pass_surface.wgsl")
);

/// The entry points a stage pass is rendered with: the full-screen vertex and
/// `veneer_pass_fragment`, which evaluates `veneer_stage` at a texel.
pub const STAGE_ENTRY_POINTS: &str = concat!(
    include_str!("../../shaders/render_pass_vertex.wgsl"),
    include_str!("../../shaders/render_pass_stage.wgsl")
);

/// The passes of a material, in the order they run: pass `i` renders buffer `i`.
#[derive(Clone, Debug, Default)]
pub struct Passes {
    pub passes: Vec<Pass>,
    /// The buffers the material's module reads, binding `k` holding `reads[k]`.
    pub reads: Vec<usize>,
    /// The positions (in the checked order) of the nodes the material's module holds.
    pub nodes: Vec<usize>,
    /// The buffer each wired sampled input reads, by node and pin index.
    pub sampled: BTreeMap<(NodeId, usize), usize>,
    /// The buffer each Image node reads (its file's pixels), by node.
    pub sources: BTreeMap<NodeId, usize>,
}

impl Passes {
    /// Whether the material has no passes (a single-pass graph).
    pub fn is_empty(&self) -> bool {
        self.passes.is_empty()
    }

    /// Whether every pass uploads a file (the material reads Image nodes and no sampled
    /// input): its buffers do not depend on the domain, so it draws on meshes at their
    /// UVs as well as flat.
    pub fn uploads_only(&self) -> bool {
        (self.passes.iter()).all(|pass| matches!(pass.kind, PassKind::Bitmap { .. }))
    }

    /// Whether `other` runs the same code over the same buffers (a renderer built for
    /// one serves the other).
    pub fn same_code(&self, other: &Passes) -> bool {
        self.passes.len() == other.passes.len()
            && (self.passes.iter().zip(&other.passes))
                .all(|(a, b)| a.spec == b.spec && a.same_work(b))
    }
}

/// One pass: what it renders into its buffer.
#[derive(Clone, Debug)]
pub struct Pass {
    /// What the pass renders, for reports and labels (`"Noise 'grain' → Blur 'soft'"`).
    pub label: String,
    /// How its buffer is stored.
    pub spec: BufferSpec,
    /// The parameter slots its module reads: a range of the material's one numbering,
    /// empty for a stage or baked parameters. What it renders changes only with them and
    /// with the buffers it reads.
    pub slots: std::ops::Range<usize>,
    pub kind: PassKind,
}

/// How a pass computes its texels.
#[derive(Clone, Debug)]
pub enum PassKind {
    /// The value of output `output` of the node at position `node` (in the checked
    /// order) at every point of the domain: `veneer_pass(s: VeneerSurface) -> vec4f`,
    /// its lanes in `.x` (a float in `.xyz`), `.xy` or `.xyz`.
    Surface {
        module: WgslModule,
        node: usize,
        output: usize,
        /// The positions of the nodes the module holds.
        nodes: Vec<usize>,
        /// The buffers it reads, binding `k` holding `reads[k]`.
        reads: Vec<usize>,
    },
    /// A node's texel-space stage over buffer `source`, the same size: `veneer_stage(
    /// texel: vec2i) -> vec4f`, reading `source` at binding 0.
    Stage {
        source: usize,
        module: WgslModule,
        stage: Arc<Stage>,
    },
    /// A bitmap file's pixels, uploaded as they are (the buffer has the bitmap's size,
    /// whatever the output's): no module runs.
    Bitmap {
        /// The file as the graph names it, relative to the graph's folder.
        path: String,
        bitmap: Arc<Bitmap>,
    },
}

impl Pass {
    /// The pass's WGSL module (none for an uploaded bitmap).
    pub fn module(&self) -> Option<&WgslModule> {
        match &self.kind {
            PassKind::Surface { module, .. } | PassKind::Stage { module, .. } => Some(module),
            PassKind::Bitmap { .. } => None,
        }
    }

    /// The buffers the pass reads, binding `k` holding entry `k`.
    pub fn reads(&self) -> Vec<usize> {
        match &self.kind {
            PassKind::Surface { reads, .. } => reads.clone(),
            PassKind::Stage { source, .. } => vec![*source],
            PassKind::Bitmap { .. } => Vec::new(),
        }
    }

    /// The buffer's side when the output is `output` texels square: its spec's, or a
    /// bitmap's own width and height.
    pub fn extent(&self, output: u32) -> (u32, u32) {
        match &self.kind {
            PassKind::Bitmap { bitmap, .. } => (bitmap.width, bitmap.height),
            _ => {
                let side = self.spec.texels(output);
                (side, side)
            }
        }
    }

    /// Whether `other` computes the same texels: the same module, or the same bitmap.
    fn same_work(&self, other: &Pass) -> bool {
        match (&self.kind, &other.kind) {
            (PassKind::Bitmap { bitmap: a, .. }, PassKind::Bitmap { bitmap: b, .. }) => {
                Arc::ptr_eq(a, b)
            }
            _ => (self.module().zip(other.module())).is_some_and(|(a, b)| a.source == b.source),
        }
    }
}

/// The name of buffer `index` in WGSL.
fn buffer_name(index: usize) -> String {
    format!("veneer_buffer_{index}")
}

/// The declarations of `reads` at group 2, binding `k` holding `reads[k]`.
fn buffer_declarations(reads: &[usize], passes: &[Pass]) -> String {
    if reads.is_empty() {
        return String::new();
    }
    let mut text = String::from(
        "\n// Buffers rendered by earlier passes (see the manifest): group 2, one binding each.\n",
    );
    for (binding, &buffer) in reads.iter().enumerate() {
        text.push_str(&format!(
            "// buffer {buffer}: {}\n@group(2) @binding({binding}) var {}: texture_2d<f32>;\n",
            super::naming::comment(&passes[buffer].label),
            buffer_name(buffer)
        ));
    }
    text
}

/// A cut: the output of a node rendered into a buffer stored as `spec`.
type CutKey = (usize, usize, BufferSpec);

/// Builds the passes of a checked graph.
struct Planner<'g> {
    graph: &'g CheckedGraph,
    options: &'g CompileOptions,
    passes: Vec<Pass>,
    cuts: FxHashMap<CutKey, usize>,
    /// The last stage buffer of each node with stages, by position.
    staged: BTreeMap<usize, usize>,
    /// The parameter slots of the modules so far (one numbering for all).
    slots: Vec<ParamSlot>,
    sampled: BTreeMap<(NodeId, usize), usize>,
    /// The buffer of each Image node, and of each bitmap already uploaded (one upload
    /// per file and edge mode, however many nodes read it).
    sources: BTreeMap<NodeId, usize>,
    uploads: Vec<(Arc<Bitmap>, crate::nodes::passes::EdgeMode, usize)>,
    /// The lanes of the whole material's mesh fields, which every module reads.
    mesh_lanes: crate::nodes::mesh_field::MeshLanes,
}

/// The module and passes of a graph with sampled inputs; `None` for a graph without.
pub(super) fn plan(
    graph: &CheckedGraph,
    options: &CompileOptions,
) -> Result<Option<(WgslModule, Passes)>, CompileError> {
    let cuts_anything = graph.order.iter().any(|checked| {
        checked
            .signature
            .inputs
            .iter()
            .zip(&checked.inputs)
            .any(|(pin, source)| pin.sampled && matches!(source, InputSource::Wire { .. }))
    });
    if !cuts_anything && graph.bitmaps.is_empty() {
        return Ok(None);
    }
    let mut planner = Planner {
        graph,
        options,
        passes: Vec::new(),
        cuts: FxHashMap::default(),
        staged: BTreeMap::new(),
        slots: Vec::new(),
        sampled: BTreeMap::new(),
        sources: BTreeMap::new(),
        uploads: Vec::new(),
        mesh_lanes: super::mesh_lanes(graph),
    };
    let material = graph.order.len() - 1;
    let (nodes, reads) = planner.part(material)?;
    let module = planner.module(&nodes, &reads, None)?;
    Ok(Some((
        module,
        Passes {
            passes: planner.passes,
            reads,
            nodes,
            sampled: planner.sampled,
            sources: planner.sources,
        },
    )))
}

impl Planner<'_> {
    /// The nodes one module holds to compute the node at `root` (its ancestors through
    /// wires that are not sampled, in order), after planning the buffers their sampled
    /// inputs read; and those buffers.
    fn part(&mut self, root: usize) -> Result<(Vec<usize>, Vec<usize>), CompileError> {
        let mut keep = BTreeSet::from([root]);
        let mut stack = vec![root];
        let mut cuts = Vec::new();
        while let Some(at) = stack.pop() {
            for (k, pin, node, _, _) in self.graph.order[at].wired_inputs() {
                let Some(from) = self.graph.index_of(node) else {
                    continue;
                };
                if pin.sampled {
                    cuts.push((at, k));
                } else if keep.insert(from) {
                    stack.push(from);
                }
            }
        }
        let mut reads = Vec::new();
        for &at in &keep {
            if let Some(buffer) = self.upload(at)
                && !reads.contains(&buffer)
            {
                reads.push(buffer);
            }
        }
        // Earlier nodes' cuts first, so that buffers number in dependency order.
        cuts.sort_unstable();
        for (at, k) in cuts {
            let buffer = self.sampled_input(at, k)?;
            if !reads.contains(&buffer) {
                reads.push(buffer);
            }
        }
        Ok((keep.into_iter().collect(), reads))
    }

    /// The buffer holding the bitmap the node at `at` reads (uploaded on first use);
    /// `None` for a node that reads none.
    fn upload(&mut self, at: usize) -> Option<usize> {
        let checked = &self.graph.order[at];
        let bitmap = self.graph.bitmaps.get(&checked.node.id)?;
        let source = checked.node.kind.definition().bitmap()?;
        let known = (self.uploads.iter())
            .find(|(seen, edge, _)| Arc::ptr_eq(seen, bitmap) && *edge == source.edge);
        let buffer = match known {
            Some(&(_, _, buffer)) => buffer,
            None => {
                self.passes.push(Pass {
                    label: format!("{} → file '{}'", checked.node, source.path),
                    spec: BufferSpec {
                        resolution: crate::nodes::passes::Resolution::Absolute,
                        size: bitmap.width.max(bitmap.height),
                        format: BufferFormat::Float32,
                        edge: source.edge,
                    },
                    slots: 0..0,
                    kind: PassKind::Bitmap {
                        path: source.path.to_string(),
                        bitmap: bitmap.clone(),
                    },
                });
                let buffer = self.passes.len() - 1;
                self.uploads.push((bitmap.clone(), source.edge, buffer));
                buffer
            }
        };
        self.sources.insert(checked.node.id, buffer);
        Some(buffer)
    }

    /// The buffer sampled input `k` of the node at `at` reads: its cut's buffer, run
    /// through the node's stages if it has any.
    fn sampled_input(&mut self, at: usize, k: usize) -> Result<usize, CompileError> {
        let checked = &self.graph.order[at];
        let InputSource::Wire { node, output, .. } = checked.inputs[k] else {
            unreachable!("a sampled input is wired");
        };
        let from = self
            .graph
            .index_of(node)
            .expect("a wire reads a checked node");
        let reader_spec = checked.node.kind.definition().buffer();
        // A sampled input wired to a Buffer node reads that node's buffer.
        let upstream = &self.graph.order[from];
        let key = match upstream.node.kind.definition().buffer() {
            Some(spec) => {
                let (source, source_output) = wired(upstream, 0, self.graph);
                (source, source_output, spec)
            }
            None => (from, output, reader_spec.unwrap_or_default()),
        };
        let mut buffer = self.cut(key)?;
        if let Some(&staged) = self.staged.get(&at) {
            buffer = staged;
        } else {
            let stages = self.stages(at)?;
            if !stages.is_empty() {
                for stage in stages {
                    buffer = self.stage_pass(at, buffer, stage)?;
                }
                self.staged.insert(at, buffer);
            }
        }
        self.sampled.insert((checked.node.id, k), buffer);
        Ok(buffer)
    }

    /// The stages of the node at `at`, from its inputs' constants.
    fn stages(&self, at: usize) -> Result<Vec<Stage>, CompileError> {
        let checked = &self.graph.order[at];
        let constant = |pin: &str| match checked.input(pin) {
            Some(InputSource::Const(value)) => Some(value.components()[0]),
            _ => None,
        };
        checked
            .node
            .kind
            .definition()
            .stages(&constant)
            .map_err(|message| {
                CompileError::Check(vec![CheckError {
                    node: Some(checked.node.id),
                    node_name: Some(checked.node.to_string()),
                    message,
                }])
            })
    }

    /// The buffer of cut `key`, planned (with the cuts it needs) on first use.
    fn cut(&mut self, key: CutKey) -> Result<usize, CompileError> {
        if let Some(&buffer) = self.cuts.get(&key) {
            return Ok(buffer);
        }
        let (node, output, spec) = key;
        let (nodes, reads) = self.part(node)?;
        let first_slot = self.slots.len();
        let module = self.module(&nodes, &reads, Some((node, output)))?;
        let slots = first_slot..self.slots.len();
        let checked = &self.graph.order[node];
        let label = format!(
            "{} → {}",
            checked.node, checked.signature.outputs[output].name
        );
        self.passes.push(Pass {
            label,
            spec,
            slots,
            kind: PassKind::Surface {
                module,
                node,
                output,
                nodes,
                reads,
            },
        });
        let buffer = self.passes.len() - 1;
        self.cuts.insert(key, buffer);
        Ok(buffer)
    }

    /// A pass running `stage` of the node at `at` over buffer `source`.
    fn stage_pass(
        &mut self,
        at: usize,
        source: usize,
        stage: Stage,
    ) -> Result<usize, CompileError> {
        let spec = BufferSpec {
            format: BufferFormat::Float32,
            ..self.passes[source].spec
        };
        let arguments = format!("{}, {}", buffer_name(source), spec.edge.wgsl());
        let node = &self.graph.order[at].node;
        let label = format!("{} {}", node, stage.label);
        let items = super::library::closure(stage.library.iter().copied());
        let mut text = format!(
            "// Pass of a material generated by Veneer {}: {}.\n// Entry point: veneer_stage(texel: vec2i) -> vec4f.\n",
            env!("CARGO_PKG_VERSION"),
            super::naming::comment(&label)
        );
        text.push_str(&buffer_declarations(&[source], &self.passes));
        for item in &items {
            text.push('\n');
            text.push_str(&item.text);
        }
        text.push_str(&format!(
            "\nfn veneer_stage(texel: vec2i) -> vec4f {{\n    return {};\n}}\n",
            (stage.wgsl)
                .replace("SOURCE_TEXTURE", &buffer_name(source))
                .replace("SOURCE", &arguments)
        ));
        counts::emitted();
        let module = WgslModule {
            module: super::validate(&text).map_err(CompileError::Validation)?,
            source: text,
            node_spans: Vec::new(),
            library: items.into_iter().map(|item| item.name).collect(),
            params: Vec::new(),
            binds_params: false,
            members: Vec::new(),
            uses: SurfaceUse::default(),
        };
        self.passes.push(Pass {
            label,
            spec,
            slots: 0..0,
            kind: PassKind::Stage {
                source,
                module,
                stage: Arc::new(stage),
            },
        });
        Ok(self.passes.len() - 1)
    }

    /// The module of the nodes at `nodes` reading buffers `reads`: the material's
    /// (`target` `None`) or a pass returning output `target.1` of the node at `target.0`.
    fn module(
        &mut self,
        nodes: &[usize],
        reads: &[usize],
        target: Option<(usize, usize)>,
    ) -> Result<WgslModule, CompileError> {
        counts::emitted();
        let part = self.graph.subset(nodes);
        let uses = match target {
            None => SurfaceUse {
                mesh_fields: self.mesh_lanes,
                ..SurfaceUse::of(&part)
            },
            // A pass reads the material's mesh-field lanes too (flat, VENEER_FLAT_FIELDS).
            Some(_) => SurfaceUse {
                mesh_fields: self.mesh_lanes,
                ..SurfaceUse::default()
            },
        };
        let members = if self.options.params == super::ParamMode::Named {
            super::parameter_members(&self.graph.parameters)
        } else {
            Vec::new()
        };
        let mut emitter = Emitter::new(
            self.options.params,
            uses.detail(self.options.detail),
            &self.graph.parameters,
            &members,
        );
        emitter.mesh_lanes = self.mesh_lanes;
        let arguments = |buffer: usize| {
            let edge = self.passes[buffer].spec.edge.wgsl();
            format!("{}, {edge}", buffer_name(buffer))
        };
        for (&(node, pin), &buffer) in &self.sampled {
            emitter.sampled.insert((node, pin), arguments(buffer));
        }
        for (&node, &buffer) in &self.sources {
            emitter.sources.insert(node, arguments(buffer));
        }
        emitter.params = self.slots.clone();
        emitter.first_slot = self.slots.len();
        let (mut blocks, emitted) = emitter.body(&part, &self.graph.bindings, &Default::default());
        let entry = match target {
            None => Entry::MATERIAL,
            Some((node, output)) => {
                let checked = &self.graph.order[node];
                let position = part
                    .index_of(checked.node.id)
                    .expect("the target is in its part");
                let value = emitted[position].outputs[output].clone();
                let ty = checked.signature.outputs[output].ty;
                blocks.push(Block {
                    node: checked.node.id,
                    text: format!("    return {};\n", lanes(&value, ty)),
                    binding: None,
                    reads: emitted[position].block.into_iter().collect(),
                });
                Entry::PASS
            }
        };
        let buffers = buffer_declarations(reads, &self.passes);
        let around = Around {
            functions: "",
            buffers: &buffers,
            entry,
        };
        let module = assemble(&part, emitter, around, &blocks, uses)?;
        self.slots = module.params.clone();
        Ok(module)
    }
}

/// A value of type `ty` as a buffer's four lanes (a float in the first three).
fn lanes(value: &str, ty: ValueType) -> String {
    match ty {
        ValueType::Float => format!("vec4f(vec3f({value}), 1.0)"),
        ValueType::Vec2 => format!("vec4f({value}, 0.0, 1.0)"),
        ValueType::Vec3 | ValueType::Color => format!("vec4f({value}, 1.0)"),
    }
}

/// The node and output input `k` of `checked` is wired to.
fn wired(
    checked: &crate::graph::check::CheckedNode,
    k: usize,
    graph: &CheckedGraph,
) -> (usize, usize) {
    match checked.inputs[k] {
        InputSource::Wire { node, output, .. } => (
            graph.index_of(node).expect("a wire reads a checked node"),
            output,
        ),
        _ => unreachable!("a sampled input is wired"),
    }
}
