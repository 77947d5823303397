//! `veneer report`: error against run time, measured on this machine, as Markdown, CSV
//! and PNG plots.

use super::Failure;
use super::output::note;
use clap::Args;
use std::path::PathBuf;

#[derive(Args)]
pub struct ReportArgs {
    /// Folder to write report.md, a CSV per table and a PNG plot per section into.
    #[arg(short, long, default_value = "report")]
    output: PathBuf,
    /// Repetitions each timing's median is over.
    #[arg(long, default_value_t = 5)]
    repetitions: usize,
    /// Smaller meshes and samples: a smoke run in a minute, not for publishing.
    #[arg(long)]
    quick: bool,
}

impl ReportArgs {
    /// Adds the report's files to `plan`.
    pub fn plan(&self, plan: &mut veneer::fsutil::OutputPlan, by: &str) {
        for path in veneer::report::files(&self.output) {
            plan.writes(path, veneer::fsutil::Naming::Implied, by);
        }
    }
}

pub fn run(args: ReportArgs) -> Result<(), Failure> {
    let limit = veneer::report::MAX_REPETITIONS;
    if !(1..=limit).contains(&args.repetitions) {
        return Err(Failure::new(format!(
            "--repetitions {}: expected 1 to {limit}",
            args.repetitions
        )));
    }
    let settings = veneer::report::Settings {
        repetitions: args.repetitions,
        quick: args.quick,
    };
    let gpu = veneer::render::GpuContext::new()?;
    let bar = indicatif::ProgressBar::new(veneer::report::steps(&settings));
    bar.set_style(
        indicatif::ProgressStyle::with_template("report [{bar:40}] {pos}/{len} {elapsed}")
            .expect("valid template"),
    );
    let started = std::time::Instant::now();
    veneer::report::write(&gpu, &settings, &args.output, &|| bar.inc(1)).map_err(Failure::new)?;
    bar.finish_and_clear();
    note(format!(
        "wrote {} in {:.0} s",
        args.output.join("report.md").display(),
        started.elapsed().as_secs_f64()
    ))
}
