//! The right-hand panel: the live material on its mesh, time and light, the distance
//! fields and picking their sources, and the selected node's thumbnail.

use crate::app::preview::frame_cache::{FIELD_VIEW_GENERATIONS, FIT_REVISIONS, material_frame};
use crate::app::preview::{fields, probe, state};
use crate::app::*;
use crate::graph::NodeKind;
use crate::graph::edit::{GraphEdit, GraphSetting};
use crate::messages::counted;
use crate::render::{Backdrop, ToneMap};

impl VeneerApp {
    /// The selected node's output, flat, above the inspector.
    pub(in crate::app) fn node_thumbnail(&mut self, ui: &mut Ui, node: egui_snarl::NodeId) {
        if !self.preview.previews.available() {
            return;
        }
        let unit_tile = self.preview.live.renders_passes();
        let key = (
            self.session.revision.number,
            self.canvas.snarl[node].id,
            unit_tile,
        );
        if self
            .preview
            .probe
            .as_ref()
            .is_none_or(|(seen, _)| *seen != key)
        {
            let mut probe = probe::probe_graph(&self.session.document.graph, key.1);
            if let Some(probe) = &mut probe {
                if unit_tile {
                    probe::over_the_unit_tile(probe);
                }
                self.preview.thumbnail.update(probe);
            }
            self.preview.probe = Some((key, probe));
        }
        let Some((_, Some(probe))) = &self.preview.probe else {
            return;
        };
        let material = if self.preview.thumbnail.errors.is_empty() {
            let cache = &mut self.preview.frames[Slot::Node as usize];
            material_frame(&self.preview.thumbnail, cache, probe, key.0)
        } else {
            None
        };
        ui.horizontal(|ui| {
            let size = egui::vec2(160.0, 160.0);
            state::thumbnail(
                ui,
                &self.preview.state,
                &mut self.preview.previews,
                (Slot::Node, material),
                size,
            );
            let graph = &self.session.document.graph;
            let kind = (graph.nodes.iter().find(|n| n.id == key.1)).map(|n| &n.kind);
            ui.weak(if matches!(kind, Some(NodeKind::Field(_))) {
                // A flat view has no mesh: distance fields read 0.
                "this node's output, flat,\nwhere distance fields read 0:\nview the field on the mesh\nwith view under the preview"
            } else if matches!(kind, Some(NodeKind::MeshField(_))) {
                "this node's output, flat,\nwhere it reads a flat plane's value:\nview the field on the mesh\nwith view under the preview"
            } else if unit_tile {
                "this node's output,\nflat over the unit tile"
            } else {
                "this node's output,\nflat over the preview square"
            });
        });
    }

    /// A texture graph's material flat over the unit tile, `side` points square, drawn
    /// again when no pointer button is held (a drag redraws the mesh's drafts alone).
    fn tile_beside_the_mesh(&mut self, ui: &mut Ui, side: f32) {
        let dragging = ui.input(|input| input.pointer.any_down());
        let material = (!dragging)
            .then(|| {
                material_frame(
                    &self.preview.live,
                    &mut self.preview.frames[Slot::Tile as usize],
                    &self.session.document.graph,
                    self.session.revision.number,
                )
            })
            .flatten();
        state::thumbnail(
            ui,
            &self.preview.state,
            &mut self.preview.previews,
            (Slot::Tile, material),
            egui::vec2(side, side),
        )
        .on_hover_text("the unit tile, flat (the 3×3 tile view: flat albedo)");
        ui.weak("unit tile");
    }

    pub(in crate::app) fn preview_panel(&mut self, ui: &mut Ui) {
        ui.horizontal(|ui| {
            let shown = std::path::Path::new(&self.preview.state.mesh)
                .file_name()
                .map(|n| n.to_string_lossy().into_owned());
            egui::ComboBox::from_id_salt("mesh")
                .selected_text(shown.unwrap_or_default())
                .show_ui(ui, |ui| {
                    for name in crate::mesh::PRIMITIVES {
                        if ui
                            .selectable_label(self.preview.state.mesh == name, name)
                            .clicked()
                        {
                            self.preview.state.mesh = name.to_string();
                            self.preview.state.file = None;
                        }
                    }
                    if ui.button("Mesh file…").clicked() {
                        self.chrome.dialog = Some(Dialog::LoadMesh {
                            path: String::new(),
                        });
                    }
                });
            ui.checkbox(&mut self.preview.state.flat, "flat albedo");
            // Always there (greyed out unless flat), so the row keeps its width.
            let flat = self.preview.state.flat;
            ui.add_enabled(
                flat,
                egui::Checkbox::new(&mut self.preview.state.repeat_tile, "3×3 tile"),
            )
            .on_hover_text("the unit tile repeated as a bake of it tiles: seams show")
            .on_disabled_hover_text("with flat albedo: the unit tile repeated, seams show");
            ui.checkbox(&mut self.preview.live.full_detail, "every octave")
                .on_hover_text("off: noise leaves out octaves finer than a pixel (less aliasing, faster far away)");
            ui.label("background");
            ui.color_edit_button_rgb(&mut self.preview.state.view.background);
        });
        let width = ui.available_width();
        self.solve_fields();
        let material = match (self.preview.previews.available(), self.preview.fields.view) {
            (false, _) => None,
            (true, Some(view)) => {
                let graph = fields::field_view_graph(view);
                self.preview.field_view.update(&graph);
                material_frame(
                    &self.preview.field_view,
                    &mut self.preview.field_view_frame,
                    &graph,
                    0,
                )
                .map(|mut frame| {
                    frame.code.generation |= FIELD_VIEW_GENERATIONS;
                    frame
                })
            }
            (true, None) => {
                // While a fit runs, the values it tries.
                let candidate = (self.fitting.run.as_ref()).and_then(|run| run.candidate.as_ref());
                let (graph, revision) = match candidate {
                    Some((graph, number)) => (graph, FIT_REVISIONS | number),
                    None => (&self.session.document.graph, self.session.revision.number),
                };
                material_frame(
                    &self.preview.live,
                    &mut self.preview.frames[Slot::Main as usize],
                    graph,
                    revision,
                )
            }
            .map(|mut frame| {
                frame.tessellation = self.tessellation_input(&frame);
                frame
            }),
        };
        if self.preview.previews.available() {
            let height = width.min(ui.available_height() * 0.55);
            // A texture graph on a mesh: its unit tile beside it.
            let tile = self.preview.live.renders_passes()
                && !self.preview.state.flat
                && self.preview.fields.view.is_none();
            let side = if tile {
                (height * 0.5).min(width * 0.3)
            } else {
                0.0
            };
            ui.horizontal_top(|ui| {
                let mesh_width = if tile {
                    width - side - ui.spacing().item_spacing.x
                } else {
                    width
                };
                let response = state::show(
                    ui,
                    &mut self.preview.state,
                    &mut self.preview.previews,
                    material,
                    egui::vec2(mesh_width, height),
                );
                self.pick_source(&response);
                self.fields_warning(ui, response.rect);
                self.no_material_note(ui, response.rect);
                if tile {
                    ui.vertical(|ui| self.tile_beside_the_mesh(ui, side));
                }
            });
        } else {
            ui.label("(no GPU: preview unavailable)");
        }
        ui.horizontal(|ui| {
            let label = if self.preview.state.playing {
                "⏸"
            } else {
                "▶"
            };
            if ui
                .button(label)
                .on_hover_text("play / pause time")
                .clicked()
            {
                self.preview.state.playing = !self.preview.state.playing;
            }
            ui.add(
                egui::Slider::new(&mut self.preview.state.view.time, 0.0..=20.0).text("time (s)"),
            );
            if ui
                .button("reset view")
                .on_hover_text("put this mesh's camera back where it starts")
                .clicked()
            {
                self.preview.state.reset_camera();
            }
        });
        if let Some(error) = self.preview.previews.error() {
            ui.colored_label(ui.visuals().warn_fg_color, format!("preview: {error}"));
        }
        ui.horizontal(|ui| {
            ui.label("light");
            let light = &mut self.preview.state.view.light;
            ui.add(
                egui::DragValue::new(&mut light[0])
                    .speed(0.02)
                    .range(-1.0..=1.0),
            );
            ui.add(
                egui::DragValue::new(&mut light[1])
                    .speed(0.02)
                    .range(-1.0..=1.0),
            );
            ui.add(
                egui::DragValue::new(&mut light[2])
                    .speed(0.02)
                    .range(-1.0..=1.0),
            );
        });
        self.surface_settings(ui);
        self.lighting_settings(ui);
        let mut shown_fields = self.session.document.graph.preview.fields.clone();
        let mesh_lanes = self
            .preview
            .live
            .compiled
            .as_ref()
            .map(|compiled| compiled.uses().mesh_fields)
            .unwrap_or_default();
        fields::fields_panel(ui, &mut shown_fields, &mut self.preview.fields, &mesh_lanes);
        self.set_preview(|preview| preview.fields = shown_fields);
        self.preview.state.tick(std::time::Instant::now());
        if self.preview.state.playing {
            ui.ctx().request_repaint();
        }
    }

    /// What the preview's drawing thread needs to refine the mesh of a displaced
    /// material whose graph asks for tessellation (the graph checked once a revision).
    fn tessellation_input(&mut self, frame: &MaterialFrame) -> Option<TessellationInput> {
        let settings = self.session.document.graph.preview.tessellation?;
        // The CPU evaluator that refines the mesh reads files but renders no passes: a
        // material with rendered passes is drawn on the mesh as it is.
        let rendered_passes =
            (frame.code.passes.as_ref()).is_some_and(|passes| !passes.uploads_only());
        if !frame.code.uses.displacement || self.preview.state.flat || rendered_passes {
            return None;
        }
        let revision = self.session.revision.number;
        if self
            .preview
            .tessellation_graph
            .as_ref()
            .is_none_or(|(seen, _)| *seen != revision)
        {
            let checked = crate::graph::check(&self.session.document.graph).ok()?;
            self.preview.tessellation_graph = Some((revision, Arc::new(checked)));
        }
        let (_, graph) = self.preview.tessellation_graph.as_ref()?;
        Some(TessellationInput {
            revision,
            graph: Arc::clone(graph),
            refinement: settings.refinement(),
        })
    }

    /// How materials lit by an environment are lit and shown: the environment (the sky,
    /// or a panorama file), its turn, exposure and tone mapper; for metallic-roughness
    /// also the key light and the backdrop (the thesis's sphere map has neither).
    fn lighting_settings(&mut self, ui: &mut Ui) {
        let shading = self.session.document.graph.shading;
        if !shading.reads_environment() {
            return;
        }
        let physical = shading == Shading::MetallicRoughness;
        // Two rows of fixed content, not one that wraps: a field turned into a text box
        // while typed in is narrower, and a row wrapped anew around it was once wider
        // than the panel, which then stayed that wide over the graph.
        ui.horizontal(|ui| {
            let lit_by = self
                .preview
                .state.environment
                .0
                .as_ref()
                .map_or(crate::render::SKY.to_string(), |e| e.name.clone());
            egui::ComboBox::from_id_salt("environment")
                .selected_text(lit_by)
                .show_ui(ui, |ui| {
                    if ui
                        .selectable_label(self.preview.state.environment.0.is_none(), crate::render::SKY)
                        .clicked()
                    {
                        self.preview.state.environment = Default::default();
                    }
                    if ui.button("Environment file…").clicked() {
                        self.chrome.dialog = Some(Dialog::LoadEnvironment {
                            path: String::new(),
                        });
                    }
                })
                .response
                .on_hover_text("the environment lighting the material: the procedural sky, or an equirectangular .hdr/.exr panorama");
            let view = &mut self.preview.state.view;
            ui.add(
                egui::DragValue::new(&mut view.environment_turn)
                    .speed(0.5)
                    .range(-180.0..=180.0)
                    .prefix("turn ")
                    .suffix("°"),
            )
            .on_hover_text("turns the environment about the vertical axis");
            if physical {
                ui.add(
                    egui::DragValue::new(&mut view.key_light)
                        .speed(0.02)
                        .range(0.0..=20.0)
                        .prefix("key light "),
                )
                .on_hover_text("irradiance of the key light (0: the environment alone)");
            }
        });
        ui.horizontal(|ui| {
            let view = &mut self.preview.state.view;
            ui.add(
                // A tenth of a stop every ten points (Shift: every hundred).
                egui::DragValue::new(&mut view.exposure)
                    .speed(0.01)
                    .range(-8.0..=8.0)
                    .prefix("exposure ")
                    .suffix(" EV"),
            );
            let tone_maps = [
                (ToneMap::PbrNeutral, "PBR Neutral"),
                (ToneMap::Aces, "ACES"),
                (ToneMap::Agx, "AgX"),
                (ToneMap::None, "no tone map"),
            ];
            choice(ui, "tone map", &mut view.tone_map, &tone_maps)
                .on_hover_text("how scene light maps to the display: Khronos PBR Neutral keeps base colours true; ACES (fitted) and AgX are filmic");
            if physical {
                let backdrops = [
                    (Backdrop::Blurred, "blurred"),
                    (Backdrop::Environment, "environment"),
                    (Backdrop::Colour, "colour"),
                ];
                ui.label("backdrop");
                choice(ui, "backdrop", &mut view.backdrop, &backdrops)
                    .on_hover_text("what shows behind the mesh: the environment blurred or sharp, or the background colour");
            }
        });
    }

    /// The material's shading and alpha mode and the preview's adaptive tessellation.
    fn surface_settings(&mut self, ui: &mut Ui) {
        let graph = &self.session.document.graph;
        let (mut shading, mut alpha) = (graph.shading, graph.alpha);
        let mut tessellation = graph.preview.tessellation;
        ui.horizontal(|ui| {
            let shading = &mut shading;
            egui::ComboBox::from_id_salt("shading")
                .selected_text(shading.name())
                .show_ui(ui, |ui| {
                    for choice in Shading::ALL {
                        ui.selectable_value(shading, choice, choice.name());
                    }
                })
                .response
                .on_hover_text("Blinn-Phong: albedo, specular and shininess under the seeds' lighting; metallic-roughness: base colour, metallic, roughness and occlusion shaded by GGX, as glTF and the engines do; thesis Phong: seed 003's listings' own lighting (Phong's R·V, N·L unclamped or, as C.4 and C.5, |N·L|, no ambient)");
            let alpha = &mut alpha;
            let name = |mode: &AlphaMode| match mode {
                AlphaMode::Mask { .. } => "cut out",
                AlphaMode::Blend => "blend",
                AlphaMode::Opaque => "opaque",
            };
            ui.label("alpha");
            egui::ComboBox::from_id_salt("alpha mode")
                .selected_text(name(alpha))
                .show_ui(ui, |ui| {
                    for mode in [AlphaMode::default(), AlphaMode::Blend, AlphaMode::Opaque] {
                        let same = std::mem::discriminant(&mode) == std::mem::discriminant(alpha);
                        if ui.selectable_label(same, name(&mode)).clicked() && !same {
                            *alpha = mode;
                        }
                    }
                })
                .response
                .on_hover_text("cut out: holes where the alpha is below the cutoff; blend: see-through in proportion to the alpha; opaque: alpha ignored");
            if let AlphaMode::Mask { cutoff } = alpha {
                // The cutoff is built into the pipeline: applied when a drag ends, not
                // at every step.
                let id = ui.id().with("alpha cutoff");
                let mut value = ui.data(|d| d.get_temp::<f64>(id)).unwrap_or(*cutoff);
                let response = ui.add(
                    egui::DragValue::new(&mut value)
                        .speed(0.01)
                        .range(0.0..=1.0)
                        .prefix("cutoff "),
                );
                if response.dragged() {
                    ui.data_mut(|d| d.insert_temp(id, value));
                } else {
                    ui.data_mut(|d| d.remove::<f64>(id));
                    *cutoff = value;
                }
            }
            let tessellation = &mut tessellation;
            let mut on = tessellation.is_some();
            if ui
                .checkbox(&mut on, "tessellate")
                .on_hover_text("refine a displaced mesh where its height needs it, until the displaced surface is within the tolerance of its triangles on screen (at rest; drafts reuse the last refinement)")
                .changed()
            {
                *tessellation = on.then(crate::graph::Tessellation::default);
            }
            if let Some(settings) = tessellation {
                ui.add(
                    egui::DragValue::new(&mut settings.tolerance)
                        .speed(0.02)
                        .range(f64::from(crate::mesh::Refinement::MIN_TOLERANCE_PX)..=8.0)
                        .suffix(" px"),
                );
            }
        });
        let graph = &self.session.document.graph;
        if shading != graph.shading {
            self.edit(GraphEdit::Set(GraphSetting::Shading(shading)));
        }
        if alpha != self.session.document.graph.alpha {
            self.edit(GraphEdit::Set(GraphSetting::Alpha(alpha)));
        }
        self.set_preview(|preview| preview.tessellation = tessellation);
    }

    /// Changes the graph's preview settings as `change` does: one edit, when it changes
    /// something.
    fn set_preview(&mut self, change: impl FnOnce(&mut crate::graph::Preview)) {
        let mut preview = self.session.document.graph.preview.clone();
        change(&mut preview);
        if preview != self.session.document.graph.preview {
            self.edit(GraphEdit::Set(GraphSetting::Preview(preview)));
        }
    }

    /// Over the bottom of the preview: why the material's distance fields could not be
    /// solved on this mesh (a GeoTexture then shows as if no front had reached anywhere,
    /// which can look like an empty preview).
    fn fields_warning(&self, ui: &mut Ui, preview: egui::Rect) {
        if let Some(error) = &self.preview.fields.error {
            warn_over(
                ui,
                preview,
                format!("⚠ fields not solved on this mesh: {error}"),
            );
        }
    }

    /// Says over the preview why it is empty, where the graph opened has never compiled
    /// (its error is in the status bar and on the node at fault).
    fn no_material_note(&self, ui: &mut Ui, preview: egui::Rect) {
        let live = &self.preview.live;
        if live.compiled.is_none() && !live.errors.is_empty() && !live.is_compiling() {
            warn_over(
                ui,
                preview,
                "⚠ nothing to show: the graph does not compile".into(),
            );
        }
    }

    /// Keeps the preview mesh's fields in step with the graph (solving in the background)
    /// and hands the solved mesh to the preview.
    pub(in crate::app) fn solve_fields(&mut self) {
        let uses = self
            .preview
            .live
            .compiled
            .as_ref()
            .map(|c| c.uses())
            .unwrap_or_default();
        let mut used = uses.fields;
        // A field view is its own material: the mesh carries what it reads.
        let mesh_lanes = match self.preview.fields.view {
            Some(fields::FieldView::Distance(slot)) => {
                used[slot.min(3)] = true;
                uses.mesh_fields
            }
            Some(fields::FieldView::Mesh(field)) => {
                crate::nodes::mesh_field::lanes(&[field.key()], [false; 4])
            }
            None => uses.mesh_fields,
        };
        let name = self.preview.state.mesh.clone();
        let preview = &self.preview.state;
        self.preview.fields.update(
            &name,
            || preview.plain_mesh(),
            &self.session.document.graph.preview.fields,
            (used, mesh_lanes),
        );
        let mesh_prefix = format!("{name}|");
        self.preview.state.prepared = self
            .preview
            .fields
            .ready
            .clone()
            .filter(|(key, _)| key.starts_with(&mesh_prefix));
    }

    /// A click on the preview while picking adds (or removes) the vertex under it as a
    /// source of the picked field.
    pub(in crate::app) fn pick_source(&mut self, response: &egui::Response) {
        let (Some(slot), Some(click)) =
            (self.preview.fields.picking, response.interact_pointer_pos())
        else {
            return;
        };
        if !response.clicked() || self.preview.state.flat {
            return;
        }
        let rect = response.rect;
        let ndc = [
            (click.x - rect.left()) / rect.width() * 2.0 - 1.0,
            1.0 - (click.y - rect.top()) / rect.height() * 2.0,
        ];
        let (origin, direction) = self
            .preview
            .state
            .view
            .ray(rect.width() / rect.height().max(1.0), ndc);
        // The solved mesh has the plain one's vertices: no need to make it again.
        let prepared = self
            .preview
            .state
            .prepared
            .as_ref()
            .map(|(_, mesh)| mesh.clone());
        let Some(mesh) = prepared.or_else(|| self.preview.state.plain_mesh()) else {
            return;
        };
        let mut fields = self.session.document.graph.preview.fields.clone();
        // Sources count vertices as the mesh file lists them.
        if let (Some(vertex), Some(field)) = (
            crate::mesh::pick_vertex(&mesh, origin, direction),
            fields.get_mut(slot),
        ) {
            fields::toggle_source(field, mesh.file_vertex(vertex));
            self.chrome.message = Some(format!(
                "field {slot}: {}",
                counted(field.sources.len(), "source")
            ));
            self.set_preview(|preview| preview.fields = fields);
        }
    }
}

/// A combo box choosing `value` among `choices` (value, label), known by `id`.
fn choice<T: Copy + PartialEq>(
    ui: &mut Ui,
    id: &str,
    value: &mut T,
    choices: &[(T, &str)],
) -> egui::Response {
    let shown = choices
        .iter()
        .find(|(option, _)| option == value)
        .map_or("", |(_, label)| *label);
    egui::ComboBox::from_id_salt(id)
        .selected_text(shown)
        .show_ui(ui, |ui| {
            for (option, label) in choices {
                ui.selectable_value(value, *option, *label);
            }
        })
        .response
}

/// A warning in a band along the bottom of the preview at `preview`.
fn warn_over(ui: &mut Ui, preview: egui::Rect, warning: String) {
    let text = egui::RichText::new(warning)
        .color(egui::Color32::from_rgb(255, 170, 120))
        .background_color(egui::Color32::from_black_alpha(200));
    let band = egui::Rect::from_min_max(
        preview.left_bottom() - egui::vec2(-6.0, 48.0),
        preview.right_bottom() - egui::vec2(6.0, 6.0),
    );
    ui.put(band, egui::Label::new(text).wrap());
}
