//! The node graph panel: our `Graph` shown and edited through egui-snarl. The `Graph`
//! stays the saved, ordered truth; the `Snarl` is rebuilt from it when it is replaced
//! (open, undo) and read back after every frame of editing.

use crate::app::canvas::catalogue::Dangling;
use crate::app::canvas::scope::{self, Declared};
use crate::app::canvas::snarl_model::would_cycle;
use crate::app::canvas::wires::{PinSide, SpottedPin};
use crate::app::inspector::group::GroupAction;
use crate::app::widgets::{input_editor, store_input, type_color};
use crate::graph::{Node, NodeId, NodeKind, PinDefault};
use egui::{Color32, Pos2, RichText, Ui};
use egui_snarl::ui::{AnyPins, PinInfo, SnarlPin, SnarlViewer};
use egui_snarl::{InPin, InPinId, OutPin, OutPinId, Snarl};
use std::collections::BTreeMap;

/// What the graph's nodes, pins and menus asked for this frame.
#[derive(Default)]
pub struct Asked {
    /// A message for the status bar (e.g. why a wire was refused).
    pub hint: Option<String>,
    /// Set when a wire is dropped on empty canvas: the add-node search opens for it.
    pub dropped: Option<DroppedWire>,
    /// The node a primary click landed on (the topmost one under it).
    pub clicked: Option<egui_snarl::NodeId>,
    /// The nodes a node menu's *Duplicate* added.
    pub duplicated: Option<Vec<egui_snarl::NodeId>>,
    /// What wires dropped on a boundary node's "+" declared.
    pub declared: Vec<Declared>,
    /// An inner input chosen for *Expose as group input*.
    pub expose: Option<InPinId>,
    /// What a group node's context menu asked.
    pub group_action: Option<GroupAction>,
}

/// The snarl viewer: how nodes, pins and menus look and what edits do.
pub struct Viewer<'a> {
    /// Compile errors by node, shown on the nodes.
    pub errors: &'a BTreeMap<Option<NodeId>, String>,
    /// Numerical hazards by node, shown on the nodes.
    pub warnings: &'a BTreeMap<NodeId, String>,
    /// Receives what the nodes and menus asked.
    pub asked: &'a mut Asked,
    /// The active node (the inspector's), its title drawn highlighted.
    pub active: Option<egui_snarl::NodeId>,
    /// The view's transform (which this viewer imposes on the snarl) and node sizes.
    pub navigation: &'a mut crate::app::canvas::navigation::Navigation,
    /// Comment frames to draw behind the nodes.
    pub frames: &'a [crate::graph::Frame],
    /// Node thumbnails: which nodes show one, and the drawn tiles.
    pub thumbnails: &'a mut crate::app::thumbnails::Thumbnails,
    /// Receives where pins and nodes are drawn.
    pub spots: crate::app::canvas::wires::SharedSpots,
    /// Whether a group's definition is shown (node thumbnails are the top level's).
    pub in_group: bool,
    /// The graph's node groups (duplicated group nodes take their pins).
    pub groups: &'a BTreeMap<String, crate::graph::group::GroupDef>,
    /// The material's shading: the inputs its lighting does not read are greyed out.
    pub shading: crate::graph::Shading,
}

impl SnarlViewer<Node> for Viewer<'_> {
    fn draw_background(
        &mut self,
        background: Option<&egui_snarl::ui::BackgroundPattern>,
        viewport: &egui::Rect,
        snarl_style: &egui_snarl::ui::SnarlStyle,
        style: &egui::Style,
        painter: &egui::Painter,
        _: &Snarl<Node>,
    ) {
        if let Some(background) = background {
            background.draw(viewport, snarl_style, style, painter);
        }
        for frame in self.frames {
            let rect = egui::Rect::from_min_max(
                Pos2::new(frame.min.0, frame.min.1),
                Pos2::new(frame.max.0, frame.max.1),
            );
            let [r, g, b] = [frame.color.0, frame.color.1, frame.color.2]
                .map(|c| (c.clamp(0.0, 1.0) * 255.0) as u8);
            painter.rect_filled(rect, 8.0, Color32::from_rgba_unmultiplied(r, g, b, 40));
            painter.rect_stroke(
                rect,
                8.0,
                egui::Stroke::new(1.5, Color32::from_rgb(r, g, b)),
                egui::StrokeKind::Inside,
            );
            let title = egui::FontId::proportional(18.0);
            painter.text(
                rect.min + egui::vec2(10.0, 8.0),
                egui::Align2::LEFT_TOP,
                &frame.title,
                title,
                Color32::from_rgb(r, g, b),
            );
        }
    }

    fn current_transform(&mut self, to_global: &mut egui::emath::TSTransform, _: &mut Snarl<Node>) {
        *to_global = self.navigation.transform;
    }

    fn title(&mut self, node: &Node) -> String {
        node.title()
    }

    fn final_node_rect(
        &mut self,
        node: egui_snarl::NodeId,
        rect: egui::Rect,
        ui: &mut Ui,
        _: &mut Snarl<Node>,
    ) {
        self.spots.borrow_mut().nodes.insert(node, rect);
        self.navigation.measured(node, rect);
        // Nodes live in a zoomed and panned layer; the pointer is in screen space.
        let to_screen = ui
            .ctx()
            .layer_transform_to_global(ui.layer_id())
            .unwrap_or_default();
        let on_screen = to_screen * rect;
        let pointer = ui.input(|input| {
            input
                .pointer
                .primary_clicked()
                .then(|| input.pointer.interact_pos())
                .flatten()
        });
        // A click on a popup, menu or dialog above the node is not a click on the node.
        let clicked = pointer.is_some_and(|pos| {
            on_screen.contains(pos)
                && ui
                    .ctx()
                    .layer_id_at(pos)
                    .is_none_or(|layer| layer.order == egui::Order::Background)
        });
        if clicked {
            self.asked.clicked = Some(node);
        }
    }

    fn show_header(
        &mut self,
        id: egui_snarl::NodeId,
        _: &[InPin],
        _: &[OutPin],
        ui: &mut Ui,
        snarl: &mut Snarl<Node>,
    ) {
        let node = &snarl[id];
        let selected = self.active == Some(id);
        ui.horizontal(|ui| {
            let title = RichText::new(node.title()).strong().size(
                crate::app::canvas::navigation::title_size(self.navigation.transform.scaling),
            );
            ui.label(if selected {
                title.color(Color32::from_rgb(255, 190, 80))
            } else {
                title
            })
            .on_hover_text(match node.kind {
                NodeKind::Material => format!(
                    "{}\nshaded {} (the preview's shading menu)",
                    crate::app::canvas::node_text::kind_tip(&node.kind),
                    self.shading.name()
                ),
                _ => crate::app::canvas::node_text::kind_tip(&node.kind),
            });
            if node.kind == NodeKind::Material {
                // The shading decides which inputs are read (the others are greyed).
                ui.weak(self.shading.name());
            }
            if let Some(warning) = self.warnings.get(&node.id) {
                ui.label(RichText::new("⚠").color(Color32::from_rgb(230, 180, 60)))
                    .on_hover_text(warning);
            }
            if let Some(error) = self.errors.get(&Some(node.id)) {
                ui.label(RichText::new("⚠").color(Color32::from_rgb(240, 80, 60)))
                    .on_hover_text(error);
            }
        });
    }

    fn has_body(&mut self, node: &Node) -> bool {
        node.kind.definition().body().is_some()
    }

    /// The picture the node's definition declares (a colour ramp's gradient).
    fn show_body(
        &mut self,
        id: egui_snarl::NodeId,
        _: &[InPin],
        _: &[OutPin],
        ui: &mut Ui,
        snarl: &mut Snarl<Node>,
    ) {
        if let Some(body) = snarl[id].kind.definition().body() {
            crate::app::inspector::body::show_body(ui, &body, crate::nodes::Body::SIZE.0);
        }
    }

    fn inputs(&mut self, node: &Node) -> usize {
        node.kind.signature().inputs.len()
    }

    fn outputs(&mut self, node: &Node) -> usize {
        node.kind.signature().outputs.len()
    }

    fn show_input(
        &mut self,
        pin: &InPin,
        ui: &mut Ui,
        snarl: &mut Snarl<Node>,
    ) -> impl SnarlPin + 'static {
        let node = &snarl[pin.id.node];
        let spec = node.kind.signature().inputs[pin.id.input];
        if crate::app::canvas::boundary::is_add_pin(node, spec.name) {
            ui.weak(spec.name)
                .on_hover_text("drop a wire from an inner output here to add a group output");
            return self.pin(spec.ty, PinSide::In(pin.id));
        }
        let ignored = node.kind == NodeKind::Material && !self.shading.reads(spec.name);
        let label = if ignored {
            RichText::new(spec.name).weak()
        } else {
            RichText::new(spec.name)
        };
        let mut tip = crate::app::canvas::node_text::input_tip(&spec);
        if ignored {
            tip = format!("{tip}\nnot read by the {} shading", self.shading.name());
        }
        let name = ui
            .add(egui::Label::new(label).sense(egui::Sense::click()))
            .on_hover_text(tip);
        let exposable = self.in_group
            && pin.remotes.is_empty()
            && crate::app::canvas::boundary::boundary(node).is_none()
            && matches!(spec.default, PinDefault::Const(_));
        if exposable {
            name.context_menu(|ui| {
                if ui.button("Expose as group input").clicked() {
                    self.asked.expose = Some(pin.id);
                    ui.close();
                }
            });
        }
        if pin.remotes.is_empty() {
            match spec.default {
                PinDefault::Const(_) => {
                    let edited = input_editor(ui, node, spec.name);
                    store_input(snarl, pin.id.node, spec.name, edited);
                }
                PinDefault::Position => {
                    ui.weak("position");
                }
                PinDefault::Required => {
                    ui.colored_label(Color32::from_rgb(240, 120, 60), "connect");
                }
                PinDefault::Builtin(shape) => {
                    ui.weak(shape);
                }
            }
        }
        self.pin(spec.ty, PinSide::In(pin.id))
    }

    fn show_output(
        &mut self,
        pin: &OutPin,
        ui: &mut Ui,
        snarl: &mut Snarl<Node>,
    ) -> impl SnarlPin + 'static {
        let node = &snarl[pin.id.node];
        let spec = node.kind.signature().outputs[pin.id.output];
        if crate::app::canvas::boundary::is_add_pin(node, spec.name) {
            ui.weak(spec.name)
                .on_hover_text("drop a wire from an inner input here to add a group input");
        } else {
            ui.label(spec.name)
                .on_hover_text(crate::app::canvas::node_text::output_tip(&spec));
        }
        self.pin(spec.ty, PinSide::Out(pin.id))
    }

    fn connect(&mut self, from: &OutPin, to: &InPin, snarl: &mut Snarl<Node>) {
        let output = snarl[from.id.node].kind.signature().outputs[from.id.output];
        let input = snarl[to.id.node].kind.signature().inputs[to.id.input];
        if crate::app::canvas::boundary::is_add_pin(&snarl[from.id.node], output.name)
            || crate::app::canvas::boundary::is_add_pin(&snarl[to.id.node], input.name)
        {
            match scope::expose(snarl, from.id, to.id) {
                Some(declared) => self.asked.declared.push(declared),
                None => {
                    self.asked.hint = Some("cannot connect: wire a + pin to an inner pin".into())
                }
            }
            return;
        }
        if !output.ty.converts_to(input.ty) {
            self.asked.hint = Some(format!(
                "cannot connect: '{}' gives {} but '{}' expects {}",
                output.name, output.ty, input.name, input.ty
            ));
            return;
        }
        if would_cycle(snarl, from.id.node, to.id.node) {
            self.asked.hint = Some("cannot connect: the wire would make a cycle".into());
            return;
        }
        snarl.drop_inputs(to.id);
        snarl.connect(from.id, to.id);
    }

    /// A wire dropped on empty canvas opens the add-node search (the app's, at the mouse)
    /// offering only the kinds it can attach to; snarl's own menu stays shut.
    fn has_dropped_wire_menu(&mut self, src_pins: AnyPins, snarl: &mut Snarl<Node>) -> bool {
        self.asked.dropped = match src_pins {
            AnyPins::Out(pins @ [pin, ..]) => Some(DroppedWire::Out(
                Dangling::FromOutput(snarl[pin.node].kind.signature().outputs[pin.output].ty),
                pins.to_vec(),
            )),
            AnyPins::In(pins @ [pin, ..]) => Some(DroppedWire::In(
                Dangling::IntoInput(snarl[pin.node].kind.signature().inputs[pin.input].ty),
                pins.to_vec(),
            )),
            _ => None,
        };
        false
    }

    fn has_footer(&mut self, node: &Node) -> bool {
        // (A group's boundary nodes stand for no node of the graph drawn.)
        crate::app::canvas::boundary::boundary(node).is_none()
            && self.thumbnails.shows(node.id)
            && !node.kind.signature().outputs.is_empty()
    }

    /// The node's thumbnail, below its pins (blank until first drawn).
    fn show_footer(
        &mut self,
        node: egui_snarl::NodeId,
        _: &[InPin],
        _: &[OutPin],
        ui: &mut Ui,
        snarl: &mut Snarl<Node>,
    ) {
        crate::app::thumbnails::show_tile(ui, self.thumbnails, &snarl[node]);
    }

    /// Boundary nodes have no menu: they cannot be duplicated or deleted.
    fn has_node_menu(&mut self, node: &Node) -> bool {
        crate::app::canvas::boundary::boundary(node).is_none()
    }

    fn show_node_menu(
        &mut self,
        node: egui_snarl::NodeId,
        _: &[InPin],
        _: &[OutPin],
        ui: &mut Ui,
        snarl: &mut Snarl<Node>,
    ) {
        if crate::app::canvas::boundary::is_instance(&snarl[node]) {
            if ui.button("Edit group (Tab)").clicked() {
                self.asked.group_action = Some(GroupAction::Enter(node));
                ui.close();
            }
            if ui.button("Ungroup (Alt+G)").clicked() {
                self.asked.group_action = Some(GroupAction::Ungroup(node));
                ui.close();
            }
            ui.separator();
        }
        if ui.button("Duplicate").clicked() {
            // Where the menu opened (where the node was right-clicked), in graph space.
            let at = self.navigation.transform.inverse() * ui.min_rect().min;
            let copies = crate::app::canvas::clipboard::duplicate(snarl, &[node], at, self.groups);
            self.asked.duplicated = Some(copies);
            ui.close();
        }
        let id = snarl[node].id;
        if ui.button("Delete").clicked() {
            snarl.remove_node(node);
            ui.close();
        }
        let hidden = self.thumbnails.hidden.contains(&id);
        let label = if hidden {
            "Show thumbnail"
        } else {
            "Hide thumbnail"
        };
        if ui.button(label).clicked() {
            if hidden {
                self.thumbnails.hidden.remove(&id);
            } else {
                self.thumbnails.hidden.insert(id);
            }
            ui.close();
        }
    }
}

impl Viewer<'_> {
    /// A pin of type `ty`, drawn in its type's colour, its place recorded.
    fn pin(&self, ty: crate::graph::ValueType, pin: PinSide) -> SpottedPin {
        SpottedPin {
            info: PinInfo::circle()
                .with_fill(type_color(ty))
                .with_wire_color(type_color(ty)),
            pin,
            spots: self.spots.clone(),
        }
    }
}

/// A wire dropped on empty canvas: the end that dangles and the pins it starts from.
#[derive(Clone, Debug, PartialEq)]
pub enum DroppedWire {
    /// Dragged out of these outputs: the new node's input takes them.
    Out(Dangling, Vec<OutPinId>),
    /// Dragged out of these inputs: the new node's output feeds them.
    In(Dangling, Vec<InPinId>),
}

impl DroppedWire {
    pub(in crate::app) fn dangling(&self) -> Dangling {
        match self {
            DroppedWire::Out(dangling, _) | DroppedWire::In(dangling, _) => *dangling,
        }
    }
}
