//! `veneer report`: measures where Veneer trades accuracy for speed and writes a report
//! (Markdown, a CSV per table, a PNG plot of error against time per section).

mod fitting;
mod geodesics;
pub mod level_of_detail;
mod materials;
mod measure;
mod mesh_fields;
mod plot;
mod table;
mod thesis;

pub use plot::{Plot, Series};
pub use table::Table;

use crate::fsutil::Naming;
use crate::render::GpuContext;
use std::path::{Path, PathBuf};

/// The most repetitions a timing may take: a median over more says nothing new, and
/// every repetition is kept in memory.
pub const MAX_REPETITIONS: usize = 1000;

/// How much to measure.
pub struct Settings {
    /// Repetitions each timing's median is over.
    pub repetitions: usize,
    /// Quick: smaller meshes, fewer points (a smoke run, not for publishing).
    pub quick: bool,
}

/// What the sections share.
struct Context<'a> {
    gpu: &'a GpuContext,
    repetitions: usize,
    /// Points per side of the precision and hash samples.
    sample_size: u32,
    /// Pixels per side of timed renders.
    timing_size: u32,
    max_octaves: u32,
    meshes: &'a [&'a str],
    /// The stand-ins for the thesis's models (its Tables 5.1–5.3).
    models: &'a [&'a str],
    progress: &'a dyn Fn(),
}

/// One part of the report; its files are named by its slug in [`SLUGS`].
struct Section {
    title: String,
    text: String,
    table: Table,
    plot: Plot,
}

/// The number of progress steps a report takes (for a progress bar).
pub fn steps(settings: &Settings) -> u64 {
    let meshes = if settings.quick { 2 } else { 4 };
    // precision cases (presets, noise and fBm of each basis, Worley) + hash rows + octave
    // kinds + detail materials + geodesic meshes + thesis models (field times, frames)
    let precision = crate::graph::PRESETS.len() + 2 * crate::graph::Basis::ALL.len() + 1;
    // ... + mesh fields (occlusion per vertex and per texel, curvature, thickness) + the
    // fitted presets
    let detail = level_of_detail::cases().len() as u64;
    precision as u64
        + 6
        + 2
        + detail
        + meshes
        + 2 * thesis::MODELS.len() as u64
        + 4
        + fitting::steps(settings.quick)
}

/// The sections' slugs, in the order they are measured and appear: each gives its
/// section's table, `<slug>.csv`, and plot, `<slug>.png`.
const SLUGS: [&str; 9] = [
    "precision",
    "hashes",
    "octaves",
    "geodesics",
    "detail",
    "distance_times",
    "frame_rates",
    "mesh_fields",
    "fitting",
];

/// The report's own page, beside the tables and plots.
const PAGE: &str = "report.md";

/// Every file a report writes into `folder`.
pub fn files(folder: &Path) -> Vec<PathBuf> {
    (SLUGS.iter())
        .flat_map(|slug| [format!("{slug}.csv"), format!("{slug}.png")])
        .chain([PAGE.to_string()])
        .map(|name| folder.join(name))
        .collect()
}

/// Measures everything and writes `report.md`, `<section>.csv` and `<section>.png` into
/// `folder`, made when missing. The files are put in place together once all are
/// written: a report that fails (a full disk, a failed measurement) leaves none of them,
/// nor the folder if it made it. `progress` is called after each step.
pub fn write(
    gpu: &GpuContext,
    settings: &Settings,
    folder: &Path,
    progress: &dyn Fn(),
) -> Result<(), String> {
    if !(1..=MAX_REPETITIONS).contains(&settings.repetitions) {
        return Err(format!(
            "repetitions {} is outside 1..={MAX_REPETITIONS}",
            settings.repetitions
        ));
    }
    let made = !folder.is_dir();
    std::fs::create_dir_all(folder).map_err(|e| format!("{}: {e}", folder.display()))?;
    let written = measure_and_write(gpu, settings, folder, progress);
    if written.is_err() && made {
        // Only an empty folder goes: everything staged in it was removed.
        let _ = std::fs::remove_dir(folder);
    }
    written
}

/// Measures the sections and writes the report's files into `folder` together.
fn measure_and_write(
    gpu: &GpuContext,
    settings: &Settings,
    folder: &Path,
    progress: &dyn Fn(),
) -> Result<(), String> {
    let meshes: &[&str] = if settings.quick {
        &["torus:24", "genus2:20"]
    } else {
        &["torus:48", "torus:96", "torus:160", "genus2:40"]
    };
    let ctx = Context {
        gpu,
        repetitions: settings.repetitions,
        sample_size: if settings.quick { 64 } else { 256 },
        timing_size: if settings.quick { 256 } else { 1024 },
        max_octaves: if settings.quick { 6 } else { 10 },
        meshes,
        models: if settings.quick {
            &thesis::QUICK_MODELS
        } else {
            &thesis::MODELS
        },
        progress,
    };
    let sections = [
        materials::precision(&ctx)?,
        materials::hashes(&ctx)?,
        materials::octaves(&ctx)?,
        geodesics::geodesics(&ctx)?,
        level_of_detail::detail(&ctx)?,
        thesis::distance_times(&ctx)?,
        thesis::frame_rates(&ctx)?,
        mesh_fields::mesh_fields(&ctx, settings.quick)?,
        fitting::fitting(&ctx, settings.quick)?,
    ];
    let mut contents: Vec<Vec<u8>> = Vec::new();
    let mut markdown = format!(
        "# Veneer: error against run time\n\nMeasured by `veneer report` (Veneer {}) on {} with the adapter {}. Each timing is the median of {} runs unless a section says otherwise; GPU times are {}. Every table is also a CSV beside this file.\n",
        env!("CARGO_PKG_VERSION"),
        measure::machine(),
        gpu.adapter_description(),
        settings.repetitions,
        if crate::render::PassTimer::supported(gpu) {
            "the time the GPU spent in the render pass (timestamp queries), without submission or reading back"
        } else {
            "wall time from submitting the render pass to its completion (the adapter has no timestamp queries), without reading back"
        }
    );
    for (slug, section) in SLUGS.iter().zip(&sections) {
        contents.push(section.table.csv().into_bytes());
        contents.push(section.plot.png()?);
        markdown.push_str(&format!(
            "\n## {}\n\n{}\n\n{}\n![{}]({slug}.png)\n\n[{slug}.csv]({slug}.csv)\n",
            section.title,
            section.text,
            section.table.markdown(),
            section.plot.title,
        ));
    }
    contents.push(markdown.into_bytes());
    let paths = files(folder);
    let files = (paths.iter().zip(&contents))
        .map(|(path, bytes)| (path.as_path(), Naming::Implied, bytes.as_slice()));
    crate::fsutil::write_together(files)
        .map_err(|(path, e)| format!("{}: cannot write: {e}", path.display()))
}
