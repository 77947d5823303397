//! `veneer report`: measures where Veneer trades accuracy for speed and writes a report
//! (Markdown, a CSV per table, a PNG plot of error against time per section).

mod geodesics;
mod materials;
mod measure;
mod plot;
mod table;
mod thesis;

pub use plot::{Plot, Series};
pub use table::Table;

use crate::render::GpuContext;
use std::path::Path;

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

/// One part of the report.
struct Section {
    slug: &'static str,
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
    precision as u64 + 6 + 2 + 3 + meshes + 2 * thesis::MODELS.len() as u64
}

/// Measures everything and writes `report.md`, `<section>.csv` and `<section>.png` into
/// `folder` (each file atomically). `progress` is called after each step.
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
    std::fs::create_dir_all(folder).map_err(|e| format!("{}: {e}", folder.display()))?;
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
        materials::detail(&ctx)?,
        thesis::distance_times(&ctx)?,
        thesis::frame_rates(&ctx)?,
    ];
    let write = |name: &str, bytes: &[u8]| {
        let path = folder.join(name);
        crate::fsutil::write_atomic(&path, bytes)
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))
    };
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
    for section in &sections {
        write(
            &format!("{}.csv", section.slug),
            section.table.csv().as_bytes(),
        )?;
        write(&format!("{}.png", section.slug), &section.plot.png()?)?;
        markdown.push_str(&format!(
            "\n## {}\n\n{}\n\n{}\n![{}]({}.png)\n\n[{}.csv]({}.csv)\n",
            section.title,
            section.text,
            section.table.markdown(),
            section.plot.title,
            section.slug,
            section.slug,
            section.slug
        ));
    }
    write("report.md", markdown.as_bytes())
}
