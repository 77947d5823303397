//! Blender's grab, for duplicates: the new nodes follow the mouse until a click puts
//! them down; Escape or a right click puts them back where the duplicate placed them.
//! The click that ends a grab is the grab's: it neither selects nor starts a drag.

use crate::graph::Node;
use egui::emath::TSTransform;
use egui::{Context, Key, Modifiers, PointerButton, Pos2};
use egui_snarl::{NodeId, Snarl};

/// Nodes following the mouse, or the button that put them down, still held.
#[derive(Clone, Debug, Default)]
pub struct Grab {
    /// The nodes and where each was placed, and the mouse then (graph coordinates).
    moving: Option<(Vec<(NodeId, Pos2)>, Pos2)>,
    /// The button that ended the grab is still down.
    holding: bool,
}

impl Grab {
    /// Starts moving `nodes` of `snarl` with the mouse, now at `mouse` (graph
    /// coordinates). Nodes grabbed before stay where they are.
    pub fn start(&mut self, snarl: &Snarl<Node>, nodes: &[NodeId], mouse: Pos2) {
        let placed = nodes
            .iter()
            .filter_map(|id| Some((*id, snarl.get_node_info(*id)?.pos)))
            .collect();
        self.moving = Some((placed, mouse));
    }

    /// Forgets the grab (the graph view is rebuilt: its node ids are others').
    pub fn forget(&mut self) {
        *self = Grab::default();
    }

    /// Whether nodes follow the mouse (the document takes in their moves as one edit,
    /// when they are put down).
    pub fn is_moving(&self) -> bool {
        self.moving.is_some()
    }

    /// Before the graph is shown: moves the grabbed nodes with the mouse, puts them
    /// down on a click or back on Escape or a right click. Returns whether this frame's
    /// pointer input is the grab's (nothing else is to select or drag with it).
    pub fn update(
        &mut self,
        ctx: &Context,
        snarl: &mut Snarl<Node>,
        to_graph: TSTransform,
    ) -> bool {
        if self.holding {
            self.holding = ctx.input(|input| input.pointer.any_down());
            self.claim_drag(ctx);
            return true;
        }
        let Some((placed, mouse)) = &mut self.moving else {
            return false;
        };
        // Nodes deleted while they followed the mouse are let go of.
        placed.retain(|(id, _)| snarl.get_node(*id).is_some());
        if placed.is_empty() {
            self.moving = None;
            return false;
        }
        let (pointer, put_down, cancel) = ctx.input(|input| {
            let pointer = &input.pointer;
            (
                pointer.latest_pos(),
                pointer.button_pressed(PointerButton::Primary),
                pointer.button_pressed(PointerButton::Secondary),
            )
        });
        let escape = ctx.input_mut(|input| input.consume_key(Modifiers::NONE, Key::Escape));
        let offset = if escape || cancel {
            Some(egui::Vec2::ZERO)
        } else {
            pointer.map(|pos| to_graph * pos - *mouse)
        };
        for (id, at) in placed {
            if let (Some(info), Some(offset)) = (snarl.get_node_info_mut(*id), offset) {
                info.pos = *at + offset;
            }
        }
        if put_down || cancel || escape {
            self.moving = None;
            self.holding = put_down || cancel;
            self.claim_drag(ctx);
        }
        true
    }

    /// The button held is the grab's: no node under it is dragged.
    fn claim_drag(&self, ctx: &Context) {
        if self.holding {
            ctx.set_dragged_id(egui::Id::new("veneer grab"));
        }
    }
}
