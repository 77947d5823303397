//! CPU twins of the WGSL library in `shaders/`: the same formulas, generic over the
//! precision (f32 like the GPU, f64 as the reference).

pub mod band_limit;
pub mod buffers;
pub mod colour;
pub mod fields;
pub mod flood_fill;
pub mod gabor;
pub mod image_ops;
pub mod instances;
pub mod jump_flood;
#[cfg(test)]
mod library_items;
pub mod noise;
pub mod octaves;
pub mod ranges;
pub mod real;
pub mod reduce;
pub mod sdf;
pub mod shapes;
pub mod worley_edge;
