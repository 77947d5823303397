//! `veneer batch`: a batch of every preset under two of its parameter presets, run as
//! four shards side by side (as a scheduler would), writes exactly the files of the
//! unsharded run.

use crate::support::{presets, stem, temp_dir, veneer};
use std::collections::BTreeMap;
use std::path::Path;

/// Every file under `dir` (relative path → bytes).
fn files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .expect("lists")
        .flatten()
        .map(|entry| {
            let name = entry.file_name().to_string_lossy().into_owned();
            (name, std::fs::read(entry.path()).expect("reads"))
        })
        .collect()
}

/// A batch file rendering every preset under its first two parameter presets into
/// `out/` (relative to the batch file).
fn batch_file() -> serde_json::Value {
    let mut jobs = Vec::new();
    for path in presets() {
        let graph = veneer::graph::load(&path).expect("preset loads");
        let names: Vec<&String> = graph.presets.keys().take(2).collect();
        assert_eq!(
            names.len(),
            2,
            "{} has two parameter presets",
            path.display()
        );
        for preset in names {
            jobs.push(serde_json::json!({
                "command": "render",
                "graph": path,
                "preset": preset,
                "output": format!("out/{}.{preset}.png", stem(&path)),
                "args": ["--size", "40"],
            }));
        }
    }
    serde_json::json!({ "jobs": jobs })
}

#[test]
fn four_shards_write_exactly_the_files_of_the_whole_batch() {
    let whole = temp_dir("batch-whole");
    let sharded = temp_dir("batch-sharded");
    for dir in [&whole, &sharded] {
        std::fs::create_dir_all(dir.join("out")).unwrap();
        std::fs::write(dir.join("batch.json"), batch_file().to_string()).unwrap();
    }
    let shards: Vec<_> = (1..=4)
        .map(|k| {
            veneer()
                .args(["batch", "batch.json", "--shard", &format!("{k}/4")])
                .current_dir(&sharded)
                .spawn()
                .expect("starts")
        })
        .collect();
    let run = veneer()
        .args(["batch", "batch.json"])
        .current_dir(&whole)
        .output()
        .expect("runs");
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    for shard in shards {
        let output = shard.wait_with_output().expect("finishes");
        assert!(output.status.success());
    }
    let expected = files(&whole.join("out"));
    assert_eq!(expected.len(), 2 * presets().len());
    assert!(expected.keys().any(|name| name == "wood.oak.png"));
    assert_eq!(files(&sharded.join("out")), expected);
    // Each shard runs a quarter: jobs K, K+4, …
    let listing = veneer()
        .args(["batch", "batch.json", "--shard", "2/4", "--dry-run"])
        .current_dir(&whole)
        .output()
        .expect("runs");
    let lines = String::from_utf8_lossy(&listing.stdout).lines().count();
    assert_eq!(lines, (2 * presets().len()).div_ceil(4));
}

#[test]
fn a_failing_job_is_reported_and_the_others_still_run() {
    let dir = temp_dir("batch-failing");
    let graph = crate::support::root("graphs/marble.ron");
    let batch = serde_json::json!({"jobs": [
        {"command": "render", "graph": graph, "preset": "no_such_preset", "output": "bad.png"},
        {"command": "render", "graph": graph, "output": "good.png", "args": ["--size", "16"]},
    ]});
    std::fs::write(dir.join("batch.json"), batch.to_string()).unwrap();
    let output = veneer()
        .args(["batch", "batch.json"])
        .current_dir(&dir)
        .output()
        .expect("runs");
    assert_eq!(output.status.code(), Some(1));
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(message.contains("job 1 (render"), "{message}");
    assert!(
        message.contains("no parameter preset named 'no_such_preset'"),
        "{message}"
    );
    assert!(dir.join("good.png").is_file());
    assert!(!dir.join("bad.png").exists());
    let bad_shard = veneer()
        .args(["batch", "batch.json", "--shard", "5/4"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(bad_shard.status.code(), Some(1));
}
