//! glTF 2.0 export (`veneer bake --gltf`): every preset, on a mesh with a UV layout or
//! given an automatic atlas (the `genus2` ones), exports to a `.glb` that the Khronos
//! glTF-Validator (installed by `.ci/run`) passes with no errors and no warnings, `.gltf`
//! with its files beside it too; the same bake gives the same bytes; a
//! metallic-roughness material's channels land in the glTF's textures and factors where
//! glTF reads them.

use crate::support::{gpu, metallic_roughness, presets, root, stem, temp_dir};
use std::path::{Path, PathBuf};
use std::process::Command;
use veneer::bake::{BakeError, ModelSettings, export_gltf};
use veneer::codegen::{Compiled, compile};
use veneer::graph::Graph;

/// Runs the glTF-Validator on `files`; panics with its report unless every file is clean.
fn validate(files: &[PathBuf]) {
    let validator = root("target/gltf-validator/node_modules/gltf-validator");
    let output = Command::new("node")
        .arg(root("tests/gltf/validate.mjs"))
        .args(files)
        .env("GLTF_VALIDATOR", &validator)
        .output()
        .unwrap_or_else(|error| {
            panic!("node is needed for the glTF-Validator (`.ci/run` installs it): {error}")
        });
    let report = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "glTF-Validator (from {}; `.ci/run` installs it):\n{report}{}",
        validator.display(),
        String::from_utf8_lossy(&output.stderr)
    );
    assert_eq!(
        report
            .lines()
            .filter(|l| l.contains(": 0 errors, 0 warnings"))
            .count(),
        files.len(),
        "{report}"
    );
}

fn compiled(graph: &Graph) -> Compiled {
    compile(graph, &Default::default()).expect("compiles")
}

fn export(compiled: &Compiled, path: &Path) -> Result<Vec<PathBuf>, BakeError> {
    let settings = ModelSettings {
        mesh: None,
        size: 64,
        time: 0.0,
    };
    export_gltf(gpu(), compiled, &settings, path, |_, _| true)
}

#[test]
fn every_preset_exports_to_a_valid_glb() {
    let dir = temp_dir("gltf-presets");
    let mut files = Vec::new();
    let (mut unwrapped, mut occluded) = (0, 0);
    for preset in presets() {
        let graph = veneer::graph::load(&preset).expect("loads");
        let written = export(
            &compiled(&graph),
            &dir.join(format!("{}.glb", stem(&preset))),
        )
        .unwrap_or_else(|error| panic!("{}: {error}", preset.display()));
        if !veneer::mesh::preview_mesh(&graph.preview.mesh)
            .expect("the preview mesh")
            .has_uv_layout()
        {
            unwrapped += 1;
        }
        // A material whose occlusion is wired (worn paint's, from ambient occlusion on
        // the mesh) carries an occlusion texture.
        let material = graph
            .nodes
            .iter()
            .find(|n| n.kind == veneer::graph::NodeKind::Material);
        let occludes = (graph.wires.iter())
            .any(|wire| Some(wire.to.node) == material.map(|m| m.id) && wire.to.pin == "occlusion");
        if occludes {
            let glb = std::fs::read(&written[0]).expect("the GLB");
            let length = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
            let json = String::from_utf8_lossy(&glb[20..20 + length]);
            assert!(
                json.contains("\"occlusionTexture\""),
                "{}: {json}",
                preset.display()
            );
            occluded += 1;
        }
        files.extend(written);
    }
    assert_eq!(files.len(), presets().len());
    // The marching-tetrahedra genus2 has no texture coordinates: those got an atlas.
    assert!(unwrapped >= 6, "{unwrapped} presets on meshes without UVs");
    assert!(occluded >= 1, "no preset wires its occlusion");
    validate(&files);
}

#[test]
fn an_export_cancelled_from_its_progress_writes_nothing() {
    let dir = temp_dir("gltf-cancelled");
    let graph = veneer::graph::preset("wood").expect("preset");
    let settings = ModelSettings {
        mesh: None,
        size: 64,
        time: 0.0,
    };
    let path = dir.join("wood.gltf");
    let mut reports = 0;
    let result = export_gltf(gpu(), &compiled(&graph), &settings, &path, |_, _| {
        reports += 1;
        false
    });
    assert!(matches!(result, Err(BakeError::Cancelled)), "{result:?}");
    assert!(reports >= 1);
    let left: Vec<_> = std::fs::read_dir(&dir).unwrap().flatten().collect();
    assert!(left.is_empty(), "a cancelled export left {left:?}");
}

#[test]
fn a_gltf_with_its_files_beside_it_validates_and_the_same_bake_gives_the_same_bytes() {
    let dir = temp_dir("gltf-separate");
    let graph = veneer::graph::load(&root("graphs/thesis_c5_water_lava.ron")).expect("loads");
    let compiled = compiled(&graph);
    let written = export(&compiled, &dir.join("lava model.gltf")).expect("exports");
    let names: Vec<String> = written
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names[0], "lava model.gltf");
    assert!(names.contains(&"lava model.bin".to_string()), "{names:?}");
    assert!(
        names.contains(&"lava model_emission.png".to_string()),
        "the lava glows: {names:?}"
    );
    validate(&written[..1]);
    let first: Vec<Vec<u8>> = written.iter().map(|p| std::fs::read(p).unwrap()).collect();
    let again = export(&compiled, &dir.join("lava model.gltf")).expect("exports again");
    let second: Vec<Vec<u8>> = again.iter().map(|p| std::fs::read(p).unwrap()).collect();
    assert!(first == second, "a second export wrote other bytes");
}

#[test]
fn metallic_roughness_channels_land_where_gltf_reads_them() {
    let dir = temp_dir("gltf-channels");
    let written = export(
        &compiled(&metallic_roughness((0.0, 0.0, 1.0))),
        &dir.join("metal.gltf"),
    )
    .expect("exports");
    validate(&written[..1]);
    let document: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&written[0]).unwrap()).unwrap();
    let material = &document["materials"][0];
    // Emission 3.0 at its brightest: the texture holds emission / 3, the strength 3.
    let strength = material["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"]
        .as_f64()
        .unwrap();
    assert!((strength - 3.0).abs() < 1e-6, "{material}");
    assert_eq!(
        document["extensionsUsed"][0],
        "KHR_materials_emissive_strength"
    );
    assert!(
        material.get("normalTexture").is_none(),
        "a flat material needs no normal map"
    );
    assert!(
        material.get("alphaMode").is_none(),
        "an opaque material is glTF's default"
    );
    let texture = |key: &serde_json::Value| {
        let index = key["index"].as_u64().unwrap() as usize;
        let uri = document["images"][index]["uri"].as_str().unwrap();
        image::open(dir.join(uri)).expect("a PNG").to_rgb8()
    };
    let orm = texture(&material["pbrMetallicRoughness"]["metallicRoughnessTexture"]);
    assert_eq!(
        material["occlusionTexture"]["index"],
        material["pbrMetallicRoughness"]["metallicRoughnessTexture"]["index"]
    );
    // R occlusion, G roughness, B metallic, at every texel (the islands are padded).
    let expected = [0.5, 0.75, 0.25].map(|v: f64| (255.0 * v).round() as u8);
    assert!(
        orm.pixels().all(|p| p.0 == expected),
        "{:?}",
        orm.get_pixel(0, 0)
    );
    // Base colour and emission are linear and stored sRGB-encoded: 0.5 → 188; emission (3, 1.5, 0) / 3 → (255, 188, 0).
    let base = texture(&material["pbrMetallicRoughness"]["baseColorTexture"]);
    assert_eq!(base.get_pixel(32, 32).0, [188, 188, 188]);
    let emission = texture(&material["emissiveTexture"]);
    assert_eq!(emission.get_pixel(32, 32).0, [255, 188, 0]);
}
