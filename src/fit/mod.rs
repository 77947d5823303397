//! Fitting a graph's parameters to a photo (`veneer fit`): the exposed parameters'
//! continuous lanes ([`space`]) moved by Adam, from several starts and coarse to fine,
//! to lower a loss that compares statistics of the rendered albedo and the photo across
//! scales ([`loss`]); the loss's derivative by every parameter is taken in reverse mode
//! through the CPU evaluator ([`tape`], [`image`]).

pub mod evolution;
pub mod graph;
pub mod image;
pub mod loss;
pub mod optimise;
pub mod recovery;
pub mod space;
pub mod spectrum;
pub mod tape;

pub use graph::{
    FIT_PRESET, FitError, FittedGraph, Prepared, fit_graph, photo_pixels, prepare, read_photo,
};
pub use optimise::{FitSettings, Fitted, Progress, Searched, StartResult, fit, random_search};

#[cfg(test)]
mod node_derivatives;

/// A small deterministic generator of numbers in [0, 1) (a 64-bit linear congruential
/// generator's top 53 bits): the same seed draws the same numbers everywhere.
pub struct Draws(u64);

impl Draws {
    /// The generator for `seed`.
    pub fn new(seed: u64) -> Draws {
        Draws(seed ^ 0x9E37_79B9_7F4A_7C15)
    }

    /// The next number.
    pub fn uniform(&mut self) -> f64 {
        self.0 = (self.0)
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}
