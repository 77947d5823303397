//! Colour: ramps from a factor to a colour, adjustments (hue/saturation/value,
//! brightness/contrast, gamma, invert, levels) and blend modes, as Blender's colour
//! nodes compute them.

use super::cpu::Eval;
use super::emit::{Emit, float_literal, value_literal};
use super::formulas::real::{Real, V3};
use super::formulas::{colour, shapes};
use super::interval::{self, Interval, Lanes};
use super::pins::{COLOR, FLOAT, REQUIRED, Signature, f, input, output, rgb};
use super::ranges::Ranges;
use super::settings::{Basis, MAX_RAMP_STOPS, RampInterpolation, RampStop, Setting, choice};
use super::value::Value;
use super::{Catalogue, Category, Configure, Definition, Evaluate};
use serde::{Deserialize, Serialize};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather
            [$($units)* (HueSaturationValue, colour) (BrightnessContrast, colour) (Gamma, colour)
                (Invert, colour) (Levels, colour)]
            [$($configured)* (ColorRamp, colour) (Blend, colour)]
            $($rest)*);
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
    /// The gradient, sampled through the node's own CPU evaluation so that it shows
    /// exactly what the shader computes, with a tick at each stop.
    fn body(&self) -> Option<super::Body<'_>> {
        let pins = self.signature().inputs;
        let colour = move |factor: f64| {
            let surface = super::cpu::Surface::<f64>::at([0.0; 3]);
            let inputs = [[factor; 3]];
            super::Evaluate::eval(self, &super::cpu::Eval::new(&pins, &inputs, &surface))[0]
        };
        Some(super::Body::Gradient {
            colour: Box::new(colour),
            ticks: self.stops.iter().map(|stop| stop.position).collect(),
        })
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
        } else if let Some((k, value)) = stops.iter().enumerate().find_map(|(k, s)| {
            [s.position, s.color.0, s.color.1, s.color.2]
                .into_iter()
                .find(|x| x.abs() > f64::from(f32::MAX))
                .map(|x| (k, x))
        }) {
            Some(format!(
                "colour ramp stop {k} holds {value:e}, beyond the f32 range (±3.4e38) that \
                 shaders compute in"
            ))
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

/// Every lane of `a` and `b` within [0, 1].
fn in_unit(lanes: &[Lanes]) -> bool {
    lanes
        .iter()
        .flatten()
        .all(|lane| lane.lo >= 0.0 && lane.hi <= 1.0)
}

/// The largest magnitude of any lane.
fn magnitude(lanes: &[Lanes]) -> f64 {
    lanes
        .iter()
        .flatten()
        .fold(0.0f64, |m, lane| m.max(lane.magnitude()))
}

/// ±`bound` in every lane, capped at the finite f32 range the shaders clamp to.
fn within(bound: f64) -> Lanes {
    let bound = bound.min(3.0e38);
    interval::splat(Interval::new(-bound, bound))
}

/// A colour adjustment: a library function of the colour and then its parameters, in
/// pin order, with its CPU twin and output range.
macro_rules! adjustment {
    ($(#[$doc:meta])* $kind:ident, $title:literal, [$($keyword:literal),*], $function:literal,
     [$($pin:expr),*], |$io:ident| $cpu:expr, |$ranges:ident| $range:expr) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct $kind;

        impl Definition for $kind {
            computed_in!(Category::Colour, unchecked);
            fn title(&self) -> &'static str {
                $title
            }
            fn keywords(&self) -> &'static [&'static str] {
                &[$($keyword),*]
            }
            fn signature(&self) -> Signature {
                Signature::new(
                    vec![input("color", COLOR, rgb(0.5, 0.5, 0.5)).limits(0.0, 1.0), $($pin),*],
                    vec![output("color", COLOR)],
                )
            }
            fn emit(&self, io: &mut Emit) {
                io.call($function);
            }
            fn ranges(&self, $ranges: &mut Ranges) -> Vec<Lanes> {
                vec![$range]
            }
        }

        impl Evaluate for $kind {
            fn eval<R: Real>(&self, $io: &Eval<R>) -> Vec<V3<R>> {
                vec![$cpu]
            }
        }

        plain_catalogue!($kind);
    };
}

adjustment!(
    /// Blender's Hue/Saturation/Value: the hue turned by `hue` turns (0 leaves it), the
    /// saturation and value scaled, blended over the input by `factor`.
    HueSaturationValue, "Hue/Saturation/Value", ["hsv", "hue", "saturation", "tint", "colour correction"],
    "veneer_hue_saturation_value_mix",
    [
        input("hue", FLOAT, f(0.0)).soft(-0.5, 0.5),
        input("saturation", FLOAT, f(1.0)).soft(0.0, 2.0),
        input("value", FLOAT, f(1.0)).soft(0.0, 2.0),
        input("factor", FLOAT, f(1.0)).limits(0.0, 1.0)
    ],
    |io| colour::hue_saturation_value_mix(
        io.input("color"),
        io.float("hue"),
        io.float("saturation"),
        io.float("value"),
        io.float("factor"),
    ),
    |io| {
        let color = io.input("color");
        let scaled = magnitude(&[color]) * io.float("value").magnitude();
        within(scaled.max(magnitude(&[color])))
    }
);

adjustment!(
    /// Blender's Brightness/Contrast: `max((1 + contrast) c + brightness - contrast / 2, 0)`.
    BrightnessContrast, "Brightness/Contrast", ["bright", "contrast", "exposure", "colour correction"],
    "veneer_brightness_contrast",
    [
        input("brightness", FLOAT, f(0.0)).soft(-1.0, 1.0),
        input("contrast", FLOAT, f(0.0)).soft(-1.0, 1.0)
    ],
    |io| colour::brightness_contrast(io.input("color"), io.float("brightness"), io.float("contrast")),
    |io| {
        let (brightness, contrast) = (io.float("brightness"), io.float("contrast"));
        let offset = brightness.sub(contrast.mul(Interval::point(0.5)));
        io.input("color").map(|c| {
            let y = c.mul(contrast.add(Interval::point(1.0))).add(offset);
            Interval::new(y.lo.max(0.0), y.hi.clamp(0.0, 3.0e38))
        })
    }
);

adjustment!(
    /// Blender's Gamma: each positive channel raised to `gamma`.
    Gamma, "Gamma", ["power", "curve", "midtones", "colour correction"],
    "veneer_gamma",
    [input("gamma", FLOAT, f(1.0)).soft(0.1, 4.0)],
    |io| colour::gamma(io.input("color"), io.float("gamma")),
    |io| {
        let gamma = io.float("gamma");
        io.input("color").map(|c| {
            let raised = super::math::power_range(c, gamma);
            Interval::new(c.lo.min(raised.lo), c.hi.max(raised.hi))
        })
    }
);

adjustment!(
    /// Blender's Invert: the colour blended towards `1 - colour` by `factor`.
    Invert, "Invert", ["negative", "complement", "one minus", "colour"],
    "veneer_invert",
    [input("factor", FLOAT, f(1.0)).limits(0.0, 1.0)],
    |io| colour::invert(io.input("color"), io.float("factor")),
    |io| io.input("color").map(|c| c.hull(Interval::new(1.0 - c.hi, 1.0 - c.lo)))
);

adjustment!(
    /// Levels (Photoshop, Substance): each channel's place between the input black and
    /// white points, curved by `gamma` (above 1 brightens the midtones), carried to the
    /// output black and white points.
    Levels, "Levels", ["input range", "output range", "black point", "white point", "colour correction"],
    "veneer_levels",
    [
        input("in_black", FLOAT, f(0.0)).limits(0.0, 1.0),
        input("in_white", FLOAT, f(1.0)).limits(0.0, 1.0),
        input("gamma", FLOAT, f(1.0)).soft(0.1, 4.0),
        input("out_black", FLOAT, f(0.0)).limits(0.0, 1.0),
        input("out_white", FLOAT, f(1.0)).limits(0.0, 1.0)
    ],
    |io| colour::levels(
        io.input("color"),
        io.float("in_black"),
        io.float("in_white"),
        io.float("gamma"),
        io.float("out_black"),
        io.float("out_white"),
    ),
    |io| interval::splat(io.float("out_black").hull(io.float("out_white")))
);

/// How [`Blend`] combines two colours (Blender's MixRGB modes).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum BlendMode {
    Multiply,
    Screen,
    Overlay,
    SoftLight,
    Difference,
}

impl BlendMode {
    /// Every mode, in menu order.
    pub const ALL: [BlendMode; 5] = [
        BlendMode::Multiply,
        BlendMode::Screen,
        BlendMode::Overlay,
        BlendMode::SoftLight,
        BlendMode::Difference,
    ];

    /// The suffix of the mode's WGSL function (`veneer_blend_<suffix>`).
    fn suffix(self) -> &'static str {
        match self {
            BlendMode::Multiply => "multiply",
            BlendMode::Screen => "screen",
            BlendMode::Overlay => "overlay",
            BlendMode::SoftLight => "soft_light",
            BlendMode::Difference => "difference",
        }
    }
}

/// Two colours combined by a blend mode, blended over the first by `factor`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Blend {
    pub mode: BlendMode,
}

impl Definition for Blend {
    computed_in!(Category::Colour, unchecked);
    fn title(&self) -> &'static str {
        "Blend"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &[
            "mix rgb",
            "multiply",
            "screen",
            "overlay",
            "soft light",
            "difference",
            "layer",
        ]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("a", COLOR, rgb(0.5, 0.5, 0.5)).limits(0.0, 1.0),
                input("b", COLOR, rgb(0.5, 0.5, 0.5)).limits(0.0, 1.0),
                input("factor", FLOAT, f(1.0)).limits(0.0, 1.0),
            ],
            vec![output("color", COLOR)],
        )
    }
    fn emit(&self, io: &mut Emit) {
        io.call(&format!("veneer_blend_{}", self.mode.suffix()));
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        let colours = [io.input("a"), io.input("b")];
        if in_unit(&colours) {
            return vec![interval::splat(Interval::UNIT)];
        }
        // |(1 - 2b) a² + 2ab| and the other modes stay below 3 (1 + m)³.
        vec![within(3.0 * (1.0 + magnitude(&colours)).powi(3))]
    }
}

impl Evaluate for Blend {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let blend = match self.mode {
            BlendMode::Multiply => colour::blend_multiply,
            BlendMode::Screen => colour::blend_screen,
            BlendMode::Overlay => colour::blend_overlay,
            BlendMode::SoftLight => colour::blend_soft_light,
            BlendMode::Difference => colour::blend_difference,
        };
        vec![blend(io.input("a"), io.input("b"), io.float("factor"))]
    }
}

impl Configure for Blend {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        vec![choice("mode", &mut self.mode, &BlendMode::ALL)]
    }
}

impl Catalogue for Blend {
    fn menu() -> Vec<(String, Self)> {
        BlendMode::ALL
            .into_iter()
            .map(|mode| (format!("Blend ({mode:?})"), Blend { mode }))
            .collect()
    }
    fn examples() -> Vec<Self> {
        BlendMode::ALL
            .into_iter()
            .map(|mode| Blend { mode })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nodes::Body;
    use crate::nodes::settings::{MathOp, RampInterpolation, RampStop};

    #[test]
    fn a_ramp_declares_its_gradient_with_a_tick_at_each_stop() {
        let stop = |position, color| RampStop { position, color };
        let ramp = ColorRamp {
            stops: vec![stop(0.2, (1.0, 0.0, 0.0)), stop(0.8, (0.0, 0.0, 1.0))],
            interpolation: RampInterpolation::Linear,
        };
        let Some(Body::Gradient { colour, ticks }) = ramp.body() else {
            panic!("a colour ramp shows its gradient");
        };
        assert_eq!(ticks, [0.2, 0.8]);
        assert_eq!(colour(0.0), [1.0, 0.0, 0.0]);
        assert_eq!(colour(1.0), [0.0, 0.0, 1.0]);
        let middle = colour(0.5);
        assert!((middle[0] - 0.5).abs() < 1e-9 && (middle[2] - 0.5).abs() < 1e-9);
        let math = crate::nodes::Math {
            op: MathOp::Divide,
            ty: crate::graph::ValueType::Float,
        };
        assert_eq!(math.shown_title(), "Divide");
        assert_eq!(ramp.shown_title(), "Colour ramp");
    }
}
