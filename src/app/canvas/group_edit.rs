//! Node groups in the editor: grouping the selection (Ctrl+G), ungrouping (Alt+G),
//! new group inputs and outputs, group nodes from the add-node search, and what a
//! group node's inspector asks. (Entering and leaving groups: `levels`.)

use crate::app::VeneerApp;
use crate::app::canvas::scope::{self, Declared};
use crate::app::canvas::snarl_model::next_node_id;
use crate::app::inspector::group::GroupAction;
use crate::app::inspector::group_interface::InterfaceEdit;
use crate::graph::edit::GraphEdit;
use crate::graph::{Graph, Node, NodeId, NodeKind, group, library};
use crate::nodes::Group;
use egui::Pos2;
use std::collections::BTreeSet;

impl VeneerApp {
    /// The selected nodes of the level shown, less its boundary nodes.
    pub(in crate::app) fn editable_selection(&self) -> Vec<egui_snarl::NodeId> {
        self.canvas
            .selection
            .iter()
            .copied()
            .filter(|id| {
                self.canvas
                    .snarl
                    .get_node(*id)
                    .is_some_and(|node| crate::app::canvas::boundary::boundary(node).is_none())
            })
            .collect()
    }

    /// Ctrl+G: the selected nodes (the Material stays out) become a new group, named
    /// `group`, `group_2`…, with one instance of it in their place, selected.
    pub(in crate::app) fn group_selection(&mut self) {
        let chosen: BTreeSet<NodeId> = self
            .editable_selection()
            .into_iter()
            .map(|id| &self.canvas.snarl[id])
            .filter(|node| node.kind != NodeKind::Material)
            .map(|node| node.id)
            .collect();
        if chosen.is_empty() {
            self.chrome.message = Some(
                "nothing to group: select nodes first (the Material node stays outside groups)"
                    .into(),
            );
            return;
        }
        let name = scope::free_name(
            self.session
                .document
                .graph
                .groups
                .keys()
                .map(String::as_str),
            "group",
        );
        let level = self.canvas.scope.level();
        // The new node takes the next free id of the level.
        self.take_in_view_edits();
        let instance = NodeId(
            self.canvas
                .snarl
                .nodes()
                .map(|node| node.id.0)
                .max()
                .unwrap_or(0)
                + 1,
        );
        let count = chosen.len();
        let edit = GraphEdit::Group {
            level,
            nodes: chosen,
            name: name.clone(),
        };
        if self.edit(edit) {
            self.new_view();
            self.select(instance);
            self.chrome.message = Some(format!(
                "grouped {} into '{name}': Tab edits it, Alt+G ungroups it",
                crate::messages::counted(count, "node")
            ));
        }
    }

    /// Alt+G: dissolves the selected group nodes into their definitions' nodes.
    pub(in crate::app) fn ungroup_selection(&mut self) {
        let instances: Vec<NodeId> = self
            .canvas
            .selection
            .iter()
            .filter_map(|id| self.canvas.snarl.get_node(*id))
            .filter(|node| crate::app::canvas::boundary::is_instance(node))
            .map(|node| node.id)
            .collect();
        self.ungroup(instances);
    }

    fn ungroup(&mut self, instances: Vec<NodeId>) {
        if instances.is_empty() {
            self.chrome.message = Some("nothing to ungroup: select a group node first".into());
            return;
        }
        let level = self.canvas.scope.level();
        let edits = instances
            .into_iter()
            .map(|node| GraphEdit::Ungroup {
                level: level.clone(),
                node,
            })
            .collect();
        if self.edit(GraphEdit::Batch(edits)) {
            self.new_view();
        }
    }

    /// Carries out what a group node's inspector or menu asked.
    pub(in crate::app) fn group_action(&mut self, action: GroupAction) {
        match action {
            GroupAction::Enter(node) => self.enter_group(node),
            GroupAction::Ungroup(node) => {
                let instance = self.canvas.snarl.get_node(node).map(|node| node.id);
                self.ungroup(instance.into_iter().collect());
            }
            GroupAction::MakeLocal(name) => {
                let edit = GraphEdit::SetLinked {
                    group: name.clone(),
                    linked: false,
                };
                if self.edit(edit) {
                    self.chrome.message = Some(format!(
                        "group '{name}' is local to this graph: library updates no longer apply"
                    ));
                }
            }
            GroupAction::SaveToLibrary(name) => {
                self.take_in_view_edits();
                let Some(definition) = self.session.document.graph.groups.get(&name) else {
                    return;
                };
                self.chrome.message = Some(match library::save_to_user(&name, definition) {
                    Ok(path) => format!("saved group '{name}' to {}", path.display()),
                    Err(error) => format!("cannot save group '{name}' to the library: {error}"),
                });
            }
        }
    }

    /// Adds what wires dropped on "+" pins declared to the group shown (before the
    /// view's wires to them are taken in).
    pub(in crate::app) fn declare(&mut self, declared: Vec<Declared>) {
        let Some(name) = self.canvas.scope.current().map(str::to_string) else {
            return;
        };
        for declaration in declared {
            let what = match &declaration {
                Declared::Input(input) => format!("input '{}'", input.name),
                Declared::Output(output) => format!("output '{}'", output.name),
            };
            let edit = declaration.edit(&name, &self.session.document.graph);
            self.chrome.message = Some(match self.commit(edit) {
                Ok(_) => format!("added {what} to group '{name}'"),
                Err(error) => format!("cannot add {what}: {error}"),
            });
        }
    }

    /// *Expose as group input* on input `pin` of an inner node: a new group input
    /// wired to it, as if a wire were dragged from *Group input*'s "+" to it.
    pub(in crate::app) fn expose_input(&mut self, pin: egui_snarl::InPinId) -> Option<Declared> {
        let input = scope::boundary_in(
            &self.canvas.snarl,
            crate::app::canvas::boundary::Boundary::Input,
        )?;
        let add = self.canvas.snarl[input]
            .kind
            .signature()
            .outputs
            .len()
            .checked_sub(1)?;
        let from = egui_snarl::OutPinId {
            node: input,
            output: add,
        };
        scope::expose(&mut self.canvas.snarl, from, pin)
    }

    /// The groups an instance can be made of at the level shown: the graph's and the
    /// library's, less those that would contain themselves. Library files that cannot
    /// be read as groups are named in the status bar.
    pub(in crate::app) fn placeable_groups(&mut self) -> Vec<String> {
        let (library, unusable) = library::list();
        if let Some(first) = unusable.first() {
            let more = match unusable.len() {
                1 => String::new(),
                n => format!(" (and {} more files)", n - 1),
            };
            self.chrome.message = Some(format!("group library: {first}{more}"));
        }
        let groups = &self.session.document.graph.groups;
        let mut names: Vec<String> = groups.keys().cloned().collect();
        names.extend(library.into_iter().map(|(name, _)| name));
        names.sort();
        names.dedup();
        if let Some(current) = self.canvas.scope.current() {
            names.retain(|name| !scope::uses(groups, name, current));
        }
        names
    }

    /// Places an instance of group `name` (the graph's, else the library's, which the
    /// graph then keeps a linked copy of) at `at`; returns its id in the view.
    pub(in crate::app) fn add_group_instance(
        &mut self,
        name: &str,
        at: Pos2,
    ) -> Option<egui_snarl::NodeId> {
        if !self.session.document.graph.groups.contains_key(name) {
            // A linked copy of the library's.
            let found = library::find(name).map_err(|error| error.to_string());
            let definition = match found {
                Ok(Some((mut definition, _))) => {
                    definition.linked = true;
                    definition
                }
                Ok(None) => {
                    self.chrome.message = Some(format!(
                        "no group named '{}' in the graph or the library",
                        crate::graph::names::shown(name)
                    ));
                    return None;
                }
                Err(error) => {
                    self.chrome.message = Some(error);
                    return None;
                }
            };
            let adopt = GraphEdit::SetGroup {
                name: name.to_string(),
                definition: Some(Box::new(definition)),
            };
            if let Err(error) = self.commit(adopt) {
                self.chrome.message = Some(error);
                return None;
            }
        }
        let interfaces = group::interfaces(&self.session.document.graph.groups);
        let pins = match interfaces.as_ref().map(|all| all.get(name)) {
            Ok(Some(interface)) => interface.signature(),
            Ok(None) => return None,
            Err(error) => {
                self.chrome.message = Some(format!("cannot use group '{name}': {}", error.message));
                return None;
            }
        };
        let kind = NodeKind::Group(Group {
            name: name.to_string(),
            pins,
        });
        let mut node = Node::new(next_node_id(&self.canvas.snarl), kind);
        node.label = name.to_string();
        Some(self.canvas.snarl.insert_node(at, node))
    }
}

/// The kind of a node of group `name` (`graph`'s, else the library's), its pins filled
/// in; `None` when there is no such group or it cannot be used.
pub(in crate::app) fn group_kind(graph: &Graph, name: &str) -> Option<NodeKind> {
    let mut groups = graph.groups.clone();
    if !groups.contains_key(name) {
        groups.insert(name.to_string(), library::find(name).ok()??.0);
    }
    let pins = group::interfaces(&groups).ok()?.get(name)?.signature();
    Some(NodeKind::Group(Group {
        name: name.to_string(),
        pins,
    }))
}

impl VeneerApp {
    /// Applies `edit` to the group shown: one undo step; the boundary node stays
    /// selected.
    pub(in crate::app) fn edit_interface(&mut self, edit: InterfaceEdit) {
        let Some(name) = self.canvas.scope.current().map(str::to_string) else {
            return;
        };
        let selected = self
            .canvas
            .selection
            .active()
            .and_then(|id| self.canvas.snarl.get_node(id));
        let side = selected.and_then(crate::app::canvas::boundary::boundary);
        let (edit, message) = match edit {
            InterfaceEdit::Rename { side, old, new } => (
                GraphEdit::RenameGroupPin {
                    group: name.clone(),
                    side,
                    old: old.clone(),
                    new: new.clone(),
                },
                Some(format!("renamed '{old}' to '{new}' in group '{name}'")),
            ),
            InterfaceEdit::Remove { side, name: pin } => (
                GraphEdit::RemoveGroupPin {
                    group: name.clone(),
                    side,
                    name: pin.clone(),
                },
                Some(format!("removed '{pin}' from group '{name}'")),
            ),
            InterfaceEdit::Input { input, .. } => (
                GraphEdit::SetGroupInput {
                    group: name.clone(),
                    input,
                },
                None,
            ),
        };
        if self.edit(edit) {
            self.chrome.message = message.or(self.chrome.message.take());
        }
        let boundary = side.and_then(|side| scope::boundary_in(&self.canvas.snarl, side));
        self.canvas.selection.set(boundary);
    }
}
