//! `veneer snapshot`: render graphs and compare them with approved golden images.
//! Exit 0 when all match, 1 when any differs, 2 on bad input.

use super::Failure;
use super::output::out;
use super::render::parse_flat;
use clap::Args;
use std::path::{Path, PathBuf};
use veneer::fsutil::{Naming, OutputPlan};
use veneer::render::{GpuContext, View};
use veneer::snapshot::{
    Outcome, Report, Settings, Tolerance, UPDATE_VARIABLE, beside, check, kept_for,
    update_requested,
};

#[derive(Args)]
pub struct SnapshotArgs {
    /// Graph files; each is compared with DIR/<graph>.png.
    #[arg(required = true)]
    graphs: Vec<PathBuf>,
    /// Folder of golden images and their .snap.ron sidecars; an adapter whose bits differ
    /// keeps its own in a subfolder named after it (`llvmpipe-gl/`), used where it exists.
    #[arg(long, value_name = "DIR")]
    golden: PathBuf,
    /// Write the renders as the new goldens (also with VENEER_UPDATE_SNAPSHOTS=1).
    #[arg(long)]
    update: bool,
    /// Override the goldens' tolerance: channel=N,share=S[,ssim=M].
    #[arg(long, value_name = "SPEC")]
    tolerance: Option<String>,
    /// Render the albedo flat over X0,Z0,X1,Z1,Y, or over each graph's preview square with `preview`.
    #[arg(
        long,
        value_name = "X0,Z0,X1,Z1,Y|preview",
        allow_hyphen_values = true,
        conflicts_with = "mesh"
    )]
    flat: Option<String>,
    /// Render on this mesh (default: each graph's preview mesh).
    #[arg(long)]
    mesh: Option<String>,
    /// Image width and height in pixels.
    #[arg(long, default_value_t = 256)]
    size: u32,
    /// Time in seconds.
    #[arg(long, default_value_t = 0.0, value_parser = super::parse_time, allow_hyphen_values = true)]
    time: f32,
    /// Print a JSON summary on stdout instead of one line per graph.
    #[arg(long)]
    json: bool,
    /// With parameter values, each golden is named `<graph>.<preset>.png` (with
    /// `--preset`) so that presets of one graph share a folder.
    #[command(flatten)]
    parameters: super::parameters::ParameterArgs,
}

impl SnapshotArgs {
    /// Adds the graphs, the parameter file and each graph's golden files to `plan`: under
    /// `--update` the golden and its sidecar are written; else they are read, and the
    /// render and difference images a mismatch leaves beside them written.
    pub fn plan(&self, plan: &mut OutputPlan, job: Option<&str>) {
        for graph in &self.graphs {
            let by = self.parameters.plan_graph(plan, job, graph);
            let golden = self.golden(graph);
            let (read, written) = if self.updating() {
                (vec![], vec![golden.clone(), beside(&golden, "snap.ron")])
            } else {
                let explained = vec![beside(&golden, "actual.png"), beside(&golden, "diff.png")];
                (vec![beside(&golden, "snap.ron"), golden], explained)
            };
            for path in read {
                plan.reads(path, &by);
            }
            for path in written {
                plan.writes(path, Naming::Implied, &by);
            }
        }
    }

    /// The golden image of `graph`: `<golden>/<graph>.png`, or `<graph>.<preset>.png`.
    fn golden(&self, graph: &Path) -> PathBuf {
        let stem = graph
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        match &self.parameters.preset {
            Some(preset) => self.golden.join(format!("{stem}.{preset}.png")),
            None => self.golden.join(format!("{stem}.png")),
        }
    }

    /// Whether the goldens are rewritten (`--update`, or the environment asks).
    fn updating(&self) -> bool {
        self.update || update_requested()
    }
}

fn bad_input(message: String) -> Failure {
    Failure(message, 2)
}

fn json_entry(report: &Report) -> serde_json::Value {
    let (status, comparison, tolerance, reasons) = match &report.outcome {
        Outcome::Matched(comparison) => (
            "matched",
            Some(*comparison),
            Some(comparison.tolerance),
            vec![],
        ),
        Outcome::Updated => ("updated", None, None, vec![]),
        Outcome::Mismatched {
            comparison,
            tolerance,
            reasons,
        } => ("differs", *comparison, Some(*tolerance), reasons.clone()),
    };
    serde_json::json!({
        "graph": report.graph.display().to_string(),
        "golden": report.golden.display().to_string(),
        "status": status,
        "max": comparison.map(|c| c.max),
        "mean": comparison.map(|c| c.mean),
        "share_outside": comparison.map(|c| c.share_outside),
        "psnr": comparison.map(|c| if c.psnr.is_finite() { serde_json::json!(c.psnr) } else { serde_json::json!("inf") }),
        "ssim": comparison.and_then(|c| c.ssim),
        "tolerance": tolerance.map(|t| t.to_string()),
        "reasons": reasons,
    })
}

pub fn run(args: SnapshotArgs) -> Result<(), Failure> {
    let tolerance = args
        .tolerance
        .as_deref()
        .map(|spec| Tolerance::parse(spec, Tolerance::SAME_ADAPTER))
        .transpose()
        .map_err(|error| bad_input(format!("--tolerance: {error}")))?;
    let view = match args.flat.as_deref() {
        Some("preview") => View::PreviewFlat,
        Some(rect) => {
            View::Flat(parse_flat(rect).map_err(|error| bad_input(format!("--flat: {error}")))?)
        }
        None => View::Mesh(args.mesh.clone()),
    };
    let settings = Settings {
        view,
        size: args.size,
        time: args.time,
        tolerance,
        parameters: args
            .parameters
            .overrides()
            .map_err(|Failure(message, _)| bad_input(message))?,
    };
    if args.golden.exists() && !args.golden.is_dir() {
        return Err(bad_input(format!(
            "--golden {}: is a file; it takes the folder of golden images",
            args.golden.display()
        )));
    }
    let update = args.updating();
    if !update && !args.golden.is_dir() {
        return Err(bad_input(format!(
            "--golden {}: no such folder; approve the first goldens with --update",
            args.golden.display()
        )));
    }
    let gpu = GpuContext::new().map_err(|error| bad_input(error.to_string()))?;
    let mut reports = Vec::new();
    for graph in &args.graphs {
        let golden = kept_for(&gpu, &args.golden(graph), update);
        let report = check(&gpu, graph, &golden, &settings, update)
            .map_err(|error| bad_input(error.to_string()))?;
        if !args.json {
            out(report.summary())?;
        }
        reports.push(report);
    }
    if args.json {
        out(serde_json::to_string_pretty(
            &reports.iter().map(json_entry).collect::<Vec<_>>(),
        )?)?;
    }
    let failed = reports.iter().filter(|r| !r.passed()).count();
    if failed == 0 {
        return Ok(());
    }
    let hint = format!(
        "{failed} of {} snapshots differ; approve with --update or {UPDATE_VARIABLE}=1",
        reports.len()
    );
    // On stderr with --json too: stdout stays the JSON alone.
    Err(Failure(hint, 1))
}
