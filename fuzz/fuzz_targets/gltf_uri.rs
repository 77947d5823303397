//! glTF files whose buffers have arbitrary URIs, built from pieces that try to leave the
//! file's folder (`..`, `/`, absolute paths, `file:`, percent-encoding, links out of the
//! folder) and arbitrary text (`data:` URIs, which read no file, are left out). Whatever
//! they are, the loader reads no file outside the glTF's folder: the files outside hold
//! the canary coordinate, which no vertex of a loaded mesh may have, and the files inside
//! never do. No panic, no hang.

#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// A coordinate only the files outside the glTF's folder hold.
const CANARY: f32 = 31337.0;

/// One piece of a URI.
#[derive(Arbitrary, Debug)]
enum Piece {
    Parent,
    Slash,
    Dot,
    Inside,
    Secret,
    /// A link in the folder to the secret outside.
    Escape,
    /// A link in the folder to the folder's parent.
    Up,
    Sub,
    /// The absolute path of the folder that holds the glTF's folder.
    Root,
    FileScheme,
    Percent(u8),
    Text(String),
}

impl Piece {
    fn text(&self) -> String {
        match self {
            Piece::Parent => "..".into(),
            Piece::Slash => "/".into(),
            Piece::Dot => ".".into(),
            Piece::Inside => "inside.bin".into(),
            Piece::Secret => "secret.bin".into(),
            Piece::Escape => "escape.bin".into(),
            Piece::Up => "up".into(),
            Piece::Sub => "sub".into(),
            Piece::Root => root().display().to_string(),
            Piece::FileScheme => "file://".into(),
            Piece::Percent(byte) => format!("%{byte:02X}"),
            Piece::Text(text) => text.clone(),
        }
    }
}

/// Buffers of up to four URIs, each read as one triangle by its own primitive.
#[derive(Arbitrary, Debug)]
struct Input {
    uris: Vec<Vec<Piece>>,
}

/// Made once per process: `ROOT/secret.bin` (a triangle of canaries), `ROOT/model/`
/// (the glTF's folder) with `inside.bin`, `sub/inside.bin`, a link `escape.bin` to the
/// secret and a link `up` to `ROOT`, and `ROOT/model/sub/secret.bin` → the secret too.
fn root() -> &'static Path {
    static ROOT: OnceLock<PathBuf> = OnceLock::new();
    ROOT.get_or_init(|| {
        let root =
            std::env::temp_dir().join(format!("veneer-fuzz-gltf-uri-{}", std::process::id()));
        let model = root.join("model");
        std::fs::create_dir_all(model.join("sub")).expect("folders");
        let triangle = |value: f32| -> Vec<u8> {
            (0..9)
                .flat_map(|k| if k % 4 == 0 { value } else { 0.5 }.to_le_bytes())
                .collect()
        };
        std::fs::write(root.join("secret.bin"), triangle(CANARY)).expect("secret");
        std::fs::write(model.join("inside.bin"), triangle(1.0)).expect("inside");
        std::fs::write(model.join("sub/inside.bin"), triangle(2.0)).expect("inside");
        for (link, target) in [
            ("escape.bin", "../secret.bin"),
            ("up", ".."),
            ("sub/secret.bin", "../../secret.bin"),
        ] {
            let _ = std::os::unix::fs::symlink(target, model.join(link));
        }
        root.canonicalize().expect("root")
    })
}

/// A glTF file of one mesh with a primitive per URI, each of a 36-byte buffer.
fn gltf(uris: &[String]) -> String {
    let each = |f: &dyn Fn(usize) -> serde_json::Value| -> Vec<serde_json::Value> {
        (0..uris.len()).map(f).collect()
    };
    serde_json::json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": each(&|k| serde_json::json!({"attributes": {"POSITION": k}}))}],
        "buffers": each(&|k| serde_json::json!({"uri": uris[k], "byteLength": 36})),
        "bufferViews": each(&|k| serde_json::json!({"buffer": k, "byteLength": 36})),
        "accessors": each(&|k| serde_json::json!({
            "bufferView": k, "componentType": 5126, "count": 3, "type": "VEC3",
            "min": [-1e9, -1e9, -1e9], "max": [1e9, 1e9, 1e9]
        })),
    })
    .to_string()
}

fuzz_target!(|input: Input| {
    let uris: Vec<String> = input
        .uris
        .iter()
        .take(4)
        .map(|pieces| pieces.iter().map(Piece::text).collect())
        .collect();
    // A data: URI could spell the canary itself, and reads no file anyway.
    if uris.is_empty() || uris.iter().any(|uri| uri.starts_with("data:")) {
        return;
    }
    // One file per process: libFuzzer runs inputs one after another.
    let path = root().join("model/model.gltf");
    std::fs::write(&path, gltf(&uris)).expect("the glTF is written");
    if let Ok(mesh) = veneer::mesh::load(&path) {
        assert!(
            !mesh.positions.iter().flatten().any(|&c| c == CANARY),
            "a file outside the glTF's folder was read: {uris:?}"
        );
    }
});
