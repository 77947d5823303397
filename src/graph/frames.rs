//! Frames: where each node of a checked graph is evaluated.
//!
//! Most nodes are evaluated once, at the point being shaded (the main frame). A node
//! with a re-evaluated input (a tile sampler's pattern, its mask) evaluates that
//! input's upstream itself, once per instance, at points of its choosing: the upstream
//! is a *local frame*, a function of the surface and the instance that the compiler
//! emits as a WGSL function and the CPU evaluator runs on its own. A node reached both
//! ways is evaluated in both; a node reached only through re-evaluated inputs is not
//! computed at the shaded point. Frames nest: a pattern may hold a tile sampler of its
//! own.
//!
//! Codegen and the CPU evaluator read this one answer, so both place the same nodes.

use super::ValueType;
use super::check::CheckedGraph;
use rustc_hash::FxHashMap;

/// The nodes of one local frame: the upstream of a re-evaluated input, returning one
/// output of its source node as the input's type.
#[derive(Clone, Debug, PartialEq)]
pub struct LocalFrame {
    /// The source node's position in the checked order.
    pub source: usize,
    /// The source's output the frame returns.
    pub output: usize,
    /// The source output's type.
    pub from: ValueType,
    /// The type the reading input converts it to.
    pub ty: ValueType,
    /// Positions of the frame's nodes, ascending (every node after those it reads); the
    /// source is the last.
    pub nodes: Vec<usize>,
}

/// The frames of a checked graph.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Frames {
    /// Positions of the nodes evaluated at the shaded point, ascending.
    pub main: Vec<usize>,
    /// The local frames, one per distinct source output and type read by re-evaluated
    /// inputs, in the order of their first readers.
    pub locals: Vec<LocalFrame>,
    /// The local frame each wired re-evaluated input reads: (reader position, pin index)
    /// → index into `locals`.
    pub sites: FxHashMap<(usize, usize), usize>,
}

impl Frames {
    /// The frames of `graph`: its roots (nodes nothing in it reads, its material or a
    /// function's outputs) head the main frame.
    pub fn of(graph: &CheckedGraph) -> Frames {
        let count = graph.order.len();
        let mut read = vec![false; count];
        let mut locals: Vec<LocalFrame> = Vec::new();
        let mut sites = FxHashMap::default();
        for (at, checked) in graph.order.iter().enumerate() {
            for (k, pin, node, output, ty) in checked.wired_inputs() {
                let Some(from) = graph.index_of(node) else {
                    continue;
                };
                read[from] = true;
                if !pin.re_evaluated {
                    continue;
                }
                let key = |frame: &LocalFrame| {
                    frame.source == from && frame.output == output && frame.ty == pin.ty
                };
                let frame = match locals.iter().position(key) {
                    Some(frame) => frame,
                    None => {
                        locals.push(LocalFrame {
                            source: from,
                            output,
                            from: ty,
                            ty: pin.ty,
                            nodes: reach(graph, &[from]),
                        });
                        locals.len() - 1
                    }
                };
                sites.insert((at, k), frame);
            }
        }
        let roots: Vec<usize> = (0..count).filter(|&at| !read[at]).collect();
        let main = if locals.is_empty() {
            (0..count).collect()
        } else {
            reach(graph, &roots)
        };
        Frames {
            main,
            locals,
            sites,
        }
    }
}

/// The nodes `roots` need through inputs that are not re-evaluated, ascending.
fn reach(graph: &CheckedGraph, roots: &[usize]) -> Vec<usize> {
    let mut keep = vec![false; graph.order.len()];
    let mut stack: Vec<usize> = roots.to_vec();
    for &root in roots {
        keep[root] = true;
    }
    while let Some(at) = stack.pop() {
        for (_, pin, node, _, _) in graph.order[at].wired_inputs() {
            if pin.re_evaluated {
                continue;
            }
            if let Some(from) = graph.index_of(node)
                && !keep[from]
            {
                keep[from] = true;
                stack.push(from);
            }
        }
    }
    (0..keep.len()).filter(|&at| keep[at]).collect()
}
