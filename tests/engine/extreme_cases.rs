//! The extreme graphs issue 32 found non-finite, and materials whose outputs sit at the
//! ends of the f32 range, through the whole chain: the CLI's bakes (EXR maps, every sample
//! finite), the CPU evaluator, and the lit preview.

use crate::extreme_settings::TARGETS;
use crate::node_kinds::graph_driving;
use veneer::eval::Surface;
use veneer::graph::{Graph, NodeKind, Value, ValueType};
use veneer::render::FlatRect;

/// Inputs of a node set by name.
type Inputs = Vec<(&'static str, Value)>;

/// The extreme graphs issue 32 found non-finite (and more like them): one node, its other
/// inputs driven by position as in the CPU–GPU comparison, the named inputs set.
fn named_cases() -> Vec<(&'static str, NodeKind, Inputs)> {
    use veneer::graph::{Basis, MathOp};
    use veneer::nodes::{
        DomainWarp, Dot, Fbm, FractalSum, Layers, Math, Mix, Noise, NoiseBump, Turbulence, Worley,
    };
    let splat3 = |x: f64| Value::Vec3(x, x, x);
    let fractal = (Basis::Gradient, 5);
    vec![
        (
            "mix-factor",
            NodeKind::Mix(Mix {
                ty: ValueType::Color,
            }),
            vec![
                ("factor", Value::Float(1.0e20)),
                ("b", Value::Color(1.0e19, 0.5, 1.0e19)),
            ],
        ),
        (
            "triangle-wave-frequency",
            NodeKind::TriangleWave,
            vec![("frequency", Value::Float(3.0e38))],
        ),
        (
            "value-sine-scale",
            NodeKind::Noise(Noise {
                basis: Basis::ValueSine,
                period: 0,
            }),
            vec![("scale", Value::Float(-3.4e38))],
        ),
        (
            "rings-axis",
            NodeKind::Rings,
            vec![("axis", splat3(0.0)), ("frequency", Value::Float(3.0e38))],
        ),
        (
            "math-multiply",
            NodeKind::Math(Math {
                op: MathOp::Multiply,
                ty: ValueType::Float,
            }),
            vec![("b", Value::Float(-3.4e38))],
        ),
        (
            "transform-scale",
            NodeKind::Transform,
            vec![("scale", splat3(3.0e38))],
        ),
        (
            "fbm-gain",
            NodeKind::Fbm(Fbm {
                basis: fractal.0,
                octaves: fractal.1,
                normalize: false,
                rotate: false,
                period: 0,
            }),
            vec![("gain", Value::Float(1.0e30))],
        ),
        (
            "turbulence-lacunarity",
            NodeKind::Turbulence(Turbulence {
                basis: fractal.0,
                octaves: fractal.1,
                normalize: true,
                rotate: true,
                period: 0,
            }),
            vec![("lacunarity", Value::Float(1.0e30))],
        ),
        (
            "fractal-sum-amplitude",
            NodeKind::FractalSum(FractalSum {
                basis: Basis::Simplex,
                octaves: fractal.1,
                normalize: false,
                rotate: false,
                period: 0,
            }),
            vec![
                ("amplitude", Value::Float(3.4e38)),
                ("gain", Value::Float(2.0)),
            ],
        ),
        (
            "domain-warp-scale",
            NodeKind::DomainWarp(DomainWarp {
                basis: Basis::ValuePcg,
                period: 0,
            }),
            vec![("scale", Value::Float(3.4e38))],
        ),
        (
            "layers-placement",
            NodeKind::Layers(Layers {
                ty: ValueType::Color,
                separate_widths: false,
            }),
            vec![
                ("centre", Value::Float(-3.4e38)),
                ("softness", Value::Float(3.4e38)),
                ("width", Value::Float(1.0)),
            ],
        ),
        (
            "sine-band-frequency",
            NodeKind::SineBand,
            vec![("frequency", Value::Float(3.4e38))],
        ),
        (
            "tiles-size",
            NodeKind::Tiles,
            vec![
                ("size", Value::Vec2(-1.0e-19, -1.0e-19)),
                ("blur", Value::Float(1.0e20)),
            ],
        ),
        (
            "remap-target",
            NodeKind::Remap,
            vec![
                ("to_min", Value::Float(-3.4e38)),
                ("to_max", Value::Float(3.4e38)),
            ],
        ),
        (
            "worley-gain",
            NodeKind::Worley(Worley {
                feature: veneer::graph::WorleyFeature::F1,
                metric: veneer::graph::Metric::Euclidean,
                octaves: 8,
                period: 0,
                points: veneer::graph::FeaturePoints::Hashed,
            }),
            vec![("gain", Value::Float(3.4e38))],
        ),
        (
            "isolines-spacing",
            NodeKind::Isolines,
            vec![("spacing", Value::Float(1.0e-38))],
        ),
        (
            "dot-constant",
            NodeKind::Dot(Dot {
                ty: ValueType::Vec3,
            }),
            vec![("a", splat3(3.4e38))],
        ),
        (
            "cylindrical-origin",
            NodeKind::Cylindrical,
            vec![("origin", splat3(3.4e38))],
        ),
        (
            "project-origin",
            NodeKind::Project,
            vec![("origin", splat3(-3.4e38)), ("direction", splat3(1.0))],
        ),
        (
            "noise-bump-strength",
            NodeKind::NoiseBump(NoiseBump {
                basis: Basis::Simplex,
                period: 0,
            }),
            vec![("strength", Value::Float(3.4e38))],
        ),
        (
            "value-gradient-scale",
            NodeKind::ValueGradientNoise,
            vec![("scale", Value::Float(3.4e38))],
        ),
        (
            "front-placement",
            NodeKind::Front,
            vec![
                ("centre", Value::Float(-3.4e38)),
                ("softness", Value::Float(3.4e38)),
                ("width", Value::Float(0.0)),
            ],
        ),
    ]
}

/// The graphs of [`named_cases`] by name: the node's outputs shown in the albedo,
/// specular and emission, its other inputs driven by position (the CLI contract's
/// generator draws them too).
pub fn named_graphs() -> Vec<(&'static str, Graph)> {
    named_cases()
        .into_iter()
        .map(|(name, kind, inputs)| {
            let (graph, _) = graph_driving(&kind, &TARGETS, |graph, node, pin| {
                let set = inputs.iter().find(|(named, _)| *named == pin.name);
                if let Some((_, value)) = set {
                    graph.set_input(node, pin.name, *value);
                }
                set.is_some()
            });
            (name, graph)
        })
        .collect()
}

/// The plane the named graphs are baked over: the driven inputs reach about ±10 there.
const WIDE: FlatRect = FlatRect {
    x0: -50.0,
    z0: -50.0,
    x1: 50.0,
    z1: 50.0,
    y: 7.0,
};

/// The named extreme graphs through the whole CLI, `veneer bake --format exr` (check,
/// compile, GPU, EXR writer), and through the CPU evaluator (f32 and f64) at the bake's
/// sample points: every sample of the albedo, specular and emission maps is finite
/// (before, +Inf or NaN; black in PNG and glTF).
#[test]
fn named_extreme_graphs_bake_finite_exr_maps_and_evaluate_finite() {
    let dir = crate::support::temp_dir("extreme-bakes");
    let rect = format!("{},{},{},{},{}", WIDE.x0, WIDE.z0, WIDE.x1, WIDE.z1, WIDE.y);
    let mut args: Vec<String> = ["bake", "--size", "16", "--flat", &rect, "--maps"]
        .map(String::from)
        .to_vec();
    args.extend([
        TARGETS.join(","),
        "--format".into(),
        "exr".into(),
        "-o".into(),
    ]);
    args.push(dir.display().to_string());
    let mut failures = Vec::new();
    for (name, graph) in named_graphs() {
        let evaluator = veneer::eval::Evaluator::new(&graph).expect("checks");
        for point in veneer::render::flat_points(WIDE, 16) {
            let wide = evaluator.eval(&Surface::<f64>::at(point));
            let narrow = evaluator.eval(&Surface::<f32>::at(point));
            let lanes = [wide.albedo, wide.specular, wide.emission];
            let finite = lanes
                .iter()
                .flatten()
                .all(|x| x.abs() <= f64::from(f32::MAX))
                && [narrow.albedo, narrow.specular, narrow.emission]
                    .iter()
                    .flatten()
                    .all(|x| x.is_finite());
            if !finite {
                failures.push(format!(
                    "{name} at {point:?} on the CPU: {wide:?} / {narrow:?}"
                ));
                break;
            }
        }
        let path = dir.join(format!("{name}.ron"));
        veneer::graph::save(&graph, &path).expect("graph saved");
        args.push(path.display().to_string());
    }
    let output = crate::support::veneer()
        .args(&args)
        .output()
        .expect("veneer runs");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    for (name, _) in named_graphs() {
        for map in TARGETS {
            let path = dir.join(format!("{name}_{map}.exr"));
            let pixels = image::open(&path).expect("an EXR").to_rgba32f();
            let bad = pixels.iter().filter(|v| !v.is_finite()).count();
            if bad > 0 {
                failures.push(format!("{name}: {bad} non-finite samples in its {map} map"));
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A material whose outputs are at the ends of the f32 range (the nodes' outputs may be:
/// they clamp there): emission × strength overflows, the bump cannot be squared, and the
/// height (3.4e38 times a position-driven scalar, so about ±3e38 in stripes) has slopes
/// past f32. `scale` stands for 3.4e38 (or a moderate value, for a reference image).
fn extreme_material(shading: veneer::graph::Shading, scale: f64) -> Graph {
    use veneer::nodes::Math;
    let mut graph = Graph {
        shading,
        ..Graph::default()
    };
    let material = graph.add("material", NodeKind::Material);
    let position = graph.add("position", NodeKind::Project);
    let ty = ValueType::Float;
    let height = graph.add(
        "height",
        NodeKind::Math(Math {
            op: veneer::graph::MathOp::Multiply,
            ty,
        }),
    );
    graph.connect(position, "x", height, "a");
    graph.set_input(height, "b", Value::Float(scale));
    graph.connect(height, "result", material, "height");
    graph.set_input(
        material,
        "emission",
        Value::Color(scale, 0.5 * scale, scale),
    );
    graph.set_input(material, "emission_strength", Value::Float(scale));
    graph.set_input(material, "bump", Value::Vec3(scale, -scale, scale));
    graph.set_input(material, "normal", Value::Vec3(scale, scale, -scale));
    graph.set_input(material, "specular", Value::Color(scale, scale, scale));
    graph.set_input(material, "shininess", Value::Float(scale));
    graph
}

/// Every map of the extreme material bakes (EXR, over a plane and into a mesh's UV
/// layout) with every sample finite, normals unit length: before, the emission map held
/// +Inf and the normal map NaN.
#[test]
fn extreme_material_outputs_bake_into_finite_maps() {
    use veneer::bake::{BakeSettings, BakeSurface, Format, Map, NormalConvention, bake};
    let dir = crate::support::temp_dir("extreme-material-bakes");
    for shading in veneer::graph::Shading::ALL {
        let compiled =
            veneer::codegen::compile(&extreme_material(shading, 3.4e38), &Default::default())
                .expect("compiles");
        for surface in [
            BakeSurface::Plane(Some(WIDE)),
            BakeSurface::MeshUv("sphere".into()),
        ] {
            let settings = BakeSettings {
                surface: surface.clone(),
                size: 32,
                maps: Map::ALL.to_vec(),
                format: Format::Exr,
                normal: NormalConvention::OpenGl,
                time: 0.0,
            };
            let maps = bake(
                crate::support::gpu(),
                &compiled,
                &settings,
                &dir.join("extreme"),
                |_, _| true,
            )
            .unwrap_or_else(|e| panic!("{shading:?} {surface:?}: {e}"));
            for baked in maps {
                let pixels = image::open(&baked.path).expect("an EXR").to_rgba32f();
                assert!(
                    pixels.iter().all(|v| v.is_finite()),
                    "{shading:?} {surface:?}: the {:?} map is not finite",
                    baked.map
                );
                if baked.map == Map::Normal {
                    for p in pixels.pixels() {
                        let n = glam::Vec3::new(p[0], p[1], p[2]) * 2.0 - glam::Vec3::ONE;
                        assert!((n.length() - 1.0).abs() < 1.0e-3, "normal {n}");
                    }
                }
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The extreme material lit on its preview mesh, in both shadings, looks as the same
/// material at moderate magnitudes does (the bump turns the normal the same way, the
/// emission saturates to white): before, the bump and the emission gave NaN, drawn black.
#[test]
fn extreme_material_outputs_light_like_saturated_ones() {
    use veneer::render::{View, render_material};
    for shading in veneer::graph::Shading::ALL {
        let image = |scale: f64| {
            let mut graph = extreme_material(shading, scale);
            // The height's relief differs with its scale; the bump and emission do not.
            graph.wires.retain(|wire| wire.to.pin != "height");
            let compiled = veneer::codegen::compile(&graph, &Default::default()).expect("compiles");
            render_material(crate::support::gpu(), &compiled, &View::Mesh(None), 48, 0.0)
                .expect("renders")
        };
        let (extreme, moderate) = (image(3.4e38), image(1.0e6));
        let diff =
            crate::support::difference(&extreme.pixels, &moderate.pixels, extreme.channels, 1);
        assert_eq!(diff.share_outside, 0.0, "{shading:?}: {diff}");
    }
}
