//! The fit's yardstick: a graph rendered at parameter values drawn at random (seeded),
//! then fitted from its own values — how near the fitted values come to the drawn ones,
//! in normalised units (a coordinate's whole span is 1).

use super::Draws;
use super::space::Space;

/// The share of each span the drawn values keep away from its ends (a material at the
/// very end of a range is often degenerate: no veins, no rings).
const MARGIN: f64 = 0.2;

/// Normalised places drawn for a trial, uniformly within each span less its margins.
pub fn draw_truth(space: &Space, seed: u64) -> Vec<f64> {
    let mut draws = Draws::new(seed);
    (space.coordinates.iter())
        .map(|_| MARGIN + (1.0 - 2.0 * MARGIN) * draws.uniform())
        .collect()
}

/// The median, over the coordinates, of the distance between fitted and true places.
pub fn median_error(fitted: &[f64], truth: &[f64]) -> f64 {
    let mut errors: Vec<f64> = (fitted.iter().zip(truth))
        .map(|(a, b)| (a - b).abs())
        .collect();
    errors.sort_by(f64::total_cmp);
    match errors.len() {
        0 => 0.0,
        n if n % 2 == 1 => errors[n / 2],
        n => (errors[n / 2 - 1] + errors[n / 2]) / 2.0,
    }
}

/// The `NAME=VALUE` assignments (`--set`'s) that give the fitted parameters their values
/// at `places`.
pub fn assignments(space: &Space, places: &[f64]) -> Vec<String> {
    (space.fitted_values(places).into_iter())
        .map(|(_, name, lanes)| {
            let lanes: Vec<String> = lanes.iter().map(|v| format!("{v}")).collect();
            format!("{name}={}", lanes.join(","))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_median_error_is_the_middle_distance() {
        assert_eq!(
            super::median_error(&[0.25, 0.5, 0.75], &[0.25, 0.375, 0.25]),
            0.125
        );
        assert_eq!(super::median_error(&[0.0, 1.0], &[0.5, 0.5]), 0.5);
    }
}
