//! Straightening the ragged edges of charts: a triangle with more of its edges on a
//! neighbouring chart than on its own (a tooth, as region growing over uneven
//! triangles leaves many) moves to that neighbour when it fits there (faces within its
//! cone and overlaps none of its triangles). Shorter edges pack tighter and make fewer
//! seams.

use super::charts::{Chart, ChartBuilder};
use super::geometry::Geometry;

/// The most passes over the triangles.
const PASSES: usize = 4;

/// The charts with their teeth moved, finished.
pub(super) fn smooth(geometry: &Geometry, mut charts: Vec<ChartBuilder>) -> Vec<Chart> {
    let mut chart_of = vec![usize::MAX; geometry.triangles.len()];
    for (index, chart) in charts.iter().enumerate() {
        for &t in chart.triangles() {
            chart_of[t as usize] = index;
        }
    }
    for _ in 0..PASSES {
        let mut moved = false;
        for t in 0..geometry.triangles.len() as u32 {
            let own = chart_of[t as usize];
            if own == usize::MAX {
                continue;
            }
            // Each neighbour's chart, counted once per shared edge; a tooth has at least
            // two edges on one other chart and fewer on its own.
            let mut across: Vec<usize> = (geometry.neighbours(t).iter())
                .map(|&next| chart_of[next as usize])
                .filter(|&chart| chart != usize::MAX)
                .collect();
            across.sort_unstable();
            let on = |chart: usize| across.iter().filter(|&&c| c == chart).count();
            let Some(&other) = (across.iter())
                .filter(|&&chart| chart != own && on(chart) >= 2 && on(chart) > on(own))
                .max_by_key(|&&chart| (on(chart), std::cmp::Reverse(chart)))
            else {
                continue;
            };
            if charts[other].try_add(t) {
                chart_of[t as usize] = other;
                moved = true;
            }
        }
        if !moved {
            break;
        }
    }
    (charts.iter_mut().enumerate()).for_each(|(index, chart)| {
        chart.retain(|t| chart_of[t as usize] == index);
    });
    (charts.into_iter())
        .filter(|chart| !chart.triangles().is_empty())
        .map(ChartBuilder::finish)
        .collect()
}
