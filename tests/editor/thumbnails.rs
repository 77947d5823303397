//! Thumbnails on nodes and wires: each node's body shows its output, drawn on the GPU
//! as the CPU evaluator computes it; they switch off per node and all at once; a
//! parameter edit redraws only the tiles it reaches, without recompiling.

use crate::support::{
    editor, flat_wood_editor, press, retype_drag_value, scratch, screen, select_node, window_image,
};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use std::collections::{BTreeMap, BTreeSet};
use veneer::app::{TILE_PIXELS, VeneerApp};
use veneer::eval::{Evaluator, Surface};
use veneer::graph::{Graph, NodeId, NodeKind, PinRef, Value, ValueType};
use veneer::nodes::{Constant, Split};

/// Steps the editor until every thumbnail is drawn as the graph now is.
pub fn settle(harness: &mut Harness<'static, VeneerApp>) {
    let started = std::time::Instant::now();
    loop {
        harness.step();
        if harness.state().thumbnails().settled() && !harness.state().thumbnails().pins().is_empty()
        {
            // One more frame, so the node bodies show the last tiles that came in.
            harness.step();
            return;
        }
        let error = harness.state().thumbnails().error.clone();
        assert!(error.is_none(), "thumbnails failed: {error:?}");
        assert!(
            started.elapsed() < std::time::Duration::from_secs(120),
            "the thumbnails did not settle"
        );
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
}

/// A constant colour, the position, and the position's x (a grey ramp), over a preview
/// square from 0 to 1 in x and z.
fn simple_graph() -> (Graph, NodeId, NodeId, NodeId) {
    let mut graph = Graph {
        name: "simple".into(),
        ..Graph::default()
    };
    graph.preview.center = (0.5, 0.0, 0.5);
    graph.preview.size = 0.5;
    let colour = graph.add(
        "orange",
        NodeKind::Constant(Constant {
            ty: ValueType::Color,
        }),
    );
    graph.set_input(colour, "value", Value::Color(0.8, 0.3, 0.1));
    let position = graph.add("where", NodeKind::Position);
    let split = graph.add(
        "across",
        NodeKind::Split(Split {
            ty: ValueType::Vec3,
        }),
    );
    graph.connect(position, "position", split, "v");
    let material = graph.add("material", NodeKind::Material);
    graph.connect(colour, "value", material, "albedo");
    for (node, at) in [
        (colour, (0.0, 0.0)),
        (position, (0.0, 180.0)),
        (split, (220.0, 180.0)),
        (material, (440.0, 0.0)),
    ] {
        graph.node_mut(node).unwrap().position = at;
    }
    (graph, colour, position, split)
}

/// The colour a tile pixel should have: `pin` wired into the albedo (a vec3 through
/// `v * 0.5 + 0.5`), evaluated on the CPU at the pixel's centre, as 8-bit.
fn expected(graph: &Graph, pin: &PinRef, ty: ValueType, i: u32, j: u32) -> [u8; 3] {
    let material = graph.material().unwrap().id;
    let mut probe = graph.clone();
    probe.connect(pin.node, &pin.pin, material, "albedo");
    let evaluator = Evaluator::new(&probe).unwrap();
    let (x, y, z) = graph.preview.center;
    let size = graph.preview.size;
    let n = f64::from(TILE_PIXELS);
    let (u, v) = ((f64::from(i) + 0.5) / n, (f64::from(j) + 0.5) / n);
    let mut surface = Surface::<f32>::at([x - size + 2.0 * size * u, y, z - size + 2.0 * size * v]);
    surface.uv = [u as f32, v as f32];
    let albedo = evaluator.eval(&surface).albedo;
    albedo.map(|c| {
        let c = if ty == ValueType::Vec3 {
            c * 0.5 + 0.5
        } else {
            c
        };
        (255.0 * c.clamp(0.0, 1.0)).round() as u8
    })
}

fn open(name: &str, graph: &Graph) -> Harness<'static, VeneerApp> {
    let dir = scratch(name);
    let path = dir.join("graph.ron");
    veneer::graph::save(graph, &path).unwrap();
    let mut harness = editor(&dir, Some(path));
    settle(&mut harness);
    harness
}

#[test]
fn each_node_shows_its_output_as_the_cpu_evaluates_it() {
    let (graph, colour, position, split) = simple_graph();
    let mut harness = open("thumbnail-pixels", &graph);
    let app = harness.state();
    let pins = [
        (PinRef::new(colour, "value"), ValueType::Color),
        (PinRef::new(position, "position"), ValueType::Vec3),
        (PinRef::new(split, "x"), ValueType::Float),
    ];
    assert_eq!(
        app.thumbnails().pins(),
        &pins.clone().map(|(pin, _)| pin),
        "one tile per node with outputs, none for the material"
    );
    for (pin, ty) in &pins {
        let tile = app
            .thumbnails()
            .tile_pixels(pin)
            .expect("the tile is drawn");
        let mut worst = 0;
        for j in 0..TILE_PIXELS {
            for i in 0..TILE_PIXELS {
                let got = tile[(j * TILE_PIXELS + i) as usize];
                let want = expected(&graph, pin, *ty, i, j);
                for k in 0..3 {
                    worst = worst.max(got[k].abs_diff(want[k]));
                }
            }
        }
        assert!(worst <= 1, "{pin:?}: off by {worst} from the CPU evaluator");
    }
    // The ramp runs black to white left to right; the position's red follows x too.
    let ramp = app.thumbnails().tile_pixels(&pins[2].0).unwrap();
    assert!(ramp[0][0] < 5 && ramp[(TILE_PIXELS - 1) as usize][0] > 250);
    // The node on screen shows the tile: a 64-point square (at the view's zoom) of the
    // constant colour (F frames every node).
    press(&mut harness, egui::Key::F, false);
    harness.run_steps(2);
    let image = screen(&mut harness);
    let side = TILE_PIXELS as f32 * harness.state().graph_to_screen().scaling;
    let orange = image
        .pixels()
        .filter(|p| {
            p.0[0].abs_diff(204) <= 2 && p.0[1].abs_diff(77) <= 2 && p.0[2].abs_diff(26) <= 2
        })
        .count();
    assert!(
        orange as f32 >= side * side * 0.9,
        "the orange node's body shows {orange} orange pixels"
    );
}

/// Right-clicks the node titled `title` and clicks `entry` in its menu.
fn node_menu(harness: &mut Harness<'static, VeneerApp>, title: &str, entry: &str) {
    let position = harness.state().graph_to_screen() * harness.get_by_label(title).rect().center();
    harness.event(egui::Event::PointerMoved(position));
    for pressed in [true, false] {
        harness.event(egui::Event::PointerButton {
            pos: position,
            button: egui::PointerButton::Secondary,
            pressed,
            modifiers: Default::default(),
        });
        harness.step();
    }
    harness.run_steps(2);
    harness.get_by_label(entry).click();
    harness.run_steps(2);
}

#[test]
fn thumbnails_switch_off_per_node_and_all_at_once() {
    let (graph, colour, position, split) = simple_graph();
    let mut harness = open("thumbnail-toggles", &graph);
    node_menu(&mut harness, "where", "Hide thumbnail");
    settle(&mut harness);
    let shown = |harness: &Harness<'static, VeneerApp>| {
        harness
            .state()
            .thumbnails()
            .pins()
            .iter()
            .map(|pin| pin.node)
            .collect::<Vec<_>>()
    };
    assert_eq!(shown(&harness), [colour, split]);
    assert!(!harness.state().thumbnails().shows(position));

    // T hides them all: no node body, no tile; the View menu brings them back.
    press(&mut harness, egui::Key::T, false);
    harness.run_steps(2);
    assert!(!harness.state().thumbnails().enabled);
    assert!(harness.state().thumbnails().pins().is_empty());
    harness.get_by_label("View").click();
    harness.run();
    harness.get_by_label("☐ Node thumbnails").click();
    settle(&mut harness);
    assert_eq!(
        shown(&harness),
        [colour, split],
        "the hidden node stays hidden"
    );
    node_menu(&mut harness, "where", "Show thumbnail");
    settle(&mut harness);
    assert_eq!(shown(&harness), [colour, position, split]);
}

/// The nodes whose output `changed` reaches (itself included).
fn downstream(graph: &Graph, changed: NodeId) -> BTreeSet<NodeId> {
    let mut reached = BTreeSet::from([changed]);
    let mut readers: BTreeMap<NodeId, Vec<NodeId>> = BTreeMap::new();
    for wire in &graph.wires {
        readers
            .entry(wire.from.node)
            .or_default()
            .push(wire.to.node);
    }
    let mut stack = vec![changed];
    while let Some(node) = stack.pop() {
        for reader in readers.get(&node).into_iter().flatten() {
            if reached.insert(*reader) {
                stack.push(*reader);
            }
        }
    }
    reached
}

#[test]
fn a_parameter_edit_redraws_only_the_tiles_it_reaches_without_recompiling() {
    let dir = scratch("thumbnail-edit");
    let mut harness = flat_wood_editor(&dir);
    settle(&mut harness);
    let app = harness.state();
    let tiles = app.thumbnails().pins().len();
    assert_eq!(
        tiles,
        app.document().graph.nodes.len() - 1,
        "every node but the material"
    );
    assert_eq!(
        app.thumbnails().tiles_drawn,
        tiles as u64,
        "each drawn once on opening"
    );
    let compiles = app.thumbnails().atlas.compiles;
    let graph = app.document().graph.clone();
    let tint = graph
        .nodes
        .iter()
        .find(|n| n.label == "tint amount")
        .unwrap()
        .id;

    select_node(&mut harness, "tint amount");
    retype_drag_value(&mut harness, "0.100", "0.3");
    settle(&mut harness);
    let app = harness.state();
    let redrawn: BTreeSet<NodeId> = app
        .thumbnails()
        .last_drawn
        .iter()
        .map(|pin| pin.node)
        .collect();
    let mut reached = downstream(&graph, tint);
    reached.retain(|node| graph.node(*node).unwrap().kind != NodeKind::Material);
    assert_eq!(redrawn, reached, "tint amount, tint shade, wood colour");
    assert_eq!(app.thumbnails().tiles_drawn, (tiles + reached.len()) as u64);
    assert_eq!(
        app.thumbnails().atlas.compiles,
        compiles,
        "a value edit never recompiles"
    );
}

/// The middle of the wire from `from` to `to` on screen (snarl's curves pass through
/// the middle of their two pins).
fn wire_middle(harness: &Harness<'static, VeneerApp>, from: &PinRef, to: &PinRef) -> egui::Pos2 {
    let app = harness.state();
    let a = app.pin_on_screen(from, true).expect("the output is drawn");
    let b = app.pin_on_screen(to, false).expect("the input is drawn");
    a.lerp(b, 0.5)
}

#[test]
fn hovering_a_wire_shows_the_value_it_carries() {
    let (mut graph, _, _, split) = simple_graph();
    let material = graph.material().unwrap().id;
    // The split's second output (z: a ramp from top to bottom) is no node's thumbnail.
    graph.connect(split, "z", material, "alpha");
    let mut harness = open("thumbnail-wire", &graph);
    let z = PinRef::new(split, "z");
    assert!(!harness.state().thumbnails().pins().contains(&z));
    let middle = wire_middle(&harness, &z, &PinRef::new(material, "alpha"));
    harness.hover_at(middle);
    settle(&mut harness);
    assert!(
        crate::support::shows(&harness, "across · z"),
        "the tooltip names the wire"
    );
    let tile = harness
        .state()
        .thumbnails()
        .tile_pixels(&z)
        .expect("the wire's tile");
    for (i, j) in [(5, 2), (30, 33), (60, 61)] {
        let got = tile[(j * TILE_PIXELS + i) as usize];
        let want = expected(&graph, &z, ValueType::Float, i, j);
        assert!(
            (0..3).all(|k| got[k].abs_diff(want[k]) <= 1),
            "({i}, {j}): {got:?}, the CPU says {want:?}"
        );
    }
    // Off the wire, no tooltip.
    harness.hover_at(middle + egui::vec2(0.0, 60.0));
    harness.run_steps(2);
    assert!(!crate::support::shows(&harness, "across · z"));
}

#[test]
fn a_node_dropped_on_a_wire_is_inserted_and_one_undo_takes_it_out() {
    let (mut graph, colour, _, _) = simple_graph();
    let material = graph.material().unwrap().id;
    let tint = graph.add(
        "tint",
        NodeKind::Constant(Constant {
            ty: ValueType::Color,
        }),
    );
    graph.node_mut(tint).unwrap().position = (220.0, 360.0);
    let mut harness = open("thumbnail-drop", &graph);
    let before = harness.state().document().graph.clone();
    let target = wire_middle(
        &harness,
        &PinRef::new(colour, "value"),
        &PinRef::new(material, "albedo"),
    );
    // Drag the tint node by its title onto the middle of the wire, in steps.
    let grab = harness.state().graph_to_screen() * harness.get_by_label("tint").rect().center();
    harness.event(egui::Event::PointerMoved(grab));
    harness.event(egui::Event::PointerButton {
        pos: grab,
        button: egui::PointerButton::Primary,
        pressed: true,
        modifiers: Default::default(),
    });
    harness.step();
    for k in 1..=10 {
        harness.event(egui::Event::PointerMoved(
            grab.lerp(target, k as f32 / 10.0),
        ));
        harness.step();
    }
    harness.event(egui::Event::PointerButton {
        pos: target,
        button: egui::PointerButton::Primary,
        pressed: false,
        modifiers: Default::default(),
    });
    harness.run_steps(3);
    let graph = &harness.state().document().graph;
    let into = |node: NodeId, pin: &str| graph.wire_into(node, pin).map(|w| w.from.clone());
    assert_eq!(into(tint, "value"), Some(PinRef::new(colour, "value")));
    assert_eq!(into(material, "albedo"), Some(PinRef::new(tint, "value")));
    press(&mut harness, egui::Key::Z, true);
    assert_eq!(
        harness.state().document().graph,
        before,
        "one undo puts the wire and the node back"
    );
}

/// The pixels of the tile of the node titled `title` (its first output) in the level
/// shown, once the thumbnails settle.
fn tile_of(harness: &mut Harness<'static, VeneerApp>, title: &str) -> Vec<[u8; 4]> {
    settle(harness);
    let node = harness
        .state()
        .level_nodes()
        .into_iter()
        .find(|node| node.label == title)
        .unwrap_or_else(|| panic!("no node '{title}' in the level shown"));
    let output = node.kind.signature().outputs[0].name;
    let pin = PinRef::new(node.id, output);
    let tile = harness.state().thumbnails().tile_pixels(&pin);
    tile.unwrap_or_else(|| panic!("no tile for '{title}'"))
}

#[test]
fn inside_a_group_each_node_shows_its_output_in_the_groups_first_instance() {
    let dissolved = tile_of(
        &mut flat_wood_editor(&scratch("thumbnail-flat")),
        "ring sharp",
    );
    let mut harness = editor(&scratch("thumbnail-group"), None);
    select_node(&mut harness, "wood");
    press(&mut harness, egui::Key::Tab, false);
    harness.run_steps(4);
    assert_eq!(harness.state().group_path(), ["ring_wood"]);
    let inside = tile_of(&mut harness, "ring sharp");
    let worst = inside
        .iter()
        .zip(&dissolved)
        .flat_map(|(a, b)| (0..3).map(move |k| a[k].abs_diff(b[k])))
        .max();
    assert_eq!(inside.len(), dissolved.len());
    assert!(
        worst <= Some(1),
        "off by {worst:?} from the group dissolved"
    );
    let rings = tile_of(&mut harness, "rings");
    assert_ne!(rings, inside, "each node its own tile");
    // Back at the top level, the group node's tile is the group's first output.
    press(&mut harness, egui::Key::Tab, false);
    harness.run_steps(4);
    assert!(harness.state().group_path().is_empty());
    tile_of(&mut harness, "wood");
}

/// The shipped texture graph with the fewest passes: a noise, its blur and its normal.
fn blurred_noise() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("graphs/texture/blurred_noise.ron")
}

#[test]
fn nodes_reading_buffers_show_them_over_the_unit_tile_as_the_flat_view_draws_them() {
    let graph = veneer::graph::load(&blurred_noise()).unwrap();
    let mut harness = open("thumbnail-buffers", &graph);
    // The blur, what reads it, and the height's normal (a stage over the noise's buffer).
    for title in ["soft", "tint", "relief"] {
        tile_of(&mut harness, title);
    }
    // The material's albedo is the tint: its tile is the material drawn flat over the
    // unit tile, with its passes rendered at the preview's pass size.
    let tint = tile_of(&mut harness, "tint");
    let gpu = veneer::render::GpuContext::new().unwrap();
    let compiled = veneer::codegen::compile(&graph, &Default::default()).unwrap();
    let mut flat = veneer::render::FlatRenderer::for_compiled(&gpu, &compiled).unwrap();
    flat.set_pass_size(Some(veneer::render::PREVIEW_PASS_SIZE));
    let drawn = flat
        .render(&gpu, veneer::bake::UNIT_TILE, TILE_PIXELS, 0.0)
        .unwrap();
    let worst = tint
        .iter()
        .zip(&drawn)
        .flat_map(|(got, want)| {
            (0..3).map(move |k| got[k].abs_diff((255.0 * want[k].clamp(0.0, 1.0)).round() as u8))
        })
        .max();
    assert_eq!(tint.len(), drawn.len());
    assert!(worst <= Some(2), "off by {worst:?} from the flat render");
}

#[test]
fn a_texture_graph_shows_its_unit_tile_beside_the_mesh_and_a_single_pass_one_does_not() {
    let mut harness = editor(&scratch("tile-beside"), Some(blurred_noise()));
    let started = std::time::Instant::now();
    // The tile is drawn once the main preview is: wait for its picture under the label.
    loop {
        harness.step();
        let strip = harness.query_by_label("unit tile").map(|label| {
            let scale = harness.ctx.pixels_per_point();
            let rect = label.rect();
            (
                rect.left() * scale,
                (rect.top() - 24.0) * scale,
                16.0 * scale,
            )
        });
        if let Some((x, y, side)) = strip {
            let image = window_image(&mut harness);
            let lightness: Vec<u32> = (0..side as u32)
                .flat_map(|dy| (0..side as u32).map(move |dx| (x as u32 + dx, y as u32 + dy)))
                .map(|(x, y)| {
                    image.get_pixel(x, y).0[..3]
                        .iter()
                        .map(|&c| u32::from(c))
                        .sum()
                })
                .collect();
            let spread = lightness.iter().max().unwrap() - lightness.iter().min().unwrap();
            // The blurred noise's ramp runs dark to light brown: no flat background.
            if spread > 30 {
                break;
            }
        }
        assert!(
            started.elapsed() < std::time::Duration::from_secs(120),
            "no tile beside the mesh"
        );
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    let mut wood = editor(&scratch("tile-beside-wood"), None);
    settle(&mut wood);
    assert!(
        wood.query_by_label("unit tile").is_none(),
        "wood has no passes"
    );
}

#[test]
fn a_texture_graphs_tiles_wait_for_a_drag_to_end_and_then_follow_it() {
    let graph = veneer::graph::load(&blurred_noise()).unwrap();
    let mut harness = open("thumbnail-drag", &graph);
    select_node(&mut harness, "grain");
    harness.run();
    let drawn = harness.state().thumbnails().tiles_drawn;
    let revision = harness.state().document().graph.clone();
    // Drag the noise's scale on its node (the inspector's field is below the window's
    // edge; the canvas's comes last, in graph coordinates) and hold the button.
    let field = harness.get_all_by_value("6.00").last().unwrap().rect();
    let from = harness.state().graph_to_screen() * field.center();
    let press = |pos, pressed| egui::Event::PointerButton {
        pos,
        button: egui::PointerButton::Primary,
        pressed,
        modifiers: Default::default(),
    };
    harness.event(egui::Event::PointerMoved(from));
    harness.run_steps(2);
    harness.event(press(from, true));
    harness.run_steps(2);
    let to = from + egui::vec2(40.0, 0.0);
    for step in 1..=8 {
        harness.event(egui::Event::PointerMoved(
            from + (to - from) * (step as f32 / 8.0),
        ));
        harness.run_steps(1);
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    harness.run_steps(4);
    assert_ne!(
        harness.state().document().graph,
        revision,
        "the drag changed the scale"
    );
    assert_eq!(
        harness.state().thumbnails().tiles_drawn,
        drawn,
        "no tile drawn while the button is held"
    );
    harness.event(press(to, false));
    settle(&mut harness);
    assert!(
        harness.state().thumbnails().tiles_drawn > drawn,
        "the tiles the drag reached are drawn once it ends"
    );
}
