//! The graph canvas: the node view (an egui-snarl view of the document's graph, whose
//! changes become graph edits: `view_edits`, and which follows the document's:
//! `snarl_patch`), its
//! navigation, selection, the add-node search, the clipboard, wires and group levels.

pub(in crate::app) mod add_node;
pub(in crate::app) mod boundary;
pub(in crate::app) mod catalogue;
pub(in crate::app) mod clipboard;
pub(in crate::app) mod grab;
pub(in crate::app) mod group_edit;
pub(in crate::app) mod levels;
pub(in crate::app) mod navigation;
pub(in crate::app) mod node_text;
pub(in crate::app) mod painting;
pub(in crate::app) mod panel;
pub(in crate::app) mod placement;
pub(in crate::app) mod scope;
pub(in crate::app) mod selection;
pub(in crate::app) mod snarl_model;
pub(in crate::app) mod snarl_patch;
pub(in crate::app) mod view_edits;
pub(in crate::app) mod viewer;
pub(in crate::app) mod wire_pointer;
pub(in crate::app) mod wires;

use crate::graph::{Node, PinRef};
use egui_snarl::Snarl;

/// The graph view's state: the snarl showing the current level, what is selected, the
/// view's transform and gestures, and the add-node search.
pub(in crate::app) struct Canvas {
    /// The view of the level shown (the top level, or the group entered).
    pub snarl: Snarl<Node>,
    /// Where pins and nodes were drawn in the last frame.
    pub spots: wires::SharedSpots,
    /// The output carried by the wire under the pointer.
    pub hovered_wire: Option<PinRef>,
    /// The node the primary button went down on, and where it was then.
    pub node_drag: Option<(egui_snarl::NodeId, egui::Pos2)>,
    /// The nodes selected (snarl ids), the active one last: the one truth, told to
    /// egui-snarl each frame.
    pub selection: selection::Selection,
    /// The node groups entered: the graph view shows the innermost one's definition.
    pub scope: scope::Scope,
    /// Bumped whenever the graph view starts afresh (entering or leaving a group,
    /// grouping): the view's id, so that egui-snarl's state of it is not carried over.
    pub view_generation: u64,
    /// The graph view's transform and the gestures moving it.
    pub navigation: navigation::Navigation,
    /// The add-node search (Space, Tab, Shift+A) and where the graph is on screen.
    pub add: add_node::AddNode,
    /// Duplicates following the mouse until a click.
    pub grab: grab::Grab,
    /// Which graph node each node of the view shows.
    pub shown: view_edits::Shown,
}

impl Canvas {
    /// A canvas showing `snarl`, nothing selected, the view framing it as on opening.
    pub fn new(snarl: Snarl<Node>) -> Canvas {
        let mut navigation = navigation::Navigation::default();
        navigation.frame(navigation::Framing::Open);
        Canvas {
            spots: Default::default(),
            hovered_wire: None,
            node_drag: None,
            selection: Default::default(),
            scope: Default::default(),
            view_generation: 0,
            navigation,
            add: Default::default(),
            grab: Default::default(),
            shown: view_edits::Shown::of(&snarl),
            snarl,
        }
    }

    /// New nodes (added, pasted, duplicated) are moved clear of the others and become
    /// the selection.
    pub fn placed(&mut self, nodes: Vec<egui_snarl::NodeId>) {
        placement::clear_of(&mut self.snarl, &nodes);
        self.selection.set(nodes);
    }
}
