//! Seamless tiles: every periodic noise baked over the unit tile gives maps whose
//! opposite edges continue each other (measured by `bake --tile`'s edge check), normal
//! maps included; the same graphs without a period are refused; a tile's interior is the
//! plain bake's.

use crate::support::{gpu, run_veneer, temp_dir};
use veneer::bake::tile::SEAM_TOLERANCE;
use veneer::bake::{BakeError, BakeSettings, BakeSurface, Format, Map, NormalConvention, bake};
use veneer::graph::{Basis, Graph, Metric, NodeKind, Value, WorleyFeature};
use veneer::nodes::{Fbm, FractalSum, Noise, Turbulence, Worley};

/// Every lattice noise with a period (in cells), and the scale that spans it over the
/// unit tile: each basis alone and in every fractal (one with a lacunarity whose powers
/// are not whole, so octaves round to whole cells), and Worley, one octave and fractal.
pub fn periodic_noises() -> Vec<(String, NodeKind, f64, Option<f64>)> {
    let mut kinds = Vec::new();
    for basis in Basis::ALL {
        let period = if basis == Basis::Simplex { 6 } else { 4 };
        let name = basis.menu_name();
        kinds.push((
            format!("noise {name}"),
            NodeKind::Noise(Noise { basis, period }),
            f64::from(period),
            None,
        ));
        // A fractal kind of this basis and period, normalised, unrotated.
        macro_rules! fractal {
            ($kind:ident, $octaves:expr) => {
                NodeKind::$kind($kind {
                    basis,
                    octaves: $octaves,
                    normalize: true,
                    rotate: false,
                    period,
                })
            };
        }
        let span = f64::from(period);
        kinds.push((format!("fbm {name}"), fractal!(Fbm, 5), span, None));
        kinds.push((
            format!("turbulence {name}, lacunarity 1.9"),
            fractal!(Turbulence, 4),
            2.0 * span,
            Some(1.9),
        ));
        kinds.push((
            format!("fractal sum {name}"),
            fractal!(FractalSum, 4),
            span,
            None,
        ));
    }
    for (octaves, period) in [(1, 5), (3, 3)] {
        kinds.push((
            format!("worley, {octaves} octaves"),
            NodeKind::Worley(Worley {
                feature: WorleyFeature::F1,
                metric: Metric::Euclidean,
                octaves,
                period,
                points: veneer::graph::FeaturePoints::Hashed,
            }),
            f64::from(period),
            None,
        ));
    }
    kinds
}

/// `kind` at `scale` (and `lacunarity`) over the surface position, as the albedo and the
/// height of a material.
pub fn noise_graph(kind: NodeKind, scale: f64, lacunarity: Option<f64>) -> Graph {
    let mut graph = Graph::default();
    let position = graph.add("position", NodeKind::Position);
    let noise = graph.add("noise", kind);
    graph.set_input(noise, "scale", Value::Float(scale));
    if let Some(lacunarity) = lacunarity {
        graph.set_input(noise, "lacunarity", Value::Float(lacunarity));
    }
    let material = graph.add("material", NodeKind::Material);
    graph.connect(position, "position", noise, "p");
    graph.connect(noise, "value", material, "albedo");
    graph.connect(noise, "value", material, "height");
    graph
}

fn tile_settings(surface: BakeSurface, size: u32, maps: Vec<Map>) -> BakeSettings {
    BakeSettings {
        surface,
        size,
        maps,
        format: Format::Png8,
        normal: NormalConvention::OpenGl,
        time: 0.0,
    }
}

fn compiled(graph: &Graph) -> veneer::codegen::Compiled {
    veneer::codegen::compile(graph, &Default::default()).expect("compiles")
}

fn pixels(path: &std::path::Path) -> image::RgbImage {
    image::open(path).expect("a PNG").to_rgb8()
}

#[test]
fn every_periodic_noise_bakes_a_tile_whose_edges_continue_each_other() {
    let dir = temp_dir("tiles-periodic");
    let settings = tile_settings(BakeSurface::Tile(None), 64, vec![Map::Albedo, Map::Normal]);
    for (name, kind, scale, lacunarity) in periodic_noises() {
        let graph = noise_graph(kind.clone(), scale, lacunarity);
        let maps = bake(
            gpu(),
            &compiled(&graph),
            &settings,
            &dir.join("tile"),
            |_, _| true,
        )
        .unwrap_or_else(|e| panic!("{name}: {e}"));
        for map in &maps {
            let seams = map.seams.expect("a tile reports its seams");
            assert!(
                seams.worst() <= SEAM_TOLERANCE,
                "{name}, {:?}: {seams:?}",
                map.map
            );
        }
        // Without its period the same noise does not tile, and the check says so
        // before anything is written.
        let mut infinite = kind;
        match &mut infinite {
            NodeKind::Noise(n) => n.period = 0,
            NodeKind::Fbm(n) => n.period = 0,
            NodeKind::Turbulence(n) => n.period = 0,
            NodeKind::FractalSum(n) => n.period = 0,
            NodeKind::Worley(n) => n.period = 0,
            _ => unreachable!(),
        }
        let stem = dir.join("infinite");
        let graph = noise_graph(infinite, scale, lacunarity);
        match bake(gpu(), &compiled(&graph), &settings, &stem, |_, _| true) {
            Err(BakeError::NotTileable(failing)) => {
                assert!(
                    failing
                        .iter()
                        .all(|(_, seams)| seams.worst() > 10.0 * SEAM_TOLERANCE),
                    "{name}: {failing:?}"
                )
            }
            other => panic!("{name} without a period: {:?}", other.map(|m| m.len())),
        }
        assert!(
            !dir.join("infinite_albedo.png").exists(),
            "{name}: nothing written"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_tiled_normal_map_rolled_half_a_tile_is_the_tile_baked_half_a_tile_along() {
    let dir = temp_dir("tiles-normal");
    let (size, half) = (64u32, 32u32);
    let graph = noise_graph(
        NodeKind::Fbm(Fbm {
            basis: Basis::Gradient,
            octaves: 4,
            normalize: true,
            rotate: false,
            period: 3,
        }),
        3.0,
        None,
    );
    let along = veneer::render::FlatRect {
        x0: 0.5,
        z0: 0.5,
        x1: 1.5,
        z1: 1.5,
        y: 0.0,
    };
    let maps = vec![Map::Normal, Map::Albedo];
    let first = bake(
        gpu(),
        &compiled(&graph),
        &tile_settings(BakeSurface::Tile(None), size, maps.clone()),
        &dir.join("first"),
        |_, _| true,
    )
    .expect("bakes");
    let second = bake(
        gpu(),
        &compiled(&graph),
        &tile_settings(BakeSurface::Tile(Some(along)), size, maps.clone()),
        &dir.join("second"),
        |_, _| true,
    )
    .expect("bakes");
    for (a, b) in first.iter().zip(&second) {
        let (a, b) = (pixels(&a.path), pixels(&b.path));
        let mut worst = 0u8;
        for (x, y, p) in a.enumerate_pixels() {
            let q = b.get_pixel((x + half) % size, (y + half) % size);
            worst = worst.max((0..3).map(|k| p[k].abs_diff(q[k])).max().unwrap_or(0));
        }
        assert!(worst <= 1, "rolled and shifted differ by up to {worst}/255");
    }
    // Away from its edges a tile is the plain bake of the same square.
    let plain = bake(
        gpu(),
        &compiled(&graph),
        &tile_settings(
            BakeSurface::Plane(Some(veneer::bake::UNIT_TILE)),
            size,
            maps,
        ),
        &dir.join("plain"),
        |_, _| true,
    )
    .expect("bakes");
    let (tile, plain_normal) = (pixels(&first[0].path), pixels(&plain[0].path));
    for (x, y, p) in tile.enumerate_pixels() {
        if (1..size - 1).contains(&x) && (1..size - 1).contains(&y) {
            assert_eq!(p, plain_normal.get_pixel(x, y), "({x}, {y})");
        }
    }
    assert_eq!(
        pixels(&first[1].path),
        pixels(&plain[1].path),
        "the albedo is the plain bake's"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bake_tile_reports_the_seams_and_refuses_a_graph_that_does_not_repeat() {
    let dir = temp_dir("tiles-cli");
    let tiling = dir.join("tiling.ron");
    let (_, kind, scale, _) = periodic_noises().remove(1);
    veneer::graph::save(&noise_graph(kind.clone(), scale, None), &tiling).expect("saved");
    let dir_arg = dir.to_str().unwrap();
    let output = run_veneer(&[
        "bake",
        tiling.to_str().unwrap(),
        "--tile",
        "--size",
        "32",
        "--maps",
        "albedo",
        "-o",
        dir_arg,
    ]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    assert!(stderr.contains("tiles: edges differ by up to"), "{stderr}");
    let NodeKind::Fbm(mut fbm) = kind else {
        unreachable!()
    };
    fbm.period = 0;
    let infinite = dir.join("infinite.ron");
    veneer::graph::save(&noise_graph(NodeKind::Fbm(fbm), scale, None), &infinite).expect("saved");
    let output = run_veneer(&[
        "bake",
        infinite.to_str().unwrap(),
        "--tile",
        "--size",
        "32",
        "-o",
        dir_arg,
    ]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("infinite.ron: the maps do not tile")
            && stderr.contains("the albedo map's edges differ by up to")
            && stderr.contains("nothing was baked"),
        "{stderr}"
    );
    assert!(!dir.join("infinite_albedo.png").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_simplex_period_that_is_not_a_multiple_of_3_is_a_check_error_naming_the_node() {
    let graph = noise_graph(
        NodeKind::Noise(Noise {
            basis: Basis::Simplex,
            period: 4,
        }),
        4.0,
        None,
    );
    let message = veneer::codegen::compile(&graph, &Default::default())
        .expect_err("refused")
        .to_string();
    assert!(
        message.contains("'noise'")
            && message.contains("multiple of 3")
            && message.contains("try 3"),
        "{message}"
    );
    let rotated = NodeKind::Fbm(Fbm {
        basis: Basis::Gradient,
        octaves: 3,
        normalize: false,
        rotate: true,
        period: 4,
    });
    let message = veneer::codegen::compile(&noise_graph(rotated, 4.0, None), &Default::default())
        .expect_err("refused")
        .to_string();
    assert!(
        message.contains("rotated octaves cannot repeat"),
        "{message}"
    );
}

/// Every periodic noise of [`periodic_noises`] in one graph, summed into the albedo.
pub fn all_periodic_noises() -> Graph {
    let mut graph = Graph::default();
    let position = graph.add("position", NodeKind::Position);
    let mut sum: Option<(veneer::graph::NodeId, &str)> = None;
    for (name, kind, scale, lacunarity) in periodic_noises() {
        let noise = graph.add(&name, kind);
        graph.set_input(noise, "scale", Value::Float(scale));
        if let Some(lacunarity) = lacunarity {
            graph.set_input(noise, "lacunarity", Value::Float(lacunarity));
        }
        graph.connect(position, "position", noise, "p");
        sum = Some(match sum {
            None => (noise, "value"),
            Some((before, pin)) => {
                let add = graph.add(
                    "sum",
                    NodeKind::Math(veneer::nodes::Math {
                        op: veneer::graph::MathOp::Add,
                        ty: veneer::graph::ValueType::Float,
                    }),
                );
                graph.connect(before, pin, add, "a");
                graph.connect(noise, "value", add, "b");
                (add, "result")
            }
        });
    }
    let material = graph.add("material", NodeKind::Material);
    let (last, pin) = sum.expect("noises");
    graph.connect(last, pin, material, "albedo");
    graph
}

/// Noise at a domain-warped point as the albedo, and a noise bump: both warp and bump
/// repeat over `period` cells (0: never) at scales that span whole periods of the tile.
pub fn warped_and_bumped(period: u32) -> Graph {
    let mut graph = Graph::default();
    let position = graph.add("position", NodeKind::Position);
    let warp = graph.add(
        "warp",
        NodeKind::DomainWarp(veneer::nodes::DomainWarp {
            basis: Basis::Gradient,
            period,
        }),
    );
    graph.set_input(warp, "scale", Value::Float(3.0));
    graph.set_input(warp, "strength", Value::Float(0.15));
    let noise = graph.add(
        "noise",
        NodeKind::Noise(Noise {
            basis: Basis::ValuePcg,
            period: 2 * period,
        }),
    );
    graph.set_input(noise, "scale", Value::Float(6.0));
    let bump = graph.add(
        "bump",
        NodeKind::NoiseBump(veneer::nodes::NoiseBump {
            basis: Basis::Simplex,
            period: 2 * period,
        }),
    );
    graph.set_input(bump, "scale", Value::Float(6.0));
    graph.set_input(bump, "strength", Value::Float(0.3));
    let material = graph.add("material", NodeKind::Material);
    graph.connect(position, "position", warp, "p");
    graph.connect(warp, "p", noise, "p");
    graph.connect(position, "position", bump, "p");
    graph.connect(noise, "value", material, "albedo");
    graph.connect(bump, "bump", material, "bump");
    graph
}

#[test]
fn a_domain_warp_and_a_noise_bump_with_periods_tile_too() {
    let dir = temp_dir("tiles-warp");
    let settings = tile_settings(BakeSurface::Tile(None), 64, vec![Map::Albedo, Map::Normal]);
    let maps = bake(
        gpu(),
        &compiled(&warped_and_bumped(3)),
        &settings,
        &dir.join("warped"),
        |_, _| true,
    )
    .expect("a periodic warp and bump tile");
    assert!(
        maps.iter()
            .all(|m| m.seams.is_some_and(|s| s.worst() <= SEAM_TOLERANCE)),
        "{:?}",
        maps.iter().map(|m| m.seams).collect::<Vec<_>>()
    );
    match bake(
        gpu(),
        &compiled(&warped_and_bumped(0)),
        &settings,
        &dir.join("infinite"),
        |_, _| true,
    ) {
        Err(BakeError::NotTileable(failing)) => assert_eq!(failing.len(), 2, "{failing:?}"),
        other => panic!("without periods: {:?}", other.map(|m| m.len())),
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The blurred-noise preset with its noise's period set to `period` cells (0: none).
fn blurred_noise_with_period(period: u32) -> Graph {
    let mut graph = veneer::graph::load(&crate::support::root("graphs/texture/blurred_noise.ron"))
        .expect("the preset loads");
    for node in &mut graph.nodes {
        if let NodeKind::Fbm(fbm) = &mut node.kind {
            fbm.period = period;
        }
    }
    graph
}

#[test]
fn a_wrapped_buffer_that_does_not_repeat_is_refused_naming_its_pass() {
    let dir = temp_dir("tile-buffer-seam");
    let settings = tile_settings(BakeSurface::Tile(None), 128, vec![Map::Albedo, Map::Normal]);
    // The material itself reads only wrapped buffers: past the tile's edges it reads
    // them from the opposite side, so only the buffer's own check sees the seam.
    match bake(
        gpu(),
        &compiled(&blurred_noise_with_period(0)),
        &settings,
        &dir.join("a"),
        |_, _| true,
    ) {
        Err(error @ BakeError::BuffersNotTileable(_)) => {
            let BakeError::BuffersNotTileable(seams) = &error else {
                unreachable!()
            };
            assert_eq!(seams.len(), 1, "{seams:?}");
            assert!(seams[0].pass.contains("'grain'"), "{}", seams[0].pass);
            assert!(
                seams[0].left_right > 0.01 && seams[0].top_bottom > 0.01,
                "{seams:?}"
            );
            assert!(error.to_string().contains("nothing was baked"), "{error}");
        }
        other => panic!(
            "a noise without a period, blurred: {:?}",
            other.map(|m| m.len())
        ),
    }
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        0,
        "nothing written"
    );
    let maps = bake(
        gpu(),
        &compiled(&blurred_noise_with_period(6)),
        &settings,
        &dir.join("b"),
        |_, _| true,
    )
    .expect("with its period the preset tiles");
    assert_eq!(maps.len(), 2);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_photo_read_as_it_is_is_named_by_a_tile_bake_and_make_tileable_clears_it() {
    use veneer::bake::bitmap_seams::{EDGE_RATIO_TOLERANCE, seamed_bitmaps};
    let source = crate::support::root("graphs/texture/gravel.ron");
    let gravel = veneer::graph::load(&source).expect("the preset loads");
    assert_eq!(
        seamed_bitmaps(&compiled(&gravel)),
        [],
        "through Make tileable"
    );
    // The same graph with the photo wired where Make tileable's result was.
    let mut raw = gravel.clone();
    let photo = raw
        .nodes
        .iter()
        .find(|n| matches!(n.kind, NodeKind::ImageFile(_)))
        .unwrap()
        .id;
    let seamless = raw
        .nodes
        .iter()
        .find(|n| matches!(n.kind, NodeKind::MakeTileable(_)))
        .unwrap()
        .id;
    for wire in &mut raw.wires {
        if wire.from.node == seamless {
            wire.from = veneer::graph::PinRef::new(photo, "value");
        }
    }
    let seamed = seamed_bitmaps(&compiled(&raw));
    assert_eq!(seamed.len(), 1, "{seamed:?}");
    assert!(seamed[0].path.ends_with("gravel.jpg"));
    assert!(
        seamed[0].ratios.iter().all(|&r| r > EDGE_RATIO_TOLERANCE),
        "{seamed:?}"
    );
    // The command line warns before it bakes (the graph beside a copy of the photo).
    let dir = temp_dir("tile-raw-photo");
    std::fs::copy(
        crate::support::root("assets/photos/gravel.jpg"),
        dir.join("gravel.jpg"),
    )
    .unwrap();
    for node in &mut raw.nodes {
        if let NodeKind::ImageFile(image) = &mut node.kind {
            image.path = "gravel.jpg".into();
        }
    }
    let path = dir.join("raw.ron");
    veneer::graph::save(&raw, &path).unwrap();
    let output = run_veneer(&[
        "bake",
        path.to_str().unwrap(),
        "--tile",
        "--size",
        "64",
        "--maps",
        "albedo",
        "-o",
        dir.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    assert!(
        stderr.contains("warning:")
            && stderr.contains("gravel.jpg")
            && stderr.contains("Make tileable"),
        "{stderr}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
