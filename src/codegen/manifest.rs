//! The export of a multi-pass material: the material's module, one module per pass, and
//! a JSON manifest that tells an engine how to run them (passes in order, each buffer's
//! size, format and edge mode, and which buffer sits at each binding of group 2).
//!
//! WGSL modules are exported as the contract has them (the engine supplies its entry
//! points: `veneer_pass(s: VeneerSurface) -> vec4f` for a surface pass,
//! `veneer_stage(texel: vec2i) -> vec4f` for a stage); the other languages carry the
//! entry points Veneer renders the passes with (`shaders/render_pass_surface.wgsl`,
//! `shaders/render_pass_stage.wgsl`), fragment `veneer_pass_fragment`.

use super::Compiled;
use super::export::{ExportError, Target, export_compiled, translate};
use super::passes::{Pass, PassKind, STAGE_ENTRY_POINTS, SURFACE_ENTRY_POINTS};
use crate::fsutil::Naming;
use crate::nodes::passes::{BufferFormat, EdgeMode, Resolution};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// The fragment entry point of an exported pass (outside WGSL).
pub const PASS_FRAGMENT_ENTRY: &str = "veneer_pass_fragment";

/// One file of an export: its name (in the export's folder) and bytes.
#[derive(Clone, Debug, PartialEq)]
pub struct ExportFile {
    pub name: String,
    pub bytes: Vec<u8>,
}

/// The manifest's name for export stem `stem`.
pub fn manifest_name(stem: &str) -> String {
    format!("{stem}.passes.json")
}

/// A multi-pass material exported for `target` under names from `stem`: the material's
/// module (`<stem>.<ext>`), pass `i`'s module (`<stem>.pass<i>.<ext>`) in order, and the
/// manifest (`<stem>.passes.json`) last. Every module is validated as a single-pass
/// export is.
pub fn export_passes(
    compiled: &Compiled,
    target: Target,
    stem: &str,
) -> Result<Vec<ExportFile>, ExportError> {
    let extension = target.extension();
    let material_file = format!("{stem}.{extension}");
    let mut files = vec![ExportFile {
        name: material_file.clone(),
        bytes: export_compiled(compiled, target)?,
    }];
    let mut passes = Vec::with_capacity(compiled.passes.passes.len());
    for (index, pass) in compiled.passes.passes.iter().enumerate() {
        let module = match export_pass(pass, target)? {
            Some(bytes) => {
                let name = format!("{stem}.pass{index}.{extension}");
                files.push(ExportFile {
                    name: name.clone(),
                    bytes,
                });
                Some(name)
            }
            None => None,
        };
        passes.push(PassEntry::new(index, pass, module, target));
    }
    let manifest = Manifest {
        veneer: env!("CARGO_PKG_VERSION"),
        target: target.name(),
        material: ModuleEntry {
            file: material_file,
            entry: if target == Target::Wgsl {
                "veneer_material"
            } else {
                super::export::FRAGMENT_ENTRY
            },
            reads: bindings(&compiled.passes.reads),
        },
        passes,
    };
    let mut text = serde_json::to_string_pretty(&manifest).expect("a manifest serialises");
    text.push('\n');
    files.push(ExportFile {
        name: manifest_name(stem),
        bytes: text.into_bytes(),
    });
    Ok(files)
}

/// [`export_passes`] for a material module written to `path`: each file's path (the
/// others beside it, named from its stem), how it is named (the material's as given,
/// the rest by Veneer) and its bytes.
pub fn export_beside(
    compiled: &Compiled,
    target: Target,
    path: &Path,
) -> Result<Vec<(PathBuf, Naming, Vec<u8>)>, ExportError> {
    let stem = path.file_stem().unwrap_or_default().to_string_lossy();
    let files = export_passes(compiled, target, &stem)?;
    Ok((files.into_iter().enumerate())
        .map(|(index, file)| {
            let naming = if index == 0 {
                Naming::Given
            } else {
                Naming::Implied
            };
            (path.with_file_name(&file.name), naming, file.bytes)
        })
        .collect())
}

/// Pass `pass`'s module for `target` (none for an uploaded bitmap).
fn export_pass(pass: &Pass, target: Target) -> Result<Option<Vec<u8>>, ExportError> {
    let Some(module) = pass.module() else {
        return Ok(None);
    };
    let source = &module.source;
    if target == Target::Wgsl {
        return Ok(Some(source.clone().into_bytes()));
    }
    let entry_points = match pass.kind {
        PassKind::Stage { .. } => STAGE_ENTRY_POINTS,
        _ => SURFACE_ENTRY_POINTS,
    };
    translate(
        &format!("{source}\n{entry_points}"),
        target,
        PASS_FRAGMENT_ENTRY,
    )
    .map(Some)
}

/// What the manifest says of an export.
#[derive(Serialize)]
struct Manifest {
    /// The Veneer version that wrote it.
    veneer: &'static str,
    target: &'static str,
    material: ModuleEntry,
    /// In the order they run: pass `i` renders buffer `i`.
    passes: Vec<PassEntry>,
}

/// A module, its entry point and the buffers it binds.
#[derive(Serialize)]
struct ModuleEntry {
    file: String,
    entry: &'static str,
    /// Group 2: which buffer sits at each binding.
    reads: Vec<Binding>,
}

/// A buffer at a binding of group 2.
#[derive(Serialize)]
struct Binding {
    binding: usize,
    buffer: usize,
}

/// One pass of the manifest.
#[derive(Serialize)]
struct PassEntry {
    /// The buffer it renders (its place in the order).
    buffer: usize,
    label: String,
    /// `surface` (the material's nodes at every texel centre of the domain), `stage`
    /// (a texel-space pass over the buffer it reads, the same size) or `bitmap` (an
    /// image file's pixels, uploaded: no module).
    kind: &'static str,
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    module: Option<ModuleEntry>,
    /// A bitmap only: the file and how its numbers become the buffer's.
    #[serde(skip_serializing_if = "Option::is_none")]
    bitmap: Option<BitmapEntry>,
    /// The buffer's side against the output's: `inherit`, `double`, `half`, `absolute`.
    resolution: &'static str,
    /// The side in texels, for `absolute`.
    #[serde(skip_serializing_if = "Option::is_none")]
    texels: Option<u32>,
    /// The WebGPU texture format.
    format: &'static str,
    /// What reads past the buffer's edges see (the modules apply it themselves, with
    /// `textureLoad`: no sampler is bound).
    edge: &'static str,
    /// A stage only: on a buffer at most this many texels a side it leaves every texel
    /// as it was, and copying its source does the same work.
    #[serde(skip_serializing_if = "Option::is_none")]
    unchanged_up_to: Option<u32>,
}

/// The file of a bitmap pass.
#[derive(Serialize)]
struct BitmapEntry {
    /// The path as the graph names it, relative to the graph file's folder.
    file: String,
    width: u32,
    height: u32,
    /// Whether the colour lanes are decoded from sRGB (`srgb`) or taken as they are
    /// (`linear`); alpha is always taken as it is.
    decode: &'static str,
}

impl PassEntry {
    fn new(buffer: usize, pass: &Pass, file: Option<String>, target: Target) -> PassEntry {
        let (kind, entry) = match (&pass.kind, target) {
            (PassKind::Surface { .. }, Target::Wgsl) => ("surface", "veneer_pass"),
            (PassKind::Stage { .. }, Target::Wgsl) => ("stage", "veneer_stage"),
            (PassKind::Surface { .. }, _) => ("surface", PASS_FRAGMENT_ENTRY),
            (PassKind::Stage { .. }, _) => ("stage", PASS_FRAGMENT_ENTRY),
            (PassKind::Bitmap { .. }, _) => ("bitmap", ""),
        };
        let spec = pass.spec;
        PassEntry {
            buffer,
            label: pass.label.clone(),
            kind,
            module: file.map(|file| ModuleEntry {
                file,
                entry,
                reads: bindings(&pass.reads()),
            }),
            bitmap: match &pass.kind {
                PassKind::Bitmap { path, bitmap } => Some(BitmapEntry {
                    file: path.clone(),
                    width: bitmap.width,
                    height: bitmap.height,
                    decode: if bitmap.from_srgb { "srgb" } else { "linear" },
                }),
                _ => None,
            },
            resolution: match spec.resolution {
                Resolution::Inherit => "inherit",
                Resolution::Double => "double",
                Resolution::Half => "half",
                Resolution::Absolute => "absolute",
            },
            texels: (spec.resolution == Resolution::Absolute).then_some(spec.size),
            format: match spec.format {
                BufferFormat::Unorm8 => "rgba8unorm",
                BufferFormat::Float16 => "rgba16float",
                BufferFormat::Float32 => "rgba32float",
            },
            edge: match spec.edge {
                EdgeMode::Wrap => "wrap",
                EdgeMode::Clamp => "clamp",
                EdgeMode::Mirror => "mirror",
            },
            unchanged_up_to: match &pass.kind {
                PassKind::Stage { stage, .. } if stage.unchanged_up_to > 0 => {
                    Some(stage.unchanged_up_to)
                }
                _ => None,
            },
        }
    }
}

/// `reads` as bindings: binding `k` holds buffer `reads[k]`.
fn bindings(reads: &[usize]) -> Vec<Binding> {
    (reads.iter().enumerate())
        .map(|(binding, &buffer)| Binding { binding, buffer })
        .collect()
}
