//! The report's fitting section: presets rendered at parameter values drawn at random
//! (seeded) and fitted back from their own values, the loss against seconds for Adam
//! from one start and from three (with and without the global search), and for random
//! search given the same time; the loss left and the median normalised parameter error
//! each reached.

use super::plot::{Plot, Series};
use super::table::{Table, number};
use super::{Context, Section};
use crate::fit::image::Canvas;
use crate::fit::recovery::{draw_truth, median_error};
use crate::fit::{FitSettings, Prepared, fit, prepare, random_search};
use std::time::{Duration, Instant};

/// The seed of the drawn values.
const SEED: u64 = 11;

/// The presets fitted: marble alone in a quick report, marble and wood otherwise.
fn graphs(quick: bool) -> &'static [&'static str] {
    if quick {
        &["marble"]
    } else {
        &["marble", "wood"]
    }
}

/// The number of progress steps the section takes.
pub fn steps(quick: bool) -> u64 {
    graphs(quick).len() as u64
}

pub fn fitting(ctx: &Context, quick: bool) -> Result<Section, String> {
    let size = if quick { 64 } else { 128 };
    let mut table = Table::new(&[
        "graph",
        "method",
        "seconds",
        "loss left",
        "median parameter error",
    ]);
    let mut series = Vec::new();
    for name in graphs(quick) {
        let graph = crate::graph::preset(name).ok_or_else(|| format!("no preset {name}"))?;
        let Prepared {
            evaluator,
            space,
            rect,
        } = prepare(&graph, None).map_err(|e| format!("{name}: {e}"))?;
        let canvas = Canvas {
            evaluator: &evaluator,
            rect,
            size,
        };
        let truth = draw_truth(&space, SEED);
        let photo = canvas.render(&space, &truth).to_photo();
        let (mut longest, mut start_loss) = (Duration::ZERO, f64::MIN_POSITIVE);
        for (starts, global) in [(1, false), (3, false), (3, true)] {
            let settings = FitSettings {
                size,
                starts,
                global,
                ..FitSettings::default()
            };
            let mut curve = Vec::new();
            let clock = Instant::now();
            let fitted = fit(&evaluator, rect, &space, &photo, &settings, |progress| {
                curve.push((progress.seconds, progress.loss));
                true
            });
            let seconds = clock.elapsed();
            longest = longest.max(seconds);
            let start = fitted.initial.total();
            start_loss = start;
            // The lowest loss so far against the time, relative to the start.
            let mut lowest = f64::INFINITY;
            let points = (curve.into_iter())
                .map(|(at, loss)| {
                    lowest = lowest.min(loss);
                    (at.max(1e-3), lowest / start)
                })
                .chain([(seconds.as_secs_f64(), fitted.parts.total() / start)])
                .collect();
            let method = format!(
                "Adam from {}{}",
                crate::messages::counted(starts, "start"),
                if global { " with global search" } else { "" }
            );
            table.push(vec![
                name.to_string(),
                method.clone(),
                number(seconds.as_secs_f64(), 3),
                format!("{:.1}%", 100.0 * fitted.parts.total() / start),
                number(median_error(&fitted.places, &truth), 3),
            ]);
            series.push(Series {
                name: format!("{name}: {method}"),
                points,
                joined: true,
            });
        }
        let settings = FitSettings {
            size,
            ..FitSettings::default()
        };
        let searched = random_search(&evaluator, rect, &space, &photo, &settings, longest);
        table.push(vec![
            name.to_string(),
            format!("random search ({} draws)", searched.draws),
            number(longest.as_secs_f64(), 3),
            format!("{:.1}%", 100.0 * searched.loss / start_loss),
            number(median_error(&searched.places, &truth), 3),
        ]);
        series.push(Series {
            name: format!("{name}: random search"),
            points: vec![(longest.as_secs_f64(), searched.loss / start_loss)],
            joined: false,
        });
        (ctx.progress)();
    }
    Ok(Section {
        title: "Fitting: loss against time".into(),
        text: format!(
            "Each preset rendered on the CPU at {size}² with its exposed parameters drawn at random (seed {SEED}, away from the ranges' ends), then fitted back from its own values by `veneer fit`'s method (Adam on normalised parameters, 40 steps a start at 64², refined up to {size}²) from one start and from three, from three with the later two searched globally first (`--global`: sep-CMA-ES, 20 generations at 64², then Adam), and by random search given as long as the longest fit. Loss left is the final loss over the loss at the preset's own values; the parameter error is the median, over the parameters' lanes, of the distance to the drawn values in units of each range. The plot shows the lowest loss so far against the time."
        ),
        table,
        plot: Plot {
            title: "Fitting: loss against time".into(),
            x_label: "time (s)".into(),
            y_label: "loss left (fraction of the start)".into(),
            series,
        },
    })
}
