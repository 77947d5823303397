//! MaterialX export, procedural tier (`veneer compile --target mtlx --tier procedural`):
//! every preset translates to a document MaterialX validates and compiles (GLSL and Metal
//! implementations of Veneer's own nodes beside it); rendered
//! through MaterialX's own GLSL generator and renderer (`tests/materialx/render.py`), every
//! preset without mesh fields draws what Veneer's flat render draws on the same adapter
//! (llvmpipe through GL); the exposed parameters are the node graph's inputs; a node that
//! cannot translate is named (and `--tier auto` bakes instead); the README's coverage
//! table is the registry's.

use crate::materialx::{check_with_materialx, compiled, export_in, named_files};
use crate::support::{
    assert_holds_only, assert_refused, difference, presets, root, stem, temp_dir, updating, veneer,
};
use std::path::{Path, PathBuf};
use std::process::Command;
use veneer::bake::{ALBEDO_OUTPUT, SurfaceModel, Tier, coverage_table};
use veneer::codegen::Compiled;

/// Exports `compiled` in the procedural tier to `path`, the files written coming back.
fn export(compiled: &Compiled, surface: SurfaceModel, path: &Path) -> Vec<PathBuf> {
    export_in(Tier::Procedural, 16, compiled, surface, path)
}

/// Whether `compiled` reads the mesh (distance or mesh fields): its document reads them
/// from textures over the mesh's UV layout, which a flat view does not have.
fn reads_mesh(compiled: &Compiled) -> bool {
    let uses = compiled.uses();
    uses.fields.iter().any(|&read| read) || uses.mesh_fields.iter().any(Option::is_some)
}

#[test]
fn every_preset_translates_to_a_document_materialx_validates_and_compiles() {
    let dir = temp_dir("materialx-procedural");
    let mut documents = Vec::new();
    let mut own_definitions = 0;
    for (index, graph) in presets().into_iter().enumerate() {
        let (surface, _, node) = SurfaceModel::ALL[index % SurfaceModel::ALL.len()];
        let path = dir.join(format!("{}.mtlx", stem(&graph)));
        let compiled = compiled(&graph);
        let written = export(&compiled, surface, &path);
        let document = std::fs::read_to_string(&path).expect("the document");
        assert!(
            document.contains(&format!("<{node} ")),
            "{}",
            graph.display()
        );
        // Every file it names lies beside it, and it reads no map but the normal's, the
        // fields' and the bitmaps'.
        for file in named_files(&document) {
            assert!(
                written.contains(&dir.join(&file)),
                "{}: {file}",
                graph.display()
            );
            assert!(
                !["_albedo.png", "_orm.png", "_emission.png", "_alpha.png"]
                    .iter()
                    .any(|map| file.ends_with(map)),
                "{}: {file} is baked",
                graph.display()
            );
        }
        // ... and nothing else is written but the definitions' functions.
        let definitions = document.contains("<nodedef ");
        own_definitions += usize::from(definitions);
        for language in ["glsl", "metal"] {
            let functions = dir.join(format!("{}_veneer.{language}", stem(&graph)));
            assert_eq!(
                written.contains(&functions),
                definitions,
                "{}",
                graph.display()
            );
        }
        assert_eq!(
            written.len(),
            1 + named_files(&document).len() + 2 * usize::from(definitions),
            "{}: {written:?}",
            graph.display()
        );
        if document.contains(".exr\"") {
            assert!(reads_mesh(&compiled) || !compiled.checked.bitmaps.is_empty());
        }
        documents.push(path);
    }
    assert!(own_definitions > 0);
    check_with_materialx(&documents);
}

/// A rectangle in Veneer's texture space over `compiled`'s preview square (off the
/// lattice, so that no pixel centre sits exactly on a pattern's step), and the same
/// rectangle in the object space MaterialX's `position` reads (the preview places the
/// mesh at `size` times its position plus `center`).
fn rectangles(compiled: &Compiled) -> (String, String) {
    let (cx, cy, cz) = compiled.preview.center;
    let size = compiled.preview.size;
    let object = [-0.53, -0.49, 0.47, 0.51, 0.13];
    let texture = [
        cx + size * object[0],
        cz + size * object[1],
        cx + size * object[2],
        cz + size * object[3],
        cy + size * object[4],
    ];
    let text = |values: &[f64]| {
        (values.iter())
            .map(|v| format!("{v}"))
            .collect::<Vec<_>>()
            .join(",")
    };
    (text(&texture), text(&object))
}

fn rgb8(path: &Path) -> Vec<u8> {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgb8()
        .into_raw()
}

/// Exports `graph` (named `name`) in the procedural tier into `dir` and renders its
/// `veneer_albedo` through MaterialX's GLSL over a flat rectangle, which must match
/// `veneer render --flat` of the same rectangle on the same adapter (llvmpipe through GL):
/// at most 1% of pixels more than 2/255 apart.
fn assert_materialx_draws_what_veneer_draws(graph: &Path, compiled: &Compiled, dir: &Path) {
    let name = stem(graph);
    let path = dir.join(format!("{name}.mtlx"));
    export(compiled, SurfaceModel::OpenPbr, &path);
    // Bitmaps are read where they are not minified (MaterialX's renderer samples
    // mipmaps, Veneer the image itself), at the flat view's uv: the place in the
    // rectangle.
    let bitmaps = &compiled.checked.bitmaps;
    let largest = (bitmaps.values())
        .map(|bitmap| bitmap.width.max(bitmap.height) + 1)
        .max();
    let size = largest.unwrap_or(0).max(160).to_string();
    let (texture, object) = rectangles(compiled);
    let veneer_png = dir.join(format!("{name}.veneer.png"));
    let rendered = veneer()
        .args(["render", "--size", &size, "--flat", &texture, "-o"])
        .arg(&veneer_png)
        .arg(graph)
        .env("WGPU_BACKEND", "gl")
        .output()
        .expect("veneer runs");
    assert!(
        rendered.status.success(),
        "{}",
        String::from_utf8_lossy(&rendered.stderr)
    );
    let document = std::fs::read_to_string(&path).unwrap();
    // The material's node graph, not a group's (which implements a definition).
    let graph_name = (document.split("<nodegraph name=\"").skip(1))
        .find(|rest| {
            !rest
                .split('>')
                .next()
                .unwrap_or_default()
                .contains("nodedef=")
        })
        .and_then(|rest| rest.split('"').next())
        .expect("a node graph");
    let materialx_png = dir.join(format!("{name}.materialx.png"));
    let mut render = Command::new("python3");
    render
        .arg(root("tests/materialx/render.py"))
        .arg(&path)
        .arg(format!("{graph_name}/{ALBEDO_OUTPUT}"))
        .args([&object, &size])
        .arg(&materialx_png)
        .env("PYTHONPATH", root("target/python"));
    if !bitmaps.is_empty() {
        render.arg("domain-uv");
    }
    let output = render.output().expect("python3 runs");
    assert!(
        output.status.success(),
        "{name}: MaterialX's render (`.ci/run` installs the package):\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let comparison = difference(&rgb8(&veneer_png), &rgb8(&materialx_png), 3, 2);
    assert!(
        comparison.share_outside <= 0.01,
        "{name}: {:.2}% of pixels differ by more than 2/255 (largest {})",
        100.0 * comparison.share_outside,
        comparison.max
    );
}

#[test]
fn materialx_glsl_draws_what_veneer_draws_for_every_preset_without_mesh_fields() {
    let dir = temp_dir("materialx-procedural-renders");
    let mut compared = Vec::new();
    for graph in presets() {
        let compiled = compiled(&graph);
        if reads_mesh(&compiled) {
            continue;
        }
        assert_materialx_draws_what_veneer_draws(&graph, &compiled, &dir);
        compared.push(stem(&graph));
    }
    assert!(compared.len() >= 8, "{compared:?}");
}

/// Wood with a second instance of its group, set apart (`ring_frequency` 1.3) and
/// blended with the first by its rings, saved into `dir`.
fn two_woods(dir: &Path) -> PathBuf {
    use veneer::graph::{Node, NodeId, NodeKind, PinRef, Value, Wire};
    let mut graph = veneer::graph::load(&root("graphs/wood.ron")).unwrap();
    for group in graph.groups.values_mut() {
        group.linked = false;
    }
    let mut second = Node::new(
        NodeId(3),
        NodeKind::Group(veneer::nodes::Group::named("ring_wood".into())),
    );
    second.label = "second wood".into();
    second.position = (0.0, 300.0);
    second
        .inputs
        .insert("ring_frequency".into(), Value::Float(1.3));
    let mut blend = Node::new(
        NodeId(4),
        NodeKind::Mix(veneer::nodes::Mix {
            ty: veneer::nodes::value::ValueType::Color,
        }),
    );
    blend.label = "blend".into();
    blend.position = (206.0, 150.0);
    graph.nodes.extend([second, blend]);
    let wire = |from: u32, from_pin: &str, to: u32, to_pin: &str| Wire {
        from: PinRef::new(NodeId(from), from_pin),
        to: PinRef::new(NodeId(to), to_pin),
    };
    graph.wires = vec![
        wire(1, "albedo", 4, "a"),
        wire(3, "albedo", 4, "b"),
        wire(3, "rings", 4, "factor"),
        wire(4, "result", 2, "albedo"),
    ];
    let path = dir.join("two_woods.ron");
    veneer::graph::save(&graph, &path).unwrap();
    path
}

#[test]
fn groups_become_node_graphs_shared_by_their_instances_and_draw_the_same() {
    let dir = temp_dir("materialx-procedural-groups");
    let graph = two_woods(&dir);
    let path = dir.join("two_woods.mtlx");
    succeeds(
        compile_mtlx("procedural", &graph, &path).args(["--set", "second wood.ring_frequency=1.7"]),
    );
    let document = std::fs::read_to_string(&path).unwrap();
    // One definition, implemented by a node graph, for both instances.
    assert_eq!(
        document
            .matches("<nodedef name=\"ND_veneer_group_ring_wood\"")
            .count(),
        1,
        "{document}"
    );
    assert!(document.contains(
        "<nodegraph name=\"NG_veneer_group_ring_wood\" nodedef=\"ND_veneer_group_ring_wood\">"
    ));
    assert_eq!(document.matches("<veneer_group_ring_wood ").count(), 2);
    // The group's inputs are the definition's, with its defaults and spans, and each
    // instance reads the material's parameters, the override among them.
    assert!(document.contains(
        "<input name=\"ring_frequency\" type=\"float\" value=\"0.5\" uimin=\"0.05\" uimax=\"5\" />"
    ));
    assert!(
        document
            .contains("<input name=\"second_wood_ring_frequency\" type=\"float\" value=\"1.7\""),
        "{document}"
    );
    assert!(document.contains(
        "<input name=\"ring_frequency\" type=\"float\" interfacename=\"second_wood_ring_frequency\" />"
    ));
    check_with_materialx(&[path]);
    // Drawn through MaterialX's GLSL as Veneer draws it (exported again, as it is), and
    // imported back as it was.
    assert_materialx_draws_what_veneer_draws(&graph, &compiled(&graph), &dir);
    let back = dir.join("back.ron");
    let document = dir.join("two_woods.mtlx");
    succeeds(veneer().arg("import").arg(&document).arg("-o").arg(&back));
    let original = veneer::graph::load(&graph).unwrap();
    let imported = veneer::graph::load(&back).unwrap();
    assert_eq!(comparable(imported), comparable(original));
}

#[test]
fn exposed_parameters_are_the_node_graphs_inputs_and_take_set_values() {
    let dir = temp_dir("materialx-procedural-parameters");
    let path = dir.join("brick.mtlx");
    let graph = root("graphs/thesis_brick.ron");
    succeeds(compile_mtlx("procedural", &graph, &path).args(["--set", "gloss_shininess=50"]));
    let document = std::fs::read_to_string(&path).unwrap();
    assert!(
        document.contains("<input name=\"gloss_shininess\" type=\"float\" value=\"50\" />"),
        "{document}"
    );
    assert!(
        document.contains("interfacename=\"gloss_shininess\""),
        "{document}"
    );
}

/// `veneer compile --target mtlx --tier TIER --size 8 GRAPH -o OUT`, ready to run.
fn compile_mtlx(tier: &str, graph: &Path, out: &Path) -> Command {
    let mut command = veneer();
    command
        .args(["compile", "--target", "mtlx", "--tier", tier, "--size", "8"])
        .arg(graph)
        .arg("-o")
        .arg(out);
    command
}

/// Runs `command`, which must succeed, and gives what it said on stderr.
fn succeeds(command: &mut Command) -> String {
    let output = command.output().expect("the command runs");
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert!(output.status.success(), "{command:?}: {stderr}");
    stderr
}

#[test]
fn a_node_that_cannot_translate_is_named_and_auto_bakes_what_it_gives() {
    let dir = temp_dir("materialx-procedural-refused");
    let graph = root("graphs/texture/blurred_noise.ron");
    let path = dir.join("blurred.mtlx");
    assert_refused(
        &mut compile_mtlx("procedural", &graph, &path),
        "node 'soft' samples its input around the point",
    );
    assert_holds_only(&dir, &[]);
    succeeds(&mut compile_mtlx("auto", &graph, &path));
    // The blur and the height-to-normal node are read from textures of what they give,
    // the rest of the graph stays nodes.
    let document = std::fs::read_to_string(&path).unwrap();
    assert!(document.contains("<nodedef "), "{document}");
    for texture in ["blurred_soft_3.exr", "blurred_relief_5.exr"] {
        assert!(document.contains(texture), "{document}");
        assert!(dir.join(texture).is_file(), "{texture}");
    }
    assert!(!document.contains("blurred_albedo.png"), "{document}");
    // A node giving a vector2, which no texture holds, makes the whole material baked.
    let planks = dir.join("planks.mtlx");
    let notes = succeeds(&mut compile_mtlx(
        "auto",
        &root("graphs/texture/planks.ron"),
        &planks,
    ));
    assert!(
        notes.contains("baked: cannot translate node 'each plank'") && notes.contains("vector2"),
        "{notes}"
    );
    assert!(
        std::fs::read_to_string(&planks)
            .unwrap()
            .contains("planks_albedo.png")
    );
}

#[test]
fn the_readme_coverage_table_is_the_registrys() {
    const BEGIN: &str =
        "<!-- materialx coverage: generated by tests/engine/materialx_procedural.rs -->\n";
    const END: &str = "<!-- end of materialx coverage -->";
    let readme_path = root("README.md");
    let readme = std::fs::read_to_string(&readme_path).unwrap();
    let table = coverage_table();
    let (before, rest) = readme
        .split_once(BEGIN)
        .expect("the README marks the table");
    let (current, after) = rest.split_once(END).expect("the README ends the table");
    if updating() {
        std::fs::write(&readme_path, format!("{before}{BEGIN}{table}{END}{after}")).unwrap();
        return;
    }
    assert_eq!(
        current, table,
        "the coverage changed (VENEER_UPDATE_GOLDEN=1 to rewrite)"
    );
}

/// `graph` as an import gives it back: the values its pins hold at their defaults left
/// out, and what a MaterialX material does not carry (the preview mesh) dropped.
fn comparable(mut graph: veneer::graph::Graph) -> veneer::graph::Graph {
    use veneer::nodes::pins::PinDefault;
    let group_nodes = graph
        .groups
        .values_mut()
        .flat_map(|group| group.nodes.iter_mut());
    for node in graph.nodes.iter_mut().chain(group_nodes) {
        let pins = node.kind.definition().signature().inputs;
        node.inputs.retain(|pin, value| {
            let default = pins.iter().find(|p| p.name == pin).map(|p| &p.default);
            default != Some(&PinDefault::Const(*value))
        });
    }
    graph.preview.mesh = String::new();
    graph.folder = Default::default();
    // Whether a group follows the library's is Veneer's to know.
    for group in graph.groups.values_mut() {
        group.linked = false;
    }
    graph
}

#[test]
fn importing_the_procedural_tier_gives_the_graph_back() {
    let dir = temp_dir("materialx-import");
    // Wood and marble keep their groups (as node graphs of their own).
    for preset in [
        "thesis_brick",
        "rusted_metal",
        "marble_tiles",
        "wood",
        "marble",
    ] {
        let graph = root(&format!("graphs/{preset}.ron"));
        let document = dir.join(format!("{preset}.mtlx"));
        export(&compiled(&graph), SurfaceModel::OpenPbr, &document);
        let back = dir.join(format!("{preset}.ron"));
        succeeds(veneer().arg("import").arg(&document).arg("-o").arg(&back));
        let original = veneer::graph::load(&graph).unwrap();
        let imported = veneer::graph::load(&back).unwrap();
        assert_eq!(comparable(imported), comparable(original), "{preset}");
    }
}

#[test]
fn documents_import_cannot_read_are_refused_naming_the_node_and_line() {
    let dir = temp_dir("materialx-import-refused");
    let graph = |nodes: &str| {
        format!(
            "<?xml version=\"1.0\"?>\n<materialx version=\"1.39\">\n  <nodegraph name=\"NG_x\">\n{nodes}    <output name=\"veneer_albedo\" type=\"color3\" nodename=\"a_1\" />\n  </nodegraph>\n</materialx>\n"
        )
    };
    let cases = [
        (
            "unknown.mtlx",
            graph(
                "    <noise3d name=\"a_1\" type=\"color3\">\n      <input name=\"amplitude\" type=\"vector3\" value=\"1, 1, 1\" />\n    </noise3d>\n",
            ),
            "unknown.mtlx:4:5: node 'a_1' (`noise3d`, color3) has no Veneer equal",
        ),
        (
            "cycle.mtlx",
            graph(
                "    <add name=\"a_1\" type=\"color3\">\n      <input name=\"in1\" type=\"color3\" nodename=\"b_2\" />\n      <input name=\"in2\" type=\"color3\" value=\"0, 0, 0\" />\n    </add>\n    <add name=\"b_2\" type=\"color3\">\n      <input name=\"in1\" type=\"color3\" nodename=\"a_1\" />\n      <input name=\"in2\" type=\"color3\" value=\"0, 0, 0\" />\n    </add>\n",
            ),
            "the nodes form a cycle: a_1 → b_2 → a_1",
        ),
        (
            "broken.mtlx",
            "<materialx version=\"1.39\">\n  <nodegraph>\n".to_string(),
            "broken.mtlx:1:1: not XML",
        ),
        (
            "output.mtlx",
            graph(
                "    <position name=\"p_2\" type=\"vector3\" />\n    <separate3 name=\"s_3\" type=\"multioutput\">\n      <input name=\"in\" type=\"vector3\" nodename=\"p_2\" />\n    </separate3>\n    <combine3 name=\"a_1\" type=\"color3\">\n      <input name=\"in1\" type=\"float\" nodename=\"s_3\" output=\"outq\" />\n    </combine3>\n",
            ),
            "reads output 'outq' of node 's_3', which has outx, outy, outz",
        ),
        (
            "texture.mtlx",
            graph(
                "    <image name=\"a_1\" type=\"color3\">\n      <input name=\"file\" type=\"filename\" value=\"a.png\" />\n    </image>\n",
            ),
            "node 'a_1' (`image`, color3) has no Veneer equal",
        ),
    ];
    for (name, text, expected) in cases {
        let document = dir.join(name);
        std::fs::write(&document, text).unwrap();
        let mut command = veneer();
        command
            .arg("import")
            .arg(&document)
            .arg("-o")
            .arg(dir.join("out.ron"));
        assert_refused(&mut command, expected);
    }
    let mut left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    left.sort();
    assert_eq!(left.len(), 5, "nothing written: {left:?}");
}
