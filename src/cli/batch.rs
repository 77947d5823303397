//! `veneer batch`: runs the render, bake, snapshot and compile jobs a batch file lists,
//! or one deterministic shard of them (`--shard K/N`), so that any scheduler (Slurm job
//! arrays, Kubernetes Indexed Jobs, a CI matrix) can spread a batch over machines with
//! no coordinator: shard K runs jobs K, K+N, K+2N, … in file order.
//!
//! Each job runs as the command line it stands for (`veneer batch --dry-run` prints
//! them), in this process; every job runs even when one fails, and the batch exits
//! with the highest exit code of its jobs. Before any job runs, the outputs of all the
//! file's jobs (every shard's) are planned together: a batch whose jobs would write one
//! file, or one job's output another's (or the batch file itself), is refused. The
//! folder each job writes into is made when missing.

use super::output::{note, out};
use super::{Cli, Failure};
use clap::{Args, Parser};
use indicatif::{ProgressBar, ProgressStyle};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use veneer::fsutil::OutputPlan;
use veneer::graph::parameters::Given;

#[derive(Args)]
pub struct BatchArgs {
    /// The batch file (RON, or JSON when it ends in `.json`). Paths in it are relative
    /// to its folder.
    file: PathBuf,
    /// Run only shard K of N (1 ≤ K ≤ N): jobs K, K+N, K+2N, … in file order.
    #[arg(long, value_name = "K/N", value_parser = parse_shard)]
    shard: Option<Shard>,
    /// Print the command line of each job of the shard and run nothing.
    #[arg(long)]
    dry_run: bool,
}

/// One shard of a batch: the `index`-th (1-based) of `count`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

impl Shard {
    /// Whether job `job` (0-based, in file order) belongs to this shard.
    pub fn has(&self, job: usize) -> bool {
        job % self.count == self.index - 1
    }
}

/// Reads `K/N`.
fn parse_shard(text: &str) -> Result<Shard, String> {
    let (index, count) = text
        .split_once('/')
        .ok_or_else(|| format!("'{text}' is not K/N (such as 2/4)"))?;
    let number = |part: &str| {
        part.trim()
            .parse::<usize>()
            .map_err(|_| format!("'{part}' is not a whole number"))
    };
    let (index, count) = (number(index)?, number(count)?);
    if count == 0 || index == 0 || index > count {
        return Err(format!(
            "shard {index}/{count}: K must be from 1 to N, and N at least 1"
        ));
    }
    Ok(Shard { index, count })
}

/// A batch file: its jobs, in order.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct BatchFile {
    jobs: Vec<Job>,
}

/// What a job runs.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq)]
#[serde(rename_all = "lowercase")]
enum Command {
    Render,
    Bake,
    Snapshot,
    Compile,
}

/// One job: a command on a graph, with parameter values and an output.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Job {
    command: Command,
    graph: PathBuf,
    /// The graph's parameter preset to start from.
    #[serde(default)]
    preset: Option<String>,
    /// Exposed parameter values, applied after the preset (each named once).
    #[serde(default, deserialize_with = "veneer::graph::keys::unique")]
    set: BTreeMap<String, Given>,
    /// The output: the PNG of `render`, the folder (or `.glb`/`.gltf` file) of `bake`,
    /// the golden folder of `snapshot`, the shader file of `compile`.
    output: PathBuf,
    /// More options of the command, as on its command line.
    #[serde(default)]
    args: Vec<String>,
}

impl Job {
    /// Whether a bake job writes a glTF model (its output ends in `.glb` or `.gltf`)
    /// rather than maps into a folder.
    fn writes_model(&self) -> bool {
        (self.output.extension()).is_some_and(|e| e == "glb" || e == "gltf")
    }

    /// The folder the job writes into, made before it runs when missing; none for a
    /// snapshot, whose golden folder must exist unless `--update` makes it.
    fn output_folder(&self, base: &Path) -> Option<PathBuf> {
        let output = base.join(&self.output);
        match self.command {
            Command::Snapshot => None,
            Command::Bake if !self.writes_model() => Some(output),
            _ => output.parent().map(Path::to_path_buf),
        }
    }

    /// The command line the job stands for, paths resolved against `base`.
    fn command_line(&self, base: &Path) -> Vec<String> {
        let path = |p: &Path| base.join(p).to_string_lossy().into_owned();
        let (graph, output) = (path(&self.graph), path(&self.output));
        let mut line: Vec<String> = vec!["veneer".into()];
        match self.command {
            Command::Render => line.extend(["render".into(), graph, "-o".into(), output]),
            Command::Compile => line.extend(["compile".into(), graph, "-o".into(), output]),
            Command::Snapshot => line.extend(["snapshot".into(), graph, "--golden".into(), output]),
            Command::Bake => {
                let flag = if self.writes_model() {
                    "--gltf"
                } else {
                    "--out-dir"
                };
                line.extend(["bake".into(), graph, flag.into(), output]);
            }
        }
        if let Some(preset) = &self.preset {
            line.extend(["--preset".into(), preset.clone()]);
        }
        for (name, value) in &self.set {
            let text = match value {
                Given::Number(x) => x.to_string(),
                Given::List(list) => list
                    .iter()
                    .map(f64::to_string)
                    .collect::<Vec<_>>()
                    .join(","),
                Given::Word(word) => word.clone(),
            };
            line.push(format!("--set={name}={text}"));
        }
        line.extend(self.args.iter().cloned());
        line
    }
}

/// How messages and the output plan name job `number` (1-based) of command line `line`.
fn job_label(number: usize, line: &[String]) -> String {
    format!("job {number} ({})", line[1..3].join(" "))
}

/// Refuses the batch when the outputs of its jobs (all of them, whichever shard runs)
/// collide with each other, with an input of another job, or with the batch file.
fn check_plan(file: &Path, lines: &[Vec<String>]) -> Result<(), Failure> {
    let mut plan = OutputPlan::new();
    plan.reads(file, "the batch");
    for (index, line) in lines.iter().enumerate() {
        // A job that does not parse fails on its own when it runs.
        if let Ok(Cli {
            command: Some(command),
        }) = Cli::try_parse_from(line)
        {
            command.plan(&mut plan, Some(&job_label(index + 1, line)));
        }
    }
    plan.check().map_err(Failure::new)
}

pub fn run(args: BatchArgs) -> Result<(), Failure> {
    let batch: BatchFile = super::read_ron_or_json(&args.file)?;
    let base = args.file.parent().unwrap_or(Path::new(""));
    let shard = args.shard.unwrap_or(Shard { index: 1, count: 1 });
    let lines: Vec<Vec<String>> = (batch.jobs.iter())
        .map(|job| job.command_line(base))
        .collect();
    check_plan(&args.file, &lines)?;
    let jobs: Vec<(usize, &Job, &Vec<String>)> = (batch.jobs.iter().zip(&lines))
        .enumerate()
        .filter(|(k, _)| shard.has(*k))
        .map(|(k, (job, line))| (k + 1, job, line))
        .collect();
    if args.dry_run {
        for (_, _, line) in &jobs {
            out(line.join(" "))?;
        }
        return Ok(());
    }
    let bar = ProgressBar::new(jobs.len() as u64).with_style(
        ProgressStyle::with_template("shard {prefix} [{bar:40}] {pos}/{len} jobs {elapsed} {msg}")
            .expect("valid template"),
    );
    bar.set_prefix(format!("{}/{}", shard.index, shard.count));
    let mut worst = 0u8;
    let mut failed = 0;
    for (number, job, line) in &jobs {
        bar.set_message(veneer::messages::printable(&line[1..3].join(" ")).into_owned());
        let outcome = Cli::try_parse_from(*line)
            .map_err(|error| Failure::new(error.to_string().trim_end().to_string()))
            .and_then(|cli| {
                if let Some(folder) = job.output_folder(base) {
                    std::fs::create_dir_all(&folder).map_err(|error| {
                        Failure::new(format!(
                            "{}: cannot make the folder: {error}",
                            folder.display()
                        ))
                    })?;
                }
                super::execute(cli)
            });
        if let Err(Failure(message, code)) = outcome
            && code > 0
        {
            failed += 1;
            worst = worst.max(code);
            bar.suspend(|| note(format!("{}: {message}", job_label(*number, line))))?;
        }
        bar.inc(1);
    }
    bar.finish_and_clear();
    let summary = format!(
        "shard {}/{}: {} run, {failed} failed",
        shard.index,
        shard.count,
        veneer::messages::counted(jobs.len(), "job")
    );
    if failed == 0 {
        note(summary)
    } else {
        Err(Failure(summary, worst))
    }
}
