//! Cellular noise: Worley's feature distances, one octave or fractal.

use super::cpu::Eval;
use super::emit::Emit;
use super::formulas::real::{Real, V3, finite, scale, splat};
use super::formulas::{noise, shapes, worley_edge};
use super::interval::{self, Interval, Lanes};
use super::pins::{FLOAT, InputPin, POINT, SCALE, Signature, f, input, output};
use super::ranges::Ranges;
use super::settings::{
    Basis, FEATURE_POINTS, FeaturePoints, METRICS, Metric, Setting, WORLEY_FEATURES, WorleyFeature,
    check_period, choice, no_period, period, period_setting,
};
use super::{Catalogue, Category, Configure, Definition, Evaluate};
use serde::{Deserialize, Serialize};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather
            [$($units)* (WorleyEdge, cellular)]
            [$($configured)* (Worley, cellular)]
            $($rest)*);
    };
}
pub(super) use kinds;

/// How far feature points stray from their cell centres (0: a regular grid).
const JITTER: InputPin = input("jitter", FLOAT, f(1.0)).limits(0.0, 1.0);

/// The integer the WGSL library uses for a Worley feature.
pub fn worley_feature_index(feature: WorleyFeature) -> i32 {
    match feature {
        WorleyFeature::F1 => 0,
        WorleyFeature::F2 => 1,
        WorleyFeature::F3 => 2,
        WorleyFeature::F2MinusF1 => 3,
    }
}

/// The integer the WGSL library uses for a distance metric.
pub fn metric_index(metric: Metric) -> i32 {
    match metric {
        Metric::Euclidean => 0,
        Metric::Manhattan => 1,
        Metric::Chebyshev => 2,
    }
}

/// Cellular (Worley) noise; more than one octave makes it fractal.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Worley {
    pub feature: WorleyFeature,
    pub metric: Metric,
    pub octaves: u32,
    /// How many cells the noise repeats over along x, y and z (0: it never repeats);
    /// each octave spans a whole number of cells over it. Graph files leave it out
    /// when 0.
    #[serde(default, skip_serializing_if = "no_period")]
    pub period: u32,
    /// Where each cell's feature point lies; graph files leave it out when hashed.
    #[serde(default, skip_serializing_if = "FeaturePoints::is_hashed")]
    pub points: FeaturePoints,
}

/// The thesis's `noiseScale`: how far simplex noise moves each feature point along
/// (1, 1, 1), in cells (C.5 uses 2.2).
const NOISE_SCALE: InputPin = input("jitter", FLOAT, f(1.0)).soft(0.0, 4.0);

impl Definition for Worley {
    fn title(&self) -> &'static str {
        "Worley"
    }
    fn category(&self) -> Category {
        Category::Cellular
    }
    fn keywords(&self) -> &'static [&'static str] {
        &[
            "voronoi", "cells", "cellular", "crackle", "stones", "seamless", "tileable",
        ]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                POINT,
                SCALE,
                match self.points {
                    FeaturePoints::Hashed => JITTER,
                    FeaturePoints::Simplex => NOISE_SCALE,
                },
                input("lacunarity", FLOAT, f(2.0)).soft(1.0, 4.0),
                input("gain", FLOAT, f(0.5)).limits(0.0, 1.0),
            ],
            vec![output("value", FLOAT)],
        )
    }
    fn reads_surface(&self) -> bool {
        false
    }
    fn basis(&self) -> Option<Basis> {
        None
    }
    fn check(&self) -> Option<String> {
        super::fractal::check_octaves(self.octaves)
            .or_else(|| check_period(self.period, None))
            .or_else(|| {
                (self.period > 0 && self.points == FeaturePoints::Simplex).then(|| {
                    "simplex feature points (the thesis's) do not repeat: set the period to 0 or use hashed points".to_string()
                })
            })
    }
    fn emit(&self, io: &mut Emit) {
        let feature = worley_feature_index(self.feature);
        let metric = metric_index(self.metric);
        let (p, scale, jitter) = (io.input("p"), io.input("scale"), io.input("jitter"));
        // A periodic noise's functions end in `_periodic` and take the period last; the
        // thesis's feature points have functions of their own (and no period).
        let (suffix, period) = match (self.points, period(self.period)) {
            (FeaturePoints::Simplex, _) => ("_simplex", String::new()),
            (FeaturePoints::Hashed, None) => ("", String::new()),
            (FeaturePoints::Hashed, Some(cells)) => ("_periodic", format!(", {cells}i")),
        };
        let expression = if self.octaves == 1 {
            io.uses(&format!("veneer_worley{suffix}"));
            io.uses("veneer_worley_feature");
            format!(
                "veneer_worley_feature(veneer_worley{suffix}({p} * {scale}, {jitter}, {metric}{period}), {feature})"
            )
        } else {
            // `veneer_CELLS_fractal` in the library, the periodic one apart.
            let fractal = match self.points {
                FeaturePoints::Simplex => "veneer_worley_simplex_fractal".to_string(),
                FeaturePoints::Hashed => format!("veneer_worley_fractal{suffix}"),
            };
            io.uses(&fractal);
            format!(
                "{fractal}({p} * {scale}, {jitter}, {metric}, {feature}, {}, {}, {}{period})",
                self.octaves,
                io.input("lacunarity"),
                io.input("gain")
            )
        };
        io.single(expression);
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        let octaves = self.octaves as i32;
        let finest = io
            .float("lacunarity")
            .magnitude()
            .max(1.0)
            .powi(octaves - 1);
        let magnitude = io.reach("p") * io.float("scale").magnitude() * finest;
        io.lattice(None, magnitude);
        let gain = io.float("gain").magnitude();
        let sum: f64 = (0..octaves).map(|k| gain.powi(k)).sum();
        // Within 2 cells of a point in Manhattan distance per axis, plus how far the
        // thesis's points stray.
        let farthest = match self.points {
            FeaturePoints::Hashed => 3.0,
            FeaturePoints::Simplex => 3.0 * (2.0 + io.float("jitter").magnitude()),
        };
        vec![interval::splat(Interval::new(0.0, farthest * sum))]
    }
}

impl Evaluate for Worley {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let feature = worley_feature_index(self.feature);
        let p = scale(io.input("p"), io.float("scale"));
        let jitter = io.float("jitter");
        let period = period(self.period);
        let octave = |q: V3<R>, period| {
            let distances = match self.points {
                FeaturePoints::Hashed => noise::worley(q, jitter, self.metric, period),
                FeaturePoints::Simplex => noise::worley_simplex(q, jitter, self.metric),
            };
            shapes::worley_feature(distances, feature)
        };
        if self.octaves == 1 {
            return vec![splat(octave(p, period))];
        }
        // A periodic octave spans a whole number of cells over the period.
        let sample = |frequency: R| match period {
            None => octave(scale(p, frequency), None),
            Some(n) => {
                let cells = noise::octave_period(n, frequency, 1);
                let ratio = R::c(f64::from(cells)) / R::c(f64::from(n));
                octave(scale(p, ratio), Some(cells))
            }
        };
        let (lacunarity, gain) = (io.float("lacunarity"), io.float("gain"));
        let (mut sum, mut amplitude, mut frequency) = (R::c(0.0), R::c(1.0), R::c(1.0));
        for _ in 0..self.octaves {
            sum = finite(sum + amplitude * sample(frequency));
            frequency = finite(frequency * lacunarity);
            amplitude = finite(amplitude * gain);
        }
        vec![splat(sum)]
    }
}

impl Configure for Worley {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        vec![
            choice("feature", &mut self.feature, &WORLEY_FEATURES),
            choice("metric", &mut self.metric, &METRICS),
            Setting::Count {
                label: "octaves",
                value: &mut self.octaves,
                range: 1..=8,
            },
            period_setting(&mut self.period),
            choice("points", &mut self.points, &FEATURE_POINTS),
        ]
    }
}

impl Catalogue for Worley {
    fn menu() -> Vec<(String, Self)> {
        vec![
            (
                "Worley".into(),
                Worley {
                    feature: WorleyFeature::F1,
                    metric: Metric::Euclidean,
                    octaves: 1,
                    period: 0,
                    points: FeaturePoints::Hashed,
                },
            ),
            (
                "Worley, fractal".into(),
                Worley {
                    feature: WorleyFeature::F2MinusF1,
                    metric: Metric::Euclidean,
                    octaves: 3,
                    period: 0,
                    points: FeaturePoints::Hashed,
                },
            ),
        ]
    }
    /// Every feature and metric; one and three octaves, infinite and repeating; the
    /// thesis's feature points with one and three octaves.
    fn examples() -> Vec<Self> {
        let hashed = WORLEY_FEATURES
            .into_iter()
            .zip(METRICS.into_iter().cycle())
            .zip([(1, 0), (1, 5), (1, 0), (3, 0)])
            .chain([((WorleyFeature::F2MinusF1, Metric::Euclidean), (3, 4))])
            .map(|((feature, metric), (octaves, period))| Worley {
                feature,
                metric,
                octaves,
                period,
                points: FeaturePoints::Hashed,
            });
        let simplex =
            [(WorleyFeature::F1, 3), (WorleyFeature::F2MinusF1, 1)].map(|(feature, octaves)| {
                Worley {
                    feature,
                    metric: Metric::Euclidean,
                    octaves,
                    period: 0,
                    points: FeaturePoints::Simplex,
                }
            });
        hashed.chain(simplex).collect()
    }
}

/// The distance to the nearest border between Worley cells (Quilez's two-pass Voronoi
/// edges over the same PCG feature points as [`Worley`]): 0 on a border, growing
/// towards the cell's feature point. Not F2 − F1, which only approximates it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorleyEdge;

impl Definition for WorleyEdge {
    computed_in!(Category::Cellular, unchecked);
    fn title(&self) -> &'static str {
        "Voronoi distance to edge"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &[
            "worley", "voronoi", "cells", "border", "cracks", "mortar", "edges",
        ]
    }
    fn signature(&self) -> Signature {
        Signature::new(vec![POINT, SCALE, JITTER], vec![output("distance", FLOAT)])
    }
    fn emit(&self, io: &mut Emit) {
        io.single(format!(
            "veneer_worley_edge({} * {}, {})",
            io.input("p"),
            io.input("scale"),
            io.input("jitter")
        ));
        io.uses("veneer_worley_edge");
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        io.sampled(None);
        vec![interval::splat(Interval::UNIT)]
    }
}

impl Evaluate for WorleyEdge {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let p = scale(io.input("p"), io.float("scale"));
        vec![splat(worley_edge::worley_edge(p, io.float("jitter")))]
    }
}

plain_catalogue!(WorleyEdge);
