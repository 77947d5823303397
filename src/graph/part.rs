//! Part of a graph: the nodes some outputs read, as a graph of its own. The thumbnails'
//! and the inspector's probe graphs are built on it, so that what they copy, key and
//! compile grows with what they show and not with the whole graph (a thumbnail near
//! the start of a 10,000-node chain reads a handful of nodes).

use super::{Graph, NodeId, Wire};
use rustc_hash::{FxHashMap, FxHashSet};

impl Graph {
    /// For every node, the nodes its wires lead to: `ends` gives a wire's node and the
    /// node it leads to (the reader, or the source).
    pub fn linked(
        &self,
        ends: impl Fn(&Wire) -> (NodeId, NodeId),
    ) -> FxHashMap<NodeId, Vec<NodeId>> {
        let mut linked: FxHashMap<NodeId, Vec<NodeId>> = FxHashMap::default();
        for (node, other) in self.wires.iter().map(ends) {
            linked.entry(node).or_default().push(other);
        }
        linked
    }

    /// `roots` and every node upstream of them (linear in the graph's wires, without
    /// recursion: chains may be thousands of nodes long).
    pub fn upstream(&self, roots: impl IntoIterator<Item = NodeId>) -> FxHashSet<NodeId> {
        reach(&self.linked(|wire| (wire.to.node, wire.from.node)), roots)
    }

    /// `roots` and every node that reads one of them, directly or not.
    pub fn downstream(&self, roots: impl IntoIterator<Item = NodeId>) -> FxHashSet<NodeId> {
        reach(&self.linked(|wire| (wire.from.node, wire.to.node)), roots)
    }

    /// The graph of the nodes in `keep` (in the file's order) and the wires between
    /// them, with the same groups, placement and shading; the parameters (and preset
    /// values) of nodes left out go, and so do the comment frames, which only the
    /// editor draws.
    pub fn part(&self, keep: &FxHashSet<NodeId>) -> Graph {
        let nodes = self.nodes.iter().filter(|node| keep.contains(&node.id));
        let wires = self
            .wires
            .iter()
            .filter(|wire| keep.contains(&wire.from.node) && keep.contains(&wire.to.node));
        let parameters: Vec<_> = self
            .parameters
            .iter()
            .filter(|parameter| keep.contains(&parameter.node))
            .cloned()
            .collect();
        let named = |name: &String| parameters.iter().any(|parameter| &parameter.name == name);
        let presets = self.presets.iter().map(|(preset, values)| {
            let values = values.iter().filter(|(name, _)| named(name));
            let values = values.map(|(name, value)| (name.clone(), value.clone()));
            (preset.clone(), values.collect())
        });
        Graph {
            version: self.version,
            name: self.name.clone(),
            preview: self.preview.clone(),
            nodes: nodes.cloned().collect(),
            wires: wires.cloned().collect(),
            frames: Vec::new(),
            alpha: self.alpha,
            shading: self.shading,
            groups: self.groups.clone(),
            presets: presets.collect(),
            parameters,
            folder: self.folder.clone(),
        }
    }
}

/// `roots` and every node `links` lead to from them, directly or not.
fn reach(
    links: &FxHashMap<NodeId, Vec<NodeId>>,
    roots: impl IntoIterator<Item = NodeId>,
) -> FxHashSet<NodeId> {
    let mut reached = FxHashSet::default();
    let mut stack: Vec<NodeId> = roots.into_iter().collect();
    while let Some(node) = stack.pop() {
        if reached.insert(node) {
            stack.extend(links.get(&node).into_iter().flatten().copied());
        }
    }
    reached
}

#[cfg(test)]
mod tests {
    use crate::graph::{Graph, NodeKind, Value};

    #[test]
    fn a_part_holds_what_its_roots_read_and_nothing_downstream() {
        // position → a → b, and position → aside.
        let mut graph = Graph::default();
        let ids = ["position", "a", "b", "aside"].map(|label| {
            let kind = match label {
                "position" => NodeKind::Position,
                _ => NodeKind::Transform,
            };
            graph.add(label, kind)
        });
        let [position, a, b, aside] = ids;
        for (from, pin, to) in [
            (position, "position", a),
            (a, "p", b),
            (position, "position", aside),
        ] {
            graph.connect(from, pin, to, "p");
        }
        graph.set_input(b, "scale", Value::Vec3(2.0, 2.0, 2.0));
        let keep = graph.upstream([a]);
        assert_eq!(keep, [position, a].into_iter().collect());
        assert_eq!(graph.downstream([a]), [a, b].into_iter().collect());
        let part = graph.part(&keep);
        let ids: Vec<_> = part.nodes.iter().map(|node| node.id).collect();
        assert_eq!(ids, [position, a], "in the file's order");
        assert_eq!(part.wires, [graph.wires[0].clone()]);
        assert_eq!(graph.part(&graph.upstream([b])).nodes[2], graph.nodes[2]);
    }

    #[test]
    fn parameters_of_nodes_left_out_go_with_their_preset_values() {
        let mut graph = Graph::default();
        let a = graph.add("a", NodeKind::Transform);
        let b = graph.add("b", NodeKind::Transform);
        for (name, node) in [("kept", a), ("gone", b)] {
            graph.parameters.push(crate::graph::parameters::Parameter {
                name: name.into(),
                node,
                pin: "scale".into(),
                range: None,
                hint: Default::default(),
            });
        }
        let values = [("kept", 1.0), ("gone", 2.0)]
            .map(|(name, value)| (name.to_string(), Value::Float(value)));
        graph
            .presets
            .insert("oak".into(), values.into_iter().collect());
        let part = graph.part(&graph.upstream([a]));
        assert_eq!(part.parameters.len(), 1);
        assert_eq!(part.parameters[0].name, "kept");
        let oak: Vec<_> = part.presets["oak"].keys().collect();
        assert_eq!(oak, ["kept"]);
    }
}
