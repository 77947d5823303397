//! Merging neighbouring charts wherever the two fit one cone (the cone of the chart
//! joined, or one round their mean normal or round their narrowest cone) and lie flat
//! without overlapping: smallest charts first, each into the neighbour it shares the
//! most edges with that takes it, until no more merge.

use super::charts::ChartBuilder;
use super::geometry::Geometry;
use std::collections::BTreeMap;

/// The most passes over the charts (each pass tries every chart once).
const PASSES: usize = 8;

/// The charts after merging.
pub(super) fn merge<'a>(
    geometry: &'a Geometry,
    charts: Vec<ChartBuilder<'a>>,
) -> Vec<ChartBuilder<'a>> {
    let mut chart_of = vec![usize::MAX; geometry.triangles.len()];
    for (index, chart) in charts.iter().enumerate() {
        for &t in chart.triangles() {
            chart_of[t as usize] = index;
        }
    }
    let mut charts: Vec<Option<ChartBuilder>> = charts.into_iter().map(Some).collect();
    // Pairs that would not merge, with the times each chart had grown then: they are
    // not tried again until one of them grows.
    let mut grown = vec![0u32; charts.len()];
    let mut refused: rustc_hash::FxHashSet<(usize, u32, usize, u32)> = Default::default();
    for _ in 0..PASSES {
        let mut by_area: Vec<(f64, usize)> = (charts.iter().enumerate())
            .filter_map(|(index, chart)| Some((chart.as_ref()?.double_area(), index)))
            .collect();
        by_area.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let mut merged = false;
        for (_, index) in by_area {
            let Some(chart) = charts[index].take() else {
                continue;
            };
            let neighbours = neighbours_by_shared_edges(geometry, &chart, &chart_of, index);
            let into = neighbours.into_iter().find(|&other| {
                let pair = (index, grown[index], other, grown[other]);
                let Some(target) = charts[other].as_mut() else {
                    return false;
                };
                if refused.contains(&pair) {
                    return false;
                }
                let joined = join(geometry, target, &chart);
                if !joined {
                    refused.insert(pair);
                }
                joined
            });
            match into {
                Some(other) => {
                    for &t in chart.triangles() {
                        chart_of[t as usize] = other;
                    }
                    grown[other] += 1;
                    merged = true;
                }
                None => charts[index] = Some(chart),
            }
        }
        if !merged {
            break;
        }
    }
    charts.into_iter().flatten().collect()
}

/// The charts sharing an edge with `chart` (numbered `index`), most shared edges first.
fn neighbours_by_shared_edges(
    geometry: &Geometry,
    chart: &ChartBuilder,
    chart_of: &[usize],
    index: usize,
) -> Vec<usize> {
    let mut shared: BTreeMap<usize, usize> = BTreeMap::new();
    for &t in chart.triangles() {
        for &next in geometry.neighbours(t) {
            let other = chart_of[next as usize];
            if other != index && other != usize::MAX {
                *shared.entry(other).or_default() += 1;
            }
        }
    }
    let mut neighbours: Vec<(usize, usize)> = shared.into_iter().collect();
    neighbours.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    neighbours.into_iter().map(|(other, _)| other).collect()
}

/// Joins chart `b` to chart `a` if their triangles fit one chart: round `a`'s axis when
/// `b`'s fit it (only `b`'s triangles are checked then), else round the mean normal of
/// both or the axis of the narrowest cone holding their normals. Says whether it did.
fn join<'a>(geometry: &'a Geometry, a: &mut ChartBuilder<'a>, b: &ChartBuilder<'a>) -> bool {
    if a.try_add_all(b.triangles()) {
        return true;
    }
    let both: Vec<u32> = a.triangles().iter().chain(b.triangles()).copied().collect();
    let Some(mean) = ChartBuilder::round_mean_of(geometry, &both) else {
        return false;
    };
    // The cone first: it is cheap and refuses most.
    let builder = if both.iter().all(|&t| mean.faces(t)) {
        Some(mean)
    } else {
        ChartBuilder::round_narrowest_cone_of(geometry, &both)
            .filter(|narrowest| both.iter().all(|&t| narrowest.faces(t)))
    };
    let Some(mut builder) = builder else {
        return false;
    };
    if both.iter().all(|&t| builder.try_add(t)) {
        *a = builder;
        true
    } else {
        false
    }
}
