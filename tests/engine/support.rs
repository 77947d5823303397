//! Shared helpers: one GPU context per test binary, preset paths, image comparison.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use veneer::render::{FlatRect, FlatRenderer, GpuContext};

/// The GPU context shared by all tests (a software adapter on CI).
pub fn gpu() -> &'static GpuContext {
    static GPU: OnceLock<GpuContext> = OnceLock::new();
    GPU.get_or_init(|| GpuContext::new().expect("tests need a wgpu adapter (lavapipe or llvmpipe)"))
}

/// Path of a file relative to the crate root.
pub fn root(relative: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(relative)
}

/// Every preset graph in `graphs/`, sorted by name.
pub fn presets() -> Vec<PathBuf> {
    graphs_in("graphs")
}

/// Every texture graph (a material with passes) in `graphs/texture/`, sorted by name.
pub fn texture_graphs() -> Vec<PathBuf> {
    graphs_in("graphs/texture")
}

/// The graph files in `folder` (relative to the repository), sorted by name.
fn graphs_in(folder: &str) -> Vec<PathBuf> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(root(folder))
        .unwrap_or_else(|e| panic!("{folder}: {e}"))
        .map(|entry| entry.expect("readable entry").path())
        .filter(|path| path.extension().is_some_and(|ext| ext == "ron"))
        .collect();
    paths.sort();
    paths
}

/// The preset's file stem (`wood` for `graphs/wood.ron`).
pub fn stem(path: &Path) -> String {
    path.file_stem()
        .expect("a file name")
        .to_string_lossy()
        .into_owned()
}

/// The snapshots' folder: goldens of CI's adapter (Vulkan/lavapipe), and in
/// `<adapter>/` subfolders (`llvmpipe-gl/`) another adapter's own, for graphs whose bits
/// differ there (see `veneer::snapshot::kept_for`).
pub fn snapshot_folder() -> PathBuf {
    root("tests/snapshots")
}

/// Whether golden WGSL files should be rewritten instead of compared.
pub fn updating() -> bool {
    std::env::var("VENEER_UPDATE_GOLDEN").is_ok_and(|value| value == "1")
}

/// The contract's flat render of a material module as 8-bit RGB.
pub fn flat_rgb8(material_wgsl: &str, rect: FlatRect, size: u32) -> Vec<u8> {
    let renderer = FlatRenderer::new(gpu(), material_wgsl).expect("the flat pipeline builds");
    let pixels = renderer
        .render(gpu(), rect, size, 0.0)
        .expect("the flat render runs");
    veneer::render::albedo_to_rgb8(&pixels)
}

/// The contract's flat render of a compiled material, its passes first if it has any.
pub fn compiled_rgb8(compiled: &veneer::codegen::Compiled, rect: FlatRect, size: u32) -> Vec<u8> {
    let renderer = FlatRenderer::for_compiled(gpu(), compiled).expect("the flat pipelines build");
    let pixels = renderer
        .render(gpu(), rect, size, 0.0)
        .expect("the flat render runs");
    veneer::render::albedo_to_rgb8(&pixels)
}

/// The CPU evaluator's (f32) version of the flat render: the same sample positions,
/// computed with the same f32 arithmetic as shaders/render_flat.wgsl (a multi-pass
/// material's buffers rendered first, as the GPU does).
pub fn cpu_flat_rgb8(graph: &veneer::graph::Graph, rect: FlatRect, size: u32) -> Vec<u8> {
    let passes = veneer::codegen::compile(graph, &Default::default())
        .map(|compiled| compiled.passes)
        .unwrap_or_default();
    let evaluator = veneer::eval::Evaluator::new(graph).expect("graph checks");
    evaluator
        .flat::<f32>(&passes, rect, size, 0.0)
        .into_iter()
        .flat_map(|material| {
            material
                .albedo
                .map(|v| (255.0 * v.clamp(0.0, 1.0)).round() as u8)
        })
        .collect()
}

/// How two square 8-bit images of `channels` channels differ, with a per-channel tolerance
/// (through the snapshot module's comparison, as users get it).
pub fn difference(
    a: &[u8],
    b: &[u8],
    channels: usize,
    tolerance: u8,
) -> veneer::snapshot::Comparison {
    let side = ((a.len() / channels) as f64).sqrt() as u32;
    let image = |pixels: &[u8]| veneer::render::Image {
        width: side,
        height: side,
        channels,
        pixels: pixels.to_vec(),
    };
    let tolerance = veneer::snapshot::Tolerance {
        channel: tolerance,
        share: 0.0,
        ssim: None,
    };
    veneer::snapshot::compare(&image(a), &image(b), &tolerance).expect("images of the same size")
}

/// A fresh folder for one test's files, under the system's temporary folder.
pub fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("veneer-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temporary folder");
    dir
}

/// The `veneer` binary under test, ready for arguments.
pub fn veneer() -> std::process::Command {
    std::process::Command::new(env!("CARGO_BIN_EXE_veneer"))
}

/// Runs `veneer args` in the repository root and returns what it did.
pub fn run_veneer(args: &[&str]) -> std::process::Output {
    veneer()
        .args(args)
        .current_dir(root(""))
        .output()
        .expect("the veneer binary runs")
}

/// A small deterministic generator (SplitMix64) for sample points; the seed tests add
/// the kinds of points they need.
pub struct Samples(pub u64);

impl Samples {
    /// The next number in [0, 1].
    pub fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        (z ^ (z >> 31)) as f64 / u64::MAX as f64
    }
}

/// A metallic-roughness material (base colour 0.5, metallic 0.25, roughness 0.75,
/// occlusion 0.5, emission (1, 0.5, 0) at strength 3) whose tangent-space normal is `normal` and whose metallic-roughness
/// other channels are these constants.
pub fn metallic_roughness(normal: (f64, f64, f64)) -> veneer::graph::Graph {
    let mut graph = veneer::graph::Graph {
        shading: veneer::graph::Shading::MetallicRoughness,
        ..veneer::graph::Graph::default()
    };
    let material = graph.add("material", veneer::graph::NodeKind::Material);
    graph.set_input(
        material,
        "albedo",
        veneer::graph::Value::Color(0.5, 0.5, 0.5),
    );
    graph.set_input(
        material,
        "normal",
        veneer::graph::Value::Vec3(normal.0, normal.1, normal.2),
    );
    graph.set_input(material, "metallic", veneer::graph::Value::Float(0.25));
    graph.set_input(material, "roughness", veneer::graph::Value::Float(0.75));
    graph.set_input(material, "occlusion", veneer::graph::Value::Float(0.5));
    graph.set_input(
        material,
        "emission",
        veneer::graph::Value::Color(1.0, 0.5, 0.0),
    );
    graph.set_input(
        material,
        "emission_strength",
        veneer::graph::Value::Float(3.0),
    );
    graph
}

/// The errors `check` gives `graph`, which it must refuse, joined by lines.
pub fn refusal(graph: &veneer::graph::Graph) -> String {
    let errors = veneer::graph::check(graph).expect_err("the check refuses it");
    errors
        .iter()
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join("\n")
}

/// Runs the Python check `script` (under the crate root) on `files` with the packages
/// `.ci/run` installs into `target/python` (`what` names them); panics with its report
/// unless it succeeds and has a line containing `passed` for every file.
pub fn python_check(script: &str, files: &[PathBuf], passed: &str, what: &str) {
    let output = std::process::Command::new("python3")
        .arg(root(script))
        .args(files)
        .env("PYTHONPATH", root("target/python"))
        .output()
        .unwrap_or_else(|error| panic!("python3 runs {script}: {error}"));
    let report = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{what} (`.ci/run` installs it into target/python):\n{report}{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let passing = report.lines().filter(|line| line.contains(passed)).count();
    assert_eq!(passing, files.len(), "{report}");
}

/// Runs `command` and checks that it fails with `expected` in its error output.
pub fn assert_refused(command: &mut std::process::Command, expected: &str) {
    let output = command.output().expect("the command runs");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "{command:?} succeeded");
    assert!(stderr.contains(expected), "{command:?}: {stderr}");
}

/// Checks that `dir` holds exactly the entries `names` (what a refused command left).
pub fn assert_holds_only(dir: &Path, names: &[&str]) {
    let mut left: Vec<String> = std::fs::read_dir(dir)
        .expect("the folder")
        .map(|entry| {
            entry
                .expect("an entry")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    left.sort();
    assert_eq!(left, names, "{}", dir.display());
}
