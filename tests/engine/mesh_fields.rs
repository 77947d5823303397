//! Mesh fields in materials: a Mesh field node's values reach the surface in a UV bake,
//! nodes asking for the same field share one lane whatever their order, distance fields
//! keep their slots and mesh fields take the free lanes, more fields than lanes and
//! settings out of range are refused by name, and `veneer mesh-field` writes one line
//! per file vertex.

use crate::support::{compiled_rgb8, cpu_flat_rgb8, gpu, run_veneer, temp_dir};
use veneer::bake::{BakeSettings, BakeSurface, Format, Map, NormalConvention, bake};
use veneer::graph::{Graph, NodeKind, Value, ValueType};
use veneer::mesh_fields::{MeshField, MeshFieldKind};
use veneer::nodes::{Combine, Mix};

/// A material whose albedo is `field` in grey (0 black, 1 white), previewed on `mesh`.
fn grey_of(fields: &[MeshField], mesh: &str) -> Graph {
    let mut graph = Graph::default();
    graph.preview.mesh = mesh.to_string();
    let material = graph.add("material", NodeKind::Material);
    let mut previous = None;
    for (k, field) in fields.iter().enumerate() {
        let node = graph.add(&format!("field {k}"), NodeKind::MeshField(*field));
        let grey = graph.add(
            &format!("grey {k}"),
            NodeKind::Mix(Mix {
                ty: ValueType::Color,
            }),
        );
        graph.set_input(grey, "a", Value::Color(0.0, 0.0, 0.0));
        graph.set_input(grey, "b", Value::Color(1.0, 1.0, 1.0));
        graph.connect(node, "value", grey, "factor");
        if let Some(before) = previous {
            graph.connect(before, "result", grey, "a");
        }
        previous = Some(grey);
    }
    if let Some(last) = previous {
        graph.connect(last, "result", material, "albedo");
    }
    graph
}

/// Flat views have no mesh: each mesh field reads what a flat plane gives (occlusion 1,
/// convexity 0, thickness 1), on the GPU as on the CPU, and a distance field beside them
/// reads 0.
#[test]
fn flat_views_read_a_flat_planes_mesh_fields() {
    let mut graph = Graph::default();
    let colour = graph.add(
        "colour",
        NodeKind::Combine(Combine {
            ty: ValueType::Color,
        }),
    );
    let kinds = [
        MeshFieldKind::Occlusion,
        MeshFieldKind::Convexity,
        MeshFieldKind::Thickness,
    ];
    for (kind, pin) in kinds.into_iter().zip(["x", "y", "z"]) {
        let node = graph.add(kind.name(), NodeKind::MeshField(MeshField::new(kind)));
        graph.connect(node, "value", colour, pin);
    }
    let distance = graph.add(
        "distance",
        NodeKind::Field(veneer::nodes::Field { slot: 0 }),
    );
    let tint = graph.add(
        "tint",
        NodeKind::Mix(Mix {
            ty: ValueType::Color,
        }),
    );
    graph.connect(colour, "v", tint, "a");
    graph.set_input(tint, "b", Value::Color(0.0, 0.0, 0.0));
    graph.connect(distance, "distance", tint, "factor");
    let material = graph.add("material", NodeKind::Material);
    graph.connect(tint, "result", material, "albedo");
    let compiled = veneer::codegen::compile(&graph, &Default::default()).expect("compiles");
    let rect = veneer::render::FlatRect {
        x0: -1.0,
        z0: -1.0,
        x1: 1.0,
        z1: 1.0,
        y: 0.0,
    };
    let gpu = compiled_rgb8(&compiled, rect, 8);
    let cpu = cpu_flat_rgb8(&graph, rect, 8);
    for pixels in [&gpu, &cpu] {
        assert!(
            pixels.chunks(3).all(|rgb| rgb == [255, 0, 255]),
            "flat pixels {:?}, expected occlusion 1, convexity 0, thickness 1",
            &pixels[..3]
        );
    }
}

fn occlusion(distance: u32) -> MeshField {
    MeshField {
        distance,
        ..MeshField::new(MeshFieldKind::Occlusion)
    }
}

#[test]
fn occlusion_reaches_the_surface_dark_inside_a_torus_ring_and_light_outside() {
    let graph = grey_of(&[occlusion(100)], "torus");
    let compiled = veneer::codegen::compile(&graph, &Default::default()).expect("compiles");
    assert_eq!(compiled.module.uses.mesh_fields[0], Some(occlusion(100)));
    let dir = temp_dir("mesh-field-bake");
    let settings = BakeSettings {
        surface: BakeSurface::MeshUv("torus".into()),
        size: 128,
        maps: vec![Map::Albedo],
        format: Format::Png8,
        normal: NormalConvention::OpenGl,
        time: 0.0,
    };
    let maps = bake(gpu(), &compiled, &settings, &dir.join("torus"), |_, _| true).expect("bakes");
    let image = image::open(&maps[0].path).expect("a PNG").to_luma8();
    // The torus's layout runs round the tube down the image: its outer equator at the top
    // and bottom rows, the inner one (facing the hole) across the middle.
    let row = |y: u32| {
        (0..128)
            .map(|x| f64::from(image.get_pixel(x, y).0[0]))
            .sum::<f64>()
            / 128.0
    };
    let (outer, inner) = (row(2), row(64));
    assert!(
        inner < outer - 40.0,
        "inside the ring {inner:.0}, outside {outer:.0}: occlusion did not reach the bake"
    );
}

/// A material bake reads its ray-cast fields per texel, not between vertices: a graph
/// whose albedo is its occlusion bakes, texel for texel, what the `ao` mesh map of the
/// same mesh gives with the node's rays per vertex an eighth as many per texel.
#[test]
fn material_bakes_cast_occlusion_per_texel_as_the_ao_map_does() {
    let graph = grey_of(&[occlusion(100)], "torus:12");
    let compiled = veneer::codegen::compile(&graph, &Default::default()).expect("compiles");
    let dir = temp_dir("mesh-field-texels");
    let settings = BakeSettings {
        surface: BakeSurface::MeshUv("torus:12".into()),
        size: 96,
        maps: vec![Map::Albedo],
        format: Format::Png8,
        normal: NormalConvention::OpenGl,
        time: 0.0,
    };
    let mut reports = Vec::new();
    let maps = bake(
        gpu(),
        &compiled,
        &settings,
        &dir.join("grey"),
        |done, total| {
            reports.push((done, total));
            true
        },
    )
    .expect("bakes");
    // Casting the texel fields shows progress before the map's tiles, on one bar.
    let total = reports.last().map(|r| r.1).unwrap_or(0);
    assert!(reports.iter().all(|r| r.1 == total) && reports.last() == Some(&(total, total)));
    assert!(reports.windows(2).all(|pair| pair[0].0 <= pair[1].0));
    assert!(reports.len() > 2, "{reports:?}");
    let albedo = image::open(&maps[0].path).expect("a PNG").to_luma8();
    let mesh = veneer::mesh::preview_mesh("torus:12")
        .expect("primitive")
        .with_uv_layout(96);
    let ao_settings = veneer::bake::MeshMapSettings {
        size: 96,
        format: Format::Png8,
        samples: 8,
        distance: 100,
        radius: 5,
        pooling: 3,
    };
    let stem = dir.join("torus");
    veneer::bake::bake_mesh_maps(
        &mesh,
        &[veneer::bake::MeshMap::Ao],
        &ao_settings,
        &[&stem],
        |_, _| {},
    )
    .expect("the ao map bakes");
    let ao = image::open(dir.join("torus_ao.png"))
        .expect("a PNG")
        .to_luma8();
    let close = (albedo.pixels().zip(ao.pixels()))
        .filter(|(a, b)| (i32::from(a.0[0]) - i32::from(b.0[0])).abs() <= 2)
        .count();
    assert!(
        close * 100 >= 98 * albedo.pixels().count(),
        "{close} of {} texels agree",
        albedo.pixels().count()
    );
    // A 12-segment torus's vertices are far apart: interpolating them would not agree.
    let darkest = |image: &image::GrayImage| image.pixels().map(|p| p.0[0]).min().unwrap_or(0);
    assert!(darkest(&ao) < 200, "the inside of the ring is occluded");
}

#[test]
fn nodes_asking_for_one_field_share_its_lane_and_lanes_do_not_follow_node_order() {
    let convexity = MeshField::new(MeshFieldKind::Convexity);
    let thickness = MeshField::new(MeshFieldKind::Thickness);
    // A convexity node's ray settings are ignored: it is the same field.
    let convexity_again = MeshField {
        samples: 7,
        ..convexity
    };
    let forwards = grey_of(
        &[occlusion(50), convexity, thickness, convexity_again],
        "sphere",
    );
    let backwards = grey_of(
        &[thickness, convexity_again, convexity, occlusion(50)],
        "sphere",
    );
    let lanes = |graph: &Graph| {
        veneer::codegen::compile(graph, &Default::default())
            .expect("compiles")
            .module
    };
    let (forwards, backwards) = (lanes(&forwards), lanes(&backwards));
    assert_eq!(forwards.uses.mesh_fields, backwards.uses.mesh_fields);
    assert_eq!(forwards.uses.mesh_fields.iter().flatten().count(), 3);
    for lane in ["x", "y", "z"] {
        assert!(forwards.source.contains(&format!("s.fields.{lane}")));
    }
    assert!(!forwards.source.contains("s.fields.w"));
}

#[test]
fn five_fields_and_settings_out_of_range_are_refused_by_name() {
    let dir = temp_dir("mesh-field-check");
    let five: Vec<MeshField> = [10, 20, 30, 40, 50].map(occlusion).to_vec();
    let path = dir.join("five.ron");
    veneer::graph::save(&grey_of(&five, "sphere"), &path).expect("saved");
    let output = run_veneer(&["check", path.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success());
    assert!(
        stderr.contains("field 4") && stderr.contains("5 different mesh fields"),
        "{stderr}"
    );
    let too_many_rays = MeshField {
        samples: 5000,
        ..occlusion(50)
    };
    let path = dir.join("rays.ron");
    veneer::graph::save(&grey_of(&[too_many_rays], "sphere"), &path).expect("saved");
    let output = run_veneer(&["check", path.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success());
    assert!(
        stderr.contains("field 0") && stderr.contains("samples 5000 is outside 1 to 4096"),
        "{stderr}"
    );
}

#[test]
fn distance_fields_keep_their_slots_and_mesh_fields_take_the_lanes_left() {
    let mut graph = grey_of(&[occlusion(50), occlusion(60)], "genus2");
    let distance = graph.add(
        "distance",
        NodeKind::Field(veneer::nodes::Field { slot: 0 }),
    );
    let material = graph
        .nodes
        .iter()
        .find(|n| n.kind == NodeKind::Material)
        .unwrap()
        .id;
    graph.connect(distance, "distance", material, "alpha");
    graph.preview.fields = vec![veneer::graph::FieldSource {
        sources: vec![0],
        method: veneer::graph::Method::Dijkstra,
    }];
    let module = veneer::codegen::compile(&graph, &Default::default())
        .expect("compiles")
        .module;
    assert_eq!(module.uses.fields, [true, false, false, false]);
    assert_eq!(
        module.uses.mesh_fields,
        [None, Some(occlusion(50)), Some(occlusion(60)), None]
    );
    // Both kinds of field reach the mesh, each in its lane.
    let mesh = veneer::render::mesh_with_fields(&graph.preview, "genus2", &module.uses, |_, _| {})
        .expect("fields");
    assert!(mesh.fields.iter().any(|f| f[0] > 0.5) && mesh.fields.iter().all(|f| f[0] <= 1.0));
    assert!(mesh.fields.iter().any(|f| f[1] < 1.0) && mesh.fields.iter().all(|f| f[3] == 0.0));
    // Three more mesh fields do not fit beside the distance field.
    let mut full = grey_of(&[10, 20, 30, 40].map(occlusion), "sphere");
    let distance = full.add(
        "distance",
        NodeKind::Field(veneer::nodes::Field { slot: 2 }),
    );
    let material = full
        .nodes
        .iter()
        .find(|n| n.kind == NodeKind::Material)
        .unwrap()
        .id;
    full.connect(distance, "distance", material, "alpha");
    let errors = veneer::graph::check(&full).expect_err("refused");
    assert!(
        errors[0]
            .to_string()
            .contains("leave 3 of a mesh's 4 field lanes free"),
        "{}",
        errors[0]
    );
}

#[test]
fn the_cli_writes_a_field_line_per_file_vertex() {
    let dir = temp_dir("mesh-field-cli");
    let csv = dir.join("mean.csv");
    let output = run_veneer(&[
        "mesh-field",
        "sphere:32",
        "--kind",
        "mean-curvature",
        "-o",
        csv.to_str().unwrap(),
    ]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let text = std::fs::read_to_string(&csv).expect("written");
    let values: Vec<f64> = text
        .lines()
        .map(|line| line.parse().expect("a number"))
        .collect();
    let sphere = veneer::mesh::primitive("sphere:32").expect("primitive");
    assert_eq!(values.len(), sphere.file_vertex_count());
    // The unit sphere's mean curvature is 1 (the seam's copies read it too).
    assert!(values.iter().all(|h| (h - 1.0).abs() < 0.01), "{values:?}");
    let refused = run_veneer(&[
        "mesh-field",
        "sphere",
        "--kind",
        "convexity",
        "--radius",
        "0",
        "-o",
        dir.join("none.csv").to_str().unwrap(),
    ]);
    assert!(!refused.status.success());
    assert!(String::from_utf8_lossy(&refused.stderr).contains("radius 0 is outside 1 to 100"));
    assert!(!dir.join("none.csv").exists());
}

/// `veneer bake --mesh M --maps ao,…` bakes the mesh's own maps per texel of its UV
/// layout with no graph: an open plane is unoccluded everywhere, faces up and has its
/// position across the map; a torus is darker inside its ring than outside.
#[test]
fn mesh_maps_bake_per_texel_without_a_graph() {
    let dir = temp_dir("mesh-maps");
    let out = dir.to_str().unwrap();
    let baked = run_veneer(&[
        "bake",
        "--mesh",
        "plane",
        "--maps",
        "ao,position,world-normal,curvature",
        "--size",
        "32",
        "--out-dir",
        out,
        "--json",
    ]);
    assert!(
        baked.status.success(),
        "{}",
        String::from_utf8_lossy(&baked.stderr)
    );
    let listed: serde_json::Value = serde_json::from_slice(&baked.stdout).expect("JSON");
    assert_eq!(listed.as_array().map(Vec::len), Some(4), "{listed}");
    let map = |name: &str| {
        image::open(dir.join(format!("plane_{name}.png")))
            .expect("a PNG")
            .to_rgb8()
    };
    assert!(map("ao").pixels().all(|p| p.0 == [255, 255, 255]));
    assert!(map("world-normal").pixels().all(|p| p.0 == [128, 255, 128]));
    assert!(map("curvature").pixels().all(|p| p.0 == [128, 128, 128]));
    let position = map("position");
    for (x, y, pixel) in position.enumerate_pixels() {
        let across = |texel: u32| (255.0 * (texel as f32 + 0.5) / 32.0).round() as i32;
        let [r, g, b] = pixel.0.map(i32::from);
        assert!((r - across(x)).abs() <= 1 && g == 128 && (b - across(y)).abs() <= 1);
    }

    let torus = run_veneer(&[
        "bake",
        "--mesh",
        "torus",
        "--maps",
        "ao",
        "--size",
        "64",
        "--distance",
        "100",
        "--out-dir",
        out,
    ]);
    assert!(
        torus.status.success(),
        "{}",
        String::from_utf8_lossy(&torus.stderr)
    );
    let ao = image::open(dir.join("torus_ao.png"))
        .expect("a PNG")
        .to_luma8();
    let row_mean = |y: u32| {
        (0..64)
            .map(|x| f64::from(ao.get_pixel(x, y).0[0]))
            .sum::<f64>()
            / 64.0
    };
    let (outside, inside) = (row_mean(0), row_mean(32));
    assert!(
        outside > 250.0 && inside < outside - 40.0,
        "outside the ring {outside}, inside {inside}"
    );
}

/// Mesh maps need a mesh, material maps a graph, and settings within their limits;
/// a refused bake writes nothing.
#[test]
fn mesh_maps_refuse_what_they_cannot_bake() {
    let dir = temp_dir("mesh-maps-refused");
    let out = dir.to_str().unwrap();
    for (args, expected) in [
        (vec!["bake", "--maps", "ao"], "give --mesh"),
        (
            vec!["bake", "--mesh", "torus", "--maps", "ao,albedo"],
            "need a graph file",
        ),
        (
            vec![
                "bake",
                "--mesh",
                "torus",
                "--maps",
                "ao",
                "--samples",
                "5000",
            ],
            "samples 5000 is outside 1 to 4096",
        ),
        (
            vec![
                "bake",
                "--mesh",
                "torus",
                "--maps",
                "thickness",
                "--pool",
                "9",
            ],
            "pooling 9 is outside 0 to 8",
        ),
    ] {
        let mut args = args;
        args.extend(["--out-dir", out]);
        let refused = run_veneer(&args);
        let stderr = String::from_utf8_lossy(&refused.stderr);
        assert!(
            !refused.status.success() && stderr.contains(expected),
            "{args:?}: {stderr}"
        );
    }
    assert_eq!(std::fs::read_dir(&dir).expect("folder").count(), 0);
}

/// A scan's worst as a file: an open sheet with two fins on its diagonal (an edge of
/// four triangles), a triangle of no area, a vertex no triangle uses, and a separate
/// tetrahedron a hundred thousand units off. Every mesh map bakes (the writer refuses a
/// non-finite texel), and the mesh bakes from itself.
#[test]
fn mesh_maps_bake_on_a_dirty_mesh() {
    let dir = temp_dir("mesh-maps-dirty");
    let obj = dir.join("dirty.obj");
    let far = 1.0e5;
    let mut text = String::from(
        "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 0.5 1 0.5\nv 0.5 -1 0.5\nv 2 0 0\nv 3 0 0\nv 4 0 0\nv 9 9 9\n",
    );
    for [x, y, z] in [
        [1.0, 1.0, 1.0],
        [-1.0, -1.0, 1.0],
        [-1.0, 1.0, -1.0],
        [1.0, -1.0, -1.0],
    ] {
        text += &format!("v {} {y} {z}\n", far + x);
    }
    text += "f 1 3 2\nf 1 4 3\nf 1 3 5\nf 1 3 6\nf 7 8 9\n";
    text += "f 11 12 14\nf 11 13 12\nf 11 14 13\nf 12 13 14\n";
    std::fs::write(&obj, text).expect("OBJ written");
    let path = obj.to_str().unwrap();
    let baked = run_veneer(&[
        "bake",
        "--mesh",
        path,
        "--maps",
        "ao,curvature,thickness,position,world-normal",
        "--size",
        "64",
    ]);
    assert!(
        baked.status.success(),
        "{}",
        String::from_utf8_lossy(&baked.stderr)
    );
    for map in ["ao", "curvature", "thickness", "position", "world-normal"] {
        image::open(dir.join(format!("dirty_{map}.png"))).expect("a PNG");
    }
    let itself = run_veneer(&["bake", "--mesh", path, "--from", path, "--size", "64"]);
    assert!(
        itself.status.success(),
        "{}",
        String::from_utf8_lossy(&itself.stderr)
    );
    let height = image::open(dir.join("dirty_height.png"))
        .expect("a PNG")
        .to_luma8();
    // On itself, every texel's ray meets its own surface: height 0 reads 0.5.
    let level = |v: u8| (i32::from(v) - 128).abs();
    let on_surface = height.pixels().filter(|p| level(p.0[0]) <= 1).count();
    assert!(
        on_surface * 2 > height.pixels().count(),
        "{on_surface} texels on the surface"
    );
}
