//! The report's level-of-detail section: for each band-limited node kind and three
//! materials, at three view widths, the error of full and footprint detail against a
//! 64-sample supersampled reference, and the time of each.

use super::materials::{gpu_ms_per_megapixel, renderer};
use super::measure::{errors, gpu_albedo};
use super::plot::{Plot, Series};
use super::table::{Table, number};
use super::{Context, Section};
use crate::codegen::Detail;
use crate::graph::{Basis, Graph, NodeId, NodeKind, Value, ValueType};
use crate::nodes::settings::{Metric, WorleyFeature};
use crate::nodes::{Combine, Fbm, MapRange, MapRangeMode, Split, Step, Worley};
use crate::render::{FlatRect, preview_rect};

/// One material the section measures.
pub struct DetailCase {
    /// What the row names: the node kind, or the preset.
    pub name: &'static str,
    pub graph: Graph,
    /// The widths of the views measured, nearest first (each a square about the origin
    /// of the xz plane).
    pub widths: [f64; 3],
}

/// The node kinds' period (or cell size): near a tenth of the nearest view, and not a
/// simple fraction of a pixel at any view, where samples would fall on the same phase.
const PERIOD: f64 = 0.0973;

/// The node kinds' views: a period over about 13 pixels of the report's 128, over 3, and
/// 1.25 periods a pixel, where the 8×8 samples of the reference still resolve it (a
/// reference wider still would alias itself).
const PATTERN_WIDTHS: [f64; 3] = [1.0, 4.0, 16.0];

/// Wires `node`'s float output `pin` into a new material's albedo as a grey.
pub fn shown_in_grey(graph: &mut Graph, node: NodeId, pin: &str) {
    let grey = graph.add(
        "grey",
        NodeKind::Combine(Combine {
            ty: ValueType::Color,
        }),
    );
    for channel in ["x", "y", "z"] {
        graph.connect(node, pin, grey, channel);
    }
    let material = graph.add("material", NodeKind::Material);
    graph.connect(grey, "v", material, "albedo");
}

/// A graph showing `kind` in grey, its inputs set to `inputs`, and its `x` input (when
/// named) wired to the position's x.
fn pattern(kind: NodeKind, x: Option<&str>, inputs: &[(&str, Value)], output: &str) -> Graph {
    let mut graph = Graph::default();
    let node = graph.add("pattern", kind);
    for (pin, value) in inputs {
        graph.set_input(node, pin, *value);
    }
    if let Some(x) = x {
        let position = graph.add("position", NodeKind::Position);
        let split = graph.add(
            "split",
            NodeKind::Split(Split {
                ty: ValueType::Vec3,
            }),
        );
        graph.connect(position, "position", split, "v");
        graph.connect(split, "x", node, x);
    }
    shown_in_grey(&mut graph, node, output);
    graph
}

/// A threshold node `kind` (input `x`) over the float output `pin` of `source`.
fn threshold(
    source: NodeKind,
    scale: f64,
    pin: &str,
    kind: NodeKind,
    inputs: &[(&str, Value)],
) -> Graph {
    let mut graph = Graph::default();
    let cells = graph.add("cells", source);
    graph.set_input(cells, "scale", Value::Float(scale));
    let node = graph.add("threshold", kind);
    for (input, value) in inputs {
        graph.set_input(node, input, *value);
    }
    graph.connect(cells, pin, node, "x");
    shown_in_grey(&mut graph, node, "result");
    graph
}

/// The measured materials: each band-limited node kind with a period (or cell) of [`PERIOD`],
/// then fBm of 8 octaves, wood and marble tiles at their preview, 10× and 100× as wide.
pub fn cases() -> Vec<DetailCase> {
    let float = Value::Float;
    let frequency = 1.0 / PERIOD;
    let mut cases = vec![
        DetailCase {
            name: "sine band",
            graph: pattern(
                NodeKind::SineBand,
                Some("x"),
                &[
                    ("frequency", float(std::f64::consts::TAU * frequency)),
                    ("distortion", float(0.0)),
                ],
                "band",
            ),
            widths: PATTERN_WIDTHS,
        },
        DetailCase {
            name: "triangle wave",
            graph: pattern(
                NodeKind::TriangleWave,
                Some("x"),
                &[("frequency", float(frequency))],
                "value",
            ),
            widths: PATTERN_WIDTHS,
        },
        DetailCase {
            name: "rings",
            graph: pattern(
                NodeKind::Rings,
                None,
                &[("frequency", float(frequency))],
                "value",
            ),
            widths: PATTERN_WIDTHS,
        },
        DetailCase {
            name: "tiles",
            graph: pattern(
                NodeKind::Tiles,
                None,
                &[
                    ("size", Value::Vec2(PERIOD, PERIOD)),
                    ("gap", Value::Vec2(0.15, 0.15)),
                ],
                "mask",
            ),
            widths: PATTERN_WIDTHS,
        },
        DetailCase {
            name: "step (Voronoi edges)",
            graph: threshold(
                NodeKind::WorleyEdge,
                frequency,
                "distance",
                NodeKind::Step(Step {
                    ty: ValueType::Float,
                }),
                &[("edge", float(0.08))],
            ),
            widths: PATTERN_WIDTHS,
        },
        DetailCase {
            name: "smoothstep (F2 − F1 borders)",
            graph: threshold(
                NodeKind::Worley(Worley {
                    feature: WorleyFeature::F2MinusF1,
                    metric: Metric::Euclidean,
                    octaves: 1,
                    period: 0,
                    points: crate::graph::FeaturePoints::Hashed,
                }),
                frequency,
                "value",
                NodeKind::Smoothstep,
                &[("edge0", float(0.05)), ("edge1", float(0.15))],
            ),
            widths: PATTERN_WIDTHS,
        },
        DetailCase {
            name: "map range, stepped",
            graph: pattern(
                NodeKind::MapRange(MapRange {
                    mode: MapRangeMode::Stepped,
                    clamp: true,
                }),
                Some("x"),
                &[
                    ("from_min", float(-0.5)),
                    ("from_max", float(0.5)),
                    ("steps", float(10.0)),
                ],
                "result",
            ),
            widths: PATTERN_WIDTHS,
        },
    ];
    let fbm = pattern(
        NodeKind::Fbm(Fbm {
            basis: Basis::Gradient,
            octaves: 8,
            normalize: true,
            rotate: false,
            period: 0,
        }),
        None,
        &[("scale", float(1.0))],
        "value",
    );
    cases.push(DetailCase {
        name: "fBm 8 (gradient)",
        widths: zoomed_out(&fbm),
        graph: fbm,
    });
    for name in ["wood", "marble_tiles"] {
        let graph = crate::graph::preset(name).expect("a shipped preset");
        cases.push(DetailCase {
            name,
            widths: zoomed_out(&graph),
            graph,
        });
    }
    cases
}

/// A material's preview square's width, 10× and 100× (wood's rings at 180 units).
fn zoomed_out(graph: &Graph) -> [f64; 3] {
    let rect = preview_rect(&graph.preview);
    [1.0, 10.0, 100.0].map(|zoom| zoom * (rect.x1 - rect.x0))
}

/// The view `width` wide about the origin, at the height `graph` is previewed at.
pub fn view(graph: &Graph, width: f64) -> FlatRect {
    let half = 0.5 * width;
    FlatRect {
        x0: -half,
        z0: -half,
        x1: half,
        z1: half,
        y: preview_rect(&graph.preview).y,
    }
}

/// Footprint detail against full evaluation, per node kind and view width.
pub(super) fn detail(ctx: &Context) -> Result<Section, String> {
    let mut table = Table::new(&[
        "material",
        "view width",
        "full: error",
        "footprint: error",
        "full ms/MP",
        "footprint ms/MP",
    ]);
    let (mut full_points, mut footprint_points) = (Vec::new(), Vec::new());
    let (size, factor) = (128u32, 8u32);
    for case in cases() {
        let full = renderer(ctx, &case.graph, Detail::Full)?;
        let footprint = renderer(ctx, &case.graph, Detail::Footprint)?;
        for width in case.widths {
            let rect = view(&case.graph, width);
            let wide =
                gpu_albedo(ctx.gpu, &full, rect, size * factor).map_err(|e| e.to_string())?;
            let reference = box_down(&wide, size as usize, factor as usize);
            let full_values = gpu_albedo(ctx.gpu, &full, rect, size).map_err(|e| e.to_string())?;
            let footprint_values =
                gpu_albedo(ctx.gpu, &footprint, rect, size).map_err(|e| e.to_string())?;
            let (_, full_error) = errors(&full_values, &reference);
            let (_, footprint_error) = errors(&footprint_values, &reference);
            // Timed at the timing size over a square widened as much, so that each
            // pixel covers what it covers in the view the errors are measured on (the
            // same rectangle at the timing size would time a view that many times
            // nearer).
            let timed = view(
                &case.graph,
                width * f64::from(ctx.timing_size) / f64::from(size),
            );
            let (full_ms, footprint_ms) = (
                gpu_ms_per_megapixel(ctx, &full, timed),
                gpu_ms_per_megapixel(ctx, &footprint, timed),
            );
            full_points.push((full_ms, full_error.max(1e-6)));
            footprint_points.push((footprint_ms, footprint_error.max(1e-6)));
            table.push(vec![
                case.name.to_string(),
                number(rect.x1 - rect.x0, 3),
                number(full_error, 2),
                number(footprint_error, 2),
                number(full_ms, 3),
                number(footprint_ms, 3),
            ]);
        }
        (ctx.progress)();
    }
    Ok(Section {
        title: "Level of detail: footprint detail against full evaluation".into(),
        text: format!(
            "Flat renders at {size}² of each node kind (a period or cell of 0.0973, over squares 1, 4 and 16 wide: a period over 13 pixels, over 3, and 1.25 periods a pixel) and of three materials (their preview square widened 1×, 10× and 100×); the error is the mean absolute difference from the same view rendered in full at {}² and box-filtered down ({} samples a pixel: the truly filtered pattern). The time is per megapixel of the same view: rendered at {}² over a square {}× as wide, so that each pixel covers as much of the pattern as in the {size}² view (timing the {size}² square itself at that size would time a view {}× nearer). Footprint detail filters over each pixel's footprint, measured by screen-space derivatives of the variable a pattern is drawn along: fractal nodes leave out octaves finer than half a pixel, fading the last; sine bands, rings, triangle waves, tiles, steps, smoothsteps and stepped ranges are box-filtered analytically, the periodic ones fading to their mean past Nyquist. Far away that is both closer to the filtered pattern and no slower; near by it changes almost nothing but costs the derivatives. A threshold of a filtered value is not the filtered threshold: where a step or smoothstep reads a pattern that has faded to its mean, the footprint view shows the threshold of the mean.",
            size * factor,
            factor * factor,
            ctx.timing_size,
            ctx.timing_size / size,
            ctx.timing_size / size,
        ),
        table,
        plot: Plot {
            title: "Detail: error against time".into(),
            x_label: "GPU time per megapixel (ms)".into(),
            y_label: "mean error against the filtered pattern".into(),
            series: vec![
                Series {
                    name: "full".into(),
                    points: full_points,
                    joined: false,
                },
                Series {
                    name: "footprint".into(),
                    points: footprint_points,
                    joined: false,
                },
            ],
        },
    })
}

/// `pixels` (size·factor squared) averaged over factor×factor blocks.
pub fn box_down(pixels: &[[f64; 3]], size: usize, factor: usize) -> Vec<[f64; 3]> {
    let wide = size * factor;
    let mut out = vec![[0.0; 3]; size * size];
    let weight = 1.0 / (factor * factor) as f64;
    for (k, value) in pixels.iter().enumerate() {
        let target = &mut out[(k / wide / factor) * size + k % wide / factor];
        for c in 0..3 {
            target[c] += value[c] * weight;
        }
    }
    out
}
