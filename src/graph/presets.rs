//! The presets shipped inside the binary (the files of `graphs/`), by file stem.

use super::Graph;

/// Every preset: its file stem and RON text.
pub const PRESETS: [(&str, &str); 10] = [
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
];

/// The embedded preset called `name`.
pub fn preset(name: &str) -> Option<Graph> {
    PRESETS
        .iter()
        .find(|(stem, _)| *stem == name)
        .and_then(|(_, text)| super::from_ron(text).ok())
}
