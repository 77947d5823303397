//! Baking: a baked albedo equals the flat render, 16-bit maps keep smooth ramps smooth,
//! normal maps follow the height field in both conventions, and an interrupted bake
//! leaves no partial file.

use crate::support::{difference, flat_rgb8, gpu, metallic_roughness, root};
use veneer::bake::{BakeSettings, BakeSurface, Format, Map, NormalConvention, bake};
use veneer::codegen::Compiled;
use veneer::graph::{Graph, NodeKind, Value};
use veneer::render::FlatRect;

/// `graph` compiled as bakes take it.
fn compiled(graph: &Graph) -> Compiled {
    veneer::codegen::compile(graph, &Default::default()).expect("compiles")
}

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("veneer-bake-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir
}

fn settings(size: u32, maps: Vec<Map>, format: Format, rect: FlatRect) -> BakeSettings {
    BakeSettings {
        surface: BakeSurface::Plane(Some(rect)),
        size,
        maps,
        format,
        normal: NormalConvention::OpenGl,
        time: 0.0,
    }
}

#[test]
fn a_baked_4096_albedo_equals_the_flat_render() {
    let graph = veneer::graph::load(&root("graphs/marble_tiles.ron")).expect("preset");
    let rect = FlatRect {
        x0: -3.0,
        z0: -3.0,
        x1: 3.0,
        z1: 3.0,
        y: 0.0,
    };
    let dir = scratch("albedo");
    let maps = bake(
        gpu(),
        &compiled(&graph),
        &settings(4096, vec![Map::Albedo], Format::Png8, rect),
        &dir.join("tiles"),
        |_, _| true,
    )
    .expect("bakes");
    let baked = image::open(&maps[0].path)
        .expect("a PNG")
        .to_rgb8()
        .into_raw();
    let source = compiled(&graph).module.source;
    let diff = difference(&baked, &flat_rgb8(&source, rect, 4096), 3, 0);
    assert_eq!(diff.max, 0, "the bake is the flat render, tiled: {diff}");
}

/// A graph whose albedo and height are both x mapped from [-1, 1] to [0, 1]: a smooth ramp.
fn ramp() -> Graph {
    let mut graph = Graph::default();
    let x = graph.add("x", NodeKind::Project);
    let ramp = graph.add("ramp", NodeKind::Remap);
    graph.connect(x, "x", ramp, "x");
    graph.set_input(ramp, "from_min", Value::Float(-1.0));
    let material = graph.add("material", NodeKind::Material);
    graph.connect(ramp, "result", material, "albedo");
    graph.connect(ramp, "result", material, "height");
    graph
}

#[test]
fn sixteen_bit_maps_keep_a_smooth_ramp_free_of_8_bit_banding() {
    let rect = FlatRect {
        x0: -1.0,
        z0: -1.0,
        x1: 1.0,
        z1: 1.0,
        y: 0.0,
    };
    let dir = scratch("ramp");
    let maps = bake(
        gpu(),
        &compiled(&ramp()),
        &settings(2048, vec![Map::Albedo], Format::Png16, rect),
        &dir.join("ramp"),
        |_, _| true,
    )
    .expect("bakes");
    let image = image::open(&maps[0].path).expect("a PNG").to_rgb16();
    let row: Vec<u16> = (0..2048).map(|x| image.get_pixel(x, 1000)[0]).collect();
    let levels = row.windows(2).filter(|pair| pair[0] != pair[1]).count() + 1;
    assert!(
        levels > 1500,
        "only {levels} distinct levels across 2048 pixels"
    );
    assert!(
        row.windows(2)
            .all(|pair| pair[1] >= pair[0] && pair[1] - pair[0] < 100),
        "monotonic, no steps"
    );
}

#[test]
fn normal_maps_tilt_with_the_height_field_and_flip_green_for_directx() {
    // Height grows with x: normals lean towards -x (red below 0.5), green stays 0.5.
    let rect = FlatRect {
        x0: -1.0,
        z0: -1.0,
        x1: 1.0,
        z1: 1.0,
        y: 0.0,
    };
    let dir = scratch("normal");
    let graph = ramp();
    let gl = bake(
        gpu(),
        &compiled(&graph),
        &settings(64, vec![Map::Normal], Format::Exr, rect),
        &dir.join("gl"),
        |_, _| true,
    )
    .unwrap();
    let texel = image::open(&gl[0].path)
        .expect("an EXR")
        .to_rgba32f()
        .get_pixel(32, 32)
        .0;
    let slope = 0.5f32; // d(height)/dx of the ramp
    let expected = glam::Vec3::new(-slope, 1.0, 0.0).normalize();
    assert!(
        (texel[0] - (0.5 + 0.5 * expected.x)).abs() < 1e-3,
        "{texel:?}"
    );
    assert!(
        (texel[1] - 0.5).abs() < 1e-4 && (texel[2] - (0.5 + 0.5 * expected.y)).abs() < 1e-3,
        "{texel:?}"
    );

    // Height grows with z (down the image): normals lean towards the top of the image, so
    // OpenGL's green (up) rises above 0.5 and DirectX's (down) falls below.
    let mut graph = ramp();
    let x = graph.nodes.iter().find(|n| n.label == "x").unwrap().id;
    graph.set_input(x, "direction", Value::Vec3(0.0, 0.0, 1.0));
    let mut dx = settings(64, vec![Map::Normal], Format::Exr, rect);
    let gl = bake(gpu(), &compiled(&graph), &dx, &dir.join("z-gl"), |_, _| {
        true
    })
    .unwrap();
    dx.normal = NormalConvention::DirectX;
    let directx = bake(gpu(), &compiled(&graph), &dx, &dir.join("z-dx"), |_, _| {
        true
    })
    .unwrap();
    let green =
        |path: &std::path::Path| image::open(path).unwrap().to_rgba32f().get_pixel(32, 32).0[1];
    assert!(green(&gl[0].path) > 0.55 && green(&directx[0].path) < 0.45);
}

#[test]
fn an_interrupted_bake_leaves_no_partial_file() {
    let dir = scratch("interrupted");
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_veneer"))
        .current_dir(root(""))
        .args([
            "bake",
            "graphs/marble.ron",
            "--size",
            "4096",
            "--maps",
            "albedo,normal,height",
            "--format",
            "exr",
            "-o",
        ])
        .arg(&dir)
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("veneer runs");
    std::thread::sleep(std::time::Duration::from_millis(1500));
    child.kill().expect("killed");
    child.wait().expect("reaped");
    for entry in std::fs::read_dir(&dir).expect("folder") {
        let path = entry.expect("entry").path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if name.starts_with('.') {
            continue; // the hidden temporary file of the map being written
        }
        // Any map present is complete: it decodes.
        image::open(&path).unwrap_or_else(|error| panic!("{name} is partial: {error}"));
    }
}

/// An 8-bit albedo bake of `size`² into the UV layout of `mesh`.
fn uv_albedo(size: u32, mesh: &str) -> BakeSettings {
    let mut uv = settings(
        size,
        vec![Map::Albedo],
        Format::Png8,
        FlatRect {
            x0: 0.0,
            z0: 0.0,
            x1: 1.0,
            z1: 1.0,
            y: 0.0,
        },
    );
    uv.surface = veneer::bake::BakeSurface::MeshUv(mesh.to_string());
    uv
}

#[test]
fn a_uv_bake_fills_the_layout_and_pads_its_seams() {
    let graph = veneer::graph::load(&root("graphs/marble.ron")).expect("preset");
    let dir = scratch("uv");
    let uv = uv_albedo(256, "sphere");
    let maps = bake(
        gpu(),
        &compiled(&graph),
        &uv,
        &dir.join("sphere"),
        |_, _| true,
    )
    .expect("bakes");
    let image = image::open(&maps[0].path).expect("a PNG").to_rgb8();
    // The sphere's latitude-longitude layout covers the whole square: no black texels,
    // and marble's two colours both appear.
    assert!(
        image.pixels().all(|p| p.0.iter().any(|&c| c > 20)),
        "uncovered texels left"
    );
    let dark = image.pixels().filter(|p| p.0[0] < 100).count();
    let light = image.pixels().filter(|p| p.0[0] > 200).count();
    assert!(dark > 1000 && light > 1000, "{dark} dark, {light} light");
}

#[test]
fn a_uv_bake_onto_a_mesh_without_uvs_bakes_into_an_atlas() {
    let graph = veneer::graph::load(&root("graphs/marble.ron")).expect("preset");
    let dir = scratch("uv-atlas");
    // A cube of quads without texture coordinates: six square charts (cut at its
    // edges), covering about 60% of the square, grown 8 texels by the padding.
    let uv = uv_albedo(256, "tests/meshes/cube_quads.ply");
    let maps = bake(gpu(), &compiled(&graph), &uv, &dir.join("cube"), |_, _| {
        true
    })
    .expect("bakes into an atlas");
    let image = image::open(&maps[0].path).expect("a PNG").to_rgb8();
    let texels = image.pixels().count() as f64;
    let covered = image
        .pixels()
        .filter(|p| p.0.iter().any(|&c| c > 20))
        .count() as f64;
    assert!(
        (0.6..0.95).contains(&(covered / texels)),
        "{covered} of {texels} texels covered"
    );
    let dark = image
        .pixels()
        .filter(|p| p.0[0] < 100 && p.0[0] > 20)
        .count();
    let light = image.pixels().filter(|p| p.0[0] > 200).count();
    assert!(dark > 500 && light > 500, "{dark} dark, {light} light");
}

#[test]
fn fill_uncovered_grows_islands_by_the_padding() {
    let nan = [f32::NAN; 4];
    let mut pixels = vec![nan; 25];
    pixels[12] = [1.0, 0.5, 0.25, 1.0];
    veneer::bake::fill_uncovered(&mut pixels, 5, 1);
    assert_eq!(
        pixels[7],
        [1.0, 0.5, 0.25, 1.0],
        "the texel above took its neighbour's value"
    );
    assert_eq!(pixels[0], [0.0; 4], "beyond the padding stays empty (0)");
}

/// A 3000² bake renders in two bands: the EXR's values, quantised as 16-bit PNG quantises,
/// give the 16-bit PNG exactly, for every map including normals across the band seam.
#[test]
fn banded_exr_and_png_bakes_agree_across_band_seams() {
    let graph = veneer::graph::load(&root("graphs/marble.ron")).expect("preset");
    let rect = veneer::render::preview_rect(&graph.preview);
    let dir = scratch("bands");
    let maps = vec![Map::Albedo, Map::Normal, Map::Height];
    let exr = bake(
        gpu(),
        &compiled(&graph),
        &settings(3000, maps.clone(), Format::Exr, rect),
        &dir.join("exr"),
        |_, _| true,
    )
    .expect("bakes EXR");
    let png = bake(
        gpu(),
        &compiled(&graph),
        &settings(3000, maps, Format::Png16, rect),
        &dir.join("png"),
        |_, _| true,
    )
    .expect("bakes PNG");
    for (exr, png) in exr.iter().zip(&png) {
        let floats = image::open(&exr.path).expect("an EXR").to_rgba32f();
        let words = image::open(&png.path).expect("a PNG").to_rgb16();
        let mismatches = floats
            .pixels()
            .zip(words.pixels())
            .filter(|(f, w)| {
                (0..3).any(|c| (65535.0 * f.0[c].clamp(0.0, 1.0)).round() as u16 != w.0[c])
            })
            .count();
        assert_eq!(mismatches, 0, "{:?}: EXR and PNG differ", exr.map);
    }
}

#[test]
fn the_tangent_space_normal_lands_in_the_normal_map_in_the_plane_s_frame() {
    let rect = FlatRect {
        x0: -1.0,
        z0: -1.0,
        x1: 1.0,
        z1: 1.0,
        y: 0.0,
    };
    let dir = scratch("tangent-normal");
    let texel = |graph: &Graph, name: &str, map: Map| {
        let baked = bake(
            gpu(),
            &compiled(graph),
            &settings(16, vec![map], Format::Exr, rect),
            &dir.join(name),
            |_, _| true,
        )
        .unwrap();
        image::open(&baked[0].path)
            .unwrap()
            .to_rgba32f()
            .get_pixel(8, 8)
            .0
    };
    // Tilted along +u (x): red rises; up the image (y): OpenGL green rises.
    let (s, c) = (0.6f32, 0.8f32);
    let red = texel(&metallic_roughness((0.6, 0.0, 0.8)), "u", Map::Normal);
    assert!(
        (red[0] - (0.5 + 0.5 * s)).abs() < 1e-4 && (red[1] - 0.5).abs() < 1e-4,
        "{red:?}"
    );
    assert!((red[2] - (0.5 + 0.5 * c)).abs() < 1e-4, "{red:?}");
    let green = texel(&metallic_roughness((0.0, 0.6, 0.8)), "v", Map::Normal);
    assert!(
        (green[1] - (0.5 + 0.5 * s)).abs() < 1e-4 && (green[0] - 0.5).abs() < 1e-4,
        "{green:?}"
    );
    // A normal that is not unit is read as its direction; a flat one leaves the map flat.
    let long = texel(&metallic_roughness((1.2, 0.0, 1.6)), "long", Map::Normal);
    assert!((long[0] - red[0]).abs() < 1e-5, "{long:?} vs {red:?}");
    let flat = texel(&metallic_roughness((0.0, 0.0, 1.0)), "flat", Map::Normal);
    assert_eq!(flat[..3], [0.5, 0.5, 1.0]);
    // The metallic-roughness maps carry the channels; ORM packs them as glTF reads them.
    let graph = metallic_roughness((0.0, 0.0, 1.0));
    assert_eq!(texel(&graph, "m", Map::Metallic)[0], 0.25);
    assert_eq!(texel(&graph, "r", Map::Roughness)[0], 0.75);
    assert_eq!(texel(&graph, "o", Map::Occlusion)[0], 0.5);
    assert_eq!(texel(&graph, "orm", Map::Orm)[..3], [0.5, 0.75, 0.25]);
    // Emission is multiplied by its strength, kept past 1 in EXR.
    assert_eq!(texel(&graph, "e", Map::Emission)[..3], [3.0, 1.5, 0.0]);
    // Under Blinn-Phong the roughness map still comes from the shininess.
    let blinn = Graph {
        shading: veneer::graph::Shading::BlinnPhong,
        ..graph
    };
    let from_shininess = (2.0f32 / (32.0 + 2.0)).sqrt();
    assert!((texel(&blinn, "bp", Map::Roughness)[0] - from_shininess).abs() < 1e-6);
}
