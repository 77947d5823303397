//! CPU twins of the WGSL library in `shaders/`: the same formulas, generic over the
//! precision (f32 like the GPU, f64 as the reference).

pub mod fields;
pub mod noise;
pub mod real;
pub mod shapes;
