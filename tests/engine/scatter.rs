//! Tile samplers and local frames (issue 33): an instance's local point maps back
//! through its transform; max of instances that do not overlap is their sum; a mask of
//! 0 removes every instance; no instance is cut at a cell border (against a brute-force
//! loop over every instance); a pattern reaching back to its own sampler is refused; a
//! group placed per instance draws as the same nodes placed by hand; instances keep
//! their random numbers when the grid grows or the graph changes elsewhere. The GPU
//! agrees with the CPU on each graph.

use crate::support::{cpu_flat_rgb8, difference, flat_rgb8};
use proptest::prelude::*;
use std::collections::BTreeSet;
use veneer::eval::Evaluator;
use veneer::graph::{Basis, Graph, MathOp, NodeId, NodeKind, Value, ValueType};
use veneer::nodes::formulas::instances::{self, BlendState, GridSettings, Placed, TileBlend};
use veneer::nodes::{Combine, Math, Noise, Split, TileSampler};
use veneer::render::FlatRect;

const RECT: FlatRect = FlatRect {
    x0: -0.3,
    z0: -0.2,
    x1: 2.3,
    z1: 1.9,
    y: 0.0,
};

/// Settings whose instances overhang their cells: turned, moved, scaled past the cell,
/// odd rows offset, non-square cells.
const OVERHANGING: [(&str, Value); 9] = [
    ("columns", Value::Float(5.0)),
    ("rows", Value::Float(4.0)),
    ("size", Value::Vec2(2.0, 1.5)),
    ("row_offset", Value::Float(0.5)),
    ("position_random", Value::Float(0.3)),
    ("rotation_random", Value::Float(1.0)),
    ("scale", Value::Float(1.4)),
    ("scale_xy", Value::Vec2(1.3, 0.7)),
    ("scale_random", Value::Float(0.3)),
];

/// A graph with one tile sampler set by `settings`, its outputs `shown` (up to three
/// float lanes: "height", "mask", "id", "random", "local.x", "local.y") as the albedo;
/// with the sampler's id.
fn sampler_graph(
    blend: TileBlend,
    settings: &[(&str, Value)],
    shown: [&str; 3],
) -> (Graph, NodeId) {
    let mut graph = Graph::default();
    let sampler = graph.add("sampler", NodeKind::TileSampler(TileSampler { blend }));
    for (pin, value) in settings {
        graph.set_input(sampler, pin, *value);
    }
    let local = graph.add(
        "local parts",
        NodeKind::Split(Split {
            ty: ValueType::Vec2,
        }),
    );
    graph.connect(sampler, "local", local, "v");
    let colour = graph.add(
        "shown",
        NodeKind::Combine(Combine {
            ty: ValueType::Color,
        }),
    );
    for (lane, output) in ["x", "y", "z"].into_iter().zip(shown) {
        match output {
            "local.x" => graph.connect(local, "x", colour, lane),
            "local.y" => graph.connect(local, "y", colour, lane),
            output => graph.connect(sampler, output, colour, lane),
        }
    }
    let material = graph.add("material", NodeKind::Material);
    graph.connect(colour, "v", material, "albedo");
    (graph, sampler)
}

/// The grid settings of `settings` over the defaults (as the node's pins give them).
fn grid_settings(settings: &[(&str, Value)]) -> GridSettings<f64> {
    let value = |pin: &str, default: Value| {
        let found = settings.iter().find(|(name, _)| *name == pin);
        found.map_or(default, |(_, value)| *value).components()
    };
    let float = |pin: &str, default: f64| value(pin, Value::Float(default))[0];
    let pair = |pin: &str, x: f64, y: f64| {
        let [a, b, _] = value(pin, Value::Vec2(x, y));
        [a, b]
    };
    GridSettings {
        size: pair("size", 1.0, 1.0),
        counts: [float("columns", 8.0), float("rows", 8.0)],
        offsets: [float("row_offset", 0.0), float("column_offset", 0.0)],
        jitter: float("position_random", 0.0),
        rotation: float("rotation", 0.0),
        rotation_random: float("rotation_random", 0.0),
        scale: float("scale", 1.0),
        scale_xy: pair("scale_xy", 1.0, 1.0),
        scale_random: float("scale_random", 0.0),
        seed: float("seed", 0.0),
        footprint: 0.0,
        splat: 0.0,
    }
}

/// Points over `RECT`, `n` × `n`, off the pixel centres.
fn points(n: usize) -> Vec<[f64; 3]> {
    let step = |k: usize, lo: f64, hi: f64| lo + (hi - lo) * (k as f64 + 0.37) / n as f64;
    (0..n * n)
        .map(|k| {
            [
                step(k % n, RECT.x0, RECT.x1),
                0.0,
                step(k / n, RECT.z0, RECT.z1),
            ]
        })
        .collect()
}

/// The albedo of `graph` at `point`, in f64.
fn albedo(evaluator: &Evaluator, point: [f64; 3]) -> [f64; 3] {
    evaluator.eval::<f64>(&evaluator.flat_surface(point)).albedo
}

/// The GPU's flat render of `graph` agrees with the CPU's (within 2/255 on 99.5% of
/// pixels).
fn gpu_agrees(graph: &Graph, what: &str) {
    let source = veneer::codegen::compile(graph, &Default::default())
        .unwrap_or_else(|e| panic!("{what}: {e}"))
        .module
        .source;
    let diff = difference(
        &cpu_flat_rgb8(graph, RECT, 64),
        &flat_rgb8(&source, RECT, 64),
        3,
        2,
    );
    assert!(
        diff.share_outside <= 0.005,
        "{what}: CPU and GPU differ: {diff}"
    );
}

#[test]
fn an_instances_local_point_maps_back_through_its_transform() {
    let (graph, _) = sampler_graph(TileBlend::Max, &OVERHANGING, ["local.x", "local.y", "id"]);
    let evaluator = Evaluator::new(&graph).expect("checks");
    let grid_of = |point: [f64; 3]| instances::setup(point, &grid_settings(&OVERHANGING));
    let mut checked = 0;
    for point in points(40) {
        let [x, y, id] = albedo(&evaluator, point);
        let grid = grid_of(point);
        // The instance that decided the point, found by its number among those that
        // reach it.
        let mut decided: Option<Placed<f64>> = None;
        instances::search(&grid, |placed| {
            if placed.instance.id == id && (placed.local[0] - x).abs() < 1e-9 {
                decided = Some(*placed);
            }
        });
        let Some(placed) = decided else {
            continue;
        };
        // Forward through the transform: scaled to the instance, turned, moved to its
        // centre, out of cell units into the tile holding the point.
        let scaled = [0, 1].map(|k| [x, y][k] * placed.size[k] * grid.cell[k]);
        let (c, s) = (placed.angle.cos(), placed.angle.sin());
        let turned = [c * scaled[0] - s * scaled[1], s * scaled[0] + c * scaled[1]];
        let back = [0, 1].map(|k| grid.corner[k] + placed.centre[k] * grid.cell[k] + turned[k]);
        let distance = (back[0] - point[0]).hypot(back[1] - point[2]);
        assert!(distance < 1e-9, "{point:?} maps back to {back:?}");
        assert!(
            x.abs() <= 0.5 && y.abs() <= 0.5,
            "{point:?}: local ({x}, {y})"
        );
        checked += 1;
    }
    assert!(checked > 800, "only {checked} points were covered");
    gpu_agrees(&graph, "local point");
}

#[test]
fn blend_max_of_instances_that_do_not_overlap_is_their_sum() {
    let apart = [
        ("columns", Value::Float(6.0)),
        ("rows", Value::Float(5.0)),
        ("scale", Value::Float(0.8)),
        ("position_random", Value::Float(0.1)),
        ("height_random", Value::Float(0.8)),
    ];
    let shown = ["height", "mask", "random"];
    let (max, _) = sampler_graph(TileBlend::Max, &apart, shown);
    let (add, _) = sampler_graph(TileBlend::Add, &apart, shown);
    let (max_cpu, add_cpu) = (Evaluator::new(&max).unwrap(), Evaluator::new(&add).unwrap());
    let mut covered = 0;
    for point in points(48) {
        let (a, b) = (albedo(&max_cpu, point), albedo(&add_cpu, point));
        assert_eq!(a, b, "at {point:?}");
        covered += usize::from(a[1] > 0.0);
    }
    assert!(covered > 500, "{covered} points covered");
    let render = |graph: &Graph| {
        let source = veneer::codegen::compile(graph, &Default::default()).unwrap();
        flat_rgb8(&source.module.source, RECT, 64)
    };
    let diff = difference(&render(&max), &render(&add), 3, 1);
    assert_eq!(diff.share_outside, 0.0, "GPU: max and add differ: {diff}");
    gpu_agrees(&max, "max");
}

#[test]
fn a_mask_of_zero_removes_every_instance() {
    // Wired: a noise times zero, read at each instance's centre.
    let (mut wired, sampler) =
        sampler_graph(TileBlend::Max, &OVERHANGING, ["height", "mask", "id"]);
    let noise = wired.add(
        "noise",
        NodeKind::Noise(Noise {
            basis: Basis::Gradient,
            period: 0,
        }),
    );
    let zero = wired.add(
        "zero",
        NodeKind::Math(Math {
            op: MathOp::Multiply,
            ty: ValueType::Float,
        }),
    );
    wired.connect(noise, "value", zero, "a");
    wired.set_input(zero, "b", Value::Float(0.0));
    wired.connect(zero, "result", sampler, "mask");
    // Unwired: the constant 0.
    let mut constant = OVERHANGING.to_vec();
    constant.push(("mask", Value::Float(0.0)));
    let (unwired, _) = sampler_graph(TileBlend::Max, &constant, ["height", "mask", "id"]);
    for (graph, what) in [(&wired, "wired"), (&unwired, "constant")] {
        let evaluator = Evaluator::new(graph).unwrap();
        for point in points(24) {
            assert_eq!(albedo(&evaluator, point), [0.0; 3], "{what} at {point:?}");
        }
        let source = veneer::codegen::compile(graph, &Default::default()).unwrap();
        let pixels = flat_rgb8(&source.module.source, RECT, 48);
        assert!(
            pixels.iter().all(|&v| v == 0),
            "{what}: the GPU draws an instance"
        );
    }
}

/// The sampler's height, mask and deciding instance at `point`, by looping over every
/// instance of the nine tiles around the point's (no search).
fn brute_force(settings: &GridSettings<f64>, point: [f64; 3]) -> [f64; 3] {
    let grid = instances::setup(point, settings);
    let [columns, rows] = grid.counts.map(|n| n as i32);
    let mut state = BlendState::start(TileBlend::Over);
    for row in -rows..2 * rows {
        for column in -columns..2 * columns {
            let placed = instances::place(&grid, column, row);
            if placed.inside && instances::keeps(&grid, &placed, 1.0, 1.0) {
                let height = instances::height(&placed, 1.0, 0.0);
                state.blend(
                    &placed,
                    instances::dome(placed.local),
                    height,
                    TileBlend::Over,
                );
            }
        }
    }
    let id = state.winner.map_or(0.0, |winner| winner.instance.id);
    [state.value, state.mask, id]
}

#[test]
fn no_instance_is_cut_at_a_cell_border() {
    let (graph, _) = sampler_graph(TileBlend::Over, &OVERHANGING, ["height", "mask", "id"]);
    let evaluator = Evaluator::new(&graph).unwrap();
    let settings = grid_settings(&OVERHANGING);
    let mut covered = 0;
    for point in points(64) {
        let expected = brute_force(&settings, point);
        let got = albedo(&evaluator, point);
        assert_eq!(got, expected, "at {point:?}");
        covered += usize::from(got[1] > 0.0);
    }
    assert!(covered > 2000, "{covered} points covered");
    gpu_agrees(&graph, "overhanging instances");
}

#[test]
fn a_pattern_that_reads_its_own_sampler_is_refused_naming_the_nodes() {
    let (mut graph, sampler) = sampler_graph(TileBlend::Max, &[], ["height", "mask", "id"]);
    let lift = graph.add(
        "lift",
        NodeKind::Math(Math {
            op: MathOp::Add,
            ty: ValueType::Float,
        }),
    );
    graph.connect(sampler, "height", lift, "a");
    graph.connect(lift, "result", sampler, "pattern");
    let message = crate::support::refusal(&graph);
    assert!(
        message.contains("re-evaluated input 'pattern' of 'sampler'") && message.contains("'lift'"),
        "{message}"
    );
}

/// A sampler placing bumps: a noise of the local point at `scale`, raised by the
/// instance's random number; the pattern's nodes.
fn bumps_graph(scale: f64, seed: f64) -> (Graph, BTreeSet<NodeId>) {
    let (mut graph, sampler) =
        sampler_graph(TileBlend::Max, &OVERHANGING, ["height", "mask", "random"]);
    graph.set_input(sampler, "seed", Value::Float(seed));
    let noise = graph.add(
        "grain",
        NodeKind::Noise(Noise {
            basis: Basis::Gradient,
            period: 0,
        }),
    );
    graph.set_input(noise, "scale", Value::Float(scale));
    let instance = graph.add("instance", NodeKind::Instance);
    let lift = graph.add(
        "lift",
        NodeKind::Math(Math {
            op: MathOp::Add,
            ty: ValueType::Float,
        }),
    );
    graph.connect(noise, "value", lift, "a");
    graph.connect(instance, "random", lift, "b");
    graph.connect(lift, "result", sampler, "pattern");
    (graph, [noise, instance, lift].into())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    /// A group placed per instance draws as its nodes placed by hand (CPU, f64).
    #[test]
    fn a_group_placed_per_instance_is_its_nodes_placed_by_hand(scale in 0.5f64..12.0, seed in 0.0f64..50.0) {
        let (inline, pattern) = bumps_graph(scale, seed);
        let mut grouped = inline.clone();
        veneer::graph::group::group_nodes(&mut grouped, &pattern, "bumps").expect("groups");
        let (a, b) = (Evaluator::new(&inline).unwrap(), Evaluator::new(&grouped).unwrap());
        for point in points(12) {
            prop_assert_eq!(albedo(&a, point), albedo(&b, point));
        }
    }
}

#[test]
fn a_placed_group_renders_as_on_the_cpu() {
    let (mut graph, pattern) = bumps_graph(5.0, 3.0);
    veneer::graph::group::group_nodes(&mut graph, &pattern, "bumps").expect("groups");
    gpu_agrees(&graph, "a group placed per instance");
}

#[test]
fn instances_keep_their_random_numbers_when_the_grid_grows_or_the_graph_changes() {
    // Cells 0.25 wide: 4 × 4 over a tile of 1, then 8 × 8 over a tile of 2.
    let random_at = |graph: &Graph, cell: [f64; 2]| {
        let evaluator = Evaluator::new(graph).unwrap();
        let centre = [0.25 * (cell[0] + 0.5), 0.0, 0.25 * (cell[1] + 0.5)];
        albedo(&evaluator, centre)[2]
    };
    let grid = |n: f64| {
        let settings = [
            ("columns", Value::Float(n)),
            ("rows", Value::Float(n)),
            ("size", Value::Vec2(n / 4.0, n / 4.0)),
            ("seed", Value::Float(7.0)),
        ];
        sampler_graph(TileBlend::Max, &settings, ["height", "mask", "random"]).0
    };
    let (small, large) = (grid(4.0), grid(8.0));
    // The same graph with another node added first (every id moves) and an unrelated
    // edit.
    let mut edited = Graph::default();
    edited.add(
        "unrelated",
        NodeKind::Noise(Noise {
            basis: Basis::Gradient,
            period: 0,
        }),
    );
    let mut ids = std::collections::BTreeMap::new();
    for node in &small.nodes {
        let id = edited.add(&node.label, node.kind.clone());
        for (pin, value) in &node.inputs {
            edited.set_input(id, pin, *value);
        }
        ids.insert(node.id, id);
    }
    for wire in &small.wires {
        edited.connect(
            ids[&wire.from.node],
            &wire.from.pin,
            ids[&wire.to.node],
            &wire.to.pin,
        );
    }
    let mut distinct = BTreeSet::new();
    for cell in [[0.0, 0.0], [1.0, 2.0], [3.0, 3.0], [2.0, 1.0]] {
        let random = random_at(&small, cell);
        assert_eq!(
            random,
            random_at(&large, cell),
            "cell {cell:?} as the grid grows"
        );
        assert_eq!(
            random,
            random_at(&edited, cell),
            "cell {cell:?} in the edited graph"
        );
        distinct.insert(random.to_bits());
    }
    assert_eq!(distinct.len(), 4, "the cells draw distinct numbers");
}

#[test]
fn a_splatter_places_exactly_its_count_per_tile_each_numbered_once() {
    for count in [1.0, 2.0, 7.0, 40.0, 100.0, 257.0, 1000.0] {
        let settings = GridSettings {
            splat: count,
            jitter: 0.5,
            ..grid_settings(&[])
        };
        let grid = instances::setup([0.3, 0.0, 0.6], &settings);
        let [columns, rows] = grid.counts.map(|n| n as i32);
        let mut ids = BTreeSet::new();
        for row in 0..rows {
            for column in 0..columns {
                let placed = instances::place(&grid, column, row);
                if instances::keeps(&grid, &placed, 1.0, 1.0) {
                    assert!(ids.insert(placed.instance.id as u32), "{count}: id twice");
                }
            }
        }
        let expected: BTreeSet<u32> = (0..count as u32).collect();
        assert_eq!(ids, expected, "{count} instances per tile");
    }
}

/// A splatter of 60 bumps, their noise in each instance's frame, over tiles of 1.5.
fn splatter_graph(projection: veneer::nodes::sampler::Projection) -> Graph {
    let mut graph = bumps_graph(4.0, 2.0).0;
    let sampler = graph
        .nodes
        .iter()
        .find(|n| n.label == "sampler")
        .unwrap()
        .id;
    let node = graph.node_mut(sampler).unwrap();
    node.kind = NodeKind::Splatter(veneer::nodes::Splatter {
        blend: TileBlend::Max,
        projection,
    });
    node.inputs.clear();
    for (pin, value) in [
        ("count", Value::Float(60.0)),
        ("size", Value::Vec2(1.5, 1.5)),
        ("scale", Value::Float(1.3)),
        ("rotation_random", Value::Float(0.5)),
    ] {
        graph.set_input(sampler, pin, value);
    }
    graph
}

#[test]
fn a_splatter_repeats_over_its_tile_and_renders_as_on_the_cpu() {
    use veneer::nodes::sampler::Projection;
    let graph = splatter_graph(Projection::Planar);
    let evaluator = Evaluator::new(&graph).unwrap();
    let mut covered = 0;
    for point in points(24) {
        let here = albedo(&evaluator, point);
        for shift in [[1.5, 0.0, 0.0], [0.0, 0.0, -3.0], [4.5, 0.0, 1.5]] {
            let there = [point[0] + shift[0], point[1], point[2] + shift[2]];
            let moved = albedo(&evaluator, there);
            let close = (0..3).all(|k| (here[k] - moved[k]).abs() < 1e-9);
            assert!(close, "{point:?}: {here:?} but {moved:?} a tile away");
        }
        covered += usize::from(here[1] > 0.0);
    }
    assert!(covered > 200, "{covered} points covered");
    gpu_agrees(&graph, "splatter");
    // Seen from above, triplanar is planar.
    let triplanar = splatter_graph(Projection::Triplanar);
    let above = Evaluator::new(&triplanar).unwrap();
    for point in points(8) {
        assert_eq!(
            albedo(&above, point),
            albedo(&evaluator, point),
            "{point:?}"
        );
    }
}

/// Samplers, shapes and local frames export to every target, each output read back by
/// its validator where Veneer has one (the SPIR-V reader once mistyped the sampler's
/// inside test).
#[test]
fn placed_patterns_export_to_every_target() {
    use veneer::codegen::ParamMode;
    use veneer::codegen::export::{Target, export};
    use veneer::nodes::sampler::Projection;
    // The pattern's noise as a group: a group placed per instance.
    let (mut placed, pattern) = bumps_graph(5.0, 1.0);
    let grain: BTreeSet<NodeId> = (placed.nodes.iter())
        .filter(|node| pattern.contains(&node.id) && node.label == "grain")
        .map(|node| node.id)
        .collect();
    veneer::graph::group::group_nodes(&mut placed, &grain, "grain").expect("groups");
    for graph in [placed, splatter_graph(Projection::Triplanar)] {
        for (target, _, _) in Target::ALL {
            for params in [ParamMode::Baked, ParamMode::Uniform] {
                export(&graph, target, params)
                    .unwrap_or_else(|e| panic!("{target:?} {params:?}: {e}"));
            }
        }
    }
}

/// A triplanar splatter reads its mask at each instance's centre in the shaded point's
/// own coordinates, whichever plane places it: on the plane seen along x, a mask of the
/// point's x (the same for every instance there) keeps every instance or none.
#[test]
fn a_triplanar_splatter_reads_its_mask_where_the_surface_is() {
    use veneer::nodes::sampler::Projection;
    use veneer::nodes::{Splatter, Step};
    let plain = splatter_graph(Projection::Triplanar);
    let mut masked = plain.clone();
    let sampler = masked
        .nodes
        .iter()
        .find(|n| n.label == "sampler")
        .unwrap()
        .id;
    let position = masked.add("position", NodeKind::Position);
    let parts = masked.add(
        "parts",
        NodeKind::Split(Split {
            ty: ValueType::Vec3,
        }),
    );
    let right = masked.add(
        "right of 0.2",
        NodeKind::Step(Step {
            ty: ValueType::Float,
        }),
    );
    masked.connect(position, "position", parts, "v");
    masked.connect(parts, "x", right, "x");
    masked.set_input(right, "edge", Value::Float(0.2));
    masked.connect(right, "result", sampler, "mask");
    assert!(matches!(
        masked.node(sampler).unwrap().kind,
        NodeKind::Splatter(Splatter { .. })
    ));
    // The GPU's module reads the mask through the same unswizzle (validated; flat views
    // see only the plane along y).
    veneer::codegen::compile(&masked, &Default::default()).expect("compiles");
    let (plain, masked) = (
        Evaluator::new(&plain).unwrap(),
        Evaluator::new(&masked).unwrap(),
    );
    let at = |evaluator: &Evaluator, x: f64, point: [f64; 3]| {
        let surface = veneer::eval::Surface {
            normal: [1.0, 0.0, 0.0],
            ..evaluator.flat_surface([x, point[2], point[0]])
        };
        evaluator.eval::<f64>(&surface).albedo
    };
    let mut covered = 0;
    for point in points(16) {
        // x = 0.3: every centre there is right of 0.2, so all are kept.
        let kept = at(&masked, 0.3, point);
        assert_eq!(kept, at(&plain, 0.3, point), "{point:?}");
        covered += usize::from(kept[1] > 0.0);
        // x = 0.1: none is.
        assert_eq!(at(&masked, 0.1, point), [0.0; 3], "{point:?}");
    }
    assert!(covered > 50, "{covered} points covered");
}
