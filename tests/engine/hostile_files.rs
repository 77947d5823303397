//! Hostile files: inputs that are devices, FIFOs or huge; glTF buffers that point outside
//! their folder; links planted where temporary files go; and files whose messages were
//! unhelpful. Each gets a message naming the file and exit code 1 (2 for `snapshot`'s bad
//! input) at once, and nothing is read or written where it should not be.

use crate::support::{root, temp_dir};
use std::os::unix::fs::{MetadataExt, PermissionsExt, symlink};
use std::path::Path;
use std::process::{Output, Stdio};
use std::time::{Duration, Instant};

/// Runs `veneer args` in `dir` with at most 4 GiB of address space, so that a read that
/// grows without end aborts instead of filling the machine's memory, and kills it after
/// 30 s, so that one that blocks fails the test instead of hanging it.
pub(crate) fn run_in(dir: &Path, args: &[&str]) -> Output {
    let mut child = std::process::Command::new("sh")
        .args(["-c", "ulimit -v 4194304; exec \"$@\"", "sh"])
        .arg(env!("CARGO_BIN_EXE_veneer"))
        .args(args)
        .current_dir(dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the veneer binary runs");
    let start = Instant::now();
    while child.try_wait().expect("wait").is_none() {
        if start.elapsed() > Duration::from_secs(30) {
            let _ = child.kill();
            let _ = child.wait();
            panic!("veneer {args:?} did not finish within 30 s");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().expect("output")
}

/// Asserts exit code `code` and a message holding every one of `words`, without a panic.
pub(crate) fn refused_with(output: &Output, code: i32, words: &[&str]) {
    let message = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(code), "{message}");
    assert!(!message.contains("panicked"), "{message}");
    for word in words {
        assert!(message.contains(word), "'{word}' not in: {message}");
    }
}

pub(crate) fn refused(output: &Output, words: &[&str]) {
    refused_with(output, 1, words);
}

pub(crate) fn succeeded(output: &Output) {
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{message}");
}

pub(crate) fn mkfifo(path: &Path) {
    let status = std::process::Command::new("mkfifo")
        .arg(path)
        .status()
        .expect("mkfifo runs");
    assert!(status.success());
}

#[test]
fn devices_and_fifos_are_refused_at_once() {
    let dir = temp_dir("special-inputs");
    symlink("/dev/zero", dir.join("zero.ron")).unwrap();
    symlink("/dev/zero", dir.join("zero.obj")).unwrap();
    mkfifo(&dir.join("fifo.ron"));
    mkfifo(&dir.join("fifo.stl"));
    refused(
        &run_in(&dir, &["check", "zero.ron"]),
        &["zero.ron: cannot read: it is a character device, not a regular file"],
    );
    refused(
        &run_in(&dir, &["check", "fifo.ron"]),
        &["fifo.ron: cannot read: it is a FIFO (named pipe), not a regular file"],
    );
    refused(
        &run_in(&dir, &["mesh", "zero.obj"]),
        &["zero.obj: it is a character device, not a regular file"],
    );
    refused(
        &run_in(&dir, &["mesh", "fifo.stl"]),
        &["fifo.stl: it is a FIFO"],
    );
    std::fs::create_dir(dir.join("model")).unwrap();
    mkfifo(&dir.join("model/pipe.bin"));
    std::fs::write(dir.join("model/pipe.gltf"), triangle_gltf("pipe.bin")).unwrap();
    refused(
        &run_in(&dir, &["mesh", "model/pipe.gltf"]),
        &["model/pipe.gltf: buffer 0: URI 'pipe.bin' cannot be read: it is a FIFO"],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_golden_image_that_is_a_device_is_refused_at_once() {
    let dir = temp_dir("special-golden");
    std::fs::create_dir(dir.join("golden")).unwrap();
    symlink("/dev/zero", dir.join("golden/wood.png")).unwrap();
    let graph = root("graphs/wood.ron");
    let output = run_in(
        &dir,
        &[
            "snapshot",
            graph.to_str().unwrap(),
            "--golden",
            "golden",
            "--size",
            "16",
        ],
    );
    refused_with(
        &output,
        2,
        &["golden/wood.png: cannot read: it is a character device"],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn files_over_the_size_limit_are_refused_before_they_are_read() {
    let dir = temp_dir("huge-inputs");
    // Sparse files: their size costs no disk.
    let sparse = |name: &str, bytes: u64| {
        std::fs::File::create(dir.join(name))
            .unwrap()
            .set_len(bytes)
            .unwrap();
    };
    sparse("huge.ron", (256 << 20) + 1);
    sparse("huge.stl", (2 << 30) + 1);
    refused(
        &run_in(&dir, &["check", "huge.ron"]),
        &["huge.ron: cannot read: the file is larger than 256 MiB, the limit for graph files"],
    );
    refused(
        &run_in(&dir, &["mesh", "huge.stl"]),
        &["huge.stl: the file is larger than 2 GiB, the limit for mesh files"],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Three vertices as little-endian f32, each coordinate `value` (`0` gives a
/// degenerate but loadable triangle).
fn triangle_bytes(values: [f32; 9]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// A glTF file whose one triangle's positions are the 36 bytes of the buffer at `uri`.
fn triangle_gltf(uri: &str) -> String {
    serde_json::json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "buffers": [{"uri": uri, "byteLength": 36}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [{
            "bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
            "min": [-1e9, -1e9, -1e9], "max": [1e9, 1e9, 1e9]
        }]
    })
    .to_string()
}

/// The coordinates of the triangle outside the glTF's folder: a value no file inside has.
const SECRET: [f32; 9] = [31337.0, 1.0, 2.0, 3.0, 31337.0, 4.0, 5.0, 6.0, 31337.0];
const INSIDE: [f32; 9] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];

#[test]
fn gltf_buffers_are_read_only_from_the_files_folder() {
    let dir = temp_dir("gltf-uris");
    let model = dir.join("model");
    std::fs::create_dir_all(model.join("sub")).unwrap();
    std::fs::write(dir.join("secret.bin"), triangle_bytes(SECRET)).unwrap();
    std::fs::write(model.join("inside.bin"), triangle_bytes(INSIDE)).unwrap();
    std::fs::write(model.join("sub/inside one.bin"), triangle_bytes(INSIDE)).unwrap();
    symlink("../secret.bin", model.join("escape.bin")).unwrap();
    symlink("..", model.join("up")).unwrap();
    let secret = dir.join("secret.bin").canonicalize().unwrap();
    let secret = secret.to_str().unwrap();
    let outside = [
        "../secret.bin".to_string(),
        "%2E%2E/secret.bin".into(),
        "sub/../../secret.bin".into(),
        "escape.bin".into(),
        "up/secret.bin".into(),
        secret.into(),
        format!("file://{secret}"),
        format!("file:{secret}"),
        "https://example.com/secret.bin".into(),
    ];
    let out = dir.join("out.obj");
    for uri in &outside {
        std::fs::write(model.join("evil.gltf"), triangle_gltf(uri)).unwrap();
        let output = run_in(
            &dir,
            &["mesh", "model/evil.gltf", "--write", out.to_str().unwrap()],
        );
        refused(
            &output,
            &[&format!("model/evil.gltf: buffer 0: URI '{uri}' refused: ")],
        );
        assert!(!out.exists(), "{uri}: the mesh was written");
    }
    let data = format!(
        "data:application/octet-stream;base64,{}",
        "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"
    );
    for uri in [
        "inside.bin",
        "sub/inside%20one.bin",
        "sub/../inside.bin",
        &data,
    ] {
        std::fs::write(model.join("good.gltf"), triangle_gltf(uri)).unwrap();
        let mesh = veneer::mesh::load(&model.join("good.gltf")).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(mesh.positions.concat(), INSIDE, "{uri}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_link_planted_where_the_temporary_file_would_go_is_left_alone() {
    let dir = temp_dir("planted-links");
    let victim = dir.join("victim.txt");
    std::fs::write(&victim, "precious").unwrap();
    // Veneer used to write `.o.wgsl.PID.tmp` without O_EXCL: links at the next few
    // thousand process ids catch the next veneer's.
    let next = std::process::Command::new("true").spawn().unwrap().id();
    for pid in next..next + 5000 {
        symlink(&victim, dir.join(format!(".o.wgsl.{pid}.tmp"))).unwrap();
    }
    let graph = root("graphs/wood.ron");
    succeeded(&run_in(
        &dir,
        &["compile", graph.to_str().unwrap(), "-o", "o.wgsl"],
    ));
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "precious");
    let written = std::fs::symlink_metadata(dir.join("o.wgsl")).unwrap();
    assert!(written.is_file(), "o.wgsl is a regular file, not a link");
    let names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| !name.starts_with(".o.wgsl."))
        .collect();
    assert_eq!(names.len(), 2, "no temporary file left: {names:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_rewritten_graph_keeps_its_mode_and_owner() {
    let dir = temp_dir("kept-mode");
    let path = dir.join("x.ron");
    std::fs::copy(root("graphs/wood.ron"), &path).unwrap();
    std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o600)).unwrap();
    let before = std::fs::metadata(&path).unwrap();
    // As root, give the file to `nobody`: rewriting it must not take it over.
    let owner = if before.uid() == 0 {
        std::os::unix::fs::chown(&path, Some(65534), Some(65534)).unwrap();
        (65534, 65534)
    } else {
        (before.uid(), before.gid())
    };
    succeeded(&run_in(&dir, &["fmt", "--arrange", "x.ron"]));
    let after = std::fs::metadata(&path).unwrap();
    assert_ne!(after.ino(), before.ino(), "replaced, not written in place");
    assert_eq!(after.mode() & 0o7777, 0o600);
    assert_eq!((after.uid(), after.gid()), owner);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn graph_files_get_messages_with_positions() {
    let dir = temp_dir("graph-messages");
    let wood = std::fs::read_to_string(root("graphs/wood.ron")).unwrap();
    // A byte-order mark, as some editors write, is skipped.
    std::fs::write(dir.join("bom.ron"), format!("\u{feff}{wood}")).unwrap();
    succeeded(&run_in(&dir, &["check", "bom.ron"]));
    // Not UTF-8: the position of the first bad byte.
    let mut latin1 = wood.clone().into_bytes();
    latin1.splice(13..13, [0xE9]); // after `    version` on line 2
    std::fs::write(dir.join("latin1.ron"), latin1).unwrap();
    refused(
        &run_in(&dir, &["check", "latin1.ron"]),
        &["latin1.ron:2:12: not UTF-8 text: byte 0xE9 is not a character"],
    );
    // Nesting past the parser's limit: a message for people, with the position.
    let deep = format!("(\n version: 1,\n extra: {}", "[".repeat(300));
    std::fs::write(dir.join("deep.ron"), deep).unwrap();
    let output = run_in(&dir, &["check", "deep.ron"]);
    refused(
        &output,
        &[
            "deep.ron:3:",
            "values are nested too deeply (more than 128 levels)",
        ],
    );
    assert!(!String::from_utf8_lossy(&output.stderr).contains("ron::Options"));
    // An input given twice.
    let twice = wood.replacen(
        "inputs: {\"scale\": Vec3(0.2, 0.2, 0.2)}",
        "inputs: {\"scale\": Vec3(0.2, 0.2, 0.2), \"scale\": Vec3(9.0, 9.0, 9.0)}",
        1,
    );
    assert_ne!(twice, wood);
    std::fs::write(dir.join("twice.ron"), twice).unwrap();
    refused(
        &run_in(&dir, &["check", "twice.ron"]),
        &[
            "twice.ron:40:",
            "node 'warp space' (#2): input 'scale' is given twice",
        ],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_negative_ply_index_is_shown_as_it_is() {
    let dir = temp_dir("ply-negative");
    let ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
               property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
               end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -2\n";
    std::fs::write(dir.join("negative.ply"), ply).unwrap();
    refused(
        &run_in(&dir, &["mesh", "negative.ply"]),
        &["negative.ply: face 0 refers to vertex -2, but there are only 3"],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
