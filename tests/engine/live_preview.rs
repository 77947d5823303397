//! The editor's live preview draws what `veneer render` draws, also for graphs with
//! more parameters than a uniform block holds (the editor then keeps them in a storage
//! buffer, and `veneer render` bakes them into the shader).

use crate::big_graphs::chain;
use crate::support::{difference, gpu, temp_dir};
use veneer::app::{LiveMaterial, UNIFORM_SLOTS};
use veneer::codegen::{CompileOptions, compile};
use veneer::graph::Graph;
use veneer::render::{
    FlatRenderer, LiveMaterialCode, LiveRenderer, MeshView, PREVIEW_PASS_SIZE, Quality, View,
    albedo_to_rgb8, render_material,
};

/// The preview's side in pixels: enough for the lattice of the sphere's triangles.
const SIZE: u32 = 256;

/// `graph` (with more parameters than a uniform block holds) drawn as the editor's
/// preview thread draws it at rest, RGBA8.
fn live_preview(graph: &Graph) -> Vec<u8> {
    let mut live = LiveMaterial::in_storage();
    live.update(graph);
    let module = &live.compiled.as_ref().expect("it compiles").module;
    assert!(
        module.params.len() > UNIFORM_SLOTS,
        "the graph's {} parameters fit a uniform block",
        module.params.len()
    );
    preview(graph).expect("the preview draws")
}

/// `graph` drawn by the editor's live renderer on its preview mesh, RGBA8.
fn preview(graph: &Graph) -> Result<Vec<u8>, veneer::render::RenderError> {
    let gpu = gpu();
    let mut live = LiveMaterial::in_storage();
    live.update(graph);
    let code = LiveMaterialCode::new(1, live.compiled.as_ref().expect("it compiles"));
    let mesh = veneer::mesh::primitive(&graph.preview.mesh).expect("the preview mesh");
    let view = MeshView::for_preview(&graph.preview);
    let sky = gpu.sky().expect("the default environment");
    let (_, pixels) = LiveRenderer::default().render(
        gpu,
        &code,
        &live.params(graph),
        "mesh",
        &mesh,
        &view,
        &sky,
        (SIZE, SIZE),
        Quality::Full,
    )?;
    Ok(pixels)
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

/// The RGB of an RGBA8 image.
fn rgb(rgba: &[u8]) -> Vec<u8> {
    rgba.chunks_exact(4)
        .flat_map(|pixel| [pixel[0], pixel[1], pixel[2]])
        .collect()
}

#[test]
fn a_multi_pass_material_previews_flat_as_its_tile_and_a_value_edit_renders_its_passes_again() {
    let gpu = gpu();
    let path = crate::support::root("graphs/texture/blurred_noise.ron");
    let graph = veneer::graph::load(&path).expect("loads");
    let mut live = LiveMaterial::in_storage();
    live.update(&graph);
    let code = LiveMaterialCode::new(1, live.compiled.as_ref().expect("it compiles"));
    assert!(code.passes.is_some(), "the material renders passes");
    let mesh = veneer::mesh::primitive("plane").expect("a plane");
    // The flat view (unlit) shows a multi-pass material's tile.
    let mut view = MeshView::for_preview(&graph.preview);
    view.unlit = true;
    let sky = gpu.sky().expect("the default environment");
    let mut renderer = LiveRenderer::default();
    let preview = |params: Vec<[f32; 4]>, renderer: &mut LiveRenderer| {
        let (size, pixels) = renderer
            .render(
                gpu,
                &code,
                &params,
                "plane",
                &mesh,
                &view,
                &sky,
                (SIZE, SIZE),
                Quality::Full,
            )
            .expect("the preview draws");
        assert_eq!(size, (SIZE, SIZE));
        rgb(&pixels)
    };
    // The flat render of the tile, its passes at the preview's resolution.
    let rendered = |graph: &Graph| {
        let baked = compile(graph, &CompileOptions::default()).expect("it compiles");
        let mut flat = FlatRenderer::for_compiled(gpu, &baked).expect("pipelines");
        flat.set_pass_size(Some(PREVIEW_PASS_SIZE));
        let tile = veneer::bake::UNIT_TILE;
        albedo_to_rgb8(&flat.render(gpu, tile, SIZE, 0.0).expect("it renders"))
    };
    let first = preview(live.params(&graph), &mut renderer);
    assert!(difference(&first, &rendered(&graph), 3, 1).passes());

    // A value upstream of the blur: the same code, new parameter values, the passes
    // rendered again by the same renderer.
    let mut edited = graph.clone();
    let grain = edited
        .nodes
        .iter()
        .find(|n| n.label == "grain")
        .expect("the noise")
        .id;
    edited.set_input(grain, "gain", veneer::graph::Value::Float(0.8));
    assert!(!live.update(&edited), "a value edit does not recompile");
    let second = preview(live.params(&edited), &mut renderer);
    assert_ne!(first, second);
    assert!(difference(&second, &rendered(&edited), 3, 1).passes());
}

#[test]
fn every_shipped_texture_graph_previews_in_the_editor() {
    for path in crate::support::texture_graphs() {
        let graph = veneer::graph::load(&path).expect("loads");
        if let Err(error) = preview(&graph) {
            panic!("{}: {error}", path.display());
        }
    }
}

#[test]
fn the_flat_views_three_by_three_tile_repeats_one_drawn_tile() {
    // A single-pass graph (the wood preset, whose field does not repeat by itself):
    // drawn 3×3, each copy is the tile drawn once, side by side, seams and all.
    let gpu = gpu();
    let graph = veneer::graph::load(&crate::support::root("graphs/wood.ron")).expect("loads");
    let mut live = LiveMaterial::in_storage();
    live.update(&graph);
    let code = LiveMaterialCode::new(1, live.compiled.as_ref().expect("it compiles"));
    let mesh = veneer::mesh::primitive("plane").expect("a plane");
    let mut view = MeshView::for_preview(&graph.preview);
    view.unlit = true;
    view.repeat_tile = true;
    let sky = gpu.sky().expect("the default environment");
    let (width, height) = (200u32, 150u32);
    let ((w, h), pixels) = LiveRenderer::default()
        .render(
            gpu,
            &code,
            &live.params(&graph),
            "plane",
            &mesh,
            &view,
            &sky,
            (width, height),
            Quality::Full,
        )
        .expect("the preview draws");
    assert_eq!((w, h), (width, height));
    let side = (height / 3) as usize;
    let at = |x: usize, y: usize| &pixels[(y * width as usize + x) * 4..][..4];
    let mut differs = false;
    for y in 0..height as usize - side {
        for x in 0..width as usize - side {
            assert_eq!(at(x, y), at(x + side, y), "({x}, {y}) across");
            assert_eq!(at(x, y), at(x, y + side), "({x}, {y}) down");
            differs |= at(x, y) != at(x + 1, y);
        }
    }
    assert!(differs, "the tile is not one colour");
    // The tile as the flat render draws it, its top-left corner where the 3×3 block
    // starts (centred).
    let baked = compile(&graph, &CompileOptions::default()).expect("it compiles");
    let tile = albedo_to_rgb8(
        &FlatRenderer::for_compiled(gpu, &baked)
            .expect("pipelines")
            .render(gpu, veneer::bake::UNIT_TILE, side as u32, 0.0)
            .expect("it renders"),
    );
    let corner = (
        width as usize / 2 - 3 * side / 2,
        height as usize / 2 - 3 * side / 2,
    );
    let shown: Vec<u8> = (0..side)
        .flat_map(|y| (0..side).map(move |x| (x, y)))
        .flat_map(|(x, y)| at(corner.0 + x, corner.1 + y)[..3].to_vec())
        .collect();
    assert!(difference(&shown, &tile, 3, 1).passes());
}
