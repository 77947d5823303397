//! Every preset loads, checks, compiles to its golden WGSL, saves byte-identically, and
//! renders (flat and on its mesh) to its golden images within the stated tolerance.

use crate::support::{
    adapter_slug, difference, flat_rgb8, gpu, presets, read_png, root, stem, updating, write_png,
};
use veneer::render::{FlatRect, MeshRenderer, MeshView};

/// Golden images may differ from a render by this much per channel...
const TOLERANCE: u8 = 8;
/// ...in at most this share of pixels. Goldens are per adapter (tests/golden/images/<adapter>/),
/// so this only absorbs driver-version noise.
const SHARE: f64 = 0.01;
const IMAGE_SIZE: u32 = 160;

fn compare_or_update_image(name: &str, pixels: &[u8], channels: usize) {
    let folder = root(&format!("tests/golden/images/{}", adapter_slug()));
    let path = folder.join(format!("{name}.png"));
    if updating() {
        std::fs::create_dir_all(&folder).expect("golden folder");
        write_png(&path, pixels, IMAGE_SIZE, channels);
        return;
    }
    assert!(
        path.exists(),
        "no golden {} for this adapter: make them with VENEER_UPDATE_GOLDEN=1",
        path.display()
    );
    let (_, _, golden) = read_png(&path);
    let diff = difference(pixels, &golden, channels, TOLERANCE);
    assert!(
        diff.share_outside <= SHARE,
        "{name}: {diff} against {}",
        path.display()
    );
}

#[test]
fn presets_load_check_and_match_their_golden_wgsl() {
    assert!(
        presets().len() >= 4,
        "the four issue-2 presets ship in graphs/"
    );
    for path in presets() {
        let graph = veneer::graph::load(&path).unwrap_or_else(|e| panic!("{e}"));
        let module = veneer::codegen::compile_graph(&graph)
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
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

#[test]
fn presets_render_flat_like_their_golden_images() {
    for path in presets() {
        let graph = veneer::graph::load(&path).expect("preset loads");
        let source = veneer::codegen::compile_graph(&graph)
            .expect("preset compiles")
            .source;
        let (c, size) = (graph.preview.center, graph.preview.size);
        let rect = FlatRect {
            x0: c.0 - size,
            z0: c.2 - size,
            x1: c.0 + size,
            z1: c.2 + size,
            y: c.1 + 0.5,
        };
        compare_or_update_image(
            &format!("{}_flat", stem(&path)),
            &flat_rgb8(&source, rect, IMAGE_SIZE),
            3,
        );
    }
}

#[test]
fn presets_render_on_their_mesh_like_their_golden_images() {
    for path in presets() {
        let graph = veneer::graph::load(&path).expect("preset loads");
        let source = veneer::codegen::compile_graph(&graph)
            .expect("preset compiles")
            .source;
        let mesh = veneer::mesh::primitive(&graph.preview.mesh).expect("preset names a primitive");
        let renderer = MeshRenderer::new(gpu(), &source).expect("mesh pipeline builds");
        let pixels = renderer
            .render(
                gpu(),
                &mesh,
                &MeshView::for_preview(&graph.preview),
                IMAGE_SIZE,
            )
            .expect("renders");
        compare_or_update_image(&format!("{}_mesh", stem(&path)), &pixels, 4);
    }
}

#[test]
fn rendering_is_deterministic_run_to_run() {
    let graph = veneer::graph::load(&root("graphs/marble.ron")).expect("preset loads");
    let source = veneer::codegen::compile_graph(&graph)
        .expect("compiles")
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
