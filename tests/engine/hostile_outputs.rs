//! Hostile outputs (issue 32): where Veneer writes. Outputs are opened by what they are,
//! not by their path (a FIFO without a reader is refused at once, a regular file under
//! `/dev/shm` is replaced whole); an output that is one of the command's inputs, or that
//! two jobs or graphs would both write, is refused with both names before any work; the
//! files Veneer names itself are never written through links; and a multi-file export
//! that fails removes what it wrote.

use crate::hostile_files::{mkfifo, refused, refused_with, run_in, succeeded};
use crate::support::{root, temp_dir};
use std::os::unix::fs::symlink;
use std::path::Path;
use std::process::Output;

/// The path of a preset graph, as an argument.
fn preset(name: &str) -> String {
    root(&format!("graphs/{name}.ron"))
        .to_string_lossy()
        .into_owned()
}

/// A copy of preset `name` at `dir/file`.
fn copy_preset(name: &str, dir: &Path, file: &str) {
    std::fs::copy(preset(name), dir.join(file)).unwrap();
}

/// Asserts that `path` still holds `bytes`.
fn unchanged(path: &Path, bytes: &[u8]) {
    let now = std::fs::read(path).unwrap_or_default();
    assert!(now == bytes, "{} was changed", path.display());
}

/// The message of a command.
fn message(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

#[test]
fn a_fifo_output_without_a_reader_is_refused_at_once() {
    let dir = temp_dir("fifo-outputs");
    copy_preset("wood", &dir, "g.ron");
    for name in ["o.wgsl", "m.obj", "frames.csv", "job.wgsl"] {
        mkfifo(&dir.join(name));
    }
    let no_reader = "it is a FIFO (named pipe) with no reader";
    refused(
        &run_in(&dir, &["compile", "g.ron", "-o", "o.wgsl"]),
        &["o.wgsl: cannot write: ", no_reader],
    );
    refused(
        &run_in(&dir, &["mesh", "torus:8", "--write", "m.obj"]),
        &["m.obj: cannot write: ", no_reader],
    );
    // Refused before any window opens.
    refused(
        &run_in(&dir, &["edit", "g.ron", "--frame-log", "frames.csv"]),
        &["frames.csv: cannot write the frame log: ", no_reader],
    );
    // One job's FIFO fails that job; the batch goes on with the next.
    let batch = serde_json::json!({"jobs": [
        {"command": "compile", "graph": "g.ron", "output": "job.wgsl"},
        {"command": "compile", "graph": "g.ron", "output": "after.wgsl"},
    ]});
    std::fs::write(dir.join("batch.json"), batch.to_string()).unwrap();
    refused(
        &run_in(&dir, &["batch", "batch.json"]),
        &["job 1 (compile", no_reader, "1 failed"],
    );
    assert!(dir.join("after.wgsl").is_file());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_fifo_output_with_a_reader_gets_the_whole_output() {
    use std::io::Read;
    use std::os::unix::fs::OpenOptionsExt;
    let dir = temp_dir("fifo-reader");
    let fifo = dir.join("o.wgsl");
    mkfifo(&fifo);
    // A reader that is there before Veneer starts, without waiting for a writer.
    let mut reader = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(&fifo)
        .unwrap();
    let mut child = crate::support::veneer()
        .args(["compile", &preset("wood"), "-o"])
        .arg(&fifo)
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut received = Vec::new();
    let mut buffer = [0u8; 1 << 16];
    loop {
        match reader.read(&mut buffer) {
            Ok(0) if child.try_wait().unwrap().is_some() => break,
            Ok(n) if n > 0 => received.extend_from_slice(&buffer[..n]),
            Ok(_) => std::thread::sleep(std::time::Duration::from_millis(10)),
            Err(error) if error.kind() == std::io::ErrorKind::WouldBlock => {
                std::thread::sleep(std::time::Duration::from_millis(10))
            }
            Err(error) => panic!("{error}"),
        }
    }
    let output = child.wait_with_output().unwrap();
    succeeded(&output);
    let direct = crate::support::run_veneer(&["compile", "graphs/wood.ron"]);
    assert!(received == direct.stdout, "the FIFO got the whole shader");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn regular_files_under_dev_and_proc_are_replaced_whole() {
    let shm = Path::new("/dev/shm");
    assert!(shm.is_dir(), "this test needs /dev/shm");
    let dir = shm.join(format!("veneer-outputs-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let expected = crate::support::run_veneer(&["compile", "graphs/wood.ron"]).stdout;
    let stale = vec![b'#'; expected.len() * 2];
    let cwd = temp_dir("proc-outputs");
    let tmp_name = format!("veneer-outputs-{}.wgsl", std::process::id());
    let cases = [
        (dir.join("x.wgsl"), dir.join("x.wgsl")),
        (
            Path::new("/dev/../tmp").join(&tmp_name),
            Path::new("/tmp").join(&tmp_name),
        ),
        (
            Path::new("/proc/self/cwd/y.wgsl").to_path_buf(),
            cwd.join("y.wgsl"),
        ),
    ];
    for (given, real) in &cases {
        std::fs::write(real, &stale).unwrap();
        let output = run_in(
            &cwd,
            &["compile", &preset("wood"), "-o", given.to_str().unwrap()],
        );
        succeeded(&output);
        let written = std::fs::read(real).unwrap();
        assert!(
            written == expected,
            "{}: {} bytes, expected {} (an old tail left?)",
            given.display(),
            written.len(),
            expected.len()
        );
        std::fs::remove_file(real).unwrap();
    }
    // A character device is written in place.
    succeeded(&run_in(
        &cwd,
        &["compile", &preset("wood"), "-o", "/dev/null"],
    ));
    std::fs::remove_dir_all(&dir).unwrap();
    std::fs::remove_dir_all(&cwd).unwrap();
}

#[test]
fn nothing_is_written_beside_a_device() {
    let dir = temp_dir("beside-device");
    let beside = Path::new("/dev/null.parameters.json");
    let _ = std::fs::remove_file(beside);
    succeeded(&run_in(
        &dir,
        &[
            "compile",
            &preset("wood"),
            "--params",
            "uniform",
            "-o",
            "/dev/null",
        ],
    ));
    assert!(!beside.exists(), "a description was written into /dev");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_output_that_is_an_input_is_refused_and_the_input_kept() {
    let dir = temp_dir("output-is-input");
    copy_preset("wood", &dir, "g.ron");
    let graph = std::fs::read(dir.join("g.ron")).unwrap();
    let same = "this output would replace the input";
    for output in ["g.ron", "./g.ron", "sub/../g.ron"] {
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        refused(
            &run_in(&dir, &["compile", "g.ron", "-o", output]),
            &[output, same],
        );
        unchanged(&dir.join("g.ron"), &graph);
    }
    refused(
        &run_in(&dir, &["render", "g.ron", "--size", "8", "-o", "g.ron"]),
        &["g.ron: ", same],
    );
    unchanged(&dir.join("g.ron"), &graph);
    refused(
        &run_in(&dir, &["edit", "g.ron", "--frame-log", "g.ron"]),
        &["g.ron: ", same],
    );
    unchanged(&dir.join("g.ron"), &graph);
    // The mesh a glTF export reads.
    succeeded(&run_in(
        &dir,
        &[
            "bake", "g.ron", "--size", "8", "--mesh", "torus:6", "--gltf", "m.glb",
        ],
    ));
    let mesh = std::fs::read(dir.join("m.glb")).unwrap();
    refused(
        &run_in(
            &dir,
            &[
                "bake", "g.ron", "--size", "8", "--mesh", "m.glb", "--gltf", "m.glb",
            ],
        ),
        &["m.glb: ", same],
    );
    unchanged(&dir.join("m.glb"), &mesh);
    // The parameter file, as the description `--params uniform` writes beside -o.
    std::fs::write(dir.join("x.parameters.json"), "{}").unwrap();
    refused(
        &run_in(
            &dir,
            &[
                "compile",
                "g.ron",
                "--params",
                "uniform",
                "-o",
                "x.wgsl",
                "--params-file",
                "x.parameters.json",
            ],
        ),
        &["x.parameters.json: ", same],
    );
    unchanged(&dir.join("x.parameters.json"), b"{}");
    assert!(!dir.join("x.wgsl").exists());
    // The batch file itself.
    let batch = serde_json::json!({"jobs": [
        {"command": "compile", "graph": "g.ron", "output": "batch.json"},
    ]})
    .to_string();
    std::fs::write(dir.join("batch.json"), &batch).unwrap();
    refused(
        &run_in(&dir, &["batch", "batch.json"]),
        &[
            "batch.json: ",
            "job 1 (compile",
            "would replace the input of the batch",
        ],
    );
    unchanged(&dir.join("batch.json"), batch.as_bytes());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn outputs_that_collide_are_refused_with_both_names() {
    let dir = temp_dir("colliding-outputs");
    copy_preset("wood", &dir, "a.ron");
    copy_preset("marble", &dir, "b.ron");
    let batch = serde_json::json!({"jobs": [
        {"command": "compile", "graph": "a.ron", "output": "out.wgsl"},
        {"command": "compile", "graph": "b.ron", "output": "./out.wgsl"},
    ]});
    std::fs::write(dir.join("batch.json"), batch.to_string()).unwrap();
    refused(
        &run_in(&dir, &["batch", "batch.json"]),
        &[
            "out.wgsl: ",
            "job 1 (compile",
            "job 2 (compile",
            "would write this file",
        ],
    );
    assert!(!dir.join("out.wgsl").exists(), "no job ran");
    // Two snapshot graphs with one stem share a golden, updated or compared.
    for sub in ["one", "two"] {
        std::fs::create_dir_all(dir.join(sub)).unwrap();
        copy_preset("wood", &dir.join(sub), "x.ron");
    }
    std::fs::create_dir_all(dir.join("gold")).unwrap();
    for update in [true, false] {
        let mut args = vec!["snapshot", "one/x.ron", "two/x.ron", "--golden", "gold"];
        args.extend(["--size", "16"]);
        if update {
            args.push("--update");
        }
        refused_with(
            &run_in(&dir, &args),
            2,
            &["gold/x.", "one/x.ron", "two/x.ron", "would write this file"],
        );
        assert_eq!(std::fs::read_dir(dir.join("gold")).unwrap().count(), 0);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_failed_gltf_export_removes_what_it_wrote() {
    let dir = temp_dir("failed-gltf");
    copy_preset("wood", &dir, "g.ron");
    std::fs::create_dir(dir.join("out_orm.png")).unwrap();
    let output = run_in(
        &dir,
        &[
            "bake", "g.ron", "--size", "8", "--mesh", "torus:6", "--gltf", "out.gltf",
        ],
    );
    refused(&output, &["out_orm.png: ", "it is a folder"]);
    assert!(!message(&output).contains("the old file is unchanged"));
    for name in ["out.gltf", "out.bin", "out_basecolor.png"] {
        assert!(!dir.join(name).exists(), "{name} was left behind");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_report_that_cannot_be_written_writes_nothing() {
    let dir = temp_dir("failed-report");
    std::fs::create_dir_all(dir.join("report/precision.png")).unwrap();
    let output = run_in(
        &dir,
        &["report", "--quick", "--repetitions", "1", "-o", "report"],
    );
    refused(&output, &["report/precision.png: ", "it is a folder"]);
    let left: Vec<_> = std::fs::read_dir(dir.join("report"))
        .unwrap()
        .map(|entry| entry.unwrap().file_name())
        .collect();
    assert_eq!(left, ["precision.png"], "nothing else was written");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn files_veneer_names_itself_are_never_written_through_links() {
    let dir = temp_dir("implied-links");
    copy_preset("wood", &dir, "base.ron");
    let victim = dir.join("victim.txt");
    std::fs::write(&victim, "precious").unwrap();
    let plant = |link: &str| symlink(&victim, dir.join(link)).unwrap();
    let link_refused = "it is a symbolic link";
    // The render a mismatched snapshot leaves beside its golden.
    std::fs::create_dir(dir.join("gold")).unwrap();
    plant("gold/base.actual.png");
    refused_with(
        &run_in(
            &dir,
            &["snapshot", "base.ron", "--golden", "gold", "--size", "16"],
        ),
        2,
        &["gold/base.actual.png: ", link_refused],
    );
    // A golden under --update.
    plant("gold/base.png");
    refused_with(
        &run_in(
            &dir,
            &[
                "snapshot", "base.ron", "--golden", "gold", "--size", "16", "--update",
            ],
        ),
        2,
        &["gold/base.png: ", link_refused],
    );
    // A texture beside a .gltf.
    plant("out_basecolor.png");
    refused(
        &run_in(
            &dir,
            &[
                "bake", "base.ron", "--size", "8", "--mesh", "torus:6", "--gltf", "out.gltf",
            ],
        ),
        &["out_basecolor.png: ", link_refused],
    );
    assert!(!dir.join("out.gltf").exists());
    // The parameter description beside a shader.
    plant("x.parameters.json");
    refused(
        &run_in(
            &dir,
            &["compile", "base.ron", "--params", "uniform", "-o", "x.wgsl"],
        ),
        &["x.parameters.json: ", link_refused],
    );
    assert!(!dir.join("x.wgsl").exists());
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "precious");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_gltf_export_to_a_full_device_names_the_device_and_the_cause() {
    let dir = temp_dir("gltf-full");
    let output = run_in(
        &dir,
        &[
            "bake",
            &preset("wood"),
            "--size",
            "8",
            "--mesh",
            "torus:6",
            "--gltf",
            "/dev/full",
        ],
    );
    refused(&output, &["/dev/full: ", "No space left on device"]);
    assert!(!message(&output).contains("/dev/full.glb"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_batch_makes_the_folders_of_its_outputs() {
    let dir = temp_dir("batch-folders");
    copy_preset("marble", &dir, "m.ron");
    let batch = serde_json::json!({"jobs": [
        {"command": "render", "graph": "m.ron", "output": "out/m.png", "args": ["--size", "8"]},
        {"command": "bake", "graph": "m.ron", "output": "out/marble/",
         "args": ["--maps", "albedo", "--size", "8"]},
        {"command": "compile", "graph": "m.ron", "output": "out/shaders/m.wgsl"},
    ]});
    std::fs::write(dir.join("batch.json"), batch.to_string()).unwrap();
    succeeded(&run_in(&dir, &["batch", "batch.json"]));
    for file in ["out/m.png", "out/marble/m_albedo.png", "out/shaders/m.wgsl"] {
        assert!(dir.join(file).is_file(), "{file}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
