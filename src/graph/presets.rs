//! The presets shipped inside the binary (the files of `graphs/`), by file stem.

use super::Graph;

/// Every preset: its file stem and RON text.
pub const PRESETS: [(&str, &str); 27] = [
    ("wood", include_str!("../../graphs/wood.ron")),
    ("marble", include_str!("../../graphs/marble.ron")),
    (
        "wood_classic",
        include_str!("../../graphs/wood_classic.ron"),
    ),
    (
        "marble_tiles",
        include_str!("../../graphs/marble_tiles.ron"),
    ),
    ("sand_water", include_str!("../../graphs/sand_water.ron")),
    (
        "moss_granite",
        include_str!("../../graphs/moss_granite.ron"),
    ),
    (
        "paint_metal_rust",
        include_str!("../../graphs/paint_metal_rust.ron"),
    ),
    ("water_lava", include_str!("../../graphs/water_lava.ron")),
    ("waves", include_str!("../../graphs/waves.ron")),
    ("isolines", include_str!("../../graphs/isolines.ron")),
    (
        "thesis_c2_sand_water",
        include_str!("../../graphs/thesis_c2_sand_water.ron"),
    ),
    (
        "thesis_c3_moss_granite",
        include_str!("../../graphs/thesis_c3_moss_granite.ron"),
    ),
    (
        "thesis_c4_paint_metal_rust",
        include_str!("../../graphs/thesis_c4_paint_metal_rust.ron"),
    ),
    (
        "thesis_c5_water_lava",
        include_str!("../../graphs/thesis_c5_water_lava.ron"),
    ),
    (
        "thesis_c6_waves",
        include_str!("../../graphs/thesis_c6_waves.ron"),
    ),
    (
        "thesis_c6_waves_adaptive",
        include_str!("../../graphs/thesis_c6_waves_adaptive.ron"),
    ),
    (
        "thesis_fig1_1_fronts",
        include_str!("../../graphs/thesis_fig1_1_fronts.ron"),
    ),
    (
        "thesis_fig5_7_opacity",
        include_str!("../../graphs/thesis_fig5_7_opacity.ron"),
    ),
    // Metallic-roughness versions of the seeds' materials.
    (
        "wood_polished",
        include_str!("../../graphs/wood_polished.ron"),
    ),
    (
        "marble_polished",
        include_str!("../../graphs/marble_polished.ron"),
    ),
    (
        "rusted_metal",
        include_str!("../../graphs/rusted_metal.ron"),
    ),
    ("lava_glow", include_str!("../../graphs/lava_glow.ron")),
    (
        "thesis_brick",
        include_str!("../../graphs/thesis_brick.ron"),
    ),
    // Worley stones, made to be fitted to a photograph of gravel (`veneer fit`).
    ("gravel", include_str!("../../graphs/gravel.ron")),
    // Materials that read what the mesh knows about itself.
    ("worn_paint", include_str!("../../graphs/worn_paint.ron")),
    ("mossy_stone", include_str!("../../graphs/mossy_stone.ron")),
    ("wax_candle", include_str!("../../graphs/wax_candle.ron")),
];

/// The embedded preset called `name`.
pub fn preset(name: &str) -> Option<Graph> {
    PRESETS
        .iter()
        .find(|(stem, _)| *stem == name)
        .and_then(|(_, text)| super::from_ron(text).ok())
        .map(|mut graph| {
            super::library::refresh(&mut graph);
            graph
        })
}
