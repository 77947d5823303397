//! What a graph declares besides its nodes and wires — its groups' names and pins, its
//! exposed parameters and its parameter presets — checked before its groups are
//! inlined, each problem naming the group, parameter or preset.

use super::check::CheckError;
use super::group::GroupDef;
use super::names::{file_name_part, shown};
use super::parameters::{ByName, Given, MAX_PARAMETERS};
use super::{Graph, MAX_TEXT_CHARS, Value, ValueType, clip};
use crate::messages::thousands;
use std::collections::HashSet;

/// Everything wrong with what `graph` declares; `parameters` are the parameters it
/// exposes.
pub(super) fn problems(graph: &Graph, parameters: &ByName) -> Vec<CheckError> {
    let mut problems = Vec::new();
    let mut nodes = Vec::new();
    for (name, definition) in &graph.groups {
        group_problems(name, definition, &mut problems);
    }
    parameter_problems(graph, parameters, &mut problems, &mut nodes);
    for (name, values) in &graph.presets {
        let preset = format!("preset '{}'", shown(name));
        if let Err(problem) = file_name_part("preset", name) {
            problems.push(problem);
        }
        if parameters.list().len() > MAX_PARAMETERS {
            continue;
        }
        for (parameter, value) in values {
            let checked = parameters
                .find(parameter)
                .and_then(|entry| entry.value_of(&Given::of(value)));
            if let Err(error) = checked {
                problems.push(format!("{preset}: {error}"));
            }
        }
    }
    let mut errors: Vec<CheckError> = problems
        .into_iter()
        .map(|message| CheckError {
            node: None,
            node_name: None,
            message,
        })
        .collect();
    errors.append(&mut nodes);
    errors
}

/// What is wrong with group `name`: its name, repeated or overlong pin names, and
/// inputs whose default does not fit their type or range.
fn group_problems(name: &str, definition: &GroupDef, problems: &mut Vec<String>) {
    if let Err(problem) = file_name_part("group", name) {
        problems.push(problem);
    }
    let group = format!("group '{}'", shown(name));
    let inputs = definition.inputs.iter().map(|input| input.name.as_str());
    let outputs = definition.outputs.iter().map(|output| output.name.as_str());
    for (side, names) in [
        ("input", inputs.collect::<Vec<_>>()),
        ("output", outputs.collect()),
    ] {
        let mut seen = HashSet::new();
        for pin in names {
            if clip(pin, MAX_TEXT_CHARS).1 {
                problems.push(format!(
                    "{group}: an {side} name is {} characters long (at most {MAX_TEXT_CHARS})",
                    thousands(pin.chars().count())
                ));
            } else if !seen.insert(pin) {
                problems.push(format!("{group} has two {side}s named '{}'", shown(pin)));
            }
        }
    }
    for input in &definition.inputs {
        let what = format!("{group} input '{}'", shown(&input.name));
        let default = input.default;
        if !default.ty().converts_to(input.ty) {
            problems.push(format!(
                "{what} is a {} but its default is a {}",
                input.ty,
                default.ty()
            ));
        } else if let Some(problem) = beyond_f32(&default) {
            problems.push(format!("{what}: the default {problem}"));
        } else if let Some(problem) = input.range.and_then(range_problem) {
            problems.push(format!("{what}: the range {problem}"));
        } else if let Some((min, max)) = input.range
            && let Some(outside) = components(&default, input.ty)
                .into_iter()
                .find(|x| !(min..=max).contains(x))
        {
            problems.push(format!(
                "{what}: the default {outside} is outside its range, {min} to {max}"
            ));
        }
    }
}

/// Exposed parameters past [`MAX_PARAMETERS`], that name no input of the graph (in
/// `at_nodes`, naming the node) or a name twice, or whose range is no range.
fn parameter_problems(
    graph: &Graph,
    parameters: &ByName,
    problems: &mut Vec<String>,
    at_nodes: &mut Vec<CheckError>,
) {
    if graph.parameters.len() > MAX_PARAMETERS || parameters.list().len() > MAX_PARAMETERS {
        problems.push(format!(
            "the graph exposes more than {} parameters (its parameter list and the unwired \
             inputs of its group nodes), the most a uniform block holds",
            thousands(MAX_PARAMETERS)
        ));
        return;
    }
    let nodes = super::parameters::first_of_each_id(graph);
    let wired: HashSet<(super::NodeId, &str)> = graph
        .wires
        .iter()
        .map(|wire| (wire.to.node, wire.to.pin.as_str()))
        .collect();
    let mut names = HashSet::new();
    for parameter in &graph.parameters {
        let name = shown(&parameter.name);
        if !names.insert(parameter.name.as_str()) {
            problems.push(format!("two parameters are named '{name}'"));
        }
        if let Some(problem) = parameter.range.and_then(range_problem) {
            problems.push(format!("parameter '{name}': the range {problem}"));
        }
        let Some(node) = nodes.get(&parameter.node) else {
            problems.push(format!(
                "parameter '{name}' exposes node #{}, which the graph does not have",
                parameter.node.0
            ));
            continue;
        };
        let problem = if node.kind.signature().input(&parameter.pin).is_none() {
            Some("which the node does not have")
        } else if wired.contains(&(node.id, parameter.pin.as_str())) {
            Some("which a wire feeds (a wired input takes no value)")
        } else {
            None
        };
        if let Some(problem) = problem {
            at_nodes.push(CheckError {
                node: Some(node.id),
                node_name: Some(node.to_string()),
                message: format!(
                    "parameter '{name}' exposes input '{}', {problem}",
                    shown(&parameter.pin)
                ),
            });
        }
    }
}

/// What is wrong with range `(min, max)`, if anything.
fn range_problem((min, max): (f64, f64)) -> Option<String> {
    if !(min.is_finite() && max.is_finite()) {
        Some(format!("({min}, {max}) is not finite"))
    } else if min > max {
        Some(format!("({min}, {max}) has its minimum above its maximum"))
    } else {
        None
    }
}

/// Why `value` cannot be computed with in f32, if it cannot.
fn beyond_f32(value: &Value) -> Option<&'static str> {
    if !value.is_finite() {
        Some("is not finite")
    } else if value
        .components()
        .iter()
        .any(|c| c.abs() > f64::from(f32::MAX))
    {
        Some("is beyond the f32 range (±3.4e38) that shaders compute in")
    } else {
        None
    }
}

/// The components of `value` as type `ty` has them.
fn components(value: &Value, ty: ValueType) -> Vec<f64> {
    value.convert(ty).components()[..ty.width()].to_vec()
}
