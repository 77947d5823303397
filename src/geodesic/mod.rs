//! Geodesic distance fields on triangle meshes: the distance along the surface from a
//! set of source vertices to every vertex (the minimum over the sources). Vertices no
//! source reaches get `f64::INFINITY`, never NaN.

mod dijkstra;

pub use dijkstra::edge_distances;

/// The largest finite value of a field (0 when none is finite).
pub fn max_finite(field: &[f64]) -> f64 {
    field
        .iter()
        .copied()
        .filter(|d| d.is_finite())
        .fold(0.0, f64::max)
}

/// `field` divided by its largest finite value, so that reached vertices lie in [0, 1];
/// unreached vertices stay infinite.
pub fn normalized(field: &[f64]) -> Vec<f64> {
    let max = max_finite(field);
    field
        .iter()
        .map(|&d| {
            if d.is_finite() && max > 0.0 {
                d / max
            } else {
                d
            }
        })
        .collect()
}
