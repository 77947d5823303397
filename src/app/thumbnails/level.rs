//! Which graph the tiles are drawn from: the top level's own, or, while a group is
//! open, the graph flattened, its nodes standing in for the group's as they work in
//! the group's first instance (what they get from the nodes around it). A tile is
//! asked for by a node of the level shown and found by the node it stands for.

use crate::graph::{Graph, NodeId, PinRef};
use rustc_hash::FxHashMap;
use std::sync::Arc;

/// The level the tiles are of, and how its nodes map to the graph they are drawn from.
#[derive(Default)]
pub(in crate::app) struct Level {
    /// The group open (`None`: the top level).
    group: Option<String>,
    /// Inside a group: the graph flattened, and the revision it was made at.
    flat: Option<(u64, Arc<Graph>)>,
    /// The flattened id of each node of the group's first instance, by its id inside
    /// the definition; and back.
    drawn_as: FxHashMap<NodeId, NodeId>,
    shown_as: FxHashMap<NodeId, NodeId>,
}

impl Level {
    /// The level shown is `group` (`None`: the top level): a change forgets the other
    /// level's mapping (no tile shows until the next update).
    pub fn show(&mut self, group: Option<&str>) {
        if self.group.as_deref() != group {
            *self = Level {
                group: group.map(str::to_string),
                ..Level::default()
            };
        }
    }

    /// The graph flattened for the group open, made again when `revision` is new;
    /// `None` at the top level (the tiles are the graph's own) or when the graph does
    /// not flatten (a group that contains itself: no tiles then).
    pub fn flattened(&mut self, graph: &Graph, revision: u64) -> Option<Arc<Graph>> {
        let group = self.group.as_deref()?;
        if let Some((made, flat)) = &self.flat
            && *made == revision
        {
            return Some(Arc::clone(flat));
        }
        let flat = crate::graph::group::flatten(graph).ok()?.into_owned();
        let mut first = None;
        self.drawn_as.clear();
        for node in &flat.nodes {
            let Some(origin) = node.origin.as_deref() else {
                continue;
            };
            if origin.definition != group {
                continue;
            }
            let path = first.get_or_insert_with(|| origin.groups.clone());
            if *path == origin.groups {
                self.drawn_as.insert(origin.id, node.id);
            }
        }
        self.shown_as = self.drawn_as.iter().map(|(&at, &id)| (id, at)).collect();
        let flat = Arc::new(flat);
        self.flat = Some((revision, Arc::clone(&flat)));
        Some(flat)
    }

    /// Whether a group is open.
    pub fn in_group(&self) -> bool {
        self.group.is_some()
    }

    /// The node of the tiles' graph that node `id` of the level shown stands for.
    pub fn drawn_node(&self, id: NodeId) -> Option<NodeId> {
        match self.group {
            None => Some(id),
            Some(_) => self.drawn_as.get(&id).copied(),
        }
    }

    /// The node of the level shown that node `id` of the tiles' graph stands for.
    pub fn shown_node(&self, id: NodeId) -> Option<NodeId> {
        match self.group {
            None => Some(id),
            Some(_) => self.shown_as.get(&id).copied(),
        }
    }

    /// [`Level::drawn_node`] of a pin.
    pub fn drawn_pin(&self, pin: &PinRef) -> Option<PinRef> {
        Some(PinRef::new(self.drawn_node(pin.node)?, &pin.pin))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inside_a_group_its_nodes_stand_for_those_of_its_first_instance() {
        let mut graph = crate::graph::preset("wood").unwrap();
        let wood = graph.nodes[0].clone();
        let mut second = wood.clone();
        second.id = graph.next_id();
        second.label = "second wood".into();
        graph.nodes.push(second);
        let sharp = graph.groups["ring_wood"]
            .nodes
            .iter()
            .find(|node| node.label == "ring sharp")
            .unwrap()
            .id;
        let mut level = Level::default();
        assert!(
            level.flattened(&graph, 1).is_none(),
            "the top level is drawn as it is"
        );
        assert_eq!(level.drawn_node(sharp), Some(sharp));
        level.show(Some("ring_wood"));
        let flat = level.flattened(&graph, 1).unwrap();
        let drawn = level.drawn_node(sharp).unwrap();
        let origin = flat.node(drawn).unwrap().origin.as_deref().unwrap();
        assert_eq!(
            (origin.id, origin.top),
            (sharp, wood.id),
            "the first instance's"
        );
        assert_eq!(level.shown_node(drawn), Some(sharp));
        assert!(Arc::ptr_eq(&flat, &level.flattened(&graph, 1).unwrap()));
        level.show(None);
        assert_eq!(level.drawn_node(sharp), Some(sharp));
    }
}
