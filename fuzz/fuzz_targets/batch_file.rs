//! `veneer batch --dry-run` on arbitrary batch files: either any text (as RON or JSON),
//! or a list of jobs built from paths that name one file in several ways (`out.png`,
//! `./out.png`, `sub/../out.png`, the batch file itself, a graph). The batch is parsed
//! and its output plan checked, never a panic; and when the plan accepts a batch, no
//! two of its jobs that write one file (render, compile, bake to a model) write the same
//! file, and none writes the batch file or a graph a job reads (compared here by lexical
//! normalisation, independently of the plan).

#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use std::ffi::OsString;
use std::path::{Component, Path, PathBuf};

// The binary's own command line: the CLI lives in the binary crate, not in the library.
#[allow(dead_code, unexpected_cfgs)]
#[path = "../../src/cli/mod.rs"]
mod cli;

/// Graph paths a job may name, relative to the batch file's folder.
const GRAPHS: [&str; 5] = ["a.ron", "./a.ron", "sub/../a.ron", "b.ron", "jobs.ron"];
/// Outputs a job may name: one file spelt several ways, folders, streams, inputs.
const OUTPUTS: [&str; 10] = [
    "out.png",
    "./out.png",
    "sub/../out.png",
    "sub/out.png",
    "out",
    "x.wgsl",
    "m.glb",
    "jobs.ron",
    "a.ron",
    "/dev/null",
];
const COMMANDS: [&str; 4] = ["render", "bake", "snapshot", "compile"];

#[derive(Arbitrary, Debug)]
struct JobSpec {
    command: u8,
    graph: u8,
    output: u8,
}

#[derive(Arbitrary, Debug)]
enum Input {
    /// Any text as the batch file, read as JSON when `json`.
    Text { json: bool, text: String },
    /// Well-formed jobs over paths that alias one another.
    Jobs(Vec<JobSpec>),
}

/// A folder of our own with the graphs the jobs name.
fn folder() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("veneer-fuzz-batch-{}", std::process::id()));
    if !dir.join("sub").is_dir() {
        std::fs::create_dir_all(dir.join("sub")).expect("scratch folder");
        for graph in ["a.ron", "b.ron"] {
            std::fs::write(dir.join(graph), "()").expect("graph");
        }
    }
    dir
}

/// `path` under `base` with `.` and `..` resolved lexically (no links in our folder).
fn normalised(base: &Path, path: &str) -> PathBuf {
    let mut resolved = PathBuf::new();
    for component in base.join(path).components() {
        match component {
            Component::CurDir => {}
            Component::ParentDir => {
                resolved.pop();
            }
            other => resolved.push(other),
        }
    }
    resolved
}

/// Whether `veneer batch FILE --dry-run` accepts the batch.
fn accepted(file: &Path) -> bool {
    let args: Vec<OsString> = ["veneer", "batch", "--dry-run"]
        .iter()
        .map(OsString::from)
        .chain([file.as_os_str().to_owned()])
        .collect();
    let cli = cli::parse_from(&args).expect("a batch command line parses");
    cli::execute(cli).is_ok()
}

fuzz_target!(|input: Input| {
    let dir = folder();
    match input {
        Input::Text { json, text } => {
            let file = dir.join(if json { "jobs.json" } else { "jobs.ron" });
            std::fs::write(&file, text).expect("batch file");
            accepted(&file);
        }
        Input::Jobs(specs) => {
            let file = dir.join("jobs.ron");
            let pick = |list: &[&'static str], k: u8| list[k as usize % list.len()];
            let jobs: Vec<(&str, &str, &str)> = specs
                .iter()
                .take(16)
                .map(|s| {
                    (
                        pick(&COMMANDS, s.command),
                        pick(&GRAPHS, s.graph),
                        pick(&OUTPUTS, s.output),
                    )
                })
                .collect();
            let text = jobs
                .iter()
                .map(|(command, graph, output)| {
                    format!("(command: {command}, graph: {graph:?}, output: {output:?})")
                })
                .collect::<Vec<_>>()
                .join(", ");
            std::fs::write(&file, format!("(jobs: [{text}])")).expect("batch file");
            if !accepted(&file) {
                return;
            }
            let inputs: Vec<PathBuf> = (jobs.iter().map(|(_, graph, _)| normalised(&dir, graph)))
                .chain([file.clone()])
                .collect();
            // Jobs whose output is one file (the others write into a folder).
            let mut single_files: Vec<PathBuf> = Vec::new();
            for (command, _, output) in &jobs {
                let written = normalised(&dir, output);
                let model = output.ends_with(".glb");
                if written.starts_with("/dev")
                    || !(matches!(*command, "render" | "compile") || model && *command == "bake")
                {
                    continue;
                }
                assert!(
                    !inputs.contains(&written),
                    "accepted a job writing an input: {jobs:?}"
                );
                assert!(
                    !single_files.contains(&written),
                    "accepted two jobs writing {}: {jobs:?}",
                    written.display()
                );
                single_files.push(written);
            }
        }
    }
});
