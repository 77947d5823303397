//! The editor's live preview draws what `veneer render` draws, also for graphs with
//! more parameters than a uniform block holds (the editor then keeps them in a storage
//! buffer, and `veneer render` bakes them into the shader).

use crate::big_graphs::chain;
use crate::support::{difference, gpu, temp_dir};
use veneer::app::{LiveMaterial, UNIFORM_SLOTS};
use veneer::codegen::{CompileOptions, compile};
use veneer::graph::Graph;
use veneer::render::{LiveMaterialCode, LiveRenderer, MeshView, Quality, View, render_material};

/// The preview's side in pixels: enough for the lattice of the sphere's triangles.
const SIZE: u32 = 256;

/// `graph` drawn as the editor's preview thread draws it at rest, RGBA8.
fn live_preview(graph: &Graph) -> Vec<u8> {
    let gpu = gpu();
    let mut live = LiveMaterial::in_storage();
    live.update(graph);
    let module = &live.compiled.as_ref().expect("it compiles").module;
    assert!(
        module.params.len() > UNIFORM_SLOTS,
        "the graph's {} parameters fit a uniform block",
        module.params.len()
    );
    let code = LiveMaterialCode {
        generation: 1,
        wgsl: module.source.as_str().into(),
        slots: module.params.len(),
        uses: module.uses,
    };
    let mesh = veneer::mesh::primitive(&graph.preview.mesh).expect("the preview mesh");
    let view = MeshView::for_preview(&graph.preview);
    let sky = gpu.sky().expect("the default environment");
    let (_, pixels) = LiveRenderer::default()
        .render(
            gpu,
            &code,
            &live.params(graph),
            "mesh",
            &mesh,
            &view,
            &sky,
            (SIZE, SIZE),
            Quality::Full,
        )
        .expect("the preview draws");
    pixels
}

#[test]
fn the_preview_of_a_two_thousand_node_chain_matches_its_render() {
    let graph = chain(2000);
    let baked = compile(&graph, &CompileOptions::default()).expect("it compiles");
    let rendered =
        render_material(gpu(), &baked, &View::Mesh(None), SIZE, 0.0).expect("it renders");
    let preview = live_preview(&graph);
    let compared = difference(&preview, &rendered.pixels, 4, 8);
    if !compared.passes() {
        let dir = temp_dir("live-preview");
        let save = |name: &str, pixels: &[u8]| {
            let image = image::RgbaImage::from_raw(SIZE, SIZE, pixels.to_vec()).unwrap();
            image.save(dir.join(name)).unwrap();
        };
        save("preview.png", &preview);
        save("render.png", &rendered.pixels);
        panic!("the preview differs from the render ({compared:?}); both in {dir:?}");
    }
}
