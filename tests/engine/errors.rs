//! What bad input gets: a message naming the file (with line and column where the parser
//! has them) or the node (label and id) and what was expected, exit code 1, and no file
//! written or damaged. The messages are snapshotted in `tests/golden/errors.txt`
//! (`VENEER_UPDATE_GOLDEN=1` rewrites it).

use crate::support::{root, run_veneer, temp_dir, updating};
use std::path::Path;
use std::process::Output;

/// Bad inputs of every kind that fail before any GPU work, so that their messages are
/// the same on every machine.
const CASES: &[&[&str]] = &[
    &["check", "tests/bad/malformed.ron"],
    &["check", "tests/bad/unknown_node.ron"],
    &["check", "tests/bad/wrong_version.ron"],
    &["check", "tests/bad/cycle.ron"],
    &["check", "tests/bad/type_mismatch.ron"],
    &["check", "tests/bad/out_of_range.ron"],
    &["check", "tests/bad/unknown_pin.ron"],
    &["check", "tests/bad/duplicate_id.ron"],
    &["check", "tests/bad/bad_value_type.ron"],
    &["check", "tests/bad/missing.ron"],
    &["compile", "tests/bad/cycle.ron"],
    &["mesh", "tests/meshes/bad_index.obj"],
    &["mesh", "tests/meshes/truncated.stl"],
    &["mesh", "teapot"],
    &["mesh", "torus:0"],
    &["mesh", "genus2:5000"],
    &[
        "geodesic",
        "torus",
        "--sources",
        "99999",
        "-o",
        "target/never.csv",
    ],
    &["render", "tests/bad/cycle.ron", "-o", "target/never.png"],
    &[
        "compile",
        "graphs/wood.ron",
        "-o",
        "tests/no such folder/wood.wgsl",
    ],
];

#[test]
fn error_messages_match_their_snapshot() {
    let mut transcript = String::new();
    for args in CASES {
        let output = run_veneer(args);
        let message = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{args:?}: {message}");
        assert!(!message.contains("panicked"), "{args:?}: {message}");
        transcript += &format!("$ veneer {}\n{message}\n", args.join(" "));
    }
    assert!(!root("target/never.csv").exists() && !root("target/never.png").exists());
    let golden = root("tests/golden/errors.txt");
    if updating() {
        std::fs::write(&golden, &transcript).expect("golden written");
    }
    let expected = std::fs::read_to_string(&golden).unwrap_or_default();
    assert!(
        transcript == expected,
        "error messages changed (VENEER_UPDATE_GOLDEN=1 to accept):\n{transcript}"
    );
}

/// `veneer compile graphs/wood.ron -o target` run in `folder` by the binary `veneer`,
/// started by `program` with `args` in front (a shell that sets limits, or setpriv that
/// drops privileges).
fn compile_through(
    program: &str,
    args: &[&str],
    (veneer, folder): (&Path, &Path),
    target: &Path,
) -> Output {
    std::process::Command::new(program)
        .args(args)
        .arg(veneer)
        .args(["compile", "graphs/wood.ron", "-o"])
        .arg(target)
        .current_dir(folder)
        .output()
        .expect("the veneer binary runs")
}

/// The write failed with exit code 1 and a message giving `cause` and saying the old
/// file is unchanged; `dir` still holds `old.wgsl` as it was and nothing else (no
/// temporary file left behind). Removes `dir`.
fn refused_with_the_old_file_intact(output: &Output, cause: &str, dir: &Path) {
    let message = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{message}");
    for words in ["cannot write", cause, "the old file is unchanged"] {
        assert!(message.contains(words), "'{words}' not in: {message}");
    }
    let names: Vec<_> = std::fs::read_dir(dir)
        .expect("folder")
        .map(|entry| entry.expect("entry").file_name())
        .collect();
    assert_eq!(names, ["old.wgsl"], "a temporary file was left behind");
    assert_eq!(
        std::fs::read_to_string(dir.join("old.wgsl")).unwrap(),
        "old"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_full_disk_leaves_the_old_file_intact_and_says_so() {
    let dir = temp_dir("full-disk");
    let target = dir.join("old.wgsl");
    std::fs::write(&target, "old").unwrap();
    // A 2 KiB file-size limit (ignoring SIGXFSZ, as a full disk does not kill a process
    // either): the generated WGSL does not fit, so the write fails part way with EFBIG,
    // as it would with ENOSPC on a full disk.
    let limits = "trap '' XFSZ; ulimit -f 2; exec \"$@\"";
    let veneer = Path::new(env!("CARGO_BIN_EXE_veneer"));
    let output = compile_through("sh", &["-c", limits, "sh"], (veneer, &root("")), &target);
    refused_with_the_old_file_intact(&output, "File too large", &dir);
}

#[test]
fn a_permission_error_leaves_the_old_file_intact_and_says_so() {
    use std::os::unix::fs::PermissionsExt;
    let dir = temp_dir("read-only");
    let target = dir.join("old.wgsl");
    std::fs::write(&target, "old").unwrap();
    std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o555)).unwrap();
    // Root ignores permissions: drop to `nobody` where we are root, with the binary and
    // the graph copied where `nobody` may read them.
    let work = temp_dir("read-only-work");
    std::fs::create_dir_all(work.join("graphs")).unwrap();
    std::fs::copy(root("graphs/wood.ron"), work.join("graphs/wood.ron")).unwrap();
    let veneer = work.join("veneer");
    std::fs::copy(env!("CARGO_BIN_EXE_veneer"), &veneer).unwrap();
    let output = if real_uid() == 0 {
        let nobody = ["--reuid=65534", "--regid=65534", "--clear-groups"];
        compile_through("setpriv", &nobody, (&veneer, &work), &target)
    } else {
        compile_through("env", &[], (&veneer, &work), &target)
    };
    std::fs::remove_dir_all(&work).unwrap();
    std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o755)).unwrap();
    refused_with_the_old_file_intact(&output, "Permission denied", &dir);
}

/// The real user id of this process, read from `/proc`.
fn real_uid() -> u32 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|status| {
            let line = status.lines().find(|l| l.starts_with("Uid:"))?;
            line.split_whitespace().nth(1)?.parse().ok()
        })
        .unwrap_or(u32::MAX)
}
