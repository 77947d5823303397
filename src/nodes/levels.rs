//! Levels: Auto levels, which reads a reduction of its whole input (its minimum,
//! maximum and mean, found in passes over its buffer; see `shaders/reduce.wgsl`), and
//! the histogram scan, a ramp that sweeps the input's range.

use super::cpu::Eval;
use super::emit::Emit;
use super::formulas::ranges;
use super::formulas::real::splat as splat_lanes;
use super::formulas::real::{Real, V3};
use super::formulas::reduce::{REDUCE_STEPS, reduce_seed, reduce_step, reduced};
use super::interval::{Interval, Lanes, splat};
use super::passes::{Stage, doubling_step_reach};
use super::pins::{FLOAT, REQUIRED, Signature, f, input, output};
use super::ranges::Ranges;
use super::sampled::image_node;
use super::settings::Basis;
use super::{Catalogue, Category, Definition, Evaluate};
use serde::{Deserialize, Serialize};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather
            [$($units)* (AutoLevels, levels) (HistogramScan, levels)]
            [$($configured)*]
            $($rest)*);
    };
}
pub(super) use kinds;

/// The outputs of Auto levels, in pin order (the lanes of `veneer_levels_read`).
const LEVELS_OUTPUTS: [&str; 4] = ["result", "min", "max", "mean"];

/// The stages that reduce a buffer: the seeds, then [`REDUCE_STEPS`] steps along the
/// rows and as many down the first column.
fn reduce_stages() -> Vec<Stage> {
    let mut stages = vec![Stage {
        label: "reduction seeds".into(),
        wgsl: "veneer_reduce_seed(SOURCE, texel)".into(),
        library: vec!["veneer_reduce_seed"],
        unchanged_up_to: 0,
        cpu: Box::new(reduce_seed),
    }];
    for (axis, name) in ["rows", "columns"].into_iter().enumerate() {
        for k in 0..REDUCE_STEPS {
            stages.push(Stage {
                label: format!("reduction, {name}, step {}", k + 1),
                wgsl: format!("veneer_reduce_step(SOURCE, texel, {axis}u, {k}u)"),
                library: vec!["veneer_reduce_step"],
                unchanged_up_to: doubling_step_reach(k),
                cpu: Box::new(move |image, texel| reduce_step(image, texel, axis, k)),
            });
        }
    }
    stages
}

/// The input stretched so that its lowest value over the whole buffer becomes 0 and its
/// highest 1 (0.5 everywhere when it is flat), and that minimum, maximum and mean.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct AutoLevels;

impl Definition for AutoLevels {
    image_node!();
    fn title(&self) -> &'static str {
        "Auto levels"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &[
            "normalize",
            "normalise",
            "stretch",
            "contrast",
            "minimum",
            "maximum",
            "average",
            "histogram",
        ]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![input("image", FLOAT, f(0.0)).sampled()],
            LEVELS_OUTPUTS
                .iter()
                .map(|&name| output(name, FLOAT))
                .collect(),
        )
    }
    fn check(&self) -> Option<String> {
        None
    }
    fn emit(&self, io: &mut Emit) {
        io.bind(
            "vec4f",
            format!("veneer_levels_read({}, s.uv)", io.input("image")),
        );
        let name = io.name();
        io.outputs(
            ["x", "y", "z", "w"]
                .map(|lane| format!("{name}.{lane}"))
                .to_vec(),
        );
        io.uses("veneer_levels_read");
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        // The totals lie within whatever the input ranges over.
        let input = io.input("image")[0];
        vec![
            splat(Interval::UNIT),
            splat(input),
            splat(input),
            splat(input),
        ]
    }
    fn stages(&self, _: &dyn Fn(&str) -> Option<f64>) -> Result<Vec<Stage>, String> {
        Ok(reduce_stages())
    }
}

impl Evaluate for AutoLevels {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let image = io.image("image");
        let [low, high, mean] = reduced(image);
        let value = image.bilinear(io.domain())[0];
        let range = high - low;
        let result = if range > 1e-30 {
            ((value - low) / range).clamp(0.0, 1.0)
        } else {
            0.5
        };
        [result, low, high, mean]
            .into_iter()
            .map(|x| [R::c(x); 3])
            .collect()
    }
}

impl Catalogue for AutoLevels {
    fn menu() -> Vec<(String, Self)> {
        vec![("Auto levels".into(), AutoLevels)]
    }
    fn examples() -> Vec<Self> {
        vec![AutoLevels]
    }
}

/// Substance's histogram scan: a ramp from 0 to 1, `1 − contrast` wide, sweeps the
/// input's [0, 1] as `position` goes from 0 (all black) to 1 (all white) — a mask from
/// a height or a grunge, harder as contrast rises.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HistogramScan;

impl Definition for HistogramScan {
    computed_in!(Category::Math, unchecked);
    fn title(&self) -> &'static str {
        "Histogram scan"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["threshold", "levels", "contrast", "mask", "cutoff"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("value", FLOAT, REQUIRED),
                input("position", FLOAT, f(0.5)).limits(0.0, 1.0),
                input("contrast", FLOAT, f(0.5)).limits(0.0, 1.0),
            ],
            vec![output("result", FLOAT)],
        )
    }
    fn emit(&self, io: &mut Emit) {
        io.call("veneer_histogram_scan");
    }
    fn ranges(&self, _: &mut Ranges) -> Vec<Lanes> {
        super::unit_range()
    }
}

impl Evaluate for HistogramScan {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        vec![splat_lanes(ranges::histogram_scan(
            io.float("value"),
            io.float("position"),
            io.float("contrast"),
        ))]
    }
}

plain_catalogue!(HistogramScan);
