//! Fitting a graph's parameters to a photo (`veneer fit`): the derivatives of a material
//! by its parameters, taken in reverse mode through the CPU evaluator ([`tape`]).

pub mod tape;

#[cfg(test)]
mod node_derivatives;
