//! MaterialX export, baked tier (`veneer compile --target mtlx`): every preset and texture
//! graph exports, the three surface models in turn, to a document that the MaterialX
//! library itself validates and turns into GLSL (`tests/materialx/check.py`, with the
//! package `.ci/run` installs into `target/python`) that glslangValidator compiles; every
//! map the document names lies beside it; the alpha, emission and normal maps appear
//! exactly when the material has them, a cut-out as a threshold at its cutoff (glTF's
//! model: its alpha mode); the same export gives the same bytes; outputs that cannot be
//! written are refused with nothing written.

use crate::support::{
    assert_holds_only, assert_refused, gpu, presets, python_check, root, stem, temp_dir,
    texture_graphs, veneer,
};
use std::path::{Path, PathBuf};
use std::process::Command;
use veneer::bake::{MaterialxSettings, SurfaceModel, Tier, export_materialx};
use veneer::codegen::{AlphaUse, Compiled, compile};

pub fn compiled(path: &Path) -> Compiled {
    let graph = veneer::graph::load(path).expect("loads");
    compile(&graph, &Default::default()).expect("compiles")
}

/// Exports `compiled` in `tier` (it must keep that tier) to `path` with maps of `size`,
/// the files written coming back.
pub fn export_in(
    tier: Tier,
    size: u32,
    compiled: &Compiled,
    surface: SurfaceModel,
    path: &Path,
) -> Vec<PathBuf> {
    let settings = MaterialxSettings {
        tier,
        surface,
        size,
        time: 0.0,
    };
    let export = export_materialx(gpu(), compiled, &settings, path, |_, _| true)
        .unwrap_or_else(|error| panic!("{}: {error}", path.display()));
    assert_eq!(export.tier, tier);
    export.files
}

fn export(compiled: &Compiled, surface: SurfaceModel, path: &Path) -> Vec<PathBuf> {
    export_in(Tier::Baked, 8, compiled, surface, path)
}

/// The file names a document's `filename` inputs give.
pub fn named_files(document: &str) -> Vec<String> {
    document
        .lines()
        .filter(|line| line.contains("type=\"filename\""))
        .filter_map(|line| line.split("value=\"").nth(1)?.split('"').next())
        .map(str::to_string)
        .collect()
}

/// The shader stages MaterialX's generators wrote beside `document`
/// (`<document>.<element>.<extension>`) whose extension is one of `extensions`.
fn stages(document: &Path, extensions: &[&str]) -> Vec<PathBuf> {
    let folder = document.parent().expect("a folder");
    let prefix = format!("{}.", document.file_name().unwrap().to_string_lossy());
    let mut stages: Vec<PathBuf> = std::fs::read_dir(folder)
        .expect("the export folder")
        .map(|entry| entry.expect("an entry").path())
        .filter(|path| {
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            let extension = path.extension().unwrap_or_default().to_string_lossy();
            name.starts_with(&prefix) && extensions.contains(&extension.as_ref())
        })
        .collect();
    stages.sort();
    stages
}

/// Runs MaterialX's own validation and GLSL and Metal generation on `documents`, then
/// glslangValidator on every GLSL stage it wrote. Metal has no compiler here: its pixel
/// stage must define each function the document's implementations name (Veneer's own node
/// functions, in naga's Metal) that the GLSL pixel stage defines.
pub fn check_with_materialx(documents: &[PathBuf]) {
    python_check(
        "tests/materialx/check.py",
        documents,
        ": valid, 1 shader",
        "MaterialX",
    );
    for document in documents {
        let glsl = stages(document, &["frag", "vert"]);
        assert_eq!(
            glsl.len(),
            2,
            "{}: a pixel and a vertex stage",
            document.display()
        );
        for stage in glsl {
            let result = Command::new("glslangValidator")
                .arg(&stage)
                .output()
                .expect("glslangValidator runs");
            assert!(
                result.status.success(),
                "{}: {}",
                stage.display(),
                String::from_utf8_lossy(&result.stdout)
            );
        }
        let metal = stages(document, &["metal"]);
        assert_eq!(metal.len(), 1, "{}: a Metal stage", document.display());
        let metal = std::fs::read_to_string(&metal[0]).expect("the Metal stage");
        let pixel =
            std::fs::read_to_string(&stages(document, &["frag"])[0]).expect("the pixel stage");
        let text = std::fs::read_to_string(document).expect("the document");
        for function in text.split("function=\"").skip(1) {
            let function = function.split('"').next().expect("a closing quote");
            let defined = format!("void {function}(");
            assert_eq!(
                metal.contains(&defined),
                pixel.contains(&defined),
                "{}: {function} is not in the Metal stage",
                document.display()
            );
        }
    }
}

#[test]
fn every_preset_exports_to_a_document_that_materialx_validates_and_compiles() {
    let dir = temp_dir("materialx-presets");
    let mut documents = Vec::new();
    let (mut cut_out, mut emissive, mut bumped) = (0, 0, 0);
    for (index, graph) in presets().into_iter().chain(texture_graphs()).enumerate() {
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
        let files = named_files(&document);
        for file in &files {
            assert!(
                written.contains(&dir.join(file)),
                "{}: {file} is not beside it",
                graph.display()
            );
        }
        assert_eq!(
            written.len(),
            1 + files.len(),
            "{}: {written:?}",
            graph.display()
        );
        let uses = compiled.uses();
        let names = |map: &str| {
            files
                .iter()
                .any(|file| file.ends_with(&format!("_{map}.png")))
        };
        assert_eq!(
            names("alpha"),
            uses.alpha != AlphaUse::Opaque,
            "{}",
            graph.display()
        );
        assert_eq!(
            names("normal"),
            uses.perturbs_normal(),
            "{}",
            graph.display()
        );
        assert_eq!(document.contains("<normalmap "), uses.perturbs_normal());
        if let AlphaUse::Mask(cutoff) = uses.alpha {
            cut_out += 1;
            let threshold = match surface {
                SurfaceModel::GltfPbr => {
                    format!("name=\"alpha_cutoff\" type=\"float\" value=\"{cutoff}\"")
                }
                _ => format!("name=\"value2\" type=\"float\" value=\"{cutoff}\""),
            };
            assert!(
                document.contains(&threshold),
                "{}:\n{document}",
                graph.display()
            );
        }
        emissive += usize::from(names("emission"));
        bumped += usize::from(names("normal"));
        documents.push(path);
    }
    assert!(
        cut_out > 0 && emissive > 0 && bumped > 0,
        "{cut_out} cut out, {emissive} emissive, {bumped} bumped"
    );
    check_with_materialx(&documents);
}

#[test]
fn every_surface_model_wires_the_same_maps_and_exports_the_same_bytes_twice() {
    let dir = temp_dir("materialx-models");
    let graph = root("graphs/lava_glow.ron");
    let compiled = compiled(&graph);
    let mut documents = Vec::new();
    for (surface, name, _) in SurfaceModel::ALL {
        let path = dir.join(format!("lava_{}.mtlx", name.replace('-', "_")));
        let first = export(&compiled, surface, &path);
        let bytes: Vec<Vec<u8>> = first
            .iter()
            .map(|file| std::fs::read(file).unwrap())
            .collect();
        let again = export(&compiled, surface, &path);
        assert_eq!(first, again);
        for (file, before) in again.iter().zip(&bytes) {
            assert_eq!(&std::fs::read(file).unwrap(), before, "{}", file.display());
        }
        let document = std::fs::read_to_string(&path).unwrap();
        // Lava glows past 1: its emission map is wired, times its brightness (the map
        // holds emission over it), and the colour maps are linear.
        assert!(
            document.contains("<multiply name=\"emission\" type=\"color3\">"),
            "{document}"
        );
        assert!(
            named_files(&document)
                .iter()
                .any(|f| f.ends_with("_emission.png")),
            "{document}"
        );
        assert!(
            document.contains("colorspace=\"lin_rec709\" />"),
            "{document}"
        );
        documents.push(path);
    }
    check_with_materialx(&documents);
    // No staging folder is left behind.
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name.starts_with(".veneer"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}

#[test]
fn outputs_a_materialx_export_cannot_write_are_refused_with_nothing_written() {
    let dir = temp_dir("materialx-refused");
    let folder = dir.join("taken.mtlx");
    std::fs::create_dir_all(&folder).unwrap();
    let wood = root("graphs/wood.ron");
    let cases: [(Vec<String>, &str); 4] = [
        (
            vec!["-o".into(), folder.display().to_string()],
            "give `-o FILE.mtlx`",
        ),
        (vec!["-o".into(), "-".into()], "give `-o FILE.mtlx`"),
        (
            vec![
                "-o".into(),
                dir.join("missing/wood.mtlx").display().to_string(),
            ],
            "does not exist",
        ),
        (
            vec![
                "--params".into(),
                "uniform".into(),
                "-o".into(),
                dir.join("wood.mtlx").display().to_string(),
            ],
            "keeps the parameters in the document",
        ),
    ];
    for (arguments, expected) in cases {
        let mut command = veneer();
        command
            .args(["compile", "--target", "mtlx", "--size", "8"])
            .arg(&wood)
            .args(&arguments);
        assert_refused(&mut command, expected);
    }
    assert_holds_only(&dir, &["taken.mtlx"]);
    assert_holds_only(&folder, &[]);
}
