//! Where nodes go on the canvas: each node's footprint (the rectangle the editor draws
//! it in), automatic layout in columns, laying out stacked nodes, and placing new nodes
//! clear of the others. No two footprints intersect after any of them.

mod arrange;
mod footprint;
mod placement;
mod unstack;

pub use arrange::{arrange, arrange_groups, arrange_in_rows, arrange_nodes};
pub use footprint::{Bounds, Footprint, bounds, footprints, overlapping};
pub use placement::{CLEARANCE, Taken};
pub use unstack::{UNSTACKED_BAND, unstack, unstack_levels};

#[cfg(test)]
mod tests;
