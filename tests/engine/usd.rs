//! USD export (`veneer bake --usd`): every preset exports, as `.usda` with its PNGs beside
//! it or as a `.usdz` package in turn, to a stage that the USD library itself opens with
//! the mesh bound to a material whose UsdPreviewSurface and MaterialX surfaces read
//! textures that resolve, and that USD's own validators pass (`tests/usd/check.py`, with
//! the `usd-core` package `.ci/run` installs into `target/python`); the same export gives
//! the same bytes; what cannot be exported is refused with nothing written.

use crate::support::{
    assert_holds_only, assert_refused, gpu, presets, python_check, root, stem, temp_dir, veneer,
};
use std::path::{Path, PathBuf};
use veneer::bake::{ModelSettings, export_usd};
use veneer::codegen::compile;

fn export(graph: &Path, path: &Path) -> Vec<PathBuf> {
    let graph = veneer::graph::load(graph).expect("loads");
    let compiled = compile(&graph, &Default::default()).expect("compiles");
    let settings = ModelSettings {
        mesh: None,
        size: 8,
        time: 0.0,
    };
    export_usd(gpu(), &compiled, &settings, path, |_, _| true)
        .unwrap_or_else(|error| panic!("{}: {error}", path.display()))
}

#[test]
fn every_preset_exports_to_a_stage_usd_opens_with_its_material_bound() {
    let dir = temp_dir("usd-presets");
    let mut stages = Vec::new();
    for (index, graph) in presets().into_iter().enumerate() {
        let extension = if index % 2 == 0 { "usda" } else { "usdz" };
        let path = dir.join(format!("{}.{extension}", stem(&graph)));
        let written = export(&graph, &path);
        assert_eq!(written[0], path);
        match extension {
            "usdz" => assert_eq!(written.len(), 1, "one package"),
            _ => assert!(
                written.len() >= 3,
                "the layer, base colour and ORM: {written:?}"
            ),
        }
        stages.push(path);
    }
    python_check("tests/usd/check.py", &stages, ": ok, ", "USD (usd-core)");
}

#[test]
fn the_same_export_gives_the_same_bytes() {
    let dir = temp_dir("usd-twice");
    for name in ["lava.usdz", "lava.usda"] {
        let path = dir.join(name);
        let first: Vec<Vec<u8>> = export(&root("graphs/lava_glow.ron"), &path)
            .iter()
            .map(|file| std::fs::read(file).unwrap())
            .collect();
        let again: Vec<Vec<u8>> = export(&root("graphs/lava_glow.ron"), &path)
            .iter()
            .map(|file| std::fs::read(file).unwrap())
            .collect();
        assert!(first == again, "{name}");
    }
}

#[test]
fn what_cannot_be_exported_is_refused_with_nothing_written() {
    let dir = temp_dir("usd-refused");
    let folder = dir.join("taken.usda");
    std::fs::create_dir_all(&folder).unwrap();
    let wood = root("graphs/wood.ron");
    let marble = root("graphs/marble.ron");
    let two = dir.join("two.usdz");
    let glb = dir.join("wood.glb");
    let cases: [(Vec<&Path>, &Path, &str); 4] = [
        (vec![&wood], &folder, "taken.usda: is a folder"),
        (vec![&wood, &marble], &two, "one graph at a time"),
        (vec![&wood], Path::new("-"), "not a stream"),
        (vec![&wood], &glb, "not a USD file name"),
    ];
    for (graphs, out, expected) in cases {
        let mut command = veneer();
        command
            .current_dir(&dir)
            .arg("bake")
            .args(&graphs)
            .args(["--size", "8", "--usd"])
            .arg(out);
        assert_refused(&mut command, expected);
    }
    // glTF has no stream either.
    let mut command = veneer();
    command
        .current_dir(&dir)
        .arg("bake")
        .arg(&wood)
        .args(["--size", "8", "--gltf", "-"]);
    assert_refused(&mut command, "a glTF export writes files, not a stream");
    assert_holds_only(&dir, &["taken.usda"]);
}
