//! What each dialog shows: its heading, fields and buttons.

use crate::app::chrome::dialogs::frame::ago;
use crate::app::chrome::dialogs::frame::{Choice, Frame};
use crate::app::chrome::dialogs::{Dialog, Pending};
use crate::app::session::document::Document;
use crate::codegen::export::Target;
use egui::Ui;

impl Dialog {
    pub(in crate::app) fn contents(&mut self, ui: &mut Ui, document: &Document, frame: &mut Frame) {
        match self {
            Dialog::Open { path } => {
                ui.heading("Open graph");
                frame.path_field(ui, path);
                frame.path_buttons(ui, "Open");
            }
            Dialog::SaveAs { path, .. } => {
                ui.heading("Save graph as");
                frame.path_field(ui, path);
                frame.path_buttons(ui, "Save");
            }
            Dialog::ExportShader {
                path,
                target,
                uniform,
            } => {
                ui.heading("Export shader");
                ui.label("veneer_material for another engine; non-WGSL targets add the veneer_fragment entry point.");
                frame.path_field(ui, path);
                let before = *target;
                let combo = egui::ComboBox::from_label("language")
                    .selected_text(target.name())
                    .show_ui(ui, |ui| {
                        for (option, name, _) in Target::ALL {
                            ui.selectable_value(target, option, name);
                        }
                    });
                frame.claims.push(combo.response.id);
                if *target != before {
                    *path = std::path::Path::new(path.trim())
                        .with_extension(target.extension())
                        .display()
                        .to_string();
                }
                frame.checkbox(
                    ui,
                    uniform,
                    "parameters as a uniform block (instead of baked constants)",
                );
                frame.path_buttons(ui, "Export");
            }
            Dialog::ExportPng { path, size, flat } => {
                ui.heading("Export PNG");
                frame.path_field(ui, path);
                ui.add(egui::Slider::new(size, 16..=4096).text("size (px)"));
                frame.checkbox(
                    ui,
                    flat,
                    "flat albedo over the preview square (instead of the lit mesh)",
                );
                frame.path_buttons(ui, "Export");
            }
            Dialog::ExportModel { path, size, format } => {
                ui.heading(format.title());
                ui.label(match format {
                    crate::bake::ModelFormat::Gltf => "The material baked into the preview mesh's UV layout: base colour, metallic-roughness, occlusion, normal and emission maps (.glb, or .gltf with PNGs beside it)",
                    crate::bake::ModelFormat::Usd => "The preview mesh bound to a material with a UsdPreviewSurface and a MaterialX OpenPBR surface over its baked maps (.usdz, or .usda with PNGs beside it)",
                });
                frame.path_field(ui, path);
                ui.add(egui::Slider::new(size, 16..=4096).text("maps (px)"));
                frame.path_buttons(ui, "Export");
            }
            Dialog::ExportMaterialx {
                path,
                size,
                surface,
                tier,
            } => {
                ui.heading("Export MaterialX");
                ui.label(match tier {
                    crate::bake::Tier::Baked => "A MaterialX 1.39 document whose surface shader reads the material's maps, baked beside it (wood.mtlx giving wood_albedo.png, wood_orm.png and so on)",
                    crate::bake::Tier::Procedural => "A MaterialX 1.39 document holding the graph itself, node by node (Veneer's own nodes' GLSL and Metal beside it as wood_veneer.glsl and .metal); the exposed parameters stay parameters. Refused, naming the nodes, where a node cannot translate",
                    crate::bake::Tier::Auto => "The graph node by node where every node translates, else its maps baked",
                });
                frame.path_field(ui, path);
                ui.horizontal(|ui| {
                    for (choice, name) in crate::bake::Tier::ALL {
                        ui.radio_value(tier, choice, name);
                    }
                });
                ui.horizontal(|ui| {
                    for (model, _, node) in crate::bake::SurfaceModel::ALL {
                        ui.radio_value(surface, model, node);
                    }
                });
                ui.add(egui::Slider::new(size, 16..=4096).text("maps (px)"));
                frame.path_buttons(ui, "Export");
            }
            Dialog::ExportMaps {
                path,
                size,
                maps,
                format,
                tile,
            } => {
                ui.heading("Export maps");
                ui.label("The material's maps over the preview square, or as one tile of a repeating texture: files named after the path, wood.png giving wood_albedo.png, wood_normal.png and so on");
                frame.path_field(ui, path);
                ui.add(egui::Slider::new(size, 16..=8192).text("size (px)"));
                egui::Grid::new("maps").show(ui, |ui| {
                    let all = crate::bake::Map::ALL.iter().zip(maps.iter_mut());
                    for (index, (map, chosen)) in all.enumerate() {
                        ui.checkbox(chosen, map.name());
                        if index % 5 == 4 {
                            ui.end_row();
                        }
                    }
                });
                let before = *format;
                ui.horizontal(|ui| {
                    for (choice, name) in [
                        (crate::bake::Format::Png8, "8-bit PNG"),
                        (crate::bake::Format::Png16, "16-bit PNG"),
                        (crate::bake::Format::Exr, "float EXR"),
                    ] {
                        ui.radio_value(format, choice, name);
                    }
                });
                if *format != before {
                    *path = std::path::Path::new(path.trim())
                        .with_extension(format.extension())
                        .display()
                        .to_string();
                }
                frame.checkbox(
                    ui,
                    tile,
                    "one tile over the unit square, its opposite edges checked to continue each other (give noises a period)",
                );
                frame.path_buttons(ui, "Export");
            }
            Dialog::LoadEnvironment { path } => {
                ui.heading("Light with an environment");
                ui.label("An equirectangular HDR panorama (.hdr or .exr, twice as wide as high) lights metallic-roughness materials");
                frame.path_field(ui, path);
                frame.path_buttons(ui, "Load");
            }
            Dialog::LoadMesh { path } => {
                ui.heading("Preview on a mesh file");
                ui.label(format!(
                    "OBJ, STL, PLY or glTF ({})",
                    crate::mesh::EXTENSIONS.join(", ")
                ));
                frame.path_field(ui, path);
                frame.path_buttons(ui, "Load");
            }
            Dialog::Replace(path, _) => {
                ui.heading("Replace file?");
                ui.label(format!(
                    "{} already exists. Replace it with this graph?",
                    path.display()
                ));
                ui.add_space(4.0);
                ui.horizontal(|ui| {
                    frame.destructive_button(ui, "Replace", Choice::Destroy);
                    ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                        frame.default_button(ui, "Cancel", Choice::Cancel);
                    });
                });
            }
            Dialog::Discard(pending) => {
                ui.heading("Unsaved changes");
                let name = document.title(document.is_dirty());
                let name = name.trim_end_matches(" — Veneer").trim_start_matches("* ");
                let then = match pending {
                    Pending::New => "starting a new graph".to_string(),
                    Pending::Open(path) => format!(
                        "opening {}",
                        path.file_name()
                            .map(|n| n.to_string_lossy().into_owned())
                            .unwrap_or_else(|| path.display().to_string())
                    ),
                    Pending::Preset(name) => format!("opening the {name} preset"),
                    Pending::Quit => "quitting".to_string(),
                };
                ui.label(format!(
                    "{name} has changes that are not saved. Save them before {then}?"
                ));
                ui.add_space(4.0);
                ui.horizontal(|ui| {
                    frame.destructive_button(ui, "Save", Choice::Save);
                    frame.destructive_button(ui, "Discard", Choice::Destroy);
                    ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                        frame.default_button(ui, "Cancel", Choice::Cancel);
                    });
                });
            }
            Dialog::Recover(saved) => {
                ui.heading("Recover unsaved work?");
                ui.label(if saved.len() == 1 {
                    "Veneer ended last time with work that was not saved. It was autosaved:"
                        .to_string()
                } else {
                    format!(
                        "{} Veneer windows ended with work that was not saved. It was autosaved:",
                        saved.len()
                    )
                });
                for (index, recovery) in saved.iter().enumerate() {
                    let from = recovery
                        .original
                        .as_ref()
                        .map(|p| p.display().to_string())
                        .unwrap_or_else(|| format!("an unsaved graph ({})", recovery.graph.name));
                    ui.horizontal(|ui| {
                        frame.destructive_button(ui, "Discard", Choice::Forget(index));
                        ui.label(format!("{from}{}", ago(recovery.saved)));
                        ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                            if index == 0 {
                                frame.default_button(ui, "Recover", Choice::Recover(index));
                            } else {
                                frame.button(ui, "Recover", Choice::Recover(index));
                            }
                        });
                    });
                }
                ui.add_space(4.0);
                ui.horizontal(|ui| {
                    ui.weak("Later keeps it for the next start.");
                    ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                        frame.button(ui, "Later", Choice::Cancel);
                    });
                });
            }
            Dialog::Message(message) => {
                ui.heading("Veneer");
                ui.label(message.as_str());
                ui.add_space(4.0);
                ui.horizontal(|ui| {
                    ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                        frame.default_button(ui, "OK", Choice::Confirm);
                    });
                });
            }
        }
    }
}
