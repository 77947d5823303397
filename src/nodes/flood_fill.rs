//! The Flood fill node: every cell of a mask (a tiles or Voronoi pattern, a painted
//! mask) gets its own random value, colour and gradient, and the point its place in the
//! cell's bounding box — what gives each stone, plank and tile its own tint. The cells
//! are labelled in passes over the mask's buffer (see `shaders/flood_fill.wgsl`).

use super::cpu::Eval;
use super::emit::Emit;
use super::formulas::flood_fill::{FILL_STEPS, fill_cell, fill_seed, fill_step};
use super::formulas::real::{Real, V3};
use super::interval::{Interval, Lanes, splat};
use super::passes::{Stage, doubling_step_reach};
use super::pins::{COLOR, FLOAT, Signature, VEC2, f, input, output};
use super::ranges::Ranges;
use super::sampled::image_node;
use super::settings::{Basis, Setting};
use super::{Catalogue, Category, Configure, Definition, Evaluate};
use serde::{Deserialize, Serialize};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather
            [$($units)*]
            [$($configured)* (FloodFill, flood_fill)]
            $($rest)*);
    };
}
pub(super) use kinds;

/// The rounds a fill may run: each lets a cell's box turn one more corner of the cell.
const ROUNDS: std::ops::RangeInclusive<u32> = 1..=16;

/// The outputs, in pin order (also the fields of `veneer_flood_fill_result`).
const OUTPUTS: [&str; 5] = ["value", "colour", "uv", "gradient", "centre"];

/// Labels the cells of `mask` (its 4-connected regions above 0.5, across the wrap when
/// its buffer wraps) and gives each a random value and colour, the point's place in
/// the cell's bounding box, a ramp across the box in a random direction, and the box's
/// centre. The labelling runs `rounds` rounds of row and column scans: one finds every
/// rectangle, four the cells of a Voronoi diagram, more slender slanted or winding
/// shapes (a cell whose box is not yet complete shows as several).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct FloodFill {
    pub rounds: u32,
}

impl Default for FloodFill {
    fn default() -> Self {
        FloodFill { rounds: 4 }
    }
}

/// The stages that label a mask buffer: the seeds, then per round a scan along the rows
/// and one along the columns, [`FILL_STEPS`] steps each.
fn label_stages(rounds: u32) -> Vec<Stage> {
    let mut stages = vec![Stage {
        label: "flood fill seeds".into(),
        wgsl: "veneer_fill_seed(SOURCE, texel)".into(),
        library: vec!["veneer_fill_seed"],
        unchanged_up_to: 0,
        cpu: Box::new(fill_seed),
    }];
    for round in 1..=rounds {
        for (axis, name) in ["rows", "columns"].into_iter().enumerate() {
            for k in 0..FILL_STEPS {
                stages.push(Stage {
                    label: format!("flood fill round {round}, {name}, step {}", k + 1),
                    wgsl: format!("veneer_fill_step(SOURCE, texel, {axis}u, {k}u)"),
                    library: vec!["veneer_fill_step"],
                    unchanged_up_to: doubling_step_reach(k),
                    cpu: Box::new(move |image, texel| fill_step(image, texel, axis, k)),
                });
            }
        }
    }
    stages
}

impl Definition for FloodFill {
    image_node!();
    fn title(&self) -> &'static str {
        "Flood fill"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &[
            "cells",
            "per tile",
            "per stone",
            "random colour",
            "label",
            "islands",
            "bounding box",
        ]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("mask", FLOAT, f(0.0)).sampled(),
                input("seed", FLOAT, f(0.0)).soft(0.0, 100.0),
            ],
            vec![
                output("value", FLOAT),
                output("colour", COLOR),
                output("uv", VEC2),
                output("gradient", FLOAT),
                output("centre", VEC2),
            ],
        )
    }
    fn check(&self) -> Option<String> {
        (!ROUNDS.contains(&self.rounds)).then(|| {
            format!(
                "rounds {} is out of range ({} to {})",
                self.rounds,
                ROUNDS.start(),
                ROUNDS.end()
            )
        })
    }
    fn emit(&self, io: &mut Emit) {
        io.bind(
            "veneer_flood_fill_result",
            format!(
                "veneer_flood_fill({}, s.uv, {})",
                io.input("mask"),
                io.input("seed")
            ),
        );
        let name = io.name();
        io.outputs(OUTPUTS.map(|field| format!("{name}.{field}")).to_vec());
        io.uses("veneer_flood_fill");
    }
    fn ranges(&self, _: &mut Ranges) -> Vec<Lanes> {
        let mut lanes = vec![splat(Interval::UNIT); OUTPUTS.len()];
        // A box across the wrap's seam has its centre past the tile's far edge.
        lanes[4] = splat(Interval::new(0.0, 1.5));
        lanes
    }
    fn stages(&self, _: &dyn Fn(&str) -> Option<f64>) -> Result<Vec<Stage>, String> {
        Ok(label_stages(self.rounds))
    }
}

impl Evaluate for FloodFill {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let seed = io.float("seed").to_f64();
        let Some(cell) = fill_cell(io.image("mask"), io.domain(), seed) else {
            return vec![[R::c(0.0); 3]; OUTPUTS.len()];
        };
        vec![
            [cell.value; 3],
            cell.colour,
            [cell.uv[0], cell.uv[1], 0.0],
            [cell.gradient; 3],
            [cell.centre[0], cell.centre[1], 0.0],
        ]
        .into_iter()
        .map(|lanes| lanes.map(R::c))
        .collect()
    }
}

impl Configure for FloodFill {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        vec![Setting::Count {
            label: "rounds",
            value: &mut self.rounds,
            range: ROUNDS,
        }]
    }
}

impl Catalogue for FloodFill {
    fn menu() -> Vec<(String, Self)> {
        vec![("Flood fill".into(), FloodFill::default())]
    }
    fn examples() -> Vec<Self> {
        vec![FloodFill::default(), FloodFill { rounds: 1 }]
    }
}
