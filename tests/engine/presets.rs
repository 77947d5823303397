//! Every preset loads, checks, compiles to its golden WGSL, saves byte-identically, and
//! renders (flat and on its mesh) like its snapshot, through `veneer::snapshot`, on the
//! default adapter and on GL; the texture graphs (materials with passes) render like
//! theirs.

use crate::support::{
    flat_rgb8, gpu, presets, root, snapshot_folder, stem, texture_graphs, updating,
};
use veneer::render::{FlatRect, GpuContext, View};
use veneer::snapshot::{Settings, assert_matches_on};

#[test]
fn presets_load_check_and_match_their_golden_wgsl() {
    assert!(
        presets().len() >= 4,
        "the four issue-2 presets ship in graphs/"
    );
    for path in presets() {
        let graph = veneer::graph::load(&path).unwrap_or_else(|e| panic!("{e}"));
        let module = veneer::codegen::compile(&graph, &Default::default())
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
            .module;
        let golden = root(&format!("tests/golden/wgsl/{}.wgsl", stem(&path)));
        if updating() {
            std::fs::write(&golden, &module.source).expect("golden WGSL written");
        } else {
            let expected = std::fs::read_to_string(&golden).expect("golden WGSL readable");
            assert!(
                module.source == expected,
                "{} differs from {}",
                path.display(),
                golden.display()
            );
        }
    }
}

#[test]
fn presets_save_byte_identically() {
    for path in presets() {
        let text = std::fs::read_to_string(&path).expect("preset readable");
        let graph = veneer::graph::from_ron(&text).expect("preset parses");
        assert_eq!(
            veneer::graph::to_ron(&graph),
            text,
            "{} is not in canonical form",
            path.display()
        );
    }
}

/// Each of `graphs` renders on `gpu` like its snapshots in `folder`: on its mesh
/// (`NAME.png`) and flat (`flat/NAME.png`), or like the adapter's own copies of them.
fn assert_snapshots(gpu: &GpuContext, graphs: &[std::path::PathBuf], folder: &std::path::Path) {
    for path in graphs {
        let name = stem(path);
        assert_matches_on(
            gpu,
            path,
            folder.join(format!("{name}.png")),
            &Settings::default(),
        );
        let flat = Settings {
            view: View::PreviewFlat,
            ..Settings::default()
        };
        assert_matches_on(gpu, path, folder.join(format!("flat/{name}.png")), &flat);
    }
}

#[test]
fn presets_render_like_their_snapshots_flat_and_on_their_mesh() {
    assert_snapshots(gpu(), &presets(), &snapshot_folder());
}

/// The same goldens on Mesa's GL adapter (llvmpipe), as on a machine without Vulkan:
/// the sine hash's presets against GL's own copies (`llvmpipe-gl/`), the rest against
/// the same files as Vulkan. Under `VENEER_UPDATE_SNAPSHOTS=1` it stands aside, so that
/// updating the goldens does not copy every preset into GL's folder.
#[test]
fn presets_render_like_their_snapshots_on_gl_too() {
    if veneer::snapshot::update_requested() {
        return;
    }
    let gl = GpuContext::on_backends(wgpu::Backends::GL).unwrap_or_else(|error| {
        panic!(
            "this test needs Mesa's GL adapter (packages libegl-mesa0 and libgl1-mesa-dri, \
             which the README's test command installs): {error}"
        )
    });
    assert_snapshots(&gl, &presets(), &snapshot_folder());
}

#[test]
fn texture_graphs_render_like_their_snapshots_flat_and_on_their_mesh() {
    assert_snapshots(gpu(), &texture_graphs(), &snapshot_folder().join("texture"));
}

#[test]
fn rendering_is_deterministic_run_to_run() {
    let graph = veneer::graph::load(&root("graphs/marble.ron")).expect("preset loads");
    let source = veneer::codegen::compile(&graph, &Default::default())
        .expect("compiles")
        .module
        .source;
    let rect = FlatRect {
        x0: -10.0,
        z0: -10.0,
        x1: 10.0,
        z1: 10.0,
        y: 0.5,
    };
    assert_eq!(flat_rgb8(&source, rect, 64), flat_rgb8(&source, rect, 64));
}
