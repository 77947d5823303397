//! Colour: ramps from a factor to a colour.

use super::cpu::Eval;
use super::emit::{Emit, float_literal, value_literal};
use super::formulas::real::{Real, V3};
use super::formulas::shapes;
use super::interval::{Interval, Lanes};
use super::pins::{COLOR, FLOAT, REQUIRED, Signature, input, output};
use super::ranges::Ranges;
use super::settings::{Basis, MAX_RAMP_STOPS, RampInterpolation, RampStop, Setting};
use super::value::Value;
use super::{Catalogue, Category, Configure, Definition, Evaluate};
use serde::{Deserialize, Serialize};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather [$($units)*] [$($configured)* (ColorRamp, colour)] $($rest)*);
    };
}
pub(super) use kinds;

/// A colour ramp over a factor, with several stops.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct ColorRamp {
    pub stops: Vec<RampStop>,
    pub interpolation: RampInterpolation,
}

impl ColorRamp {
    fn color(&self, k: usize) -> String {
        let (r, g, b) = self.stops[k].color;
        value_literal(&Value::Color(r, g, b))
    }
}

impl Definition for ColorRamp {
    fn title(&self) -> &'static str {
        "Colour ramp"
    }
    computed_in!(Category::Colour);
    fn keywords(&self) -> &'static [&'static str] {
        &["color ramp", "gradient", "lookup", "palette", "valtorgb"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![input("factor", FLOAT, REQUIRED)],
            vec![output("color", COLOR)],
        )
    }
    fn check(&self) -> Option<String> {
        let stops = &self.stops;
        if stops.is_empty() {
            Some("a colour ramp needs at least one stop".into())
        } else if stops.len() > MAX_RAMP_STOPS {
            Some(format!(
                "the colour ramp has {} stops (at most {MAX_RAMP_STOPS})",
                crate::messages::thousands(stops.len())
            ))
        } else if stops.iter().any(|s| {
            !s.position.is_finite()
                || ![s.color.0, s.color.1, s.color.2]
                    .iter()
                    .all(|c| c.is_finite())
        }) {
            Some("colour ramp stops must be finite".into())
        } else if stops
            .windows(2)
            .any(|pair| pair[1].position < pair[0].position)
        {
            Some("colour ramp stops must be sorted by position".into())
        } else {
            None
        }
    }
    fn emit(&self, io: &mut Emit) {
        if self.stops.len() == 1 {
            io.single(self.color(0));
            return;
        }
        let (name, factor) = (io.name(), io.input("factor"));
        io.var("vec3f", self.color(0));
        for k in 1..self.stops.len() {
            let (p0, p1) = (
                float_literal(self.stops[k - 1].position),
                float_literal(self.stops[k].position),
            );
            let color = self.color(k);
            io.statement(match self.interpolation {
                RampInterpolation::Linear => {
                    format!("{name} = veneer_ramp_linear({name}, {color}, {factor}, {p0}, {p1});")
                }
                RampInterpolation::Constant => {
                    format!("{name} = veneer_ramp_constant({name}, {color}, {factor}, {p1});")
                }
            });
        }
        io.uses(match self.interpolation {
            RampInterpolation::Linear => "veneer_ramp_linear",
            RampInterpolation::Constant => "veneer_ramp_constant",
        });
    }
    fn ranges(&self, _: &mut Ranges) -> Vec<Lanes> {
        let hull = |k: usize| {
            self.stops
                .iter()
                .map(|s| [s.color.0, s.color.1, s.color.2][k])
                .fold(Interval::new(f64::INFINITY, f64::NEG_INFINITY), |h, c| {
                    h.hull(Interval::point(c))
                })
        };
        vec![[hull(0), hull(1), hull(2)]]
    }
}

impl Evaluate for ColorRamp {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let t = io.float("factor");
        let mut color = shapes::color(self.stops[0].color);
        for pair in self.stops.windows(2) {
            let next = shapes::color(pair[1].color);
            color = match self.interpolation {
                RampInterpolation::Linear => shapes::mix3(
                    color,
                    next,
                    shapes::linearstep(R::c(pair[0].position), R::c(pair[1].position), t),
                ),
                RampInterpolation::Constant if t >= R::c(pair[1].position) => next,
                RampInterpolation::Constant => color,
            };
        }
        vec![color]
    }
}

impl Configure for ColorRamp {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        vec![Setting::Ramp {
            stops: &mut self.stops,
            interpolation: &mut self.interpolation,
        }]
    }
}

fn stop(position: f64, color: (f64, f64, f64)) -> RampStop {
    RampStop { position, color }
}

impl Catalogue for ColorRamp {
    fn menu() -> Vec<(String, Self)> {
        vec![(
            "Colour ramp".into(),
            ColorRamp {
                stops: vec![stop(0.0, (0.05, 0.05, 0.05)), stop(1.0, (0.95, 0.95, 0.95))],
                interpolation: RampInterpolation::Linear,
            },
        )]
    }
    fn examples() -> Vec<Self> {
        vec![
            ColorRamp {
                stops: vec![
                    stop(0.2, (0.9, 0.1, 0.1)),
                    stop(0.5, (0.1, 0.8, 0.2)),
                    stop(0.5, (0.2, 0.2, 0.9)),
                    stop(0.9, (1.0, 1.0, 0.3)),
                ],
                interpolation: RampInterpolation::Linear,
            },
            ColorRamp {
                stops: vec![stop(0.3, (0.1, 0.2, 0.3)), stop(0.6, (0.7, 0.5, 0.1))],
                interpolation: RampInterpolation::Constant,
            },
        ]
    }
}
