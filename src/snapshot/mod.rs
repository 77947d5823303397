//! Graph-to-image snapshot testing: render a graph, compare it with an approved golden
//! image, and explain any difference. Used by `veneer snapshot`, by Veneer's own tests,
//! and by other crates' tests through [`assert_matches`].

mod compare;
mod record;

pub use compare::{Comparison, Tolerance, compare, heat_map, ssim};
pub use record::{SnapshotRecord, fnv1a};

use crate::codegen::{CompileError, CompileOptions};
use crate::fsutil::{ReadLimit, read_limited};
use crate::graph::{Basis, CheckedGraph, LoadError};
use crate::render::{GpuContext, Image, RenderError, View, render_material};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// The environment variable that makes snapshots rewrite their goldens.
pub const UPDATE_VARIABLE: &str = "VENEER_UPDATE_SNAPSHOTS";

/// How to render a graph for a snapshot, and how close it must be.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    pub view: View,
    pub size: u32,
    pub time: f32,
    /// Overrides the tolerance the golden's sidecar declares.
    pub tolerance: Option<Tolerance>,
    /// Values for the graph's exposed parameters.
    pub parameters: crate::graph::parameters::Overrides,
}

impl Default for Settings {
    /// The graph's preview mesh at 256×256, time 0, the golden's own tolerance.
    fn default() -> Settings {
        Settings {
            view: View::Mesh(None),
            size: 256,
            time: 0.0,
            tolerance: None,
            parameters: Default::default(),
        }
    }
}

/// What became of one snapshot.
#[derive(Clone, Debug, PartialEq)]
pub enum Outcome {
    /// The render matches the golden.
    Matched(Comparison),
    /// The golden (and its sidecar) were written.
    Updated,
    /// The render does not match; `actual` and `diff` images were written next to the golden.
    Mismatched {
        comparison: Option<Comparison>,
        tolerance: Tolerance,
        reasons: Vec<String>,
    },
}

/// The result of checking one graph against its golden.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    pub graph: PathBuf,
    pub golden: PathBuf,
    pub outcome: Outcome,
}

impl Report {
    /// Whether the snapshot passed (matched or was updated).
    pub fn passed(&self) -> bool {
        !matches!(self.outcome, Outcome::Mismatched { .. })
    }

    /// One human-readable line (plus reasons on mismatch).
    pub fn summary(&self) -> String {
        let name = self.graph.display();
        match &self.outcome {
            Outcome::Matched(comparison) => format!("{name}: ok ({comparison})"),
            Outcome::Updated => format!("{name}: golden written to {}", self.golden.display()),
            Outcome::Mismatched {
                comparison,
                tolerance,
                reasons,
            } => {
                let measured = comparison
                    .map(|c| format!(" ({c}; tolerance {tolerance})"))
                    .unwrap_or_default();
                let mut text = format!("{name}: DIFFERS from {}{measured}", self.golden.display());
                for reason in reasons {
                    text.push_str("\n  - ");
                    text.push_str(reason);
                }
                text
            }
        }
    }
}

/// A snapshot that could not be taken at all: a bad graph, a failed render, a golden
/// that cannot be read or written.
#[derive(Debug, thiserror::Error)]
pub enum SnapshotError {
    /// The graph file could not be read or parsed.
    #[error(transparent)]
    Load(#[from] LoadError),
    /// A parameter override does not fit the graph.
    #[error("{graph}: {error}")]
    Parameter {
        graph: PathBuf,
        #[source]
        error: crate::graph::parameters::ParameterError,
    },
    /// The graph does not compile.
    #[error("{graph}: {error}")]
    Compile {
        graph: PathBuf,
        #[source]
        error: CompileError,
    },
    /// The render failed (no GPU, the GPU refused it, the mesh or its fields failed).
    #[error("{graph}: {error}")]
    Render {
        graph: PathBuf,
        #[source]
        error: RenderError,
    },
    /// The render could not be encoded as PNG.
    #[error(transparent)]
    Encode(RenderError),
    /// The golden is not a readable PNG.
    #[error("{path}: {message}")]
    Golden { path: PathBuf, message: String },
    /// A golden, its sidecar or an explanation image could not be read or written, or
    /// their folder made.
    #[error("{path}: {what}{error}")]
    File {
        path: PathBuf,
        /// `cannot read: `, `cannot write: ` or nothing (making the folder).
        what: &'static str,
        #[source]
        error: std::io::Error,
    },
}

/// Whether `VENEER_UPDATE_SNAPSHOTS=1` asks for goldens to be rewritten.
pub fn update_requested() -> bool {
    std::env::var(UPDATE_VARIABLE)
        .is_ok_and(|value| value == "1" || value.eq_ignore_ascii_case("true"))
}

/// `golden` with its extension replaced: `marble.png` → `marble.<suffix>`.
pub fn beside(golden: &Path, suffix: &str) -> PathBuf {
    let stem = golden
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    golden.with_file_name(format!("{stem}.{suffix}"))
}

/// Whether a node the material reads hashes with the sine hash, whose bits differ
/// between adapters.
fn uses_sine_hash(graph: &CheckedGraph) -> bool {
    graph
        .order
        .iter()
        .any(|checked| checked.node.kind.basis() == Some(Basis::ValueSine))
}

/// The failure to write `path`.
fn cannot_write(path: &Path, error: std::io::Error) -> SnapshotError {
    SnapshotError::File {
        path: path.to_path_buf(),
        what: "cannot write: ",
        error,
    }
}

/// Writes `bytes` to `path`, a file of the golden folder Veneer names itself (never
/// through a link: [`crate::fsutil::Naming::Implied`]).
fn write(path: &Path, bytes: &[u8]) -> Result<(), SnapshotError> {
    crate::fsutil::write_implied(path, bytes).map_err(|error| cannot_write(path, error))
}

/// Writes the golden and its sidecar together: neither is left without the other.
fn write_golden(
    golden: &Path,
    png: &[u8],
    sidecar: &Path,
    record: &[u8],
) -> Result<(), SnapshotError> {
    use crate::fsutil::Naming::Implied;
    crate::fsutil::write_together([(golden, Implied, png), (sidecar, Implied, record)])
        .map_err(|(path, error)| cannot_write(&path, error))
}

/// Why a render and its golden may differ, read from the golden's sidecar.
fn explain(recorded: &SnapshotRecord, current: &SnapshotRecord) -> Vec<String> {
    let mut reasons = Vec::new();
    if recorded.graph_hash != current.graph_hash {
        reasons.push("the graph changed since the golden was made".to_string());
    } else if recorded.shader_hash != current.shader_hash {
        reasons.push(format!(
            "the graph is unchanged but its generated shader differs: the golden was made by Veneer {}, this is {}",
            recorded.veneer, current.veneer
        ));
    }
    if (&recorded.view, recorded.size, recorded.time) != (&current.view, current.size, current.time)
    {
        reasons.push(format!(
            "render settings differ: golden {:?} at {} px, t = {}; now {:?} at {} px, t = {}",
            recorded.view, recorded.size, recorded.time, current.view, current.size, current.time
        ));
    }
    if (&recorded.adapter, &recorded.backend) != (&current.adapter, &current.backend) {
        reasons.push(format!(
            "the golden was made on {} ({}), this run is on {} ({})",
            recorded.adapter, recorded.backend, current.adapter, current.backend
        ));
        if recorded.adapter_dependent {
            reasons.push("the graph uses the sine hash, whose bits differ between adapters: keep one golden per adapter".into());
        }
    }
    reasons
}

/// Renders `graph_path` and compares it with `golden` (a PNG with a `.snap.ron` sidecar
/// beside it), or writes both when `update` is set. On a mismatch, writes
/// `<golden>.actual.png` and `<golden>.diff.png` beside the golden.
pub fn check(
    gpu: &GpuContext,
    graph_path: &Path,
    golden: &Path,
    settings: &Settings,
    update: bool,
) -> Result<Report, SnapshotError> {
    let mut graph = crate::graph::load(graph_path)?;
    settings
        .parameters
        .apply(&mut graph)
        .map_err(|error| SnapshotError::Parameter {
            graph: graph_path.to_path_buf(),
            error,
        })?;
    let compiled =
        crate::codegen::compile(&graph, &CompileOptions::default()).map_err(|error| {
            SnapshotError::Compile {
                graph: graph_path.to_path_buf(),
                error,
            }
        })?;
    let image = render_material(gpu, &compiled, &settings.view, settings.size, settings.time)
        .map_err(|error| SnapshotError::Render {
            graph: graph_path.to_path_buf(),
            error,
        })?;
    let info = gpu.adapter.get_info();
    let current = SnapshotRecord {
        veneer: env!("CARGO_PKG_VERSION").to_string(),
        adapter: info.name.clone(),
        backend: format!("{:?}", info.backend),
        graph_hash: fnv1a(crate::graph::to_ron(&graph).as_bytes()),
        shader_hash: fnv1a(compiled.source().as_bytes()),
        view: settings.view.clone(),
        size: settings.size,
        time: settings.time,
        tolerance: settings.tolerance.unwrap_or(Tolerance::SAME_ADAPTER),
        cross_adapter: Tolerance::CROSS_ADAPTER,
        adapter_dependent: uses_sine_hash(&compiled.checked),
    };
    let sidecar = beside(golden, "snap.ron");
    let report = |outcome| Report {
        graph: graph_path.to_path_buf(),
        golden: golden.to_path_buf(),
        outcome,
    };
    if update {
        let png = image.to_png().map_err(SnapshotError::Encode)?;
        let config = ron::ser::PrettyConfig::new().struct_names(false);
        let record =
            ron::ser::to_string_pretty(&current, config).expect("records serialise") + "\n";
        if let Some(folder) = golden.parent().filter(|f| !f.as_os_str().is_empty()) {
            std::fs::create_dir_all(folder).map_err(|error| SnapshotError::File {
                path: folder.to_path_buf(),
                what: "",
                error,
            })?;
        }
        write_golden(golden, &png, &sidecar, record.as_bytes())?;
        remove_leftovers(golden);
        return Ok(report(Outcome::Updated));
    }
    let mismatch = |comparison, tolerance, reasons: Vec<String>| -> Result<Report, SnapshotError> {
        write(
            &beside(golden, "actual.png"),
            &image.to_png().map_err(SnapshotError::Encode)?,
        )?;
        Ok(report(Outcome::Mismatched {
            comparison,
            tolerance,
            reasons,
        }))
    };
    let golden_bytes = match read_limited(golden, ReadLimit::IMAGE) {
        Ok(bytes) => bytes,
        Err(error) if error.kind() == std::io::ErrorKind::NotFound => {
            let reason = format!(
                "no golden at {}: approve this render with --update or {UPDATE_VARIABLE}=1",
                golden.display()
            );
            return mismatch(None, current.tolerance, vec![reason]);
        }
        Err(error) => {
            return Err(SnapshotError::File {
                path: golden.to_path_buf(),
                what: "cannot read: ",
                error,
            });
        }
    };
    let expected = Image::from_png(&golden_bytes).map_err(|message| SnapshotError::Golden {
        path: golden.to_path_buf(),
        message,
    })?;
    let recorded: Option<SnapshotRecord> = read_limited(&sidecar, ReadLimit::GRAPH)
        .ok()
        .and_then(|bytes| String::from_utf8(bytes).ok())
        .and_then(|text| ron::from_str(&text).ok());
    let same_adapter = recorded
        .as_ref()
        .is_none_or(|r| (&r.adapter, &r.backend) == (&current.adapter, &current.backend));
    let tolerance = settings.tolerance.unwrap_or(match &recorded {
        Some(record) if same_adapter => record.tolerance,
        Some(record) => record.cross_adapter,
        None => Tolerance::SAME_ADAPTER,
    });
    let mut reasons = match &recorded {
        Some(record) => explain(record, &current),
        None => vec![format!(
            "no sidecar {} records how the golden was made",
            sidecar.display()
        )],
    };
    match compare(&image, &expected, &tolerance) {
        Ok(comparison) if comparison.passes() => {
            remove_leftovers(golden);
            Ok(report(Outcome::Matched(comparison)))
        }
        Ok(comparison) => {
            let diff = heat_map(&image, &expected)
                .to_png()
                .map_err(SnapshotError::Encode)?;
            write(&beside(golden, "diff.png"), &diff)?;
            mismatch(Some(comparison), tolerance, reasons)
        }
        Err(shape) => {
            reasons.insert(0, shape);
            mismatch(None, tolerance, reasons)
        }
    }
}

fn remove_leftovers(golden: &Path) {
    for suffix in ["actual.png", "diff.png"] {
        let _ = std::fs::remove_file(beside(golden, suffix));
    }
}

/// The GPU context snapshot assertions share within one process.
fn shared_gpu() -> &'static GpuContext {
    static GPU: OnceLock<GpuContext> = OnceLock::new();
    GPU.get_or_init(|| {
        GpuContext::new()
            .unwrap_or_else(|error| panic!("snapshot tests need a wgpu adapter: {error}"))
    })
}

/// For `cargo test`: renders `graph` and panics unless it matches `golden` (writing the
/// golden instead when `VENEER_UPDATE_SNAPSHOTS=1`), or the adapter's own copy of it
/// ([`kept_for`]). On a mismatch the panic message explains why, and
/// `<golden>.actual.png` and `<golden>.diff.png` are left beside it.
pub fn assert_matches(graph: impl AsRef<Path>, golden: impl AsRef<Path>, settings: &Settings) {
    assert_matches_on(shared_gpu(), graph, golden, settings);
}

/// [`assert_matches`] on adapter `gpu`.
pub fn assert_matches_on(
    gpu: &GpuContext,
    graph: impl AsRef<Path>,
    golden: impl AsRef<Path>,
    settings: &Settings,
) {
    let update = update_requested();
    let golden = kept_for(gpu, golden.as_ref(), update);
    let report = check(gpu, graph.as_ref(), &golden, settings, update)
        .unwrap_or_else(|error| panic!("snapshot of {} failed: {error}", graph.as_ref().display()));
    assert!(report.passed(), "{}", report.summary());
}

/// The name of the subfolder that keeps an adapter's own goldens, `<device>-<backend>` in
/// lower case (`llvmpipe-gl`): graphs whose bits differ between adapters (the sine
/// hash's) need one golden per adapter, kept beside the others.
pub fn adapter_folder(gpu: &GpuContext) -> String {
    let info = gpu.adapter.get_info();
    let device = info.name.split_whitespace().next().unwrap_or("unknown");
    format!("{device}-{:?}", info.backend).to_lowercase()
}

/// Where `gpu` keeps golden `golden`: under [`adapter_folder`] in the golden's folder
/// (`tests/snapshots/llvmpipe-gl/wood.png` for `tests/snapshots/wood.png`) when that
/// subfolder exists and holds the file, or when updating; else `golden` itself (the
/// graph renders alike on every adapter, or the adapter keeps no goldens of its own).
pub fn kept_for(gpu: &GpuContext, golden: &Path, update: bool) -> PathBuf {
    let (Some(folder), Some(name)) = (golden.parent(), golden.file_name()) else {
        return golden.to_path_buf();
    };
    let own = folder.join(adapter_folder(gpu));
    let kept = own.join(name);
    if own.is_dir() && (update || kept.is_file()) {
        kept
    } else {
        golden.to_path_buf()
    }
}
