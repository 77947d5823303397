//! The sidecar next to a golden image (`<graph>.snap.ron`): what made it, so that a
//! mismatch can say whether the graph, Veneer or the adapter changed.

use super::Tolerance;
use crate::render::View;
use serde::{Deserialize, Serialize};

/// Everything recorded about how a golden image was made.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SnapshotRecord {
    /// Veneer version that rendered the golden.
    pub veneer: String,
    /// Adapter name and backend that rendered it.
    pub adapter: String,
    pub backend: String,
    /// FNV-1a hash of the graph's canonical RON.
    pub graph_hash: String,
    /// FNV-1a hash of the generated WGSL: changes when codegen or the library changes.
    pub shader_hash: String,
    pub view: View,
    pub size: u32,
    pub time: f32,
    /// Tolerance when compared on the adapter that made the golden...
    pub tolerance: Tolerance,
    /// ...and on any other adapter.
    pub cross_adapter: Tolerance,
    /// The graph uses the sine hash, whose bits differ between adapters: compare it only
    /// on the adapter that made it.
    pub adapter_dependent: bool,
}

/// 64-bit FNV-1a of `bytes` as 16 hex digits: stable across platforms and Rust versions.
pub fn fnv1a(bytes: &[u8]) -> String {
    let hash = bytes.iter().fold(0xcbf29ce484222325u64, |hash, byte| {
        (hash ^ u64::from(*byte)).wrapping_mul(0x100000001b3)
    });
    format!("{hash:016x}")
}

#[cfg(test)]
mod tests {
    #[test]
    fn fnv1a_matches_the_published_test_vectors() {
        assert_eq!(super::fnv1a(b""), "cbf29ce484222325");
        assert_eq!(super::fnv1a(b"a"), "af63dc4c8601ec8c");
        assert_eq!(super::fnv1a(b"foobar"), "85944171f73967e8");
    }
}
