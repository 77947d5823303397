//! `veneer fit`, as a user runs it: a preset rendered flat at parameter values drawn at
//! random is fitted back from the preset's own values (the parameters a statistical
//! loss can tell apart), and every kind of bad input is refused with nothing written.

use crate::support::{run_veneer, temp_dir};
use veneer::eval::Evaluator;
use veneer::fit::recovery::{assignments, draw_truth, median_error};
use veneer::fit::space::Space;

/// Runs `veneer fit graph photo --size size` with `extra` arguments, writing `output`,
/// and returns its JSON summary.
fn fit_json(
    graph: &str,
    photo: &std::path::Path,
    size: &str,
    extra: &[&str],
    output: &std::path::Path,
) -> serde_json::Value {
    let (photo, output) = (
        photo.to_str().expect("a UTF-8 path"),
        output.to_str().expect("a UTF-8 path"),
    );
    let mut args = vec!["fit", graph, photo, "--size", size, "--json", "-o", output];
    args.extend(extra);
    let fit = run_veneer(&args);
    assert!(fit.status.success(), "{fit:?}");
    serde_json::from_slice(&fit.stdout).expect("the summary is JSON")
}

/// The fit's JSON summary, with the fitted places of `space`'s coordinates.
struct Summary {
    initial: f64,
    fitted: f64,
    places: Vec<f64>,
}

fn summary(value: &serde_json::Value, space: &Space) -> Summary {
    let places = (space.coordinates.iter())
        .map(|c| {
            let name = &space.names[c.parameter];
            let lane = value["parameters"][name][c.lane].as_f64();
            c.place(lane.unwrap_or_else(|| panic!("{name}.{} in {value}", c.lane)))
        })
        .collect();
    Summary {
        initial: value["initial_total"].as_f64().expect("initial_total"),
        fitted: value["fitted_total"].as_f64().expect("fitted_total"),
        places,
    }
}

/// Renders `graph` flat over its preview square with `fitted` drawn at random, fits
/// those parameters back, and returns the median normalised error and the loss's
/// fraction left.
fn recover(graph: &str, fitted: &[&str], seed: u64) -> (f64, f64) {
    let dir = temp_dir(&format!("fit-{seed}"));
    let loaded = veneer::graph::load(&crate::support::root(graph)).expect("the preset loads");
    let evaluator = Evaluator::new(&loaded).expect("the preset checks");
    let names: Vec<String> = fitted.iter().map(ToString::to_string).collect();
    let space =
        Space::of(&evaluator.graph().parameters, |_| true, Some(&names)).expect("the names");
    let truth = draw_truth(&space, seed);
    let rect = veneer::render::preview_rect(&loaded.preview);
    let flat = format!(
        "--flat={},{},{},{},{}",
        rect.x0, rect.z0, rect.x1, rect.z1, rect.y
    );
    let target = dir.join("target.png");
    let mut render = vec!["render", graph, &flat, "--size", "128"];
    let sets = assignments(&space, &truth);
    for set in &sets {
        render.extend(["--set", set]);
    }
    render.extend(["-o", target.to_str().expect("a UTF-8 path")]);
    let rendered = run_veneer(&render);
    assert!(rendered.status.success(), "{rendered:?}");
    let output = dir.join("fitted.ron");
    let params = fitted.join(",");
    let result = summary(
        &fit_json(graph, &target, "64", &["--params", &params], &output),
        &space,
    );
    // The written graph carries the values, and the `fit` preset too.
    let written = std::fs::read_to_string(&output).expect("the fitted graph");
    assert!(written.contains("\"fit\": {"), "{written}");
    (
        median_error(&result.places, &truth),
        result.fitted / result.initial,
    )
}

#[test]
fn fitting_recovers_the_values_a_preset_was_rendered_at() {
    for (graph, fitted, seed) in [
        (
            "graphs/marble.ron",
            &["vein_frequency", "vein_colour", "stone_colour"][..],
            3,
        ),
        (
            "graphs/wood.ron",
            &["ring_frequency", "early_wood", "grain_stretch"][..],
            5,
        ),
    ] {
        let (error, left) = recover(graph, fitted, seed);
        assert!(error <= 0.05, "{graph}: median normalised error {error}");
        assert!(left <= 0.1, "{graph}: {left} of the starting loss left");
    }
}

#[test]
fn basins_are_measured_along_each_coordinate_from_the_truth() {
    use veneer::fit::image::Canvas;
    use veneer::fit::loss::Loss;
    use veneer::fit::recovery::{basin_width, near};
    let loaded =
        veneer::graph::load(&crate::support::root("graphs/marble.ron")).expect("marble loads");
    let evaluator = Evaluator::new(&loaded).expect("marble checks");
    let names = ["vein_frequency".to_string(), "stone_colour".to_string()];
    let space = Space::of(&evaluator.graph().parameters, |_| true, Some(&names)).expect("names");
    let canvas = Canvas {
        evaluator: &evaluator,
        rect: veneer::render::preview_rect(&loaded.preview),
        size: 16,
    };
    let truth = draw_truth(&space, 4);
    let loss = Loss::new(1);
    let target = loss.target(&canvas.render(&space, &truth), true);
    // A colour lane's loss rises all the way to both ends of its span.
    let red = (space.coordinates.iter())
        .position(|c| space.names[c.parameter] == "stone_colour")
        .expect("the stone colour");
    let width = basin_width(&canvas, (&loss, &target), &space, &truth, red, 0.0);
    assert_eq!(width, Some(1.0));
    // The frequency's does not: other vein counts line up with the target elsewhere.
    let width = basin_width(&canvas, (&loss, &target), &space, &truth, 0, 0.0);
    assert!(width.is_some_and(|w| w < 1.0), "{width:?}");
    // Nothing changes by more than a huge loss: flat.
    let width = basin_width(&canvas, (&loss, &target), &space, &truth, red, 1e9);
    assert_eq!(width, None);
    // Nearby starts stay within reach of the truth and within the span.
    for (start, true_place) in near(&truth, 0.1, 7).iter().zip(&truth) {
        assert!((start - true_place).abs() <= 0.1 && (0.0..=1.0).contains(start));
    }
}

/// A graph whose albedo is one of three colours (red, green, blue: the choice `look`)
/// times the colour `tint`.
fn three_looks() -> veneer::graph::Graph {
    use veneer::graph::group::Hint;
    use veneer::graph::parameters::Parameter;
    use veneer::graph::{Graph, NodeKind, Value, ValueType};
    let mut graph = Graph::default();
    let switch = graph.add(
        "look",
        NodeKind::Switch(veneer::nodes::Switch {
            ty: ValueType::Color,
        }),
    );
    for (pin, colour) in [
        ("a", (1.0, 0.0, 0.0)),
        ("b", (0.0, 1.0, 0.0)),
        ("c", (0.0, 0.0, 1.0)),
    ] {
        graph.set_input(switch, pin, Value::Color(colour.0, colour.1, colour.2));
    }
    graph.set_input(switch, "choice", Value::Float(0.0));
    let tint = graph.add(
        "tint",
        NodeKind::Math(veneer::nodes::Math {
            op: veneer::graph::MathOp::Multiply,
            ty: ValueType::Color,
        }),
    );
    graph.set_input(tint, "b", Value::Color(1.0, 1.0, 1.0));
    let material = graph.add("material", NodeKind::Material);
    graph.connect(switch, "result", tint, "a");
    graph.connect(tint, "result", material, "albedo");
    graph.parameters = vec![
        Parameter {
            name: "look".into(),
            node: switch,
            pin: "choice".into(),
            range: None,
            hint: Hint::Choice(vec!["red".into(), "green".into(), "blue".into()]),
        },
        Parameter {
            name: "tint".into(),
            node: tint,
            pin: "b".into(),
            range: None,
            hint: Hint::Colour,
        },
    ];
    graph
}

#[test]
fn choices_are_searched_with_the_continuous_parameters() {
    let dir = temp_dir("fit-choices");
    let graph = dir.join("three looks.ron");
    veneer::graph::save(&three_looks(), &graph).expect("the graph is written");
    // A photo of the blue look at half strength.
    let photo = dir.join("dim blue.png");
    image::RgbImage::from_pixel(48, 48, image::Rgb([0, 0, 128]))
        .save(&photo)
        .expect("a photo");
    let output = dir.join("fitted.ron");
    let graph = graph.to_str().expect("a UTF-8 path");
    let value = fit_json(graph, &photo, "32", &[], &output);
    assert_eq!(
        value["parameters"]["look"][0].as_f64(),
        Some(2.0),
        "{value}"
    );
    let blue = value["parameters"]["tint"][2].as_f64().expect("the tint");
    assert!((blue - 0.5).abs() < 0.05, "{value}");
    let fitted = value["fitted_total"].as_f64().expect("fitted_total");
    assert!(fitted < 1e-3, "{value}");
}

#[test]
fn a_group_input_its_read_outputs_do_not_use_is_not_fitted() {
    use veneer::graph::group::{GroupInput, Hint};
    let dir = temp_dir("fit-unused-input");
    let mut marble = veneer::graph::preset("marble").expect("the marble preset");
    let definition = marble
        .groups
        .get_mut("veined_marble")
        .expect("marble's group");
    definition.linked = false;
    definition.inputs.push(GroupInput {
        name: "unused".into(),
        ty: veneer::graph::ValueType::Float,
        default: veneer::graph::Value::Float(0.5),
        range: Some((0.0, 1.0)),
        hint: Hint::Slider,
    });
    let graph = dir.join("marble with an unused input.ron");
    veneer::graph::save(&marble, &graph).expect("the graph is written");
    let graph = graph.to_str().expect("a UTF-8 path");
    let photo = dir.join("photo.png");
    image::RgbImage::from_pixel(40, 40, image::Rgb([200, 190, 180]))
        .save(&photo)
        .expect("a photo");
    let output = dir.join("fitted.ron");
    let refused = run_veneer(&[
        "fit",
        graph,
        photo.to_str().expect("a UTF-8 path"),
        "--params",
        "unused",
        "-o",
        output.to_str().expect("a UTF-8 path"),
    ]);
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert_eq!(refused.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("parameter 'unused' does not reach the albedo"),
        "{stderr}"
    );
    // Fitting everything leaves it out and keeps the others.
    let steps = ["--steps", "1", "--starts", "1"];
    let value = fit_json(graph, &photo, "32", &steps, &output);
    let fitted = value["parameters"].as_object().expect("the parameters");
    assert!(
        !fitted.contains_key("unused") && fitted.contains_key("vein_colour"),
        "{value}"
    );
}

/// The CRC-32 of PNG chunks (of the type and data).
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &byte in bytes {
        crc ^= u32::from(byte);
        for _ in 0..8 {
            crc = (crc >> 1) ^ (0xEDB8_8320 & (crc & 1).wrapping_neg());
        }
    }
    !crc
}

/// A PNG whose header says `width`×`height`, with no pixel data (the size is read from
/// the header, so its pixels are never asked for).
fn png_header(width: u32, height: u32) -> Vec<u8> {
    let mut header = Vec::new();
    header.extend(width.to_be_bytes());
    header.extend(height.to_be_bytes());
    header.extend([8, 2, 0, 0, 0]);
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    for (kind, data) in [
        (b"IHDR", header),
        (b"IDAT", Vec::new()),
        (b"IEND", Vec::new()),
    ] {
        let chunk = [&kind[..], &data].concat();
        png.extend(
            u32::try_from(data.len())
                .expect("a small chunk")
                .to_be_bytes(),
        );
        png.extend(&chunk);
        png.extend(crc32(&chunk).to_be_bytes());
    }
    png
}

#[test]
fn bad_photos_graphs_and_names_are_refused_with_nothing_written() {
    let dir = temp_dir("fit-refusals");
    let photo = dir.join("photo.png");
    image::RgbImage::from_pixel(48, 48, image::Rgb([120, 90, 60]))
        .save(&photo)
        .expect("a photo");
    let garbage = dir.join("garbage.png");
    std::fs::write(&garbage, "not a picture").expect("a file");
    let tiny = dir.join("tiny.png");
    image::RgbImage::new(20, 20)
        .save(&tiny)
        .expect("a tiny photo");
    let huge = dir.join("huge.png");
    std::fs::write(&huge, png_header(20_000, 20_000)).expect("a huge header");
    let output = dir.join("fitted.ron");
    let text = |path: &std::path::Path| path.to_str().expect("a UTF-8 path").to_string();
    let cases: [(&str, String, &[&str], &str); 9] = [
        (
            "graphs/marble.ron",
            text(&garbage),
            &[],
            "garbage.png: cannot read the photo",
        ),
        (
            "graphs/marble.ron",
            text(&tiny),
            &[],
            "is 20×20 pixels: give one at least 32",
        ),
        (
            "graphs/marble.ron",
            text(&huge),
            &[],
            "is 20000×20000 pixels: give one of at most",
        ),
        (
            "graphs/wood_classic.ron",
            text(&photo),
            &[],
            "exposes no parameter (float, vector, colour, toggle or choice) that reaches the albedo",
        ),
        (
            "graphs/wood_classic.ron",
            text(&photo),
            &["--params", "gloss_shininess"],
            "parameter 'gloss_shininess' does not reach the albedo",
        ),
        (
            "graphs/marble.ron",
            text(&photo),
            &["--params", "vein_frequency,veins_everywhere"],
            "the graph exposes no parameter 'veins_everywhere' (it exposes vein_frequency,",
        ),
        (
            "graphs/thesis_c4_paint_metal_rust.ron",
            text(&photo),
            &[],
            "reads a field of the mesh",
        ),
        (
            "graphs/texture/worn_bricks.ron",
            text(&photo),
            &[],
            "is a buffered pass",
        ),
        (
            "graphs/marble.ron",
            text(&photo),
            &["--budget", "1e20"],
            "--budget 100000000000000000000: too many seconds",
        ),
    ];
    // Outputs that cannot be written are refused before the work.
    let missing = dir.join("no such folder").join("fitted.ron");
    for (out, expected) in [
        (missing.to_str().expect("a UTF-8 path"), "does not exist"),
        (dir.to_str().expect("a UTF-8 path"), "is a folder"),
    ] {
        let started = std::time::Instant::now();
        let photo = text(&photo);
        let run = run_veneer(&["fit", "graphs/marble.ron", &photo, "-o", out]);
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(1), "{out}: {stderr}");
        assert!(stderr.contains(expected), "{out}: {stderr}");
        assert!(
            started.elapsed().as_secs() < 5,
            "{out}: refused only after fitting"
        );
    }
    for (graph, photo, extra, expected) in cases {
        let mut args = vec!["fit", graph, &photo];
        args.extend(extra);
        args.extend(["-o", output.to_str().expect("a UTF-8 path")]);
        let run = run_veneer(&args);
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(1), "{args:?}: {stderr}");
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
        assert!(!output.exists(), "{args:?} wrote {}", output.display());
    }
}

#[test]
fn photographs_of_gravel_and_brick_lower_their_presets_loss_by_half() {
    for (graph, photo) in [
        ("graphs/gravel.ron", "target/photos/gravel.png"),
        ("graphs/thesis_brick.ron", "target/photos/brick.png"),
    ] {
        let photo = crate::support::root(photo);
        assert!(
            photo.exists(),
            "{}: one of the CC0 photographs `.ci/run` takes out of scikit-image's package",
            photo.display()
        );
        let dir = temp_dir("fit-photos");
        let output = dir.join("fitted.ron");
        let value = fit_json(graph, &photo, "64", &[], &output);
        let (initial, fitted) = (
            value["initial_total"].as_f64(),
            value["fitted_total"].as_f64(),
        );
        let (initial, fitted) = (initial.expect("initial"), fitted.expect("fitted"));
        assert!(fitted <= 0.5 * initial, "{graph}: {initial} → {fitted}");
    }
}

#[test]
fn images_of_any_side_in_range_fit_odd_ones_included() {
    let dir = temp_dir("fit-odd");
    let photo = dir.join("photo.png");
    image::RgbImage::from_fn(40, 40, |x, y| {
        image::Rgb([(x * 6) as u8, (y * 6) as u8, 90])
    })
    .save(&photo)
    .expect("a photo");
    // Pyramid levels of odd sides (17 → 8, 65 → 32 → 16) pass their derivatives down.
    for size in ["17", "65"] {
        let output = dir.join(format!("fitted {size}.ron"));
        let steps = ["--steps", "2", "--starts", "1"];
        let value = fit_json("graphs/marble.ron", &photo, size, &steps, &output);
        assert!(value["fitted_total"].as_f64().is_some(), "{value}");
    }
}

#[test]
fn a_global_search_starts_at_the_graphs_values_and_gives_the_same_file_twice() {
    let dir = temp_dir("fit-global");
    let photo = dir.join("photo.png");
    let render = [
        "render",
        "graphs/marble.ron",
        "--flat=-8,-8,8,8,0.5",
        "--size",
        "64",
        "--set",
        "vein_frequency=14",
        "--set",
        "stone_colour=0.6,0.5,0.4",
        "-o",
        photo.to_str().expect("a UTF-8 path"),
    ];
    let rendered = run_veneer(&render);
    assert!(rendered.status.success(), "{rendered:?}");
    let extra = [
        "--global",
        "--steps",
        "8",
        "--starts",
        "3",
        "--params",
        "vein_frequency,stone_colour",
    ];
    let outputs = [dir.join("first.ron"), dir.join("second.ron")];
    let values: Vec<serde_json::Value> = (outputs.iter())
        .map(|output| fit_json("graphs/marble.ron", &photo, "32", &extra, output))
        .collect();
    let value = &values[0];
    let initial = value["initial_total"].as_f64().expect("initial_total");
    let fitted = value["fitted_total"].as_f64().expect("fitted_total");
    assert!(fitted < initial, "{value}");
    // At 32² the coarse stage is the last: the second start's search began where the
    // first start did, at the graph's values; the third at a random draw.
    let starts = value["starts"].as_array().expect("starts");
    assert_eq!(starts.len(), 3, "{value}");
    assert_eq!(starts[1]["initial"], value["initial_total"], "{value}");
    assert_ne!(starts[2]["initial"], value["initial_total"], "{value}");
    assert_eq!(values[0]["parameters"], values[1]["parameters"]);
    let files = outputs.map(|output| std::fs::read(output).expect("a fitted graph"));
    assert_eq!(files[0], files[1]);
}
