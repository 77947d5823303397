//! Node groups in the editor: grouping the selection (Ctrl+G), ungrouping (Alt+G),
//! new group inputs and outputs, group nodes from the add-node search, and what a
//! group node's inspector asks. (Entering and leaving groups: `levels`.)

use crate::app::VeneerApp;
use crate::app::canvas::scope::{self, Declared};
use crate::app::canvas::snarl_model::next_node_id;
use crate::app::inspector::group::GroupAction;
use crate::app::inspector::group_interface::InterfaceEdit;
use crate::graph::{Graph, Node, NodeId, NodeKind, group, group_interface, library};
use crate::nodes::Group;
use egui::Pos2;
use std::collections::BTreeSet;

impl VeneerApp {
    /// Runs `edit` on a copy of the whole graph, then takes the result in and shows
    /// it: one undo step. When `edit` fails nothing changes.
    pub(in crate::app) fn edit_document<T>(
        &mut self,
        edit: impl FnOnce(&mut Self, &mut Graph) -> Result<T, String>,
    ) -> Result<T, String> {
        self.sync_document();
        let mut graph = self.session.document.graph.clone();
        let done = edit(self, &mut graph)?;
        group::resolve(&mut graph);
        graph.canonicalize();
        self.session.document.graph = graph;
        self.rebuild_snarl();
        Ok(done)
    }

    /// Runs `edit` on the level shown as a whole graph (a group's definition with its
    /// boundary as one node), then shows the result: one undo step.
    pub(in crate::app) fn edit_level<T>(
        &mut self,
        edit: impl FnOnce(&mut Graph) -> Result<T, String>,
    ) -> Result<T, String> {
        let shown = self.canvas.scope.current().map(str::to_string);
        let done = self.edit_document(|app, graph| match shown {
            None => edit(graph),
            Some(name) => {
                let (mut local, definition) =
                    scope::as_graph(graph, &name).ok_or("the group shown is gone")?;
                let done = edit(&mut local)?;
                scope::put_back(graph, &name, definition, local);
                app.unlink_edited(graph, &name);
                Ok(done)
            }
        })?;
        self.new_view();
        Ok(done)
    }

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
        match self.edit_level(|graph| group::group_nodes(graph, &chosen, &name)) {
            Ok(instance) => {
                self.select(instance);
                self.chrome.message = Some(format!(
                    "grouped {} into '{name}': Tab edits it, Alt+G ungroups it",
                    crate::app::chrome::menus::counted(chosen.len(), "node")
                ));
            }
            Err(error) => self.chrome.message = Some(format!("cannot group: {error}")),
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
        let done = self.edit_level(|graph| {
            instances
                .iter()
                .try_for_each(|id| group::ungroup(graph, *id).map(drop))
        });
        if let Err(error) = done {
            self.chrome.message = Some(format!("cannot ungroup: {error}"));
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
                if let Some(definition) = self.session.document.graph.groups.get_mut(&name) {
                    definition.linked = false;
                    self.chrome.message = Some(format!(
                        "group '{name}' is local to this graph: library updates no longer apply"
                    ));
                }
            }
            GroupAction::SaveToLibrary(name) => {
                self.sync_document();
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

    /// Adds what wires dropped on "+" pins declared to the group shown.
    pub(in crate::app) fn declare(&mut self, declared: Vec<Declared>) {
        let Some(name) = self.canvas.scope.current().map(str::to_string) else {
            return;
        };
        let Some(definition) = self.session.document.graph.groups.get_mut(&name) else {
            return;
        };
        for declaration in declared {
            let added = match declaration {
                Declared::Input(input) => {
                    let text = format!("added input '{}' to group '{name}'", input.name);
                    definition.inputs.push(input);
                    text
                }
                Declared::Output(output) => {
                    let text = format!("added output '{}' to group '{name}'", output.name);
                    definition.outputs.push(output);
                    text
                }
            };
            self.chrome.message = Some(added);
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
        if let Err(message) = library::adopt(&mut self.session.document.graph, name) {
            self.chrome.message = Some(message);
            return None;
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
        let done = self.edit_document(|app, graph| {
            app.unlink_edited(graph, &name);
            match edit {
                InterfaceEdit::Rename { side, old, new } => {
                    group_interface::rename(graph, &name, side, &old, &new)?;
                    Ok(Some(format!(
                        "renamed '{old}' to '{new}' in group '{name}'"
                    )))
                }
                InterfaceEdit::Remove { side, name: pin } => {
                    group_interface::remove(graph, &name, side, &pin)?;
                    Ok(Some(format!("removed '{pin}' from group '{name}'")))
                }
                InterfaceEdit::Input { name: pin, input } => {
                    let definition = graph.groups.get_mut(&name);
                    let declared = definition
                        .and_then(|definition| definition.inputs.iter_mut().find(|i| i.name == pin))
                        .ok_or(format!("group '{name}' has no input '{pin}'"))?;
                    *declared = input;
                    Ok(None)
                }
            }
        });
        match done {
            Ok(message) => self.chrome.message = message.or(self.chrome.message.take()),
            Err(error) => self.chrome.message = Some(error),
        }
        let boundary = side.and_then(|side| scope::boundary_in(&self.canvas.snarl, side));
        self.canvas.selection.set(boundary);
    }
}
