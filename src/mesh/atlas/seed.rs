//! The first charts: grown one after another, each from the first triangle no chart
//! holds yet, breadth first across edges.

use super::charts::ChartBuilder;
use super::geometry::Geometry;
use std::collections::VecDeque;

/// Grows charts over the triangles that are neither degenerate nor `taken`, marking
/// them taken.
pub(super) fn grow_charts<'a>(geometry: &'a Geometry, taken: &mut [bool]) -> Vec<ChartBuilder<'a>> {
    let mut visited = vec![0u32; geometry.triangles.len()];
    let mut charts = Vec::new();
    for seed in 0..geometry.triangles.len() as u32 {
        if geometry.degenerate[seed as usize] || taken[seed as usize] {
            continue;
        }
        let chart = chart_from(geometry, seed, taken, &mut visited, charts.len() as u32);
        for &t in chart.triangles() {
            taken[t as usize] = true;
        }
        charts.push(chart);
    }
    charts
}

/// The chart grown from `seed`: first round the seed's normal, then once more round
/// the mean normal of what that gave (a better centred cone), keeping the larger.
/// `visited` marks what each growth has queued with a number of its own, made from
/// `stamp` (one per chart).
fn chart_from<'a>(
    geometry: &'a Geometry,
    seed: u32,
    taken: &[bool],
    visited: &mut [u32],
    stamp: u32,
) -> ChartBuilder<'a> {
    let mut grow = |builder: ChartBuilder<'a>, pass: u32| {
        grow_from(builder, seed, taken, visited, 2 * stamp + pass)
    };
    let first = grow(
        ChartBuilder::new(geometry, geometry.normals[seed as usize]),
        1,
    );
    // A seed outside the centred cone grows nothing, and the first stays.
    let centred = ChartBuilder::round_mean_of(geometry, first.triangles());
    match centred.map(|builder| grow(builder, 2)) {
        Some(second) if second.double_area() > first.double_area() => second,
        _ => first,
    }
}

/// `builder` grown breadth first from `seed` across edges over triangles not `taken`;
/// `visited` marks with `stamp` what this growth has queued.
fn grow_from<'a>(
    mut builder: ChartBuilder<'a>,
    seed: u32,
    taken: &[bool],
    visited: &mut [u32],
    stamp: u32,
) -> ChartBuilder<'a> {
    let geometry = builder.geometry();
    let mut queue = VecDeque::from([seed]);
    visited[seed as usize] = stamp;
    while let Some(t) = queue.pop_front() {
        if !builder.try_add(t) {
            continue;
        }
        for &next in geometry.neighbours(t) {
            let next_index = next as usize;
            if visited[next_index] != stamp && !taken[next_index] {
                visited[next_index] = stamp;
                queue.push_back(next);
            }
        }
    }
    builder
}
