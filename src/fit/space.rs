//! What a fit adjusts: the continuous lanes of a graph's exposed parameters (floats,
//! vectors, colours), each mapped to [0, 1] over its range so that one step size suits
//! them all.

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

/// The coordinates a fit moves and the parameters' values it starts from.
#[derive(Clone, Debug)]
pub struct Space {
    pub coordinates: Vec<Coordinate>,
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
    /// A named parameter that is not continuous (a toggle or a choice).
    NotContinuous(String),
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
            SpaceError::NotContinuous(name) => write!(
                f,
                "parameter '{name}' is a toggle or a choice, which a fit does not move"
            ),
            SpaceError::Unseen(name) => write!(
                f,
                "parameter '{name}' does not reach the albedo, which is what a fit compares with the photo"
            ),
            SpaceError::Nothing => f.write_str(
                "the graph exposes no continuous parameter (float, vector or colour) that reaches the albedo, to fit",
            ),
        }
    }
}

/// Whether a parameter is moved continuously (not a toggle or a choice).
fn continuous(parameter: &Exposed) -> bool {
    matches!(parameter.hint, Hint::Slider | Hint::Colour)
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
    /// The space of `parameters` (a checked graph's), all continuous ones that `seen`
    /// (the albedo reaches them) or those `only` names.
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
                    Some(parameter) if !continuous(parameter) => {
                        return Err(SpaceError::NotContinuous(name.clone()));
                    }
                    Some(parameter) if !seen(parameter) => {
                        return Err(SpaceError::Unseen(name.clone()));
                    }
                    Some(_) => {}
                }
            }
        }
        let base: Vec<V3<f64>> = parameters.iter().map(|p| p.value.components()).collect();
        let mut coordinates = Vec::new();
        for (index, parameter) in parameters.iter().enumerate() {
            let chosen = only.is_none_or(|only| only.contains(&parameter.name));
            if !chosen || !continuous(parameter) || !seen(parameter) {
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
        if coordinates.is_empty() {
            return Err(SpaceError::Nothing);
        }
        Ok(Space {
            coordinates,
            base,
            names: parameters.iter().map(|p| p.name.clone()).collect(),
        })
    }

    /// The fitted parameters' values at `places`: each moved parameter's index, name
    /// and lanes (as many as its type has).
    pub fn fitted_values(&self, places: &[f64]) -> Vec<(usize, &str, Vec<f64>)> {
        let values = self.values(places);
        (self.names.iter().enumerate())
            .filter_map(|(index, name)| {
                let width = (self.coordinates.iter())
                    .filter(|c| c.parameter == index)
                    .count();
                (width > 0).then(|| (index, name.as_str(), values[index][..width].to_vec()))
            })
            .collect()
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
