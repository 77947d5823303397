//! Baking one tile of a repeating texture: whether the maps' opposite edges continue
//! each other, measured on the rows and columns just beyond the bake's edges, and those
//! rows' heights, which a tiling normal map's differences reach across its top and
//! bottom edges.

use super::maps::Map;
use crate::render::{FlatChannels, FlatRect, FlatRenderer, GpuContext, RenderError};

/// How far a tile's opposite edges are from continuing each other: the largest
/// difference, over the material outputs a map is made from, between the pixels just
/// past one edge (as if the image went on) and the pixels along the opposite edge,
/// which repeat them when the texture tiles.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Seams {
    /// Past the right edge against the left edge, and past the left against the right.
    pub left_right: f32,
    /// Past the bottom edge against the top edge, and past the top against the bottom.
    pub top_bottom: f32,
}

impl Seams {
    /// The larger of the two.
    pub fn worst(self) -> f32 {
        self.left_right.max(self.top_bottom)
    }
}

/// A seam as messages write it: `0`, three decimals, or for tiny ones two significant
/// digits in scientific notation.
pub fn seam_text(seam: f32) -> String {
    if seam == 0.0 {
        "0".into()
    } else if seam >= 1.0e-3 {
        format!("{seam:.3}")
    } else {
        format!("{seam:.1e}")
    }
}

/// The largest seam a tile passes with, in the material outputs' units. Positions a
/// period apart differ by f32 rounding (about 1e-7 of the rectangle), which moves a
/// periodic noise by about 1e-5 at the presets' scales; a graph that does not repeat
/// over the tile misses by tenths.
pub const SEAM_TOLERANCE: f32 = 1.0e-3;

/// What a tile check found for one group of material outputs.
struct EdgeCheck {
    seams: Seams,
    /// The outputs of the rows just above the top edge and just below the bottom edge.
    above: Vec<[f32; 4]>,
    below: Vec<[f32; 4]>,
}

/// The edge checks of a tile bake: one per group of material outputs its maps are made
/// from.
pub struct TileEdges(Vec<(FlatChannels, EdgeCheck)>);

impl TileEdges {
    /// Checks the edges of a size×size bake of `maps` over `rect`, each group of
    /// material outputs once.
    pub fn check(
        gpu: &GpuContext,
        flat: &FlatRenderer,
        rect: FlatRect,
        size: u32,
        time: f32,
        maps: &[Map],
    ) -> Result<TileEdges, RenderError> {
        let mut checks: Vec<(FlatChannels, EdgeCheck)> = Vec::new();
        for map in maps {
            let channels = map.channels();
            if !checks.iter().any(|(done, _)| *done == channels) {
                checks.push((
                    channels,
                    check_edges(gpu, flat, rect, size, time, channels)?,
                ));
            }
        }
        Ok(TileEdges(checks))
    }

    /// The check of the outputs `map` is made from, if it was checked.
    fn of(&self, map: Map) -> Option<&EdgeCheck> {
        let channels = map.channels();
        self.0
            .iter()
            .find(|(c, _)| *c == channels)
            .map(|(_, check)| check)
    }

    /// How far `map`'s opposite edges are from continuing each other.
    pub fn seams(&self, map: Map) -> Option<Seams> {
        self.of(map).map(|check| check.seams)
    }

    /// Each of `maps` whose seams are past [`SEAM_TOLERANCE`], with them.
    pub fn failing(&self, maps: &[Map]) -> Vec<(Map, Seams)> {
        (maps.iter())
            .filter_map(|&map| Some((map, self.seams(map)?)))
            .filter(|(_, seams)| seams.worst() > SEAM_TOLERANCE)
            .collect()
    }

    /// The heights of the rows just above and just below the tile, for its normal map
    /// ([`super::Converter::tiling`]), when the height was checked.
    pub fn heights_beyond(&self) -> Option<(Vec<f32>, Vec<f32>)> {
        let heights = |row: &[[f32; 4]]| row.iter().map(|p| p[0]).collect();
        let check = self.of(Map::Height)?;
        Some((heights(&check.above), heights(&check.below)))
    }
}

/// Renders `channels` along the four edges of a size×size bake of `rect` and just
/// beyond them, and measures the seams.
fn check_edges(
    gpu: &GpuContext,
    flat: &FlatRenderer,
    rect: FlatRect,
    size: u32,
    time: f32,
    channels: FlatChannels,
) -> Result<EdgeCheck, RenderError> {
    let n = i64::from(size);
    let region =
        |origin, extent| flat.render_region(gpu, rect, size, time, channels, origin, extent);
    let column = |i| region((i, 0), (1, size));
    let row = |j| region((0, j), (size, 1));
    let left_right = largest_difference(&column(n)?, &column(0)?)
        .max(largest_difference(&column(-1)?, &column(n - 1)?));
    let (above, below) = (row(-1)?, row(n)?);
    let top_bottom =
        largest_difference(&below, &row(0)?).max(largest_difference(&above, &row(n - 1)?));
    Ok(EdgeCheck {
        seams: Seams {
            left_right,
            top_bottom,
        },
        above,
        below,
    })
}

/// The largest difference between corresponding lanes (NaN counts as infinite).
fn largest_difference(a: &[[f32; 4]], b: &[[f32; 4]]) -> f32 {
    a.iter()
        .flatten()
        .zip(b.iter().flatten())
        .map(|(x, y)| {
            let d = (x - y).abs();
            if d.is_nan() { f32::INFINITY } else { d }
        })
        .fold(0.0, f32::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_largest_difference_counts_every_lane_and_nan_as_infinite() {
        let a = [[0.0, 1.0, 2.0, 3.0], [0.5; 4]];
        let b = [[0.0, 1.0, 2.5, 3.0], [0.5; 4]];
        assert_eq!(largest_difference(&a, &b), 0.5);
        assert_eq!(largest_difference(&a, &a), 0.0);
        let nan = [[f32::NAN; 4], [0.5; 4]];
        assert_eq!(largest_difference(&nan, &a), f32::INFINITY);
    }
}
