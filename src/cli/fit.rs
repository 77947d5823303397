//! `veneer fit`: a graph's exposed parameters fitted to a photo.

use super::parameters::ParameterArgs;
use super::{Failure, by, in_file, load_graph, write_output};
use clap::Args;
use std::path::PathBuf;
use veneer::fit::{FitSettings, fit_graph, read_photo};
use veneer::fsutil::{Naming, OutputPlan};

#[derive(Args)]
pub struct FitArgs {
    /// The graph whose parameters are fitted.
    graph: PathBuf,
    /// The photo to look like (PNG, JPEG, OpenEXR or Radiance HDR); its middle square is
    /// compared with the graph's albedo over the preview square.
    photo: PathBuf,
    /// The parameters to fit, separated by commas [default: every float, vector and
    /// colour the graph exposes that reaches the albedo, toggles and choices searched].
    #[arg(long, value_delimiter = ',', value_name = "NAMES")]
    params: Option<Vec<String>>,
    /// Stop after this many seconds, keeping the best values found.
    #[arg(long, value_name = "SECONDS")]
    budget: Option<f64>,
    /// Adam steps per start at 64² (half as many refine the best at 128², a quarter at
    /// 256², … up to --size).
    #[arg(long, default_value_t = FitSettings::default().steps)]
    steps: usize,
    /// Starts: the graph's own values, then random draws within the ranges.
    #[arg(long, default_value_t = FitSettings::default().starts as u32, value_parser = clap::value_parser!(u32).range(1..))]
    starts: u32,
    /// The side in pixels of the images compared at the end, from 8 to 2048 (the fit
    /// starts at 64 and doubles up to it).
    #[arg(long, default_value_t = FitSettings::default().size)]
    size: u32,
    /// Draws the random starts and the loss's directions.
    #[arg(long, default_value_t = FitSettings::default().seed)]
    seed: u64,
    /// The photo is the graph's own flat render over its preview square (`veneer render
    /// --flat`): compare pixel by pixel too.
    #[arg(long)]
    aligned: bool,
    /// The starts after the first search globally before descending (an evolution
    /// strategy, sep-CMA-ES, for half --steps generations at 64²: the second from the
    /// graph's values, the others from random draws). Slower, and it finds lower losses
    /// where descent alone stops in a near local minimum.
    #[arg(long)]
    global: bool,
    /// Print a JSON summary on stdout.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    parameters: ParameterArgs,
    /// The fitted graph to write: the graph with the fitted values, also kept as its
    /// parameter preset `fit`.
    #[arg(short, long)]
    output: PathBuf,
}

impl FitArgs {
    /// Adds the graph and photo read and the graph written to `plan`.
    pub fn plan(&self, plan: &mut OutputPlan, job: Option<&str>) {
        let by = by(job, &self.graph);
        plan.reads(&self.graph, &by);
        plan.reads(&self.photo, &by);
        plan.writes(&self.output, Naming::Given, &by);
    }
}

/// The summary `--json` prints.
#[derive(serde::Serialize)]
struct Summary<'a> {
    initial: veneer::fit::loss::LossParts,
    initial_total: f64,
    fitted: veneer::fit::loss::LossParts,
    fitted_total: f64,
    parameters: std::collections::BTreeMap<&'a str, Vec<f64>>,
    starts: &'a [veneer::fit::StartResult],
    steps: usize,
    seconds: f64,
    cut_short: bool,
}

pub fn run(args: FitArgs) -> Result<(), Failure> {
    let mut graph = load_graph(&args.graph)?;
    args.parameters.apply(&mut graph, &args.graph)?;
    if !(8..=2048).contains(&args.size) {
        return Err(Failure::new(format!(
            "--size {}: give a side from 8 to 2048 pixels",
            args.size
        )));
    }
    let budget = match args.budget {
        Some(seconds) if !(seconds.is_finite() && seconds > 0.0) => {
            return Err(Failure::new(format!(
                "--budget {seconds}: give a positive number of seconds"
            )));
        }
        Some(seconds) => Some(
            std::time::Duration::try_from_secs_f64(seconds)
                .map_err(|_| Failure::new(format!("--budget {seconds}: too many seconds")))?,
        ),
        None => None,
    };
    // The output's place is checked before the work, not after it.
    if super::names_folder(&args.output) {
        return Err(Failure::new(format!(
            "{}: is a folder; give the output a file name",
            args.output.display()
        )));
    }
    let folder = args.output.parent().filter(|f| !f.as_os_str().is_empty());
    if let Some(folder) = folder.filter(|folder| !folder.is_dir()) {
        return Err(Failure::new(format!(
            "{}: the folder {} does not exist",
            args.output.display(),
            folder.display()
        )));
    }
    // Names as typed, spaces around them or a trailing comma forgiven.
    let params: Option<Vec<String>> = (args.params.as_ref()).map(|names| {
        (names.iter())
            .map(|name| name.trim().to_string())
            .filter(|name| !name.is_empty())
            .collect()
    });
    let photo = read_photo(&args.photo).map_err(|error| in_file(&args.photo, error))?;
    let settings = FitSettings {
        size: args.size,
        steps: args.steps,
        starts: args.starts as usize,
        budget,
        seed: args.seed,
        aligned: args.aligned,
        global: args.global,
    };
    let bar = indicatif::ProgressBar::new(0).with_style(
        indicatif::ProgressStyle::with_template(
            "{prefix:>8} [{bar:40}] {pos}/{len} steps {elapsed} {msg}",
        )
        .expect("valid template"),
    );
    bar.set_prefix("fit");
    let result = fit_graph(&graph, &photo, params.as_deref(), &settings, |progress| {
        bar.set_length(progress.total_steps as u64);
        bar.set_position(progress.step as u64);
        let start = match progress.start {
            Some(start) => format!("start {}", start + 1),
            None => "refining".to_string(),
        };
        bar.set_message(format!("{start}, loss {:.5}", progress.loss));
        true
    })
    .map_err(|error| in_file(&args.graph, error))?;
    bar.finish_and_clear();
    write_output(
        Some(&args.output),
        veneer::graph::to_ron(&result.graph).as_bytes(),
    )?;
    let fitted = &result.fitted;
    let (before, after) = (fitted.initial.total(), fitted.parts.total());
    super::output::note(format_args!(
        "loss {before:.6} → {after:.6} ({:+.1}%) in {} steps, {:.1} s{}; wrote {}",
        100.0 * (after - before) / before.max(f64::MIN_POSITIVE),
        fitted.steps,
        fitted.seconds,
        if fitted.cut_short {
            " (budget reached)"
        } else {
            ""
        },
        args.output.display()
    ))?;
    if args.json {
        let parameters = (result.space.fitted_values(&fitted.places).into_iter())
            .map(|(_, name, lanes)| (name, lanes))
            .collect();
        let summary = Summary {
            initial: fitted.initial,
            initial_total: before,
            fitted: fitted.parts,
            fitted_total: after,
            parameters,
            starts: &fitted.starts,
            steps: fitted.steps,
            seconds: fitted.seconds,
            cut_short: fitted.cut_short,
        };
        let text = serde_json::to_string_pretty(&summary).expect("serialisable");
        super::output::out_bytes(format!("{text}\n").as_bytes())?;
    }
    Ok(())
}
