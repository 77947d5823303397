//! Node footprints against what the editor draws: every node of every preset, and of
//! the groups they define, is drawn inside the footprint `veneer::graph::layout`
//! reckons for it, and no two nodes are drawn over each other, as shipped or after
//! *Arrange nodes*.

use super::support::{click_node, editor, press, scratch, wheel_notch};
use egui::{Event, Rect, pos2};
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};
use veneer::app::VeneerApp;
use veneer::graph::layout::{Bounds, bounds, footprints};
use veneer::graph::{Graph, Node, NodeId, Wire};

/// The zoom from which node titles are drawn at their usual size (24 canvas units);
/// zoomed out further they grow to stay legible, past any footprint.
const LEGIBLE_ZOOM: f32 = 0.5;

/// The editor on the preset `name`.
fn open(name: &str) -> Harness<'static, VeneerApp> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("graphs")
        .join(format!("{name}.ron"));
    editor(&scratch(&format!("footprints-{name}")), Some(path))
}

/// Zooms in about the graph's middle until titles are drawn at their usual size, and
/// lets the nodes' sizes settle.
fn zoom_to_legible(harness: &mut Harness<'static, VeneerApp>) {
    harness.event(Event::PointerMoved(pos2(465.0, 450.0)));
    while harness.state().graph_to_screen().scaling < LEGIBLE_ZOOM {
        wheel_notch(harness);
    }
    harness.run_steps(12);
}

/// A widget's rectangle (canvas units).
fn rect_of(node: &egui_kittest::Node<'_>) -> Option<Rect> {
    let b = node.accesskit_node().bounding_box()?;
    Some(Rect::from_min_max(
        pos2(b.x0 as f32, b.y0 as f32),
        pos2(b.x1 as f32, b.y1 as f32),
    ))
}

/// One node as the editor drew it: its frame, and its thumbnail where it has one.
struct Drawn {
    id: NodeId,
    frame: Rect,
    thumbnail: Option<Rect>,
}

/// Where each node of the level shown was drawn, found by its position: a node's frame
/// is the largest widget whose top-left corner is its footprint's (the frame's margin up
/// and left of the node's position); its thumbnail is the picture named after it that
/// starts within the frame's width.
fn drawn(harness: &Harness<'static, VeneerApp>, nodes: &[Node]) -> Vec<Drawn> {
    let frames: Vec<Rect> = harness
        .query_all_by(|node| node.role() == egui::accesskit::Role::Unknown)
        .filter_map(|node| rect_of(&node))
        .collect();
    // A footprint's corner does not depend on the node's wires.
    let corners = bounds(nodes, &[]);
    nodes
        .iter()
        .zip(corners)
        .map(|(node, footprint)| {
            let corner = pos2(footprint.min.0, footprint.min.1);
            let frame = *frames
                .iter()
                .filter(|rect| (rect.min - corner).length() < 0.5)
                .max_by(|a, b| a.area().total_cmp(&b.area()))
                .unwrap_or_else(|| panic!("{node} is not drawn at {:?}", node.position));
            let thumbnail = harness
                .query_all_by_label(&format!("{} thumbnail", node.title()))
                .filter_map(|picture| rect_of(&picture))
                .find(|rect| frame.x_range().contains(rect.min.x));
            Drawn {
                id: node.id,
                frame,
                thumbnail,
            }
        })
        .collect()
}

/// Checks that each of `nodes` (joined by `wires`) is drawn inside its footprint and
/// that no two are drawn over each other; `level` names them in messages. Returns the
/// largest margin a footprint leaves beyond its drawn node, in width and height.
fn check_level(
    harness: &Harness<'static, VeneerApp>,
    level: &str,
    nodes: &[Node],
    wires: &[Wire],
) -> (f32, f32) {
    let rects = drawn(harness, nodes);
    let reckoned = footprints(nodes, wires);
    let mut spare = (0.0f32, 0.0f32);
    for (drawn, footprint) in rects.iter().zip(&reckoned) {
        let node = nodes
            .iter()
            .find(|node| node.id == drawn.id)
            .expect("a node");
        let Bounds { min, max } = footprint.at(node.position);
        let inside = |rect: &Rect| {
            min.0 <= rect.min.x && min.1 <= rect.min.y && rect.max.x <= max.0 && rect.max.y <= max.1
        };
        // The thumbnail under the pins too (a picture beside the pins once pushed it a
        // thumbnail's height down, out of the frame and over the next node).
        if let Some(thumbnail) = drawn.thumbnail {
            assert!(
                inside(&thumbnail),
                "{level}: {node}'s thumbnail is drawn at {thumbnail:?}, outside its footprint"
            );
        }
        let rect = drawn.frame;
        assert!(
            inside(&rect),
            "{level}: {node} is drawn {:.1} × {:.1}, its footprint is {} × {}",
            rect.width(),
            rect.height(),
            footprint.width,
            footprint.height
        );
        spare.0 = spare.0.max(footprint.width - rect.width());
        spare.1 = spare.1.max(footprint.height - rect.height());
    }
    assert_apart(level, &rects);
    spare
}

/// Checks that no two of the drawn nodes `rects` overlap.
fn assert_apart(level: &str, rects: &[Drawn]) {
    for (
        k,
        Drawn {
            id: a,
            frame: first,
            ..
        },
    ) in rects.iter().enumerate()
    {
        for Drawn {
            id: b,
            frame: second,
            ..
        } in &rects[k + 1..]
        {
            assert!(
                !first.intersects(*second),
                "{level}: nodes {a} and {b} are drawn over each other: {first:?}, {second:?}"
            );
        }
    }
}

/// The nodes of a group's definition and its wires.
fn inside(graph: &Graph, group: &str) -> (Vec<Node>, Vec<Wire>) {
    let definition = &graph.groups[group];
    (definition.nodes.clone(), definition.wires.clone())
}

#[test]
fn every_preset_node_is_drawn_inside_its_footprint_and_clear_of_the_others() {
    let mut spare = (0.0f32, 0.0f32);
    for (name, _) in veneer::graph::PRESETS {
        let graph = veneer::graph::preset(name).expect("a preset");
        let mut harness = open(name);
        zoom_to_legible(&mut harness);
        let top = check_level(&harness, name, &graph.nodes, &graph.wires);
        spare = (spare.0.max(top.0), spare.1.max(top.1));
        let instances = graph
            .nodes
            .iter()
            .filter_map(|node| Some((node.title(), veneer::graph::group::group_name(node)?)));
        for (title, group) in instances {
            click_node(&mut harness, &title);
            press(&mut harness, egui::Key::Tab, false);
            zoom_to_legible(&mut harness);
            let (nodes, wires) = inside(&graph, group);
            let level = format!("{name} › {group}");
            let within = check_level(&harness, &level, &nodes, &wires);
            spare = (spare.0.max(within.0), spare.1.max(within.1));
            press(&mut harness, egui::Key::Tab, false);
        }
    }
    // Footprints more generous than this would lay nodes out needlessly far apart (a
    // footprint allows for a warning sign, numbers of four decimals and, inside groups
    // where none is drawn yet, a thumbnail).
    assert!(spare.0 < 120.0 && spare.1 < 100.0, "{spare:?}");
}

#[test]
fn arranged_nodes_are_never_drawn_over_each_other() {
    for (name, _) in veneer::graph::PRESETS {
        let mut harness = open(name);
        harness.get_by_label("Edit").click_accesskit();
        harness.run_steps(2);
        harness.get_by_label("Arrange nodes").click_accesskit();
        harness.run_steps(4);
        zoom_to_legible(&mut harness);
        let mut arranged = veneer::graph::preset(name).expect("a preset");
        veneer::graph::layout::arrange(&mut arranged);
        assert_apart(name, &drawn(&harness, &arranged.nodes));
    }
}
