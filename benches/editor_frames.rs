//! The editor's responsiveness, measured end to end in one run: the real app driven by
//! egui_kittest on this machine's adapter (llvmpipe or lavapipe without a GPU).
//!
//! - **Wood, a parameter dragged** (the inspector's shininess, one pixel a frame): the
//!   main thread's frame, and where it goes (`FrameProfile`: reading the graph back,
//!   the compile check, lint, thumbnails, history, the panels), the window's painting
//!   (tessellation and wgpu, with kittest's readback), and the preview thread's draft
//!   draw of the same frame next to the full draw it refines to.
//! - **A structural edit, to the first frame showing the new material**: compile, the
//!   new pipeline (the driver compiles it at its first draw, included) and the draw,
//!   against a parameter edit drawn with the pipeline it has (the baseline); and the UI's
//!   next frame while the preview thread compiles.
//! - **2,000 nodes**: the main thread's frame while a parameter is dragged, and while
//!   nothing happens. **10,000 nodes**: the compile on opening (parameters in a storage
//!   buffer); the preview thread then builds the pipeline while the UI answers.

use criterion::{Criterion, criterion_group, criterion_main};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use veneer::app::{LiveMaterial, VeneerApp};
use veneer::graph::{Graph, NodeKind, Value};
use veneer::render::{GpuContext, LiveMaterialCode, LiveRenderer, MeshView, Quality};

#[path = "../tests/engine/big_graphs.rs"]
#[allow(dead_code)]
mod big_graphs;

const WOOD: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/graphs/wood.ron");

type Editor = Harness<'static, VeneerApp>;

/// The editor in a 1400×900 window on `graph`, autosaving into a scratch folder.
fn editor(graph: &Path) -> Editor {
    let dir = std::env::temp_dir().join(format!("veneer-bench-editor-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch folder");
    let recovery = dir.join("recovery.ron");
    let graph = graph.to_path_buf();
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1400.0, 900.0))
        .wgpu()
        .build_eframe(move |cc| VeneerApp::with_recovery_file(cc, Some(graph), recovery));
    settle(&mut harness);
    harness
}

/// Steps until the previews show what was asked of them.
fn settle(harness: &mut Editor) {
    let started = Instant::now();
    harness.step();
    while !harness.state().preview_settled() && started.elapsed() < Duration::from_secs(120) {
        std::thread::sleep(Duration::from_millis(5));
        harness.step();
    }
    harness.step();
}

/// Clicks the node titled `title` (its largest label) so that the inspector shows it.
fn select(harness: &mut Editor, title: &str) {
    let rect = harness
        .query_all_by_label(title)
        .map(|node| node.rect())
        .max_by(|a, b| a.height().total_cmp(&b.height()))
        .expect("the node is on screen");
    let at = harness.state().graph_to_screen() * rect.center();
    click(harness, at);
}

fn click(harness: &mut Editor, at: egui::Pos2) {
    harness.event(egui::Event::PointerMoved(at));
    for pressed in [true, false] {
        harness.event(egui::Event::PointerButton {
            pos: at,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: Default::default(),
        });
        harness.step();
    }
    harness.step();
}

/// Presses the pointer on the inspector's first drag value showing `shown`; returns
/// where the drag goes on from.
fn grab(harness: &mut Editor, shown: &str) -> egui::Pos2 {
    let at = harness
        .get_all_by_value(shown)
        .next()
        .expect("a drag value shows it")
        .rect()
        .center();
    harness.event(egui::Event::PointerMoved(at));
    harness.step();
    harness.event(egui::Event::PointerButton {
        pos: at,
        button: egui::PointerButton::Primary,
        pressed: true,
        modifiers: Default::default(),
    });
    harness.step();
    at
}

/// Drags on one pixel from `at` and steps one frame; returns the new position.
fn drag_frame(harness: &mut Editor, at: egui::Pos2, right: bool) -> egui::Pos2 {
    let next = at + egui::vec2(if right { 1.0 } else { -1.0 }, 0.0);
    harness.event(egui::Event::PointerMoved(next));
    harness.step();
    next
}

/// Sums `part` of the app's frame profile over `frames` dragged frames.
fn dragged_frames(
    harness: &mut Editor,
    at: &mut egui::Pos2,
    frames: u64,
    part: impl Fn(&mut Editor, egui::Pos2) -> (Duration, egui::Pos2),
) -> Duration {
    let mut total = Duration::ZERO;
    for _ in 0..frames {
        let (spent, next) = part(harness, *at);
        *at = next;
        total += spent;
    }
    total
}

/// A part of the app's frame profile.
type ProfilePart = fn(&veneer::app::FrameProfile) -> Duration;

/// Benches `part` of the frames of a drag going on from `at` (back and forth: each
/// sample turns).
fn bench_dragged(
    group: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    name: &str,
    harness: &mut Editor,
    at: &mut egui::Pos2,
    right: &mut bool,
    part: ProfilePart,
) {
    group.bench_function(name, |b| {
        b.iter_custom(|frames| {
            *right = !*right;
            let going_right = *right;
            let step = |harness: &mut Editor, at: egui::Pos2| {
                let next = drag_frame(harness, at, going_right);
                (part(&harness.state().profile()), next)
            };
            dragged_frames(harness, at, frames, step)
        })
    });
}

fn wood_drag(c: &mut Criterion) {
    let mut harness = editor(Path::new(WOOD));
    select(&mut harness, "material");
    let mut at = grab(&mut harness, "24.0");
    let mut right = true;
    let mut group = c.benchmark_group("editor: wood, a frame while a parameter is dragged");
    group.sample_size(20);
    group.measurement_time(Duration::from_secs(5));
    let mut profiled = |name: &str, part: ProfilePart| {
        bench_dragged(&mut group, name, &mut harness, &mut at, &mut right, part);
    };
    profiled("main thread: the app's whole frame", |p| p.total);
    profiled("of which the main thread's CPU time", |p| p.cpu);
    profiled("of which: reading the graph back (sync)", |p| p.sync);
    profiled("of which: compile check", |p| p.compile);
    profiled("of which: lint", |p| p.lint);
    profiled("of which: thumbnails", |p| p.thumbnails);
    profiled("of which: history, title, autosave", |p| p.history);
    profiled("of which: panels (egui, egui-snarl)", |p| p.panels());
    group.bench_function("main thread: the step as kittest runs it", |b| {
        b.iter_custom(|frames| {
            right = !right;
            let step = |harness: &mut Editor, at: egui::Pos2| {
                let started = Instant::now();
                let next = drag_frame(harness, at, right);
                (started.elapsed(), next)
            };
            dragged_frames(&mut harness, &mut at, frames, step)
        })
    });
    group.bench_function("painting the window (tessellation, wgpu, readback)", |b| {
        b.iter_custom(|frames| {
            right = !right;
            let mut total = Duration::ZERO;
            for _ in 0..frames {
                at = drag_frame(&mut harness, at, right);
                let started = Instant::now();
                harness.render().expect("the window renders");
                total += started.elapsed();
            }
            total
        })
    });
    assert_eq!(
        harness.state().live().compiles,
        1,
        "a drag never recompiles"
    );
    group.finish();
    drop(harness);
    preview_draws(c);
}

/// The preview thread's work per dragged frame (a draft) and at rest (the full draw),
/// at the size the preview has in the editor's window.
fn preview_draws(c: &mut Criterion) {
    let gpu = GpuContext::new().expect("a wgpu adapter");
    let sky = gpu.sky().expect("the default environment");
    let graph = veneer::graph::load(Path::new(WOOD)).expect("wood preset");
    let (code, params) = live_code(&graph, 1);
    let mesh = veneer::mesh::primitive(&graph.preview.mesh).expect("the preview mesh");
    let view = MeshView::for_preview(&graph.preview);
    let size = (460, 400);
    let mut renderer = LiveRenderer::default();
    let mut group = c.benchmark_group(format!(
        "editor: the preview thread's draw of wood, {}×{} on {}",
        size.0,
        size.1,
        gpu.adapter_description()
    ));
    group.sample_size(20);
    for (name, quality) in [
        (
            "at rest: full resolution, 4× multisampled (baseline)",
            Quality::Full,
        ),
        (
            "while dragging: a draft (its resolution from its own time)",
            Quality::Draft,
        ),
    ] {
        group.bench_function(name, |b| {
            b.iter(|| {
                renderer
                    .render(
                        &gpu, &code, &params, "mesh", &mesh, &view, &sky, size, quality,
                    )
                    .expect("draws")
            })
        });
    }
    group.finish();
    // Alone on the machine; in the editor, drawing beside the window, drafts take longer
    // and settle coarser.
    eprintln!(
        "drafts settled at 1/{} of the preview's resolution each way",
        renderer.draft_scale.divisor()
    );
}

/// `graph` compiled as the editor compiles it, as generation `generation`.
fn live_code(graph: &Graph, generation: u64) -> (LiveMaterialCode, Vec<[f32; 4]>) {
    let mut live = LiveMaterial::in_storage();
    live.update(graph);
    let code = LiveMaterialCode::new(generation, live.compiled.as_ref().expect("it compiles"));
    (code, live.params(graph))
}

fn structural_edit(c: &mut Criterion) {
    let gpu = GpuContext::new().expect("a wgpu adapter");
    let sky = gpu.sky().expect("the default environment");
    let mut graph = veneer::graph::load(Path::new(WOOD)).expect("wood preset");
    let mesh = veneer::mesh::primitive(&graph.preview.mesh).expect("the preview mesh");
    let view = MeshView::for_preview(&graph.preview);
    let material = graph.material().expect("material").id;
    let size = (460, 400);
    let mut renderer = LiveRenderer::default();
    let mut group = c.benchmark_group(format!(
        "editor: an edit of wood to the first frame showing it, on {}",
        gpu.adapter_description()
    ));
    group.sample_size(10);
    // The full draw of `code` with `params`, as the preview thread draws at rest.
    let draw = |renderer: &mut LiveRenderer, code: &LiveMaterialCode, params: &[[f32; 4]]| {
        renderer.render(
            &gpu,
            code,
            params,
            "mesh",
            &mesh,
            &view,
            &sky,
            size,
            Quality::Full,
        )
    };
    let (code, mut params) = live_code(&graph, 0);
    draw(&mut renderer, &code, &params).expect("draws");
    group.bench_function(
        "parameter edit: new values, the pipeline it has (baseline)",
        |b| {
            b.iter(|| {
                params[0][0] += 0.001;
                draw(&mut renderer, &code, &params).expect("draws")
            })
        },
    );
    // Alternate between two structures so that every iteration really recompiles.
    let constant = graph.add(
        "specular level",
        NodeKind::Constant(veneer::nodes::Constant {
            ty: veneer::graph::ValueType::Color,
        }),
    );
    graph.set_input(constant, "value", Value::Color(0.2, 0.2, 0.2));
    let mut generation = 1;
    group.bench_function(
        "structural edit: compile, new pipeline (driver compile at first draw), draw",
        |b| {
            b.iter(|| {
                if generation % 2 == 1 {
                    graph.connect(constant, "value", material, "specular");
                } else {
                    graph
                        .wires
                        .retain(|w| !(w.to.node == material && w.to.pin == "specular"));
                }
                generation += 1;
                let (code, params) = live_code(&graph, generation);
                draw(&mut renderer, &code, &params).expect("draws")
            })
        },
    );
    group.finish();
    ui_while_compiling(c);
}

/// The editor's next frames right after a structural edit, while the preview thread
/// builds the new pipeline: what a click waits for.
fn ui_while_compiling(c: &mut Criterion) {
    let mut harness = editor(Path::new(WOOD));
    let mut group = c.benchmark_group("editor: wood, the UI while a new material compiles");
    group.sample_size(10);
    let mut wired = false;
    group.bench_function(
        "the first frame after a structural edit (main thread)",
        |b| {
            b.iter_custom(|edits| {
                let mut total = Duration::ZERO;
                for _ in 0..edits {
                    // Toggle the flat view's "every octave" detail: a recompile of the material.
                    wired = !wired;
                    harness.state_mut().set_full_detail(wired);
                    let started = Instant::now();
                    harness.event(egui::Event::PointerMoved(egui::pos2(300.0, 300.0)));
                    harness.step();
                    harness.step();
                    total += started.elapsed() / 2;
                    settle(&mut harness);
                }
                total
            })
        },
    );
    group.finish();
}

/// A chain graph of `nodes` nodes laid out in rows, in a scratch file.
fn chain_file(nodes: usize) -> PathBuf {
    let mut graph = big_graphs::chain(nodes);
    veneer::graph::layout::arrange_in_rows(&mut graph, 1620.0, 1000.0);
    let path = std::env::temp_dir().join(format!(
        "veneer-bench-chain-{nodes}-{}.ron",
        std::process::id()
    ));
    veneer::graph::save(&graph, &path).expect("scratch graph");
    path
}

fn big_graphs_frames(c: &mut Criterion) {
    let path = chain_file(2000);
    let mut harness = editor(&path);
    // The chain's first node, at the top left where the graph opens.
    select(&mut harness, "start");
    let mut group = c.benchmark_group("editor: a 2,000-node chain");
    group.sample_size(10);
    group.bench_function("a frame with nothing happening (main thread)", |b| {
        b.iter_custom(|frames| {
            let mut total = Duration::ZERO;
            for _ in 0..frames {
                harness.step();
                total += harness.state().profile().total;
            }
            total
        })
    });
    let mut at = grab(&mut harness, "1.000");
    let mut right = true;
    let parts: [(&str, ProfilePart); 2] = [
        ("a frame while a parameter is dragged (main thread)", |p| {
            p.total
        }),
        ("of which the main thread's CPU time", |p| p.cpu),
    ];
    for (name, part) in parts {
        bench_dragged(&mut group, name, &mut harness, &mut at, &mut right, part);
    }
    group.finish();
    drop(harness);
    let _ = std::fs::remove_file(&path);

    let graph = big_graphs::chain(10_000);
    let mut group = c.benchmark_group("editor: a 10,000-node chain");
    group.sample_size(10);
    undo_on_ten_thousand_nodes(&mut group);
    group.bench_function(
        "open: check and compile it for the preview (main thread)",
        |b| {
            b.iter(|| {
                let mut live = LiveMaterial::in_storage();
                live.update(&graph);
                let module = &live.compiled.as_ref().expect("it compiles").module;
                assert!(module.params.len() > veneer::app::UNIFORM_SLOTS);
                live
            })
        },
    );
    group.finish();
}

/// A node in the middle of a 10,000-node chain deleted, then undone and redone: the
/// main thread's frame of each (the edit, the view following it and the compile check),
/// against a frame with nothing happening.
fn undo_on_ten_thousand_nodes(
    group: &mut criterion::BenchmarkGroup<criterion::measurement::WallTime>,
) {
    let path = chain_file(10_000);
    let mut harness = editor(&path);
    let middle = harness.state().document().graph.nodes[5_000].id;
    let remove = veneer::graph::edit::GraphEdit::RemoveNodes {
        level: veneer::graph::edit::Level::Top,
        nodes: vec![middle],
    };
    harness
        .state_mut()
        .apply_edit(remove)
        .expect("the node goes");
    harness.step();
    // The main thread's time: the undo (made outside a frame, as a script does) and the
    // frame after it.
    let frame = |harness: &mut Editor, travel: fn(&mut VeneerApp)| {
        let started = Instant::now();
        travel(harness.state_mut());
        let travelled = started.elapsed();
        harness.step();
        travelled + harness.state().profile().total
    };
    group.bench_function("a frame with nothing happening (main thread)", |b| {
        b.iter_custom(|frames| (0..frames).map(|_| frame(&mut harness, |_| {})).sum())
    });
    group.bench_function(
        "undo then redo of a node deleted, two frames (main thread)",
        |b| {
            b.iter_custom(|pairs| {
                (0..pairs)
                    .map(|_| {
                        frame(&mut harness, VeneerApp::undo) + frame(&mut harness, VeneerApp::redo)
                    })
                    .sum()
            })
        },
    );
    drop(harness);
    let _ = std::fs::remove_file(&path);
}

criterion_group!(benches, wood_drag, structural_edit, big_graphs_frames);
criterion_main!(benches);
