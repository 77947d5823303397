//! The command-line contract under generated hostile input. Argument vectors are built
//! from every subcommand and from hostile values — sizes and counts from 0 to past
//! memory, non-numbers, special files (`/dev/zero`, a FIFO, a folder, a link to
//! `/dev/zero`), missing and full outputs, outputs that are FIFOs without a reader,
//! regular files under `/dev/shm` longer than what replaces them, outputs that are the
//! command's own inputs, batches whose jobs collide or write their own batch file, preset
//! and group names shaped as paths out of their folders, and graphs whose node settings
//! and constants sit at the ends of the f32 range — and the real binary must, for each:
//! exit 0, 1 or 2 with a message when not 0, never panic nor die by a signal, finish
//! within a time limit under a 6 GiB address-space limit, touch no file but its outputs,
//! never change one of its inputs, leave no output that ends in the old file's tail, and
//! write only finite samples into EXR maps. The generator is seeded, so a failure names a
//! case that replays.

use crate::support::root;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant, SystemTime};

/// Cases per run: each starts the binary once (a GPU context for most).
const CASES: u32 = 96;
/// Longer than any refused or small command takes; a hang passes it.
const TIME_LIMIT: Duration = Duration::from_secs(30);
/// The address space a command may take: far above what these inputs need, far below
/// what reading `/dev/zero` or an unbounded allocation reaches.
const ADDRESS_SPACE: u64 = 6 << 30;

/// Inputs every case's folder holds; the hostile ones are made by [`fixture`].
const GRAPHS: &[&str] = &["wood.ron", "fields.ron"];
const HOSTILE_GRAPHS: &[&str] = &[
    "escaping-group.ron",
    "zero.ron",
    "fifo.ron",
    "folder.ron",
    "empty.ron",
    "missing.ron",
    "mesh.obj",
];
const MESHES: &[&str] = &["sphere", "plane:3", "mesh.obj", "torus:8"];
const HOSTILE_MESHES: &[&str] = &[
    "torus:0",
    "torus:99999",
    "zero.obj",
    "fifo.obj",
    "folder.obj",
    "missing.obj",
    "empty.stl",
    "wood.ron",
];
/// Preset names that would name files out of a golden folder, or no file at all.
const HOSTILE_PRESETS: &[&str] = &[
    "x/../../escape",
    "../escape",
    "/tmp/escape",
    "",
    ".",
    "nope",
];
const SIZES: &[&str] = &["1", "7", "32"];
const HOSTILE_SIZES: &[&str] = &["0", "200000", "4294967296", "-3", "abc", "NaN"];
const HOSTILE_NUMBERS: &[&str] = &["0", "-1", "1e30", "-1e-30", "NaN", "inf", "x"];
const OUTPUTS: &[&str] = &["out/a.png", "out/a b.png"];
/// `{shm}` stands for a folder of the case's own under `/dev/shm`.
const HOSTILE_OUTPUTS: &[&str] = &[
    "out",
    "out/",
    "missing/a.png",
    "full",
    "-",
    "wood.ron",
    "mesh.obj",
    "pipe.out",
    "out/stale.out",
    "{shm}/stale.out",
];
/// What the outputs the fixture makes beforehand hold: far longer than anything a command
/// writes over them, so that a write in place without truncating leaves its tail.
const STALE: &[u8] = b"STALE OLD CONTENT ";
const STALE_REPEATS: usize = 1 << 16;
/// The outputs the fixture fills with [`STALE`] content.
const STALE_OUTPUTS: &[&str] = &["out/stale.out", "{shm}/stale.out"];
/// Batch files in every case's folder: (name, content, what the batch may write).
const BATCHES: &[(&str, &str, &[&str])] = &[
    (
        "ok.json",
        r#"{"jobs": [{"command": "compile", "graph": "wood.ron", "output": "made/a.wgsl"},
                     {"command": "compile", "graph": "fields.ron", "output": "out/b.wgsl"}]}"#,
        &["made", "made/a.wgsl", "out/b.wgsl"],
    ),
    (
        "collide.json",
        r#"{"jobs": [{"command": "compile", "graph": "wood.ron", "output": "out/same.wgsl"},
                     {"command": "compile", "graph": "fields.ron", "output": "./out/same.wgsl"}]}"#,
        &[],
    ),
    (
        "self.json",
        r#"{"jobs": [{"command": "compile", "graph": "wood.ron", "output": "self.json"}]}"#,
        &[],
    ),
    (
        "fifo.json",
        r#"{"jobs": [{"command": "compile", "graph": "wood.ron", "output": "pipe.out"},
                     {"command": "compile", "graph": "fields.ron", "output": "out/c.wgsl"}]}"#,
        &["out/c.wgsl"],
    ),
];
/// Flags that take no value (every other option takes one).
const FLAGS: &[&str] = &[
    "--arrange",
    "--robust",
    "--normalize",
    "--update",
    "--json",
    "--dry-run",
];
/// Options whose value is a file the command reads.
const INPUT_OPTIONS: &[&str] = &["--mesh", "--params-file", "--environment"];

/// A folder with every input the generator names: real graphs and a mesh, and hostile
/// stand-ins (links to `/dev/zero` and `/dev/full`, FIFOs, folders, empty files), old
/// outputs here and in `shm`, and the batch files.
fn fixture(dir: &Path, shm: &Path) {
    std::fs::create_dir_all(dir.join("out")).expect("folder");
    std::fs::copy(root("graphs/wood.ron"), dir.join("wood.ron")).expect("copied");
    std::fs::copy(root("graphs/isolines.ron"), dir.join("fields.ron")).expect("copied");
    // The wood preset with its linked group named as a path out of the library.
    let wood = std::fs::read_to_string(root("graphs/wood.ron")).expect("the wood preset");
    std::fs::write(
        dir.join("escaping-group.ron"),
        wood.replace("\"ring_wood\"", "\"../../escape/ring_wood\""),
    )
    .expect("written");
    std::fs::copy(root("tests/meshes/tetrahedron.obj"), dir.join("mesh.obj")).expect("copied");
    for name in ["zero.ron", "zero.obj"] {
        std::os::unix::fs::symlink("/dev/zero", dir.join(name)).expect("link");
    }
    std::os::unix::fs::symlink("/dev/full", dir.join("full")).expect("link");
    for name in ["fifo.ron", "fifo.obj", "pipe.out"] {
        let status = Command::new("mkfifo")
            .arg(dir.join(name))
            .status()
            .expect("mkfifo");
        assert!(status.success());
    }
    for name in ["folder.ron", "folder.obj"] {
        std::fs::create_dir_all(dir.join(name)).expect("folder");
    }
    for name in ["empty.ron", "empty.stl"] {
        std::fs::write(dir.join(name), b"").expect("written");
    }
    std::fs::create_dir_all(shm).expect("a folder under /dev/shm");
    for output in STALE_OUTPUTS {
        std::fs::write(in_case(dir, shm, output), STALE.repeat(STALE_REPEATS)).expect("written");
    }
    for (name, content, _) in BATCHES {
        std::fs::write(dir.join(name), content).expect("written");
    }
    for (name, graph) in extreme_graphs() {
        veneer::graph::save(&graph, &dir.join(name)).expect("written");
    }
}

/// Where `name` (an argument, `{shm}` standing for the case's folder under `/dev/shm`)
/// is, for a command run in `dir`.
fn in_case(dir: &Path, shm: &Path, name: &str) -> PathBuf {
    match name.strip_prefix("{shm}") {
        Some(rest) => PathBuf::from(format!("{}{rest}", shm.display())),
        None => dir.join(name),
    }
}

/// Graphs whose node settings and constants sit at the ends of the f32 range, by file
/// name: the extreme-settings test's named cases, which must give finite outputs, and
/// a colour ramp with a stop past f32, which `check` refuses.
fn extreme_graphs() -> Vec<(String, veneer::graph::Graph)> {
    crate::extreme_cases::named_graphs()
        .into_iter()
        .map(|(name, graph)| (format!("extreme-{name}.ron"), graph))
        .chain([(
            "extreme-ramp-stop.ron".to_string(),
            crate::extreme_settings::ramp_graph(1.0e308),
        )])
        .collect()
}

/// One of `values`.
fn pick(values: &'static [&'static str]) -> impl Strategy<Value = String> {
    proptest::sample::select(values).prop_map(str::to_string)
}

/// An option and its value, or nothing.
fn option(
    name: &'static str,
    values: impl Strategy<Value = String> + 'static,
) -> BoxedStrategy<Vec<String>> {
    prop_oneof![
        Just(Vec::new()),
        values.prop_map(move |value| vec![name.to_string(), value]),
    ]
    .boxed()
}

/// A flag, or nothing.
fn flag(name: &'static str) -> BoxedStrategy<Vec<String>> {
    prop_oneof![Just(Vec::new()), Just(vec![name.to_string()])].boxed()
}

/// Options in any order, each present or not.
fn options(choices: Vec<BoxedStrategy<Vec<String>>>) -> impl Strategy<Value = Vec<String>> {
    choices.prop_shuffle().prop_map(|parts| parts.concat())
}

/// Mostly a usual value, sometimes a hostile one: commands must get past parsing to
/// meet the hostile values deeper in.
fn usual_or(
    usual: &'static [&'static str],
    hostile: &'static [&'static str],
) -> BoxedStrategy<String> {
    prop_oneof![3 => pick(usual), 1 => pick(hostile)].boxed()
}

/// A whole command line.
fn command_line() -> impl Strategy<Value = Vec<String>> {
    let extreme: Vec<String> = extreme_graphs().into_iter().map(|(name, _)| name).collect();
    let graph = move || {
        prop_oneof![
            4 => usual_or(GRAPHS, HOSTILE_GRAPHS),
            1 => proptest::sample::select(extreme.clone()),
        ]
    };
    let graphs = || proptest::collection::vec(graph(), 1..3);
    let mesh = || usual_or(MESHES, HOSTILE_MESHES);
    let size = || usual_or(SIZES, HOSTILE_SIZES);
    let output = || option("-o", usual_or(OUTPUTS, HOSTILE_OUTPUTS));
    let time = || option("--time", usual_or(&["0", "2.5"], HOSTILE_NUMBERS));
    // Preset names become golden file names (`snapshot`): none may leave the folder.
    let preset = || option("--preset", usual_or(&["oak", "walnut"], HOSTILE_PRESETS));
    let flat = || {
        usual_or(
            &["0,0,1,1,0", "-2,-2,2,2,0.5"],
            &["0,0,1e39,1,0", "1,2,3", "NaN,0,1,1,0"],
        )
    };
    let render = (
        graph(),
        options(vec![
            output(),
            option("--size", size()),
            option("--mesh", mesh()),
            time(),
            option("--flat", flat()),
            option("--detail", usual_or(&["footprint", "full"], &["none"])),
            preset(),
        ]),
    )
        .prop_map(|(graph, rest)| [vec!["render".into(), graph], rest].concat());
    let bake = (
        graphs(),
        options(vec![
            option(
                "-o",
                usual_or(&["out"], &["missing", "full", "wood.ron", "out/"]),
            ),
            option("--size", size()),
            option("--mesh", mesh()),
            option("--flat", flat()),
            option(
                "--maps",
                usual_or(
                    &["albedo", "normal,height", "roughness"],
                    &["albedo,albedo", "nope", ""],
                ),
            ),
            option("--format", usual_or(&["png16", "exr", "png"], &["gif"])),
            time(),
        ]),
    )
        .prop_map(|(graphs, rest)| [vec!["bake".into()], graphs, rest].concat());
    let compile = (
        graph(),
        options(vec![
            option(
                "-o",
                usual_or(&["out/a.wgsl", "out/a.glsl", "-"], HOSTILE_OUTPUTS),
            ),
            option(
                "--target",
                usual_or(&["glsl", "spv", "hlsl", "msl", "wgsl"], &["cobol"]),
            ),
            option("--params", usual_or(&["uniform", "baked"], &["none"])),
            preset(),
        ]),
    )
        .prop_map(|(graph, rest)| [vec!["compile".into(), graph], rest].concat());
    let check = graphs().prop_map(|graphs| [vec!["check".into()], graphs].concat());
    let fmt = (graphs(), flag("--arrange"))
        .prop_map(|(graphs, rest)| [vec!["fmt".into()], rest, graphs].concat());
    let mesh_command = (
        mesh(),
        options(vec![
            option("--weld", usual_or(&["0", "0.001"], HOSTILE_NUMBERS)),
            option(
                "--write",
                usual_or(&["out/m.obj"], &["full", "out/", "missing/m.obj", "-"]),
            ),
            flag("--json"),
        ]),
    )
        .prop_map(|(mesh, rest)| [vec!["mesh".into(), mesh], rest].concat());
    let geodesic = (
        mesh(),
        options(vec![
            option(
                "--sources",
                usual_or(&["0", "1,2"], &["-1", "99999999", "", "0,x"]),
            ),
            option("--sources", usual_or(&["3"], &["", "4294967296"])),
            option(
                "--method",
                usual_or(&["heat", "exact", "dijkstra"], &["magic"]),
            ),
            option("--time-factor", usual_or(&["1", "10"], HOSTILE_NUMBERS)),
            flag("--robust"),
            flag("--normalize"),
        ]),
    )
        .prop_map(|(mesh, rest)| [vec!["geodesic".into(), mesh], rest].concat());
    let geodesic = (geodesic, usual_or(&["out/f.csv", "-"], HOSTILE_OUTPUTS))
        .prop_map(|(line, output)| [line, vec!["-o".into(), output]].concat());
    let golden = usual_or(
        &["out", "out/golden"],
        &["full", "missing/deeper", "wood.ron"],
    );
    let snapshot = (
        graphs(),
        golden,
        options(vec![
            option("--size", size()),
            option(
                "--tolerance",
                usual_or(
                    &["channel=2,share=0.001"],
                    &["channel=-1", "share=NaN", "x"],
                ),
            ),
            option(
                "--flat",
                usual_or(&["preview", "0,0,1,1,0"], &["bad", "0,0,1e39,1,0"]),
            ),
            option("--mesh", mesh()),
            time(),
            flag("--update"),
            flag("--json"),
            preset(),
        ]),
    )
        .prop_map(|(graphs, golden, rest)| {
            [
                vec!["snapshot".into()],
                graphs,
                vec!["--golden".into(), golden],
                rest,
            ]
            .concat()
        });
    let batch = (
        pick(&["ok.json", "collide.json", "self.json", "fifo.json"]),
        option("--shard", usual_or(&["1/2", "2/2"], &["0/2"])),
        flag("--dry-run"),
    )
        .prop_map(|(file, shard, dry_run)| [vec!["batch".into(), file], shard, dry_run].concat());
    // Only refused counts: a whole report takes a minute.
    let report = pick(&["0", "1001", "18446744073709551616", "-1"]).prop_map(|count| {
        [
            "report",
            "--quick",
            "-o",
            "out/report",
            "--repetitions",
            &count,
        ]
        .map(String::from)
        .to_vec()
    });
    prop_oneof![
        render,
        bake,
        compile,
        check,
        fmt,
        mesh_command,
        geodesic,
        snapshot,
        batch,
        report
    ]
}

/// Every file under `dir` (not following links) with its size and modification time.
fn listing(dir: &Path) -> BTreeMap<PathBuf, Option<(u64, SystemTime)>> {
    let mut files = BTreeMap::new();
    let mut pending = vec![dir.to_path_buf()];
    while let Some(folder) = pending.pop() {
        for entry in std::fs::read_dir(&folder).expect("listable").flatten() {
            let path = entry.path();
            let meta = std::fs::symlink_metadata(&path).expect("metadata");
            if meta.is_dir() {
                pending.push(path.clone());
            }
            let stamp = meta
                .is_file()
                .then(|| (meta.len(), meta.modified().expect("mtime")));
            files.insert(path.strip_prefix(dir).expect("inside").to_path_buf(), stamp);
        }
    }
    files
}

/// The files a command line reads: its arguments that are no option's value, and the
/// values of [`INPUT_OPTIONS`] (a batch reads its batch file).
fn inputs(args: &[String]) -> Vec<&str> {
    let mut inputs = Vec::new();
    let mut rest = args[1..].iter();
    while let Some(arg) = rest.next() {
        if !arg.starts_with('-') || arg == "-" {
            inputs.push(arg.as_str());
        } else if !FLAGS.contains(&arg.as_str())
            && let Some(value) = rest.next()
            && INPUT_OPTIONS.contains(&arg.as_str())
        {
            inputs.push(value.as_str());
        }
    }
    inputs
}

/// Whether a command line may write `path` (relative to its folder): its outputs that are
/// not also its inputs, and the graphs `fmt` rewrites in place.
fn may_write(args: &[String], path: &Path) -> bool {
    let name = path.to_string_lossy();
    let named = args.iter().any(|arg| *arg == name);
    if args[0] == "batch" {
        let (_, _, writes) = BATCHES
            .iter()
            .find(|(file, _, _)| *file == args[1])
            .expect("a batch file of the fixture");
        return writes.contains(&name.as_ref());
    }
    if args[0] != "fmt" && inputs(args).contains(&name.as_ref()) {
        return false;
    }
    // Inside an output, or a folder made on the way to one.
    let under_output = args.windows(2).any(|pair| {
        let output = Path::new(pair[1].trim_end_matches('/'));
        ["-o", "--golden", "--write"].contains(&pair[0].as_str())
            && (path.starts_with(output) || output.starts_with(path))
    });
    // `compile -o out/a.wgsl --params uniform` describes the parameters beside it.
    let description = args[0] == "compile"
        && args.windows(2).any(|pair| {
            let output = Path::new(&pair[1]);
            let stem = output.file_stem().unwrap_or_default().to_string_lossy();
            pair[0] == "-o" && output.with_file_name(format!("{stem}.parameters.json")) == path
        });
    // `bake` without `-o` writes `<graph>_<map>.<ext>` into the folder it runs in.
    let baked_here = args[0] == "bake"
        && !args.iter().any(|arg| arg == "-o")
        && path
            .parent()
            .is_some_and(|folder| folder.as_os_str().is_empty())
        && inputs(args).iter().any(|graph| {
            let stem = Path::new(graph).file_stem().unwrap_or_default();
            name.starts_with(&format!("{}_", stem.to_string_lossy()))
        });
    under_output || description || baked_here || (args[0] == "fmt" && named)
}

/// Runs one command line in a fresh fixture and checks the contract.
fn run_case(args: &[String], case: usize) -> Result<(), TestCaseError> {
    let name = format!("veneer-contract-{}-{case}", std::process::id());
    let dir = std::env::temp_dir().join(&name);
    let shm = Path::new("/dev/shm").join(&name);
    for folder in [&dir, &shm] {
        let _ = std::fs::remove_dir_all(folder);
    }
    fixture(&dir, &shm);
    let before = listing(&dir);
    let shm_text = shm.to_string_lossy();
    let args: Vec<String> = args
        .iter()
        .map(|arg| arg.replace("{shm}", &shm_text))
        .collect();
    let args = args.as_slice();
    let mut child = Command::new("prlimit")
        .arg(format!("--as={ADDRESS_SPACE}"))
        .arg(env!("CARGO_BIN_EXE_veneer"))
        .args(args)
        .current_dir(&dir)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("prlimit runs");
    let started = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().expect("waits") {
            break status;
        }
        if started.elapsed() > TIME_LIMIT {
            let _ = child.kill();
            let _ = child.wait();
            return Err(TestCaseError::fail(format!(
                "{args:?} ran past {TIME_LIMIT:?}"
            )));
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let mut message = String::new();
    std::io::Read::read_to_string(&mut child.stderr.take().expect("piped"), &mut message)
        .expect("stderr");
    let code = status.code();
    prop_assert!(
        matches!(code, Some(0..=2)),
        "{args:?}: exit {status} (a signal, or an undocumented code): {message}"
    );
    prop_assert!(!message.contains("panicked"), "{args:?}: {message}");
    prop_assert!(
        code == Some(0) || !message.trim().is_empty(),
        "{args:?}: no message"
    );
    let after = listing(&dir);
    for (path, stamp) in &after {
        let changed = before.get(path) != Some(stamp);
        prop_assert!(
            !changed || may_write(args, path),
            "{args:?} touched {} outside its outputs",
            path.display()
        );
        prop_assert!(
            !path
                .file_name()
                .is_some_and(|n| n.to_string_lossy().ends_with(".tmp")),
            "{args:?} left {} behind",
            path.display()
        );
    }
    for path in before.keys().filter(|path| !after.contains_key(*path)) {
        prop_assert!(may_write(args, path), "{args:?} removed {}", path.display());
    }
    for output in STALE_OUTPUTS {
        let bytes = std::fs::read(in_case(&dir, &shm, output)).unwrap_or_default();
        let whole = bytes == STALE.repeat(STALE_REPEATS);
        prop_assert!(
            whole || !bytes.windows(STALE.len()).any(|w| w == STALE),
            "{args:?} left the old tail of {output}"
        );
    }
    for path in after
        .keys()
        .filter(|path| path.extension().is_some_and(|e| e == "exr"))
    {
        let pixels = image::open(dir.join(path)).expect("an EXR").to_rgba32f();
        prop_assert!(
            pixels.iter().all(|v| v.is_finite()),
            "{args:?} wrote a non-finite sample into {}",
            path.display()
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
    let _ = std::fs::remove_dir_all(&shm);
    Ok(())
}

#[test]
fn generated_command_lines_keep_the_contract() {
    let config = Config {
        cases: CASES,
        failure_persistence: None,
        ..Config::default()
    };
    let rng = TestRng::deterministic_rng(RngAlgorithm::ChaCha);
    let mut runner = TestRunner::new_with_rng(config, rng);
    let case = std::sync::atomic::AtomicUsize::new(0);
    let result = runner.run(&command_line(), |args| {
        run_case(
            &args,
            case.fetch_add(1, std::sync::atomic::Ordering::Relaxed),
        )
    });
    if let Err(error) = result {
        panic!("{error}");
    }
}

/// The extreme graphs on fixed command lines through the same contract: baked together
/// into EXR maps (every sample finite), checked together (the ramp past f32 refused with
/// a message), and each compiled.
#[test]
fn extreme_graphs_keep_the_contract_with_finite_maps() {
    let names: Vec<String> = extreme_graphs().into_iter().map(|(name, _)| name).collect();
    let finite: Vec<String> = names
        .iter()
        .filter(|name| *name != "extreme-ramp-stop.ron")
        .cloned()
        .collect();
    let bake = [
        "bake", "--format", "exr", "--size", "8", "-o", "out", "--maps",
    ]
    .map(String::from)
    .into_iter()
    .chain(["albedo,specular,emission,normal".to_string()])
    .chain(finite.iter().cloned())
    .collect();
    let check = [vec!["check".to_string()], names.clone()].concat();
    let compiles = names.iter().map(|name| {
        ["compile", name, "-o", "out/a.wgsl"]
            .map(String::from)
            .to_vec()
    });
    for (case, args) in [bake, check].into_iter().chain(compiles).enumerate() {
        if let Err(error) = run_case(&args, 10_000 + case) {
            panic!("{error}");
        }
    }
}
