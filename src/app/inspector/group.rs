//! The inspector's part for a group node: its group, whether it follows the library,
//! and what can be done with it.

use crate::graph::group::GroupDef;
use egui::{RichText, Ui};

/// What a group node's inspector or context menu asks of the editor.
#[derive(Clone, Debug, PartialEq)]
pub enum GroupAction {
    /// Show the group's definition (Tab).
    Enter(egui_snarl::NodeId),
    /// Dissolve the instance into its definition's nodes (Alt+G).
    Ungroup(egui_snarl::NodeId),
    /// Stop the group following the library.
    MakeLocal(String),
    /// Write the group to the user library.
    SaveToLibrary(String),
}

/// The group section of instance `node` of group `name`, defined as `definition`.
pub fn show(
    ui: &mut Ui,
    node: egui_snarl::NodeId,
    name: &str,
    definition: Option<&GroupDef>,
) -> Option<GroupAction> {
    let mut action = None;
    ui.horizontal(|ui| {
        ui.label("group");
        ui.label(RichText::new(name).strong());
        match definition {
            Some(definition) if definition.linked => {
                ui.weak("linked to the library");
            }
            Some(_) => {
                ui.weak("local to this graph");
            }
            None => {
                ui.colored_label(egui::Color32::from_rgb(240, 80, 60), "not defined");
            }
        }
    });
    ui.horizontal_wrapped(|ui| {
        if ui
            .button("Edit group")
            .on_hover_text("show the group's nodes (Tab; Tab again goes back)")
            .clicked()
        {
            action = Some(GroupAction::Enter(node));
        }
        if ui
            .button("Ungroup")
            .on_hover_text("put the group's nodes in place of this node (Alt+G)")
            .clicked()
        {
            action = Some(GroupAction::Ungroup(node));
        }
        if definition.is_some_and(|definition| definition.linked)
            && ui
                .button("Make local")
                .on_hover_text("keep this graph's copy: library updates no longer apply")
                .clicked()
        {
            action = Some(GroupAction::MakeLocal(name.to_string()));
        }
        if definition.is_some()
            && ui
                .button("Save to library")
                .on_hover_text("write the group to your library, for every graph")
                .clicked()
        {
            action = Some(GroupAction::SaveToLibrary(name.to_string()));
        }
    });
    action
}
