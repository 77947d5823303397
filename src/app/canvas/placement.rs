//! Where new nodes go: added, pasted and duplicated nodes are moved, together, to the
//! nearest spot where none of them lies on a node already there. A node drawn before is
//! as big as it was drawn; a new one is as big as [`footprint`] reckons.

use crate::graph::{InputPin, Node, PinDefault, ValueType};
use egui::{Rect, Vec2, vec2};
use egui_snarl::{NodeId, Snarl};

/// Room kept between a placed node and the others, in graph units.
const GAP: f32 = 16.0;
/// The grid the nearest free spot is looked for on, and how many steps out it looks.
const STEP: f32 = 20.0;
const STEPS: i32 = 40;
/// What the editor draws a node with at a zoom of one or more (graph units, measured on
/// the presets): its title and margins, a row per pin, the thumbnail under the pins; a
/// character of the title and of a pin's name, a number field, a colour swatch, the
/// words shown for a position or a pin to connect, the pins and margins across.
const TITLE: f32 = 46.0;
const ROW: f32 = 21.0;
const THUMBNAIL: f32 = 67.0;
const TITLE_CHAR: f32 = 12.0;
const LABEL_CHAR: f32 = 7.0;
const FIELD: f32 = 48.0;
const SWATCH: f32 = 40.0;
const WORD: f32 = 56.0;
const ACROSS: f32 = 40.0;
const MIN_WIDTH: f32 = 140.0;

/// Moves the nodes `placed` of `snarl` together (their layout kept) to the nearest spot,
/// from where they are, where none of them lies on another node. `drawn` gives where
/// the other nodes were last drawn (graph coordinates), if they were.
///
/// (Sizes of nodes never drawn are this file's estimate: `crate::graph::layout`'s node
/// footprints are to take its place.)
pub fn clear_of(
    snarl: &mut Snarl<Node>,
    placed: &[NodeId],
    drawn: impl Fn(NodeId) -> Option<Rect>,
) {
    let rect = |id: NodeId| {
        let info = snarl.get_node_info(id)?;
        let size = drawn(id)
            .filter(|_| !placed.contains(&id))
            .map_or_else(|| footprint(&info.value), |rect| rect.size());
        Some(Rect::from_min_size(info.pos, size))
    };
    let block: Vec<Rect> = placed.iter().filter_map(|id| rect(*id)).collect();
    let Some(bounds) = block.iter().copied().reduce(Rect::union) else {
        return;
    };
    let reach = bounds.expand(STEP * STEPS as f32 + GAP);
    let others: Vec<Rect> = snarl
        .node_ids()
        .filter(|(id, _)| !placed.contains(id))
        .filter_map(|(id, _)| rect(id))
        .filter(|other| other.intersects(reach))
        .map(|other| other.expand(GAP))
        .collect();
    let clear = |offset: Vec2| {
        block.iter().all(|rect| {
            let rect = rect.translate(offset);
            others.iter().all(|other| !other.intersects(rect))
        })
    };
    let offset = nearest_first()
        .find(|offset| clear(*offset))
        .unwrap_or_else(|| {
            // Nothing free near: below every node.
            let bottom = others.iter().map(|r| r.max.y).fold(bounds.min.y, f32::max);
            vec2(0.0, bottom - bounds.min.y)
        });
    for id in placed {
        if let Some(info) = snarl.get_node_info_mut(*id) {
            info.pos += offset;
        }
    }
}

/// The offsets of the search grid, nearest first (ties in a fixed order).
fn nearest_first() -> impl Iterator<Item = Vec2> {
    let mut steps: Vec<(i32, i32)> = (-STEPS..=STEPS)
        .flat_map(|y| (-STEPS..=STEPS).map(move |x| (x, y)))
        .collect();
    // Of spots as near, below and right first.
    steps.sort_by_key(|&(x, y)| (x * x + y * y, y < 0, x < 0, y, x));
    steps
        .into_iter()
        .map(|(x, y)| vec2(x as f32, y as f32) * STEP)
}

/// How big the editor draws `node` (unwired, at a zoom of one or more), reckoned from
/// its title and pins.
fn footprint(node: &Node) -> Vec2 {
    let signature = node.kind.signature();
    let chars = |text: &str| text.chars().count() as f32;
    let field = |pin: &InputPin| match (&pin.default, pin.ty) {
        (PinDefault::Const(_), ValueType::Color) => SWATCH,
        (PinDefault::Const(_), ty) => ty.width() as f32 * FIELD,
        (PinDefault::Position | PinDefault::Required, _) => WORD,
    };
    let inputs = signature
        .inputs
        .iter()
        .map(|pin| chars(pin.name) * LABEL_CHAR + field(pin))
        .fold(0.0, f32::max);
    let outputs = signature
        .outputs
        .iter()
        .map(|pin| chars(pin.name) * LABEL_CHAR)
        .fold(0.0, f32::max);
    let title = chars(node.display_name()) * TITLE_CHAR + ACROSS;
    let width = title.max(inputs + outputs + ACROSS).max(MIN_WIDTH);
    let rows = signature.inputs.len().max(signature.outputs.len()) as f32;
    let thumbnail = if signature.outputs.is_empty() {
        0.0
    } else {
        THUMBNAIL
    };
    vec2(width, TITLE + ROW * rows + thumbnail)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::app::canvas::snarl_model::snarl_from_graph;
    use crate::graph::NodeKind;
    use egui::Pos2;

    fn corner(snarl: &Snarl<Node>, id: NodeId) -> Pos2 {
        snarl.get_node_info(id).expect("a node").pos
    }

    fn rect(snarl: &Snarl<Node>, id: NodeId) -> Rect {
        Rect::from_min_size(corner(snarl, id), footprint(&snarl[id]))
    }

    #[test]
    fn a_node_put_on_others_moves_to_the_nearest_free_spot() {
        let graph = crate::app::preset("marble").expect("the marble preset");
        let mut snarl = snarl_from_graph(&graph);
        let first = snarl.node_ids().next().expect("a node").0;
        let on_it = corner(&snarl, first) + vec2(10.0, 10.0);
        let node = Node::new(crate::graph::NodeId(900), NodeKind::Material);
        let new = snarl.insert_node(on_it, node);
        clear_of(&mut snarl, &[new], |_| None);
        let placed = rect(&snarl, new);
        for (id, _) in snarl.node_ids().filter(|(id, _)| *id != new) {
            assert!(!rect(&snarl, id).intersects(placed), "on node {id:?}");
        }
        assert!(
            (placed.min - on_it).length() < 800.0,
            "moved far: {placed:?}"
        );
        // A spot already free is kept.
        let free = placed.min;
        clear_of(&mut snarl, &[new], |_| None);
        assert_eq!(corner(&snarl, new), free);
    }

    #[test]
    fn placed_nodes_move_together_and_drawn_sizes_count() {
        let mut snarl = Snarl::new();
        let kind = || NodeKind::Material;
        let old = snarl.insert_node(Pos2::ZERO, Node::new(crate::graph::NodeId(1), kind()));
        let a = snarl.insert_node(Pos2::ZERO, Node::new(crate::graph::NodeId(2), kind()));
        let b = snarl.insert_node(
            Pos2::new(0.0, 400.0),
            Node::new(crate::graph::NodeId(3), kind()),
        );
        // The old node was drawn 1000 units wide: nothing may land there.
        let drawn = |id| (id == old).then(|| Rect::from_min_size(Pos2::ZERO, vec2(1000.0, 50.0)));
        clear_of(&mut snarl, &[a, b], drawn);
        assert_eq!(corner(&snarl, b) - corner(&snarl, a), vec2(0.0, 400.0));
        let wide = Rect::from_min_size(Pos2::ZERO, vec2(1000.0, 50.0));
        assert!(!wide.intersects(rect(&snarl, a)) && !wide.intersects(rect(&snarl, b)));
    }
}
