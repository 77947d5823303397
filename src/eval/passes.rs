//! The CPU reference of a multi-pass material: every pass rendered into an image, in
//! order, as the GPU renders its buffers (texel centres over the flat domain, values
//! stored at the buffer's format), for the material's sampled inputs to read.

use super::{Evaluator, Material, Real, Surface};
use crate::codegen::passes::{PassKind, Passes};
use crate::graph::NodeId;
use crate::graph::check::CheckedNode;
use crate::nodes::formulas::buffers::Image;
use crate::render::{FlatRect, flat_points};
use rayon::prelude::*;
use std::collections::BTreeMap;

/// The images of a material's passes, and which one each sampled input reads.
#[derive(Clone, Debug, Default)]
pub struct Buffers {
    /// Pass `i`'s buffer.
    pub images: Vec<Image>,
    sampled: BTreeMap<(NodeId, usize), usize>,
    /// The image each Image node reads.
    sources: BTreeMap<NodeId, usize>,
    /// The positions of the nodes the material's module holds (the material's part:
    /// a Buffer node read only through sampled inputs is in none).
    pub(super) material_nodes: Vec<usize>,
}

impl Buffers {
    /// The files `graph`'s Image nodes read, each as its node's image: all a graph
    /// without sampled inputs needs (its bitmaps do not depend on the domain).
    pub(super) fn bitmaps_of(graph: &crate::graph::CheckedGraph) -> Buffers {
        let mut buffers = Buffers::default();
        for checked in &graph.order {
            let (Some(bitmap), Some(source)) = (
                graph.bitmaps.get(&checked.node.id),
                checked.node.kind.definition().bitmap(),
            ) else {
                continue;
            };
            buffers
                .sources
                .insert(checked.node.id, buffers.images.len());
            buffers.images.push(Image::of_bitmap(bitmap, source.edge));
        }
        buffers
    }

    /// The image each input pin of `checked` reads (`None` for pins not sampled).
    pub(super) fn of(&self, checked: &CheckedNode) -> Vec<Option<&Image>> {
        if self.sampled.is_empty() {
            return Vec::new();
        }
        (0..checked.inputs.len())
            .map(|pin| {
                let buffer = self.sampled.get(&(checked.node.id, pin))?;
                Some(&self.images[*buffer])
            })
            .collect()
    }

    /// The image of the bitmap `checked` reads (an Image node).
    pub(super) fn source_of(&self, checked: &CheckedNode) -> Option<&Image> {
        let buffer = self.sources.get(&checked.node.id)?;
        Some(&self.images[*buffer])
    }
}

impl Evaluator {
    /// Renders `passes` (planned for this graph) for an output of size² pixels over
    /// `rect` at `time`, in f64 from the f32 texel positions the GPU computes.
    pub fn render_passes(&self, passes: &Passes, rect: FlatRect, size: u32, time: f32) -> Buffers {
        let mut buffers = Buffers {
            images: Vec::with_capacity(passes.passes.len()),
            sampled: passes.sampled.clone(),
            sources: passes.sources.clone(),
            material_nodes: passes.nodes.clone(),
        };
        for pass in &passes.passes {
            let side = pass.spec.texels(size);
            let image = match &pass.kind {
                PassKind::Surface {
                    node,
                    output,
                    nodes,
                    ..
                } => {
                    let ty = self.graph.order[*node].signature.outputs[*output].ty;
                    let points = flat_points(rect, side);
                    let texels = (0..points.len())
                        .into_par_iter()
                        .map(|k| {
                            let t = [k as u32 % side, k as u32 / side]
                                .map(|i| f64::from((i as f32 + 0.5) / side as f32));
                            let surface = Surface {
                                uv: t,
                                time: f64::from(time),
                                ..self.flat_surface(points[k])
                            };
                            // Every node of the pass's part, as its module computes them
                            // (the instance is the shaded point's: none).
                            let none = crate::nodes::cpu::Instance::none();
                            let nodes = nodes.iter().copied();
                            let values = self.values(&surface, &buffers, nodes, Some(&none), None);
                            let value = values[*node][*output];
                            let lanes = match ty.width() {
                                1 => [value[0], value[0], value[0], 1.0],
                                2 => [value[0], value[1], 0.0, 1.0],
                                _ => [value[0], value[1], value[2], 1.0],
                            };
                            lanes.map(|lane| pass.spec.format.quantise(lane as f32))
                        })
                        .collect();
                    Image {
                        width: side,
                        height: side,
                        edge: pass.spec.edge,
                        texels,
                    }
                }
                PassKind::Stage { source, stage, .. } => {
                    buffers.images[*source].map_texels(|image, texel| (stage.cpu)(image, texel))
                }
                PassKind::Bitmap { bitmap, .. } => Image::of_bitmap(bitmap, pass.spec.edge),
            };
            buffers.images.push(image);
        }
        buffers
    }

    /// The flat render on the CPU in precision `R`: the material at every pixel centre
    /// of a size² image over `rect`, rows from the top. A multi-pass material (`passes`
    /// not empty) has its buffers rendered first and its pixels' uv at their place in
    /// the rectangle, as `render_flat.wgsl` gives it; a single-pass one has uv 0.
    pub fn flat<R: Real + Send>(
        &self,
        passes: &Passes,
        rect: FlatRect,
        size: u32,
        time: f32,
    ) -> Vec<Material<R>> {
        let buffers = self.render_passes(passes, rect, size, time);
        let domain_uv = !passes.is_empty();
        let points = flat_points(rect, size);
        (0..points.len())
            .into_par_iter()
            .map(|k| {
                let mut surface = self.flat_surface::<R>(points[k]);
                surface.time = R::c(f64::from(time));
                if domain_uv {
                    surface.uv = [k as u32 % size, k as u32 / size]
                        .map(|i| R::c(f64::from((i as f32 + 0.5) / size as f32)));
                }
                self.eval_reading(&surface, &buffers)
            })
            .collect()
    }
}
