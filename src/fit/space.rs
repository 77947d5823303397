//! What a fit adjusts: the continuous lanes of a graph's exposed parameters (floats,
//! vectors, colours), each mapped to [0, 1] over its range so that one step size suits
//! them all; and its toggles and choices, searched option by option.

use crate::graph::group::Hint;
use crate::graph::parameters::Exposed;
use crate::nodes::formulas::real::{Real, V3};

/// One lane of one exposed parameter, and the span it moves in.
#[derive(Clone, Debug, PartialEq)]
pub struct Coordinate {
    /// The parameter's index in the checked graph's list.
    pub parameter: usize,
    /// Which lane of its value.
    pub lane: usize,
    pub low: f64,
    pub high: f64,
}

impl Coordinate {
    /// The value at normalised place `t` (0 the low end, 1 the high end).
    pub fn value<R: Real>(&self, t: R) -> R {
        R::c(self.low) + t * R::c(self.high - self.low)
    }

    /// The normalised place of `value`, clamped to [0, 1].
    pub fn place(&self, value: f64) -> f64 {
        ((value - self.low) / (self.high - self.low)).clamp(0.0, 1.0)
    }
}

/// A toggle or choice a fit searches: the parameter's index, and the values it may
/// take (0 and 1; each option's index).
#[derive(Clone, Debug, PartialEq)]
pub struct Discrete {
    pub parameter: usize,
    pub options: Vec<f64>,
}

/// The coordinates a fit moves, the toggles and choices it searches, and the
/// parameters' values it starts from.
#[derive(Clone, Debug)]
pub struct Space {
    pub coordinates: Vec<Coordinate>,
    pub discrete: Vec<Discrete>,
    /// Every exposed parameter's value, the fitted ones' included.
    pub base: Vec<V3<f64>>,
    /// The parameters' names, by index.
    pub names: Vec<String>,
}

/// Why a fit has nothing (or something unknown) to adjust.
#[derive(Clone, Debug, PartialEq)]
pub enum SpaceError {
    /// A parameter `--params` names that the graph does not expose.
    Unknown { name: String, exposed: Vec<String> },
    /// A named parameter that does not reach the albedo (which is what a fit compares).
    Unseen(String),
    /// No continuous parameter that reaches the albedo, to fit.
    Nothing,
}

impl std::fmt::Display for SpaceError {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        match self {
            SpaceError::Unknown { name, exposed } => write!(
                f,
                "the graph exposes no parameter '{name}' (it exposes {})",
                match exposed.is_empty() {
                    true => "none".to_string(),
                    false => exposed.join(", "),
                }
            ),
            SpaceError::Unseen(name) => write!(
                f,
                "parameter '{name}' does not reach the albedo, which is what a fit compares with the photo"
            ),
            SpaceError::Nothing => f.write_str(
                "the graph exposes no parameter (float, vector, colour, toggle or choice) that reaches the albedo, to fit",
            ),
        }
    }
}

/// The values a toggle or choice may take; `None` for a parameter moved continuously.
fn options(parameter: &Exposed) -> Option<Vec<f64>> {
    match &parameter.hint {
        Hint::Slider | Hint::Colour => None,
        Hint::Toggle => Some(vec![0.0, 1.0]),
        Hint::Choice(names) => Some((0..names.len()).map(|k| k as f64).collect()),
    }
}

/// The span a lane of `parameter` moves in: its range, [0, 1] for a colour without one,
/// else its value ± the larger of 1 and its magnitude.
fn span(parameter: &Exposed, value: f64) -> (f64, f64) {
    match (parameter.range, &parameter.hint) {
        (Some((low, high)), _) if low < high => (low, high),
        (_, Hint::Colour) => (0.0, 1.0),
        _ => {
            let reach = value.abs().max(1.0);
            (value - reach, value + reach)
        }
    }
}

impl Space {
    /// The space of `parameters` (a checked graph's), all that `seen` (the albedo
    /// reaches them) or those `only` names.
    pub fn of(
        parameters: &[Exposed],
        seen: impl Fn(&Exposed) -> bool,
        only: Option<&[String]>,
    ) -> Result<Space, SpaceError> {
        if let Some(only) = only {
            for name in only {
                match parameters.iter().find(|p| &p.name == name) {
                    None => {
                        return Err(SpaceError::Unknown {
                            name: name.clone(),
                            exposed: parameters.iter().map(|p| p.name.clone()).collect(),
                        });
                    }
                    Some(parameter) if !seen(parameter) => {
                        return Err(SpaceError::Unseen(name.clone()));
                    }
                    Some(_) => {}
                }
            }
        }
        let base: Vec<V3<f64>> = parameters.iter().map(|p| p.value.components()).collect();
        let (mut coordinates, mut discrete) = (Vec::new(), Vec::new());
        for (index, parameter) in parameters.iter().enumerate() {
            let chosen = only.is_none_or(|only| only.contains(&parameter.name));
            if !chosen || !seen(parameter) {
                continue;
            }
            if let Some(options) = options(parameter) {
                discrete.push(Discrete {
                    parameter: index,
                    options,
                });
                continue;
            }
            for (lane, &value) in base[index].iter().enumerate().take(parameter.ty.width()) {
                let (low, high) = span(parameter, value);
                coordinates.push(Coordinate {
                    parameter: index,
                    lane,
                    low,
                    high,
                });
            }
        }
        if coordinates.is_empty() && discrete.is_empty() {
            return Err(SpaceError::Nothing);
        }
        Ok(Space {
            coordinates,
            discrete,
            base,
            names: parameters.iter().map(|p| p.name.clone()).collect(),
        })
    }

    /// The fitted parameters' values at `places`: each moved or searched parameter's
    /// index, name and lanes (as many as its type has).
    pub fn fitted_values(&self, places: &[f64]) -> Vec<(usize, &str, Vec<f64>)> {
        let values = self.values(places);
        (self.names.iter().enumerate())
            .filter_map(|(index, name)| {
                let lanes = (self.coordinates.iter())
                    .filter(|c| c.parameter == index)
                    .count();
                let searched = self.discrete.iter().any(|d| d.parameter == index);
                let width = if searched { 1 } else { lanes };
                (width > 0).then(|| (index, name.as_str(), values[index][..width].to_vec()))
            })
            .collect()
    }

    /// The toggles' and choices' values now, in the order of `discrete`.
    pub fn choices(&self) -> Vec<f64> {
        (self.discrete.iter())
            .map(|d| self.base[d.parameter][0])
            .collect()
    }

    /// This space with the toggles and choices at `choices` (in the order of
    /// `discrete`).
    pub fn with_choices(&self, choices: &[f64]) -> Space {
        let mut space = self.clone();
        for (discrete, &value) in self.discrete.iter().zip(choices) {
            space.base[discrete.parameter][0] = value;
        }
        space
    }

    /// This space with its base values at `places` (a fit from there starts there).
    pub fn starting_at(&self, places: &[f64]) -> Space {
        Space {
            base: self.values(places),
            ..self.clone()
        }
    }

    /// The normalised places of the base values.
    pub fn start(&self) -> Vec<f64> {
        (self.coordinates.iter())
            .map(|c| c.place(self.base[c.parameter][c.lane]))
            .collect()
    }

    /// Every parameter's value with the coordinates at `places` (given as `R`, so they
    /// may be a fit's variables).
    pub fn values<R: Real>(&self, places: &[R]) -> Vec<V3<R>> {
        let mut values: Vec<V3<R>> = self.base.iter().map(|v| v.map(R::c)).collect();
        for (coordinate, &t) in self.coordinates.iter().zip(places) {
            values[coordinate.parameter][coordinate.lane] = coordinate.value(t);
        }
        values
    }
}
