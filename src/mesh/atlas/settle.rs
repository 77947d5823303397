//! Settling charts into compact patches round the directions the surface faces (Lloyd's
//! iteration, as in variational shape approximation): every chart is regrown round its
//! mean normal from the triangle nearest its centre, all charts at once, each triangle
//! going to the chart that reaches it at the least cost — how far it faces from the
//! chart's axis plus how far it lies from the chart's centre; what none can take gets
//! charts of its own.

use super::charts::ChartBuilder;
use super::geometry::Geometry;
use glam::DVec3;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// How many times charts are regrown.
const ROUNDS: usize = 2;

/// What lying one chart radius (of a disc of the chart's area, or of the mean chart's
/// if larger) from its centre costs, against facing away from its axis (1 − cos of the
/// angle): 0.2 is as much as facing 37° away.
const COMPACTNESS: f64 = 0.2;

/// The charts after [`ROUNDS`] rounds of regrowing.
pub(super) fn settle<'a>(
    geometry: &'a Geometry,
    mut charts: Vec<ChartBuilder<'a>>,
) -> Vec<ChartBuilder<'a>> {
    for _ in 0..ROUNDS {
        charts = regrow(geometry, &charts);
    }
    charts
}

/// A chart being regrown: round its previous mean normal, from its previous centre.
struct Regrowing<'a> {
    builder: ChartBuilder<'a>,
    centre: DVec3,
    /// 1 / radius² of a disc of the chart's area (or the mean chart's, if larger).
    inverse_radius_squared: f64,
}

impl Regrowing<'_> {
    /// The cost of adding triangle `t`, as bits that order like it.
    fn cost(&self, t: u32) -> u64 {
        let geometry = self.builder.geometry();
        let distance_squared = centroid(geometry, t).distance_squared(self.centre);
        let cost = self.builder.deviation(t)
            + COMPACTNESS * distance_squared * self.inverse_radius_squared;
        cost.to_bits()
    }
}

/// The centroid of triangle `t`.
fn centroid(geometry: &Geometry, t: u32) -> DVec3 {
    (geometry.triangles[t as usize].iter())
        .map(|&v| geometry.positions[v as usize])
        .sum::<DVec3>()
        / 3.0
}

/// One round: all charts regrown at once from their centres.
fn regrow<'a>(geometry: &'a Geometry, charts: &[ChartBuilder<'a>]) -> Vec<ChartBuilder<'a>> {
    let count = geometry.triangles.len();
    let mut regrowing: Vec<Regrowing> = Vec::with_capacity(charts.len());
    // Candidates as (cost bits, chart, triangle), least cost first.
    let mut queue: BinaryHeap<Reverse<(u64, u32, u32)>> = BinaryHeap::new();
    // A small chart is given the radius of a chart of the mean area, so that it can grow.
    let mean_chart_double_area =
        geometry.double_areas.iter().sum::<f64>() / charts.len().max(1) as f64;
    for chart in charts {
        let Some(builder) = ChartBuilder::round_mean_of(geometry, chart.triangles()) else {
            continue;
        };
        let areas = chart
            .triangles()
            .iter()
            .map(|&t| geometry.double_areas[t as usize]);
        let double_area: f64 = areas.clone().sum();
        let centre = (chart.triangles().iter().zip(areas))
            .map(|(&t, area)| centroid(geometry, t) * area)
            .sum::<DVec3>()
            / double_area;
        let chart_regrowing = Regrowing {
            builder,
            centre,
            inverse_radius_squared: 2.0 * std::f64::consts::PI
                / double_area.max(mean_chart_double_area),
        };
        let seed = (chart.triangles().iter().copied())
            .min_by_key(|&t| (chart_regrowing.cost(t), t))
            .expect("a chart with a mean normal has triangles");
        queue.push(Reverse((
            chart_regrowing.cost(seed),
            regrowing.len() as u32,
            seed,
        )));
        regrowing.push(chart_regrowing);
    }
    let mut taken = vec![false; count];
    // The last chart to queue each triangle: a chart queues a triangle at one cost, so
    // once is enough.
    let mut queued_by = vec![u32::MAX; count];
    while let Some(Reverse((_, chart, t))) = queue.pop() {
        let chart_regrowing = &mut regrowing[chart as usize];
        if taken[t as usize] || !chart_regrowing.builder.try_add(t) {
            continue;
        }
        taken[t as usize] = true;
        for &next in geometry.neighbours(t) {
            if !taken[next as usize] && queued_by[next as usize] != chart {
                queued_by[next as usize] = chart;
                queue.push(Reverse((chart_regrowing.cost(next), chart, next)));
            }
        }
    }
    let mut regrown: Vec<ChartBuilder> = (regrowing.into_iter())
        .map(|chart| chart.builder)
        .filter(|builder| !builder.triangles().is_empty())
        .collect();
    regrown.extend(super::seed::grow_charts(geometry, &mut taken));
    regrown
}
