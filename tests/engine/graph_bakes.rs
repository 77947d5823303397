//! Graph bake nodes: a graph file's map as a buffer. The bake draws the map as the
//! file's own material draws it (GPU and CPU alike), an unwired map is its constant,
//! the file is read relative to the baking graph and its own files relative to it,
//! Save as keeps the path naming the same file, and every way a file can fail is a
//! check error naming the node and the file, with nothing written.

use crate::passes::{TILE, show};
use crate::support::{compiled_rgb8, cpu_flat_rgb8, root, run_veneer, temp_dir};
use std::path::Path;
use veneer::codegen::{CompileError, compile};
use veneer::graph::{Folder, Graph, NodeKind};
use veneer::nodes::{BakedMap, GraphBake};

/// A graph in `folder` whose albedo is `map` of the graph file at `path`.
fn baking(folder: &Path, path: &str, map: BakedMap) -> Graph {
    let mut graph = Graph::default();
    let bake = GraphBake {
        path: path.into(),
        map,
        ..GraphBake::default()
    };
    let node = graph.add("bake", NodeKind::GraphBake(bake));
    show(&mut graph, node, "value", map.ty());
    graph.folder = Folder(Some(folder.to_path_buf()));
    graph
}

/// A folder holding the shipped blurred-noise graph as `sub/noise.ron`.
fn folder_with_noise(name: &str) -> std::path::PathBuf {
    let dir = temp_dir(name);
    std::fs::create_dir_all(dir.join("sub")).expect("makes the folder");
    let noise = root("graphs/texture/blurred_noise.ron");
    std::fs::copy(noise, dir.join("sub/noise.ron")).expect("copies");
    dir
}

#[test]
fn a_bake_draws_the_files_map_as_the_file_draws_it_on_the_gpu_and_the_cpu() {
    // Over the tile, the bake's buffer (float, the output's size) is read at its texel
    // centres: the same albedo as the file's own flat render.
    let dir = folder_with_noise("graph-bake-draws");
    let graph = baking(&dir, "sub/noise.ron", BakedMap::Albedo);
    let compiled = compile(&graph, &Default::default()).expect("compiles");
    let file = veneer::graph::load(&dir.join("sub/noise.ron")).expect("loads");
    let own = compile(&file, &Default::default()).expect("compiles");
    assert_eq!(
        compiled.passes.passes.len(),
        own.passes.passes.len() + 1,
        "the file's passes and the bake's buffer"
    );
    let size = 48;
    let drawn = compiled_rgb8(&compiled, TILE, size);
    let steps = |a: &[u8], b: &[u8]| (a.iter().zip(b)).map(|(p, q)| p.abs_diff(*q)).max();
    assert!(steps(&drawn, &compiled_rgb8(&own, TILE, size)) <= Some(1));
    assert!(steps(&drawn, &cpu_flat_rgb8(&graph, TILE, size)) <= Some(1));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_unwired_map_is_the_materials_constant() {
    // The noise graph sets its roughness to 0.7 and leaves metallic at its default, 0:
    // neither needs a pass.
    let dir = folder_with_noise("graph-bake-constants");
    for (map, value) in [(BakedMap::Roughness, 0.7), (BakedMap::Metallic, 0.0)] {
        let graph = baking(&dir, "sub/noise.ron", map);
        let compiled = compile(&graph, &Default::default()).expect("compiles");
        assert!(compiled.passes.is_empty(), "{map:?}");
        let evaluator = veneer::eval::Evaluator::new(&graph).expect("checks");
        let albedo = evaluator
            .eval(&veneer::eval::Surface::<f64>::at([0.3, 0.0, 0.6]))
            .albedo;
        assert!((albedo[0] - value).abs() < 1e-6, "{map:?}: {albedo:?}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_baked_files_own_files_are_read_relative_to_it_and_save_as_keeps_the_path() {
    // The gravel graph reads a photo beside the repository's assets; baked from a
    // folder elsewhere, the photo is still found.
    let dir = temp_dir("graph-bake-folders");
    let gravel = root("graphs/texture/gravel.ron");
    let path = veneer::bitmaps::relative_to(&dir, &gravel);
    let path = path.to_str().expect("utf-8");
    let mut graph = baking(&dir, path, BakedMap::Albedo);
    let compiled = compile(&graph, &Default::default()).expect("the bake and its photo read");
    assert!(!compiled.passes.is_empty());
    // Save as two folders down: the path climbs two more.
    graph.move_to(Folder::of_file(&dir.join("a/b/moved.ron")));
    let NodeKind::GraphBake(bake) = &graph.nodes[0].kind else {
        panic!("the bake comes first");
    };
    assert_eq!(bake.path, format!("../../{path}"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn unusable_graph_files_are_check_errors_naming_the_node_and_the_file() {
    let dir = folder_with_noise("graph-bake-errors");
    std::fs::write(
        dir.join("broken.ron"),
        "(\n  version: 1,\n  nodes: oops,\n)",
    )
    .unwrap();
    std::os::unix::fs::symlink("/etc/hostname", dir.join("link.ron")).ok();
    // Two files baking each other.
    for (file, other) in [("ping.ron", "pong.ron"), ("pong.ron", "ping.ron")] {
        veneer::graph::save(&baking(&dir, other, BakedMap::Albedo), &dir.join(file)).unwrap();
    }
    let mut no_material = Graph::default();
    no_material.add("lonely", NodeKind::Position);
    veneer::graph::save(&no_material, &dir.join("bare.ron")).unwrap();
    for (file, says) in [
        ("missing.ron", "cannot be read"),
        ("broken.ron", "does not load: 3:"),
        ("link.ron", "a link leads it out of"),
        (
            "ping.ron",
            "bakes itself: 'ping.ron' › 'pong.ron' › 'ping.ron'",
        ),
        (
            "bare.ron",
            "does not check: the graph has no Material output node",
        ),
        ("", "no graph file chosen"),
    ] {
        let graph = baking(&dir, file, BakedMap::Albedo);
        let Err(CompileError::Check(errors)) = compile(&graph, &Default::default()) else {
            panic!("{file}: the check refuses it");
        };
        let message = errors[0].to_string();
        assert!(message.contains("node 'bake'"), "{message}");
        assert!(
            message.contains(file) && message.contains(says),
            "{message}"
        );
    }
    // The command line: exit 1 naming the node and the file, nothing written.
    let graph = dir.join("bakes_broken.ron");
    veneer::graph::save(&baking(&dir, "broken.ron", BakedMap::Albedo), &graph).unwrap();
    let out = dir.join("maps");
    std::fs::create_dir_all(&out).unwrap();
    let (graph, out_dir) = (graph.to_str().unwrap(), out.to_str().unwrap());
    let output = run_veneer(&["bake", graph, "--tile", "--size", "16", "-o", out_dir]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("node 'bake'") && stderr.contains("graph 'broken.ron'"));
    assert_eq!(
        std::fs::read_dir(&out).unwrap().count(),
        0,
        "nothing written"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_bake_the_material_does_not_read_is_not_read() {
    // Like an Image node's file: a bake left unwired (just added, its file not chosen
    // yet) does not stop the material.
    let dir = folder_with_noise("graph-bake-unread");
    let mut graph = baking(&dir, "sub/noise.ron", BakedMap::Albedo);
    graph.add("new bake", NodeKind::GraphBake(GraphBake::default()));
    let compiled = compile(&graph, &Default::default()).expect("the material compiles");
    let file = veneer::graph::load(&dir.join("sub/noise.ron")).expect("loads");
    let own = compile(&file, &Default::default()).expect("compiles");
    assert_eq!(compiled.passes.passes.len(), own.passes.passes.len() + 1);
    let _ = std::fs::remove_dir_all(&dir);
}
