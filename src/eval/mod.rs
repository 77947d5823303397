//! CPU reference evaluator.
