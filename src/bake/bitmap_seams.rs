//! The bitmaps whose seams a tile would show: a bitmap that wraps is read across the
//! tile's edges as if it went on, so the tile check (which evaluates the material past
//! its edges) sees its own edges continue, whatever the file holds. A bitmap cannot be
//! evaluated past its edge either; its seam is measured instead (see
//! [`Bitmap::edge_ratios`](crate::bitmaps::Bitmap::edge_ratios)) and followed through the
//! passes to the material, except through *Make tileable*, which removes it.

use crate::codegen::Compiled;
use crate::codegen::passes::PassKind;
use crate::graph::NodeKind;
use crate::nodes::passes::EdgeMode;

/// How much more a bitmap's wrap may jump than its neighbouring texels do, on average,
/// before its seam counts: a bitmap that tiles scores about 1 (its wrap is one more pair
/// of neighbours), the raw photo in `assets/photos/` 2.8 left/right and 3.5 top/bottom.
pub const EDGE_RATIO_TOLERANCE: f32 = 1.6;

/// A bitmap whose seam reaches the material's maps.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SeamedBitmap {
    /// The file as the graph names it.
    pub path: String,
    /// Its wrap's jump against its neighbouring texels' (left/right, top/bottom).
    pub ratios: [f32; 2],
}

/// The bitmaps that wrap, have a seam, and reach the material other than through
/// *Make tileable*, in pass order.
pub fn seamed_bitmaps(compiled: &Compiled) -> Vec<SeamedBitmap> {
    let passes = &compiled.passes;
    // The bitmap pass whose seam each buffer carries, if one does, and each seamed
    // bitmap's ratios.
    let mut carries: Vec<Option<usize>> = Vec::with_capacity(passes.passes.len());
    let mut seamed = std::collections::BTreeMap::new();
    for (index, pass) in passes.passes.iter().enumerate() {
        let carried = match &pass.kind {
            PassKind::Bitmap { path, bitmap } if pass.spec.edge == EdgeMode::Wrap => {
                let ratios = bitmap.edge_ratios();
                let over = ratios.iter().any(|&ratio| ratio > EDGE_RATIO_TOLERANCE);
                if over {
                    let path = path.clone();
                    seamed.insert(index, SeamedBitmap { path, ratios });
                }
                over.then_some(index)
            }
            PassKind::Bitmap { .. } => None,
            PassKind::Stage { source, .. } => carries[*source],
            PassKind::Surface { nodes, .. } => read_as_is(compiled, nodes, &carries).next(),
        };
        carries.push(carried);
    }
    let reached: std::collections::BTreeSet<usize> =
        read_as_is(compiled, &passes.nodes, &carries).collect();
    (reached.into_iter())
        .filter_map(|index| seamed.remove(&index))
        .collect()
}

/// The seamed bitmaps (by pass) that the nodes at `positions` (in the checked order)
/// read as they are: an Image node's own file, or a buffer carrying a seam read by any
/// node but *Make tileable*.
fn read_as_is<'a>(
    compiled: &'a Compiled,
    positions: &'a [usize],
    carries: &'a [Option<usize>],
) -> impl Iterator<Item = usize> + 'a {
    let passes = &compiled.passes;
    positions.iter().flat_map(move |&at| {
        let checked = &compiled.checked.order[at];
        let id = checked.node.id;
        let removes_seams = matches!(checked.node.kind, NodeKind::MakeTileable(_));
        let sampled = (0..checked.inputs.len())
            .filter(move |_| !removes_seams)
            .filter_map(move |pin| passes.sampled.get(&(id, pin)));
        let own = passes.sources.get(&id);
        (sampled.chain(own)).filter_map(|&buffer| carries[buffer])
    })
}

impl std::fmt::Display for SeamedBitmap {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let [left_right, top_bottom] = self.ratios;
        write!(
            f,
            "image '{}' reaches the maps as it is (not through Make tileable), and its wrap \
             jumps {left_right:.1}× (left/right) and {top_bottom:.1}× (top/bottom) as much as \
             its neighbouring texels do: the tile will show its seam",
            self.path
        )
    }
}
