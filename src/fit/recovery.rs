//! The fit's yardstick: a graph rendered at parameter values drawn at random (seeded),
//! then fitted from its own values — how near the fitted values come to the drawn ones,
//! in normalised units (a coordinate's whole span is 1).

use super::Draws;
use super::image::Canvas;
use super::loss::{Loss, Target};
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

/// `truth` with each place moved by up to `reach` either way (seeded), kept within
/// [0, 1]: a start inside the truth's neighbourhood.
pub fn near(truth: &[f64], reach: f64, seed: u64) -> Vec<f64> {
    let mut draws = Draws::new(seed);
    (truth.iter())
        .map(|t| (t + reach * (2.0 * draws.uniform() - 1.0)).clamp(0.0, 1.0))
        .collect()
}

/// Samples per unit of a coordinate's span in a basin scan.
const SCAN_STEPS: usize = 64;

/// How far a descent could start from a coordinate's true place and still slide back to
/// it, the others held true: the loss is scanned along the coordinate outward from the
/// truth (steps of 1/64) on either side until it stops rising; the basin's width is the
/// nearer of the two turns (a side that rises all the way to its end of the span does
/// not bound it). `None` where the loss changes by no more than `flat` along the whole
/// line (the coordinate cannot be told from the image).
pub fn basin_width(
    canvas: &Canvas,
    (loss, target): (&Loss, &Target),
    space: &Space,
    truth: &[f64],
    coordinate: usize,
    flat: f64,
) -> Option<f64> {
    let at = |t: f64| {
        let mut places = truth.to_vec();
        places[coordinate] = t;
        loss.evaluate(&canvas.render(space, &places), target)
            .0
            .total()
    };
    let centre = at(truth[coordinate]);
    let mut highest: f64 = 0.0;
    let mut widths = Vec::new();
    for side in [-1.0, 1.0] {
        let mut last = centre;
        let mut turn = None;
        for step in 1..=SCAN_STEPS {
            let t = truth[coordinate] + side * step as f64 / SCAN_STEPS as f64;
            if !(0.0..=1.0).contains(&t) {
                break;
            }
            let value = at(t);
            highest = highest.max((value - centre).abs());
            if value < last {
                turn = Some((step - 1) as f64 / SCAN_STEPS as f64);
                break;
            }
            last = value;
        }
        widths.extend(turn);
    }
    if highest <= flat {
        return None;
    }
    Some(widths.into_iter().fold(1.0, f64::min))
}

/// The median, over the coordinates, of the distance between fitted and true places.
pub fn median_error(fitted: &[f64], truth: &[f64]) -> f64 {
    median(
        fitted
            .iter()
            .zip(truth)
            .map(|(a, b)| (a - b).abs())
            .collect(),
    )
}

/// The middle of `values` (the mean of the middle two for an even count; 0 for none).
pub fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    match values.len() {
        0 => 0.0,
        n if n % 2 == 1 => values[n / 2],
        n => (values[n / 2 - 1] + values[n / 2]) / 2.0,
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
