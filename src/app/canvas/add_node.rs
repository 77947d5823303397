//! The add-node search, as in Blender: Space, Tab, Shift+A, *Edit → Add node*, a right
//! click on empty canvas or a wire dropped there open it at the mouse (the graph's centre
//! when the mouse is elsewhere) with its text box focused. Typing filters, Up and Down
//! move the highlight, Enter or a click picks, Escape or a click elsewhere closes. The
//! node appears under the mouse; a dropped wire is connected to it. Pastes and duplicates
//! land at the mouse too, and comment frames are added from the same search or Ctrl+J.
//! The search lists the node groups too (the graph's and the library's): picking one
//! places an instance, the graph keeping a linked copy of a library group.

use crate::app::VeneerApp;
use crate::app::canvas::catalogue::{self, Entry, Item};
use crate::app::canvas::snarl_model::{frame_around, next_node_id};
use crate::app::canvas::viewer::DroppedWire;
use crate::graph::{Node, NodeKind};
use egui::{Id, Key, Modifiers, Pos2, Rect, Vec2};
use egui_snarl::{InPinId, OutPinId};

/// The open search.
#[derive(Clone, Debug)]
pub struct Search {
    /// The popup's top-left corner on screen (the mouse when it opened).
    screen: Pos2,
    /// Where a new node goes, in graph coordinates.
    graph: Pos2,
    text: String,
    /// Index of the highlighted entry among those shown.
    highlight: usize,
    /// Set when the highlight moved by key, so the list scrolls to it.
    scroll: bool,
    /// The wire the new node is for, if any.
    dropped: Option<DroppedWire>,
    /// The text the key that opened the search types, kept out of the search when it
    /// arrives in the frame after the key (as when events come one frame each).
    swallow: Option<(u64, String)>,
    /// Enter came in the same frame as typed letters: pick once the list shows them.
    confirm: bool,
    /// The node groups offered (read when the search opened).
    groups: Vec<String>,
}

/// The add-node search's state and what placing needs: where the graph is on screen.
#[derive(Clone, Debug, Default)]
pub struct AddNode {
    search: Option<Search>,
    /// The graph panel's rectangle on screen (as last shown).
    graph_rect: Option<Rect>,
}

impl AddNode {
    /// Remembers where the graph panel is on screen.
    pub fn set_graph_rect(&mut self, rect: Rect) {
        self.graph_rect = Some(rect);
    }
}

/// Where the pointer sits over a new node's top-left corner: over its title, a little in.
const GRAB: Vec2 = Vec2::new(40.0, 12.0);

/// A new frame's tint (as `frame_around` gives).
const FRAME_COLOR: (f32, f32, f32) = (0.45, 0.65, 0.95);

/// The search popup's layer and text box.
fn popup_id() -> Id {
    Id::new("veneer-add-node")
}

fn text_id() -> Id {
    popup_id().with("text")
}

impl VeneerApp {
    /// The mouse on screen when it is over the graph, else the graph's centre; and that
    /// point in graph coordinates.
    pub(in crate::app) fn placement(&self, ctx: &egui::Context) -> (Pos2, Pos2) {
        let rect = self
            .canvas
            .add
            .graph_rect
            .unwrap_or_else(|| ctx.content_rect());
        let screen = ctx
            .input(|input| input.pointer.hover_pos())
            .filter(|pos| rect.contains(*pos))
            .unwrap_or_else(|| rect.center());
        (screen, self.canvas.navigation.transform.inverse() * screen)
    }

    /// Opens the add-node search at the mouse, for `dropped` if a wire was dropped.
    /// The text `typed` by the key that opened it (" " for Space, "A" for Shift+A) does
    /// not go into the search.
    pub(in crate::app) fn open_add_node(
        &mut self,
        ctx: &egui::Context,
        dropped: Option<DroppedWire>,
        typed: Option<&str>,
    ) {
        let (screen, graph) = self.placement(ctx);
        let swallowed = ctx.input_mut(|input| {
            let before = input.events.len();
            input.events.retain(
                |event| !matches!(event, egui::Event::Text(text) if Some(text.as_str()) == typed),
            );
            input.events.len() < before
        });
        let swallow = typed
            .filter(|_| !swallowed)
            .map(|text| (ctx.cumulative_pass_nr() + 1, text.to_string()));
        self.canvas.add.search = Some(Search {
            screen,
            graph,
            text: String::new(),
            highlight: 0,
            scroll: false,
            dropped,
            swallow,
            confirm: false,
            groups: self.placeable_groups(),
        });
        ctx.memory_mut(|memory| memory.request_focus(text_id()));
        ctx.request_repaint();
    }

    fn close_add_node(&mut self, ctx: &egui::Context) {
        self.canvas.add.search = None;
        ctx.memory_mut(|memory| memory.surrender_focus(text_id()));
    }

    /// Shows the add-node search if it is open, and adds what is picked.
    pub(in crate::app) fn add_node_popup(&mut self, ctx: &egui::Context) {
        let Some(search) = self.canvas.add.search.as_mut() else {
            return;
        };
        if self.chrome.dialog.is_some() {
            self.close_add_node(ctx);
            return;
        }
        if let Some((pass, text)) = search.swallow.take() {
            if pass == ctx.cumulative_pass_nr() {
                ctx.input_mut(|input| {
                    input
                        .events
                        .retain(|event| !matches!(event, egui::Event::Text(t) if *t == text))
                });
            } else if pass > ctx.cumulative_pass_nr() {
                search.swallow = Some((pass, text));
            }
        }
        let dangling = search.dropped.as_ref().map(DroppedWire::dangling);
        let selected = !self.canvas.selection.is_empty();
        // Comment frames and the Material are the top level's.
        let top = self.canvas.scope.current().is_none();
        // On a dropped wire, groups are offered by their pins, as nodes are.
        let group_kinds: std::collections::BTreeMap<&str, NodeKind> = match dangling {
            Some(_) => search
                .groups
                .iter()
                .filter_map(|name| {
                    Some((
                        name.as_str(),
                        crate::app::canvas::group_edit::group_kind(
                            &self.session.document.graph,
                            name,
                        )?,
                    ))
                })
                .collect(),
            None => Default::default(),
        };
        let usable = |entry: &Entry| match (&entry.item, dangling) {
            (Item::Node(NodeKind::Material), _) if !top => false,
            (Item::Node(_), None) | (Item::Group(_), None) => true,
            (Item::Frame, None) => top,
            (Item::FrameSelection, None) => top && selected,
            (Item::Node(kind), Some(dangling)) => {
                catalogue::compatible_pin(kind, dangling).is_some()
            }
            (Item::Group(name), Some(dangling)) => group_kinds
                .get(name.as_str())
                .is_some_and(|kind| catalogue::compatible_pin(kind, dangling).is_some()),
            (_, Some(_)) => false,
        };
        let entries: Vec<Entry> = if search.text.trim().is_empty() {
            catalogue::entries(&search.groups)
        } else {
            catalogue::search(&search.text, &search.groups)
        }
        .into_iter()
        .filter(usable)
        .collect();

        // The search takes the keys it answers before its text box sees them.
        let key = |key| ctx.input_mut(|input| input.consume_key(Modifiers::NONE, key));
        let last = entries.len().saturating_sub(1);
        if key(Key::ArrowDown) {
            search.highlight = (search.highlight + 1).min(last);
            search.scroll = true;
        }
        if key(Key::ArrowUp) {
            search.highlight = search.highlight.saturating_sub(1);
            search.scroll = true;
        }
        search.highlight = search.highlight.min(last);
        // Enter typed in the same frame as letters picks from the list those letters give,
        // shown next frame (a fast typist or a script sends them together).
        let letters = ctx.input(|input| {
            input
                .events
                .iter()
                .any(|event| matches!(event, egui::Event::Text(_)))
        });
        let enter = key(Key::Enter);
        let mut picked = if letters {
            search.confirm |= enter;
            ctx.request_repaint();
            None
        } else {
            (enter || std::mem::take(&mut search.confirm)).then_some(search.highlight)
        };
        if key(Key::Escape) {
            self.close_add_node(ctx);
            return;
        }

        let title = if dangling.is_some() {
            "Add and connect"
        } else {
            "Add node"
        };
        let browsing = search.text.trim().is_empty();
        let shown = egui::Area::new(popup_id())
            .order(egui::Order::Foreground)
            .fixed_pos(search.screen)
            .constrain(true)
            .show(ctx, |ui| {
                egui::Frame::popup(ui.style()).show(ui, |ui| {
                    ui.set_width(240.0);
                    ui.label(egui::RichText::new(title).strong());
                    if !ui.memory(|memory| memory.has_focus(text_id())) {
                        ui.memory_mut(|memory| memory.request_focus(text_id()));
                    }
                    let edit = ui.add(
                        egui::TextEdit::singleline(&mut search.text)
                            .id(text_id())
                            .hint_text("search nodes…")
                            .desired_width(f32::INFINITY),
                    );
                    if edit.changed() {
                        search.highlight = 0;
                        search.scroll = true;
                    }
                    ui.separator();
                    // As tall as the entries up to 320 points, whatever the last search
                    // showed (the area otherwise kept the height of a short list), and
                    // no taller than the room below the mouse, so it opens there.
                    let below = ctx.content_rect().max.y - ui.cursor().min.y - 12.0;
                    let height = below.clamp(120.0, 320.0);
                    egui::ScrollArea::vertical()
                        .max_height(height)
                        .min_scrolled_height(height)
                        .auto_shrink([false, true])
                        .show(ui, |ui| {
                            let mut group = "";
                            for (index, entry) in entries.iter().enumerate() {
                                if browsing && entry.group() != group {
                                    group = entry.group();
                                    ui.label(egui::RichText::new(group).weak().small());
                                }
                                let row = ui.add(
                                    egui::Button::selectable(
                                        index == search.highlight,
                                        &entry.name,
                                    )
                                    .min_size(egui::vec2(ui.available_width(), 0.0)),
                                );
                                if index == search.highlight && search.scroll {
                                    row.scroll_to_me(None);
                                }
                                if row.clicked() {
                                    picked = Some(index);
                                }
                            }
                            if entries.is_empty() {
                                ui.weak("nothing matches");
                            }
                        });
                    search.scroll = false;
                });
            });

        let pressed_elsewhere = ctx.input(|input| {
            input.pointer.any_pressed()
                && input
                    .pointer
                    .interact_pos()
                    .is_some_and(|pos| !shown.response.rect.contains(pos))
        });
        if let Some(entry) = picked.and_then(|index| entries.into_iter().nth(index)) {
            let search = self.canvas.add.search.clone().expect("the search is open");
            self.close_add_node(ctx);
            self.add_entry(entry, search);
        } else if pressed_elsewhere {
            self.close_add_node(ctx);
        }
    }

    /// Adds what `entry` names where `search` was opened, wired to its dropped wire.
    fn add_entry(&mut self, entry: Entry, search: Search) {
        let added = match entry.item {
            Item::Frame => {
                let mut frames = self.session.document.graph.frames.clone();
                frames.push(crate::graph::Frame {
                    title: "Comment".into(),
                    min: (search.graph.x - GRAB.x, search.graph.y - GRAB.y),
                    max: (
                        search.graph.x - GRAB.x + 400.0,
                        search.graph.y - GRAB.y + 260.0,
                    ),
                    color: FRAME_COLOR,
                });
                self.set_frames(frames);
                return;
            }
            Item::FrameSelection => {
                self.frame_selection();
                return;
            }
            Item::Group(name) => self.add_group_instance(&name, search.graph - GRAB),
            Item::Node(kind) => {
                let node = Node::new(next_node_id(&self.canvas.snarl), kind);
                Some(self.canvas.snarl.insert_node(search.graph - GRAB, node))
            }
        };
        let Some(id) = added else {
            return;
        };
        if let Some(dropped) = search.dropped {
            self.wire_dropped(id, dropped);
        }
        // The new node is the selection, its settings in the inspector.
        self.canvas.placed(vec![id]);
    }

    /// Connects new node `id` to the wire `dropped` by its first compatible pin.
    fn wire_dropped(&mut self, id: egui_snarl::NodeId, dropped: DroppedWire) {
        let pin = catalogue::compatible_pin(&self.canvas.snarl[id].kind, dropped.dangling());
        match (dropped, pin) {
            (DroppedWire::Out(_, pins), Some(input)) => {
                for from in pins {
                    if self.canvas.snarl.get_node(from.node).is_some() {
                        self.canvas.snarl.connect(from, InPinId { node: id, input });
                    }
                }
            }
            (DroppedWire::In(_, pins), Some(output)) => {
                for to in pins {
                    if self.canvas.snarl.get_node(to.node).is_some() {
                        self.canvas.snarl.drop_inputs(to);
                        self.canvas.snarl.connect(OutPinId { node: id, output }, to);
                    }
                }
            }
            _ => {}
        }
    }

    /// Ctrl+J and *Edit → Frame selected nodes*: a comment frame around the selection
    /// (at the top level: frames are the graph's, not a group's).
    pub(in crate::app) fn frame_selection(&mut self) {
        if self.canvas.scope.current().is_some() {
            self.chrome.message =
                Some("comment frames belong to the top level: Tab out of the group first".into());
            return;
        }
        match frame_around(&self.canvas.snarl, &self.canvas.selection, "Comment") {
            Some(frame) => {
                let mut frames = self.session.document.graph.frames.clone();
                frames.push(frame);
                self.set_frames(frames);
            }
            None => self.chrome.message = Some("select the nodes to frame first".into()),
        }
    }

    /// Pastes copied nodes at the mouse, clear of the others; they become the selection.
    pub(in crate::app) fn paste_at_mouse(&mut self, ctx: &egui::Context, text: &str) {
        let (_, at) = self.placement(ctx);
        let groups = &self.session.document.graph.groups;
        match crate::app::canvas::clipboard::paste(&mut self.canvas.snarl, text, at, groups) {
            Ok(pasted) => self.canvas.placed(pasted),
            Err(error) => self.chrome.message = Some(format!("nothing pasted: {error}")),
        }
    }

    /// Duplicates the selected nodes at the mouse, clear of the others: the copies are
    /// the selection, and follow the mouse until a click.
    pub(in crate::app) fn duplicate_at_mouse(&mut self, ctx: &egui::Context) {
        let (_, at) = self.placement(ctx);
        let selection = self.editable_selection();
        let groups = &self.session.document.graph.groups;
        let copies = crate::app::canvas::clipboard::duplicate(
            &mut self.canvas.snarl,
            &selection,
            at,
            groups,
        );
        if !copies.is_empty() {
            self.grab_new(ctx, copies);
        }
    }
}
