//! The material function's text: one `veneer_material` for graphs of up to
//! [`PART_NODES`] nodes with code, and for larger ones a chain of part functions, each
//! handing the values later parts read on in a struct. WGSL compilers (naga among them)
//! slow down more than linearly on one very long function; parts keep the cost linear.

use crate::graph::NodeId;
use std::collections::BTreeSet;
use std::fmt::Write;
use std::ops::Range;

/// The most nodes with code in one function of the generated WGSL.
pub const PART_NODES: usize = 256;

/// One node's code in the material function.
pub struct Block {
    pub node: NodeId,
    /// The node's comment and statements, indented and one per line.
    pub text: String,
    /// The identifier the statements bind and its WGSL type, if they bind one.
    pub binding: Option<(String, &'static str)>,
    /// Earlier blocks whose binding these statements read (indices into the body).
    pub reads: Vec<usize>,
}

/// The function a module's body becomes: its name and what it returns.
#[derive(Clone, Copy)]
pub struct Entry {
    pub name: &'static str,
    pub returns: &'static str,
}

impl Entry {
    /// `veneer_material(s) -> VeneerMaterial`: a material's (or its last pass's) entry.
    pub const MATERIAL: Entry = Entry {
        name: "veneer_material",
        returns: "VeneerMaterial",
    };
    /// `veneer_pass(s) -> vec4f`: a pass rendering one value into a buffer.
    pub const PASS: Entry = Entry {
        name: "veneer_pass",
        returns: "vec4f",
    };
}

/// Appends the function(s) `entry` for `body` (in dependency order, the block that
/// returns last) to `source`; returns where each node's code landed.
pub fn write_entry(
    source: &mut String,
    body: &[Block],
    entry: Entry,
) -> Vec<(Range<usize>, NodeId)> {
    let Entry {
        name: function,
        returns: function_returns,
    } = entry;
    let mut spans = Vec::with_capacity(body.len());
    if body.len() <= PART_NODES {
        let _ = write!(
            source,
            "\n// ---- the material graph\n\nfn {function}(s: VeneerSurface) -> {function_returns} {{\n"
        );
        write_blocks(source, body, &mut spans);
        source.push_str("}\n");
        return spans;
    }
    let parts: Vec<Range<usize>> = (0..body.len())
        .step_by(PART_NODES)
        .map(|start| start..body.len().min(start + PART_NODES))
        .collect();
    let part_of = |block: usize| block / PART_NODES;
    // What each part reads from earlier parts, and what it hands on: (block, name, type).
    let mut reads: Vec<BTreeSet<usize>> = vec![BTreeSet::new(); parts.len()];
    let mut handed_on: Vec<BTreeSet<usize>> = vec![BTreeSet::new(); parts.len()];
    for (index, block) in body.iter().enumerate() {
        for &read in &block.reads {
            if part_of(read) < part_of(index) && body[read].binding.is_some() {
                reads[part_of(index)].insert(read);
                handed_on[part_of(read)].insert(read);
            }
        }
    }
    let bound = |blocks: &BTreeSet<usize>| -> Vec<(usize, &str, &str)> {
        blocks
            .iter()
            .filter_map(|&b| {
                let (name, ty) = body[b].binding.as_ref()?;
                Some((b, name.as_str(), *ty))
            })
            .collect()
    };
    let _ = writeln!(
        source,
        "\n// ---- the material graph, in {} parts of at most {PART_NODES} nodes",
        parts.len()
    );
    let mut calls = String::new();
    for (part, blocks) in parts.iter().enumerate() {
        let number = part + 1;
        let last = number == parts.len();
        let outputs = bound(&handed_on[part]);
        let returns = if last {
            format!(" -> {function_returns}")
        } else if outputs.is_empty() {
            String::new()
        } else {
            let _ = writeln!(source, "\nstruct veneer_part_{number} {{");
            for (_, name, ty) in &outputs {
                let _ = writeln!(source, "    {name}: {ty},");
            }
            source.push_str("}\n");
            format!(" -> veneer_part_{number}")
        };
        let inputs = bound(&reads[part]);
        let _ = write!(source, "\nfn {function}_part_{number}(s: VeneerSurface");
        let mut call = format!("{function}_part_{number}(s");
        for (b, name, ty) in &inputs {
            let _ = write!(source, ", {name}: {ty}");
            let _ = write!(call, ", veneer_values_{}.{name}", part_of(*b) + 1);
        }
        let _ = writeln!(source, "){returns} {{");
        write_blocks(source, &body[blocks.clone()], &mut spans);
        if !last && !outputs.is_empty() {
            let names: Vec<&str> = outputs.iter().map(|(_, name, _)| *name).collect();
            let _ = writeln!(
                source,
                "    return veneer_part_{number}({});",
                names.join(", ")
            );
        }
        source.push_str("}\n");
        let _ = match (last, outputs.is_empty()) {
            (true, _) => writeln!(calls, "    return {call});"),
            (false, false) => writeln!(calls, "    let veneer_values_{number} = {call});"),
            (false, true) => writeln!(calls, "    {call});"),
        };
    }
    let _ = writeln!(
        source,
        "\nfn {function}(s: VeneerSurface) -> {function_returns} {{"
    );
    source.push_str(&calls);
    source.push_str("}\n");
    spans
}

/// Appends `blocks`, recording where each one lands.
fn write_blocks(source: &mut String, blocks: &[Block], spans: &mut Vec<(Range<usize>, NodeId)>) {
    for block in blocks {
        let start = source.len();
        source.push_str(&block.text);
        spans.push((start..source.len(), block.node));
    }
}
