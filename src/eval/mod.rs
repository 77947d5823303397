//! CPU reference evaluator: the same graph, the same formulas as the generated WGSL,
//! evaluated at one point in f32 (like the GPU) or f64 (the reference). Each node kind's
//! formulas are in its definition (`nodes/`).

mod passes;

pub use crate::nodes::cpu::Surface;
pub use crate::nodes::formulas::buffers::Image;
pub use crate::nodes::formulas::real::Real;
pub use passes::Buffers;

use crate::graph::check::{CheckedGraph, CheckedNode, InputSource};
use crate::graph::frames::Frames;
use crate::graph::{CheckError, Graph};
use crate::nodes::cpu::Eval;
use crate::nodes::cpu::Instance;
use crate::nodes::formulas::real::V3;
use crate::nodes::mesh_field::MeshLanes;
use std::collections::BTreeMap;

/// What a material returns (the CPU side of `VeneerMaterial`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material<R> {
    pub albedo: [R; 3],
    pub alpha: R,
    pub specular: [R; 3],
    pub shininess: R,
    pub bump: [R; 3],
    pub height: R,
    /// Light the surface gives off whatever the lighting (seed 003's ambient glow).
    pub emission: [R; 3],
    /// Metallic-roughness shading: 0 dielectric to 1 metal.
    pub metallic: R,
    /// Perceptual roughness, 0 mirror to 1 matte.
    pub roughness: R,
    /// Tangent-space normal (x along +u, y up the image, z out of the surface).
    pub normal: [R; 3],
    /// Multiplies `emission`.
    pub emission_strength: R,
    /// Ambient occlusion, 1 unoccluded.
    pub occlusion: R,
}

impl<R: Real> Material<R> {
    /// The material node's inputs, read by pin name.
    fn from_inputs(io: &Eval<R>) -> Material<R> {
        Material {
            albedo: io.input("albedo"),
            alpha: io.float("alpha"),
            specular: io.input("specular"),
            shininess: io.float("shininess"),
            bump: io.input("bump"),
            height: io.float("height"),
            emission: io.input("emission"),
            metallic: io.float("metallic"),
            roughness: io.float("roughness"),
            normal: io.input("normal"),
            emission_strength: io.float("emission_strength"),
            occlusion: io.float("occlusion"),
        }
    }
}

/// A graph prepared for evaluation at many points.
pub struct Evaluator {
    graph: CheckedGraph,
    /// Position in `graph.order` of every node id.
    index: BTreeMap<crate::graph::NodeId, usize>,
    /// The files the graph's Image nodes read, which need no pass rendered first.
    bitmaps: Buffers,
    /// Which mesh field each lane of the surface's `fields` holds (as the compiled
    /// material assigns them).
    mesh_lanes: MeshLanes,
    /// Where each node is evaluated: at the point, or per instance in a local frame.
    frames: Frames,
    /// Whether the node at each position is evaluated at the shaded point.
    in_main: Vec<bool>,
    /// The exposed parameter each constant input holds: (position in the order, input
    /// index) → index in `graph.parameters`, where the types agree.
    parameter_inputs: BTreeMap<(usize, usize), usize>,
}

impl Evaluator {
    /// Checks `graph` and prepares it.
    pub fn new(graph: &Graph) -> Result<Evaluator, Vec<CheckError>> {
        Ok(Evaluator::from_checked(crate::graph::check(graph)?))
    }

    /// Prepares an already checked graph.
    pub fn from_checked(graph: CheckedGraph) -> Evaluator {
        let index = graph
            .order
            .iter()
            .enumerate()
            .map(|(i, c)| (c.node.id, i))
            .collect();
        let bitmaps = Buffers::bitmaps_of(&graph);
        let frames = Frames::of(&graph);
        let mut in_main = vec![false; graph.order.len()];
        for &at in &frames.main {
            in_main[at] = true;
        }
        let mut parameter_inputs = BTreeMap::new();
        for (at, checked) in graph.order.iter().enumerate() {
            for (k, pin) in checked.signature.inputs.iter().enumerate() {
                let bound = graph.bindings.get(&(checked.node.id, pin.name.to_string()));
                let parameter = bound.and_then(|name| {
                    (graph.parameters.iter()).position(|p| &p.name == name && p.ty == pin.ty)
                });
                if let Some(parameter) = parameter {
                    parameter_inputs.insert((at, k), parameter);
                }
            }
        }
        Evaluator {
            parameter_inputs,
            frames,
            in_main,
            mesh_lanes: crate::codegen::mesh_lanes(&graph),
            graph,
            index,
            bitmaps,
        }
    }

    /// The surface of a flat view at `position` ([`Surface::at`]), its mesh-field lanes
    /// holding what a flat plane gives (`VENEER_FLAT_FIELDS` of the compiled module).
    pub fn flat_surface<R: Real>(&self, position: [f64; 3]) -> Surface<R> {
        let flat = crate::nodes::mesh_field::flat_fields(&self.mesh_lanes);
        Surface {
            fields: flat.map(|value| R::c(f64::from(value))),
            ..Surface::at(position)
        }
    }

    /// The material at one point, in precision `R` (a graph without sampled inputs; its
    /// Image nodes read their files).
    pub fn eval<R: Real>(&self, surface: &Surface<R>) -> Material<R> {
        self.eval_reading(surface, &self.bitmaps)
    }

    /// The material at one point, its sampled inputs reading `buffers` (the passes
    /// rendered by [`Evaluator::render_passes`]).
    pub fn eval_reading<R: Real>(&self, surface: &Surface<R>, buffers: &Buffers) -> Material<R> {
        self.eval_parameters(surface, buffers, None)
    }

    /// The material at one point (a graph without sampled inputs), its exposed
    /// parameters holding `parameters` (one value per parameter of the checked graph, in
    /// its order) rather than their values: what a fit differentiates by.
    pub fn eval_with<R: Real>(&self, surface: &Surface<R>, parameters: &[V3<R>]) -> Material<R> {
        self.eval_parameters(surface, &self.bitmaps, Some(parameters))
    }

    /// The checked graph evaluated.
    pub fn graph(&self) -> &CheckedGraph {
        &self.graph
    }

    /// [`Evaluator::eval_reading`], the exposed parameters holding `parameters` if given.
    fn eval_parameters<R: Real>(
        &self,
        surface: &Surface<R>,
        buffers: &Buffers,
        parameters: Option<&[V3<R>]>,
    ) -> Material<R> {
        let material = self.graph.order.len() - 1;
        let values = if buffers.material_nodes.is_empty() {
            self.values(surface, buffers, 0..material, None, parameters)
        } else {
            let part = buffers.material_nodes.iter().copied();
            let part = part.filter(|&at| at != material);
            self.values(surface, buffers, part, None, parameters)
        };
        let checked = &self.graph.order[material];
        let inputs = self.inputs(material, &values, surface, parameters);
        Material::from_inputs(&Eval::new(&checked.signature.inputs, &inputs, surface))
    }

    /// The outputs of the nodes at `positions` (ascending, in the checked order; the
    /// others stay empty), at one point: of those the shaded point evaluates, or inside
    /// a local frame (`instance` given) all of them.
    fn values<R: Real>(
        &self,
        surface: &Surface<R>,
        buffers: &Buffers,
        positions: impl IntoIterator<Item = usize>,
        instance: Option<&Instance<R>>,
        parameters: Option<&[V3<R>]>,
    ) -> Vec<Vec<V3<R>>> {
        let mut values: Vec<Vec<V3<R>>> = vec![Vec::new(); self.graph.order.len()];
        for at in positions {
            if instance.is_none() && !self.in_main[at] {
                continue;
            }
            let checked = &self.graph.order[at];
            let inputs = self.inputs(at, &values, surface, parameters);
            let images = buffers.of(checked);
            let reevaluate = |k: usize, surface: &Surface<R>, instance: &Instance<R>| {
                let frame = self.frames.sites.get(&(at, k))?;
                Some(self.local_value(*frame, surface, instance, buffers))
            };
            let io = Eval::new(&checked.signature.inputs, &inputs, surface)
                .with_images(&images)
                .with_source(buffers.source_of(checked))
                .with_mesh_lanes(self.mesh_lanes)
                .in_frame(&reevaluate, instance);
            values[at] = checked.node.kind.eval(&io);
        }
        values
    }

    /// The value local frame `frame` returns at `surface` for `instance`.
    fn local_value<R: Real>(
        &self,
        frame: usize,
        surface: &Surface<R>,
        instance: &Instance<R>,
        buffers: &Buffers,
    ) -> V3<R> {
        let local = &self.frames.locals[frame];
        let nodes = local.nodes.iter().copied();
        let values = self.values(surface, buffers, nodes, Some(instance), None);
        (values[local.source].get(local.output).copied()).unwrap_or([R::c(0.0); 3])
    }

    /// The input values of the node at position `at`, its wires reading `values`, its
    /// inputs holding exposed parameters reading `parameters` if given.
    fn inputs<R: Real>(
        &self,
        at: usize,
        values: &[Vec<V3<R>>],
        surface: &Surface<R>,
        parameters: Option<&[V3<R>]>,
    ) -> Vec<V3<R>> {
        let checked = &self.graph.order[at];
        (checked.inputs.iter().enumerate())
            .map(|(k, source)| match source {
                // A sampled input's upstream is in another pass: the node reads its
                // buffer instead.
                InputSource::Wire { node, output, .. } => (values[self.index[node]].get(*output))
                    .copied()
                    .unwrap_or([R::c(0.0); 3]),
                // Looked up only when parameters are given: every other evaluation
                // reads the constant as it is.
                InputSource::Const(value) => (parameters)
                    .and_then(|given| Some(given[*self.parameter_inputs.get(&(at, k))?]))
                    .unwrap_or_else(|| value.components().map(R::c)),
                InputSource::Position => surface.position,
            })
            .collect()
    }
}

/// The outputs of a node whose inputs are all known constants, evaluated in f32 as the
/// GPU would (codegen folds such nodes into literals).
pub(crate) fn constant_outputs(checked: &CheckedNode, inputs: &[[f32; 3]]) -> Vec<[f32; 3]> {
    let surface = Surface::<f32>::at([0.0; 3]);
    let io = Eval::new(&checked.signature.inputs, inputs, &surface);
    checked.node.kind.eval(&io)
}
