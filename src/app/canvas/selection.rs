//! The one selection of the graph view, as in Blender: the nodes selected, in order, the
//! last one *active* (the inspector shows it). A click selects a node alone (Shift adds
//! it or makes it active, and deselects the active one; Ctrl toggles it); a box replaces
//! the selection (Shift adds to it, Ctrl removes from it); a click on empty canvas is an
//! empty box. egui-snarl is told the selection each frame, to draw and drag it.

use crate::graph::Node;
use egui::Modifiers;
use egui_snarl::{NodeId, Snarl};

/// The selected nodes of the level shown, the active one last.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Selection(Vec<NodeId>);

impl std::ops::Deref for Selection {
    type Target = [NodeId];

    fn deref(&self) -> &[NodeId] {
        &self.0
    }
}

impl Selection {
    /// The active node: the one clicked last.
    pub fn active(&self) -> Option<NodeId> {
        self.0.last().copied()
    }

    /// Selects nothing.
    pub fn clear(&mut self) {
        self.0.clear();
    }

    /// Selects `nodes` (each once), the last one active.
    pub fn set(&mut self, nodes: impl IntoIterator<Item = NodeId>) {
        self.0.clear();
        for node in nodes {
            self.0.retain(|n| *n != node);
            self.0.push(node);
        }
    }

    /// A click on `node` with `modifiers` held.
    pub fn click(&mut self, node: NodeId, modifiers: Modifiers) {
        let selected = self.0.contains(&node);
        if modifiers.command {
            if selected {
                self.0.retain(|n| *n != node);
            } else {
                self.0.push(node);
            }
        } else if modifiers.shift {
            let active = self.active() == Some(node);
            self.0.retain(|n| *n != node);
            if !active {
                self.0.push(node);
            }
        } else {
            self.set([node]);
        }
    }

    /// A box drawn around `nodes` with `modifiers` held. The active node stays active
    /// while it stays selected.
    pub fn boxed(&mut self, mut nodes: Vec<NodeId>, modifiers: Modifiers) {
        nodes.sort_by_key(|node| node.0);
        let active = self.active();
        if modifiers.command {
            self.0.retain(|n| !nodes.contains(n));
            return;
        }
        if !modifiers.shift {
            self.0.retain(|n| Some(*n) == active && nodes.contains(n));
        }
        let added = nodes.into_iter().filter(|n| !self.0.contains(n));
        let at = self.0.len() - usize::from(active.is_some_and(|a| self.0.contains(&a)));
        self.0.splice(at..at, added.collect::<Vec<_>>());
    }

    /// Forgets the nodes `snarl` no longer has.
    pub fn retain_existing(&mut self, snarl: &Snarl<Node>) {
        self.0.retain(|node| snarl.get_node(*node).is_some());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ids(numbers: &[usize]) -> Vec<NodeId> {
        numbers.iter().map(|n| NodeId(*n)).collect()
    }

    fn selection(numbers: &[usize]) -> Selection {
        let mut selection = Selection::default();
        selection.set(ids(numbers));
        selection
    }

    #[test]
    fn a_click_selects_alone_shift_adds_or_activates_ctrl_toggles() {
        let mut selection = selection(&[1, 2]);
        selection.click(NodeId(3), Modifiers::NONE);
        assert_eq!(*selection, ids(&[3]));
        selection.click(NodeId(4), Modifiers::SHIFT);
        selection.click(NodeId(3), Modifiers::SHIFT);
        assert_eq!(
            *selection,
            ids(&[4, 3]),
            "Shift on a selected node activates it"
        );
        selection.click(NodeId(3), Modifiers::SHIFT);
        assert_eq!(
            *selection,
            ids(&[4]),
            "Shift on the active node deselects it"
        );
        selection.click(NodeId(5), Modifiers::COMMAND);
        assert_eq!(selection.active(), Some(NodeId(5)));
        selection.click(NodeId(5), Modifiers::COMMAND);
        assert_eq!(*selection, ids(&[4]));
    }

    #[test]
    fn a_box_replaces_shift_adds_ctrl_removes_and_the_active_node_stays_active() {
        let mut selection = selection(&[1, 2]);
        selection.boxed(ids(&[5, 3]), Modifiers::NONE);
        assert_eq!(*selection, ids(&[3, 5]));
        selection.boxed(ids(&[1]), Modifiers::SHIFT);
        assert_eq!(*selection, ids(&[3, 1, 5]), "added before the active node");
        selection.boxed(ids(&[5, 1]), Modifiers::NONE);
        assert_eq!(*selection, ids(&[1, 5]), "the active node stays active");
        selection.boxed(ids(&[5]), Modifiers::COMMAND);
        assert_eq!(*selection, ids(&[1]));
        selection.boxed(Vec::new(), Modifiers::SHIFT);
        assert_eq!(
            *selection,
            ids(&[1]),
            "a Shift click on empty canvas keeps it"
        );
        selection.boxed(Vec::new(), Modifiers::NONE);
        assert!(selection.is_empty(), "a click on empty canvas clears it");
    }
}
