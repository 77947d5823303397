//! Image nodes: files relative to the graph's folder, read texel for texel on the GPU
//! and the CPU, flood-filled when they are hand-drawn masks, refused with the node and
//! the file named when they cannot be used, and exported with a manifest entry.

use crate::passes::{TILE, pixel_differences, show, tolerance};
use crate::support::{gpu, run_veneer, temp_dir};
use veneer::codegen::{CompileError, compile};
use veneer::graph::{Graph, NodeKind, Shading, ValueType};
use veneer::nodes::passes::{EdgeMode, Filter};
use veneer::nodes::{FloodFill, ImageFile};
use veneer::render::FlatRenderer;

/// A graph in `folder` showing output `output` of an Image node reading `path`.
fn image_graph(folder: &std::path::Path, image: ImageFile, output: &str, ty: ValueType) -> Graph {
    let mut graph = Graph::default();
    let node = graph.add("photo", NodeKind::ImageFile(image));
    show(&mut graph, node, output, ty);
    graph.folder = veneer::graph::Folder(Some(folder.to_path_buf()));
    graph
}

/// A non-square RGBA picture whose every texel differs.
fn picture(width: u32, height: u32) -> image::RgbaImage {
    image::RgbaImage::from_fn(width, height, |x, y| {
        image::Rgba([
            (x * 255 / width) as u8,
            (y * 255 / height) as u8,
            ((x * 7 + y * 13) % 256) as u8,
            (255 - (x + y) % 200) as u8,
        ])
    })
}

#[test]
fn image_nodes_read_their_files_alike_on_the_gpu_and_the_cpu() {
    let dir = temp_dir("bitmap-gpu-cpu");
    std::fs::create_dir_all(dir.join("graphs")).unwrap();
    std::fs::create_dir_all(dir.join("assets")).unwrap();
    picture(40, 24).save(dir.join("assets/pic.png")).unwrap();
    let float = image::Rgba32FImage::from_fn(9, 5, |x, y| {
        image::Rgba([x as f32 * 3.5 - 6.0, y as f32 * 0.25, 100.0, 1.0])
    });
    float.save(dir.join("assets/height.exr")).unwrap();
    let mut failures = Vec::new();
    for (file, colour_space) in [
        ("../assets/pic.png", veneer::bitmaps::ColourSpace::Auto),
        ("../assets/pic.png", veneer::bitmaps::ColourSpace::Srgb),
        ("../assets/height.exr", veneer::bitmaps::ColourSpace::Auto),
    ] {
        for edge in EdgeMode::ALL {
            for filter in Filter::ALL {
                for (output, ty) in [
                    ("colour", ValueType::Color),
                    ("alpha", ValueType::Float),
                    ("value", ValueType::Float),
                ] {
                    let image = ImageFile {
                        path: file.to_string(),
                        colour_space,
                        edge,
                        filter,
                    };
                    let graph = image_graph(&dir.join("graphs"), image, output, ty);
                    let compiled = compile(&graph, &Default::default())
                        .unwrap_or_else(|e| panic!("{file} {edge:?} {filter:?}: {e}"));
                    // Past the tile too, where the edge mode decides.
                    let rect = veneer::render::FlatRect {
                        x0: -0.6,
                        z0: -0.3,
                        x1: 1.7,
                        z1: 1.4,
                        y: 0.0,
                    };
                    let differences = pixel_differences(&compiled, rect, 50);
                    let scale = if file.ends_with("exr") { 100.0 } else { 1.0 };
                    let allowed = tolerance(&compiled) * scale;
                    let worst = differences.iter().copied().fold(0.0, f64::max);
                    if worst > allowed {
                        failures.push(format!(
                            "{file} {colour_space:?} {edge:?} {filter:?} {output}: off by {worst:.2e}"
                        ));
                    }
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn a_square_image_drawn_at_its_size_gives_back_its_texels() {
    let dir = temp_dir("bitmap-texels");
    let picture = picture(32, 32);
    picture.save(dir.join("pic.png")).unwrap();
    for shading in Shading::ALL {
        let image = ImageFile {
            path: "pic.png".into(),
            ..ImageFile::default()
        };
        let mut graph = image_graph(&dir, image, "colour", ValueType::Color);
        graph.shading = shading;
        let compiled = compile(&graph, &Default::default()).expect("the graph compiles");
        let pixels = FlatRenderer::for_compiled(gpu(), &compiled)
            .expect("the pipelines build")
            .render(gpu(), TILE, 32, 0.0)
            .expect("the passes render");
        for (pixel, texel) in pixels.iter().zip(picture.pixels()) {
            for lane in 0..3 {
                let stored = f32::from(texel.0[lane]) / 255.0;
                // A Blinn-Phong (or thesis) graph's colours are display values: the
                // file's numbers; a metallic-roughness graph's are linear light: decoded
                // from sRGB.
                let expected = if shading.is_linear() {
                    veneer::bitmaps::srgb_to_linear(stored)
                } else {
                    stored
                };
                assert!(
                    (pixel[lane] - expected).abs() < 1e-6,
                    "{shading:?}: {pixel:?} against {texel:?}"
                );
            }
        }
    }
}

/// The cells of `mask` (a boolean per texel, rows from the top), 4-connected across the
/// wrap: each texel's cell number, `None` outside the mask.
fn cells(mask: &[bool], side: usize) -> Vec<Option<usize>> {
    let mut parent: Vec<usize> = (0..mask.len()).collect();
    fn root(parent: &mut [usize], mut at: usize) -> usize {
        while parent[at] != at {
            parent[at] = parent[parent[at]];
            at = parent[at];
        }
        at
    }
    for y in 0..side {
        for x in 0..side {
            let at = y * side + x;
            for next in [y * side + (x + 1) % side, ((y + 1) % side) * side + x] {
                if mask[at] && mask[next] {
                    let (a, b) = (root(&mut parent, at), root(&mut parent, next));
                    parent[a] = b;
                }
            }
        }
    }
    (0..mask.len())
        .map(|at| mask[at].then(|| root(&mut parent, at)))
        .collect()
}

#[test]
fn a_hand_drawn_mask_gets_one_flood_fill_value_per_cell_across_the_wrap() {
    // tests/data/hand_mask.png: eight shapes drawn by hand (a ring, an arch, two
    // polygons, two ellipses, and two discs each cut by a seam), 128², hard-edged.
    let side = 128;
    let mut graph = Graph::default();
    let image = graph.add(
        "mask",
        NodeKind::ImageFile(ImageFile {
            path: "tests/data/hand_mask.png".into(),
            colour_space: veneer::bitmaps::ColourSpace::Linear,
            ..ImageFile::default()
        }),
    );
    let fill = graph.add("fill", NodeKind::FloodFill(FloodFill::default()));
    graph.connect(image, "value", fill, "mask");
    show(&mut graph, fill, "value", ValueType::Float);
    let compiled = compile(&graph, &Default::default()).expect("the fill compiles");
    let differences = pixel_differences(&compiled, TILE, side as u32);
    assert!(
        differences.iter().all(|&d| d <= tolerance(&compiled)),
        "the GPU's fill matches the CPU's"
    );
    let pixels = FlatRenderer::for_compiled(gpu(), &compiled)
        .expect("the passes' pipelines build")
        .render(gpu(), TILE, side as u32, 0.0)
        .expect("the passes render");
    let decoded = image::open(crate::support::root("tests/data/hand_mask.png"))
        .unwrap()
        .into_luma8();
    let mask: Vec<bool> = decoded.pixels().map(|p| p.0[0] > 127).collect();
    let cells = cells(&mask, side);
    let mut value_of_cell = std::collections::BTreeMap::new();
    for (pixel, cell) in pixels.iter().zip(&cells) {
        match cell {
            None => assert_eq!(pixel[0], 0.0, "outside the mask"),
            Some(cell) => {
                let value = *value_of_cell.entry(*cell).or_insert(pixel[0].to_bits());
                assert_eq!(value, pixel[0].to_bits(), "one value in cell {cell}");
            }
        }
    }
    let distinct: std::collections::BTreeSet<u32> = value_of_cell.values().copied().collect();
    assert_eq!(value_of_cell.len(), 8, "the drawing has eight cells");
    assert_eq!(
        distinct.len(),
        value_of_cell.len(),
        "each cell its own value"
    );
}

#[test]
fn unusable_images_are_check_errors_naming_the_node_and_the_file() {
    let dir = temp_dir("bitmap-errors");
    std::fs::write(dir.join("broken.png"), b"\x89PNG\r\n\x1a\n garbage").unwrap();
    std::os::unix::fs::symlink("/etc/hostname", dir.join("link.png")).ok();
    for (file, says) in [
        ("missing.png", "cannot be read"),
        ("broken.png", "does not decode"),
        ("link.png", "a link leads it out of"),
        ("", "no file chosen"),
    ] {
        let image = ImageFile {
            path: file.into(),
            ..ImageFile::default()
        };
        let graph = image_graph(&dir, image, "colour", ValueType::Color);
        let Err(CompileError::Check(errors)) = compile(&graph, &Default::default()) else {
            panic!("{file}: the check refuses it");
        };
        let message = errors[0].to_string();
        assert!(
            message.contains("node 'photo'") && message.contains(&format!("image '{file}'")),
            "{message}"
        );
        assert!(message.contains(says), "{message}");
    }
}

#[test]
fn the_cli_reads_images_beside_the_graph_and_refuses_broken_ones_writing_nothing() {
    let dir = temp_dir("bitmap-cli");
    std::fs::create_dir_all(dir.join("graphs")).unwrap();
    picture(16, 16).save(dir.join("pic.png")).unwrap();
    let graph = image_graph(
        &dir,
        ImageFile {
            path: "../pic.png".into(),
            ..ImageFile::default()
        },
        "colour",
        ValueType::Color,
    );
    let file = dir.join("graphs/photo.ron");
    veneer::graph::save(&graph, &file).unwrap();
    let out = dir.join("out");
    std::fs::create_dir_all(&out).unwrap();
    // Run from another folder: the path is relative to the graph, not to the shell.
    let baked = run_veneer(&[
        "bake",
        file.to_str().unwrap(),
        "--size",
        "16",
        "--maps",
        "albedo",
        "--tile",
        "--out-dir",
        out.to_str().unwrap(),
    ]);
    assert!(
        baked.status.success(),
        "{}",
        String::from_utf8_lossy(&baked.stderr)
    );
    assert!(out.join("photo_albedo.png").exists());
    std::fs::write(dir.join("pic.png"), b"not a png").unwrap();
    let out = dir.join("refused");
    std::fs::create_dir_all(&out).unwrap();
    let refused = run_veneer(&[
        "bake",
        file.to_str().unwrap(),
        "--size",
        "16",
        "--tile",
        "--out-dir",
        out.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert_eq!(refused.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("image '../pic.png'"), "{stderr}");
    let written = std::fs::read_dir(&out).map_or(0, |entries| entries.count());
    assert_eq!(written, 0, "nothing written");
}

#[test]
fn an_exported_image_material_lists_its_file_in_the_manifest() {
    let dir = temp_dir("bitmap-export");
    picture(12, 8).save(dir.join("pic.png")).unwrap();
    let graph = image_graph(
        &dir,
        ImageFile {
            path: "pic.png".into(),
            ..ImageFile::default()
        },
        "value",
        ValueType::Float,
    );
    let compiled = compile(&graph, &Default::default()).unwrap();
    for (target, _, _) in veneer::codegen::export::Target::ALL {
        let files = veneer::codegen::manifest::export_passes(&compiled, target, "photo")
            .unwrap_or_else(|e| panic!("{target:?}: {e}"));
        // The material's module and the manifest: the upload has no module.
        assert_eq!(files.len(), 2, "{target:?}");
        let manifest: serde_json::Value = serde_json::from_slice(&files[1].bytes).unwrap();
        let pass = &manifest["passes"][0];
        assert_eq!(pass["kind"], "bitmap");
        assert_eq!(pass["bitmap"]["file"], "pic.png");
        assert_eq!(pass["bitmap"]["width"], 12);
        assert_eq!(pass["bitmap"]["decode"], "linear");
        assert_eq!(manifest["material"]["reads"][0]["buffer"], 0);
    }
}

#[test]
fn a_material_that_only_reads_files_draws_on_meshes_like_its_colour_would() {
    // A file of one colour, and the same colour as a constant: on a mesh (at its UVs)
    // the two draw the same picture; the CPU evaluator reads the file too.
    let dir = temp_dir("bitmap-mesh");
    image::RgbaImage::from_pixel(5, 3, image::Rgba([200, 120, 40, 255]))
        .save(dir.join("flat.png"))
        .unwrap();
    let from_file = image_graph(
        &dir,
        ImageFile {
            path: "flat.png".into(),
            ..ImageFile::default()
        },
        "colour",
        ValueType::Color,
    );
    let mut constant = Graph::default();
    let colour = constant.add(
        "colour",
        NodeKind::Constant(veneer::nodes::Constant {
            ty: ValueType::Color,
        }),
    );
    constant.set_input(
        colour,
        "value",
        veneer::graph::Value::Color(200.0 / 255.0, 120.0 / 255.0, 40.0 / 255.0),
    );
    show(&mut constant, colour, "value", ValueType::Color);
    let file_compiled = compile(&from_file, &Default::default()).unwrap();
    assert!(file_compiled.passes.uploads_only());
    let constant_compiled = compile(&constant, &Default::default()).unwrap();
    for mesh in ["sphere", "torus"] {
        let view = veneer::render::View::Mesh(Some(mesh.into()));
        let drawn = |compiled| {
            veneer::render::render_material(gpu(), compiled, &view, 96, 0.0)
                .unwrap_or_else(|e| panic!("{mesh}: {e}"))
        };
        assert_eq!(drawn(&file_compiled), drawn(&constant_compiled), "{mesh}");
    }
    // Baked over the sphere's UV layout (the CLI's `bake --mesh`) the maps are the same
    // bytes too, and a glTF export bakes it.
    let out = dir.join("maps");
    std::fs::create_dir_all(&out).unwrap();
    for (name, graph) in [("file", &from_file), ("constant", &constant)] {
        let file = dir.join(format!("{name}.ron"));
        veneer::graph::save(graph, &file).unwrap();
        for extra in [
            vec![
                "--mesh",
                "sphere",
                "--maps",
                "albedo",
                "-o",
                out.to_str().unwrap(),
            ],
            vec![
                "--gltf",
                dir.join(format!("{name}.glb"))
                    .to_str()
                    .unwrap()
                    .to_string()
                    .leak(),
            ],
        ] {
            let mut args = vec!["bake", file.to_str().unwrap(), "--size", "64"];
            args.extend(extra);
            let baked = run_veneer(&args);
            assert!(
                baked.status.success(),
                "{}",
                String::from_utf8_lossy(&baked.stderr)
            );
        }
    }
    let read = |name: &str| std::fs::read(dir.join(name)).unwrap();
    assert_eq!(
        read("maps/file_albedo.png"),
        read("maps/constant_albedo.png")
    );
    assert!(
        read("file.glb").starts_with(b"glTF"),
        "the glTF export bakes it"
    );
    let evaluator = veneer::eval::Evaluator::from_checked(file_compiled.checked.clone());
    let albedo = evaluator
        .eval(&veneer::eval::Surface::<f64>::at([0.3, 0.1, 0.2]))
        .albedo;
    assert!((albedo[0] - 200.0 / 255.0).abs() < 1e-6, "{albedo:?}");
}

#[test]
fn a_new_time_renders_the_passes_again_but_not_the_uploads() {
    // A file blurred: at a new time the blur's surface pass and its two axes render
    // again; the file, which no time changes, is not uploaded again.
    let mut graph = Graph::default();
    let photo = graph.add(
        "photo",
        NodeKind::ImageFile(ImageFile {
            path: "hand_mask.png".into(),
            ..ImageFile::default()
        }),
    );
    let blur = graph.add(
        "soft",
        NodeKind::Blur(veneer::nodes::Blur {
            ty: ValueType::Float,
            unit: veneer::nodes::RadiusUnit::Texels,
        }),
    );
    graph.connect(photo, "value", blur, "image");
    show(&mut graph, blur, "result", ValueType::Float);
    graph.folder = veneer::graph::Folder(Some(crate::support::root("tests/data")));
    let compiled = compile(&graph, &Default::default()).expect("compiles");
    let uploads = (compiled.passes.passes.iter())
        .filter(|pass| matches!(pass.kind, veneer::codegen::passes::PassKind::Bitmap { .. }))
        .count() as u64;
    assert_eq!(uploads, 1);
    let flat = FlatRenderer::for_compiled(gpu(), &compiled).expect("pipelines");
    flat.render(gpu(), TILE, 16, 0.0).expect("renders");
    let all = flat.passes_rendered();
    assert_eq!(all, compiled.passes.passes.len() as u64);
    flat.render(gpu(), TILE, 16, 1.0).expect("renders");
    assert_eq!(flat.passes_rendered() - all, all - uploads);
}

/// A bitmap placed per instance by a tile sampler (its pattern's colour) reads the file
/// over each instance's square, alike on the GPU and the CPU; the instances outside
/// their squares stay black.
#[test]
fn a_bitmap_placed_per_instance_reads_the_file_over_each_instance() {
    use veneer::nodes::formulas::instances::TileBlend;
    let dir = temp_dir("bitmap-per-instance");
    std::fs::create_dir_all(dir.join("graphs")).unwrap();
    picture(40, 24).save(dir.join("pic.png")).unwrap();
    let image = ImageFile {
        path: "../pic.png".into(),
        colour_space: veneer::bitmaps::ColourSpace::Auto,
        edge: EdgeMode::Clamp,
        filter: Filter::Bilinear,
    };
    let mut graph = Graph::default();
    let photo = graph.add("photo", NodeKind::ImageFile(image));
    let sampler = graph.add(
        "sampler",
        NodeKind::TileSampler(veneer::nodes::TileSampler {
            blend: TileBlend::Max,
        }),
    );
    for (pin, value) in [("columns", 3.0), ("rows", 2.0), ("scale", 0.8)] {
        graph.set_input(sampler, pin, veneer::graph::Value::Float(value));
    }
    graph.set_input(sampler, "rotation", veneer::graph::Value::Float(30.0));
    let square = graph.add(
        "square",
        NodeKind::Shape(veneer::nodes::Shape {
            shape: veneer::nodes::ShapeKind::Box,
        }),
    );
    graph.set_input(square, "half_size", veneer::graph::Value::Vec2(0.5, 0.5));
    graph.connect(square, "fill", sampler, "pattern");
    graph.connect(photo, "colour", sampler, "pattern_colour");
    show(&mut graph, sampler, "colour", ValueType::Color);
    graph.folder = veneer::graph::Folder(Some(dir.join("graphs")));
    let compiled = compile(&graph, &Default::default()).expect("compiles");
    let differences = pixel_differences(&compiled, TILE, 48);
    // Texel edges and instance edges within rounding of a pixel centre may fall either
    // way: all but a few pixels agree.
    let off = (differences.iter())
        .filter(|d| **d > tolerance(&compiled))
        .count();
    assert!(
        off * 100 <= differences.len(),
        "{off} of {} pixels differ",
        differences.len()
    );
    // The file shows: the pixels span its colours, not one colour per instance.
    let evaluator = veneer::eval::Evaluator::new(&graph).unwrap();
    let centre = [1.0 / 6.0, 0.0, 0.25];
    let reds: std::collections::BTreeSet<u64> = (0..8)
        .map(|k| {
            let point = [centre[0] + 0.02 * f64::from(k), 0.0, centre[2]];
            let surface = evaluator.flat_surface(point);
            (evaluator.eval::<f64>(&surface).albedo[0] * 1e6) as u64
        })
        .collect();
    assert!(reds.len() >= 4, "{reds:?}");
    let _ = std::fs::remove_dir_all(&dir);
}
