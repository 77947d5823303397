//! Exposed parameters: the named values of a graph that stay changeable from the CLI
//! (`--set`, `--params-file`, `--preset`), the editor and engines that load an export.
//!
//! A graph exposes its [`Parameter`] entries (top-level input pins given a name) and
//! every unwired input of its group nodes, including the inputs those inherit from
//! groups nested inside (see `graph::group`).

use super::group::{self, Bindings, Hint};
use super::{Graph, NodeId, PinRef, Value, ValueType};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, HashMap, HashSet};

/// A top-level input pin exposed under a name.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Parameter {
    pub name: String,
    pub node: NodeId,
    pub pin: String,
    /// The span offered (inclusive); the pin's own span when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub range: Option<(f64, f64)>,
    #[serde(default)]
    pub hint: Hint,
}

/// One parameter a graph exposes, resolved: its type and current value.
#[derive(Clone, Debug, PartialEq)]
pub struct Exposed {
    pub name: String,
    pub ty: ValueType,
    /// The value the graph holds now (its default for engines).
    pub value: Value,
    pub range: Option<(f64, f64)>,
    pub hint: Hint,
    /// The groups it comes from, outermost first (empty for a top-level pin).
    pub group_path: Vec<String>,
    /// The top-level input that holds it.
    pub target: PinRef,
}

/// The most parameters a graph exposes: `--params uniform` makes each a member of one
/// uniform struct, which must fit the 64 KiB uniform block every device offers (a vec3
/// member takes 16 bytes).
pub const MAX_PARAMETERS: usize = 4_096;

/// The parameters `graph` exposes, in a stable order: its [`Parameter`] list, then the
/// unwired inputs of its group nodes by node id. A name taken already is qualified by
/// its node's label (`bark.scale`). At most [`MAX_PARAMETERS`] + 1: enough for the
/// check to refuse a graph that exposes more.
pub fn exposed(graph: &Graph) -> Vec<Exposed> {
    let mut list: Vec<Exposed> = Vec::new();
    let nodes = if graph.parameters.is_empty() {
        HashMap::new()
    } else {
        first_of_each_id(graph)
    };
    for parameter in graph.parameters.iter().take(MAX_PARAMETERS + 1) {
        let Some(node) = nodes.get(&parameter.node) else {
            continue;
        };
        let signature = node.kind.signature();
        let Some((_, pin)) = signature.input(&parameter.pin) else {
            continue;
        };
        let value = match (node.inputs.get(&parameter.pin), pin.default) {
            (Some(value), _) => value.convert(pin.ty),
            (None, super::PinDefault::Const(value)) => value,
            (None, _) => Value::Float(0.0).convert(pin.ty),
        };
        let range = parameter.range.or_else(|| {
            (pin.range.min.is_finite() && pin.range.max.is_finite())
                .then_some((pin.range.min, pin.range.max))
        });
        list.push(Exposed {
            name: parameter.name.clone(),
            ty: pin.ty,
            value,
            range,
            hint: parameter.hint.clone(),
            group_path: Vec::new(),
            target: PinRef::new(node.id, &parameter.pin),
        });
    }
    let interfaces = group::interfaces(&graph.groups).unwrap_or_default();
    let wired: HashSet<(NodeId, &str)> = graph
        .wires
        .iter()
        .map(|wire| (wire.to.node, wire.to.pin.as_str()))
        .collect();
    let mut taken: HashSet<String> = list.iter().map(|entry| entry.name.clone()).collect();
    let mut instances: Vec<_> = graph.nodes.iter().collect();
    instances.sort_by_key(|node| node.id);
    for node in instances {
        let Some(interface) = group::group_name(node).and_then(|name| interfaces.get(name)) else {
            continue;
        };
        for entry in &interface.inputs {
            if list.len() > MAX_PARAMETERS {
                return list;
            }
            if wired.contains(&(node.id, entry.input.name.as_str())) {
                continue;
            }
            let exposed = instance_parameter(node, entry, &taken);
            taken.insert(exposed.name.clone());
            list.push(exposed);
        }
    }
    list
}

/// The first node of each id of `graph`, as [`Graph::node`] finds it.
pub(super) fn first_of_each_id(graph: &Graph) -> HashMap<NodeId, &super::Node> {
    let mut nodes = HashMap::with_capacity(graph.nodes.len());
    for node in &graph.nodes {
        nodes.entry(node.id).or_insert(node);
    }
    nodes
}

/// Input `entry` of group node `node`, named apart from the names `taken`.
fn instance_parameter(
    node: &super::Node,
    entry: &group::InterfaceInput,
    taken: &HashSet<String>,
) -> Exposed {
    let group = group::group_name(node).unwrap_or_default();
    let pin = &entry.input.name;
    let name = if taken.contains(pin) {
        format!("{}.{pin}", node.display_name())
    } else {
        pin.clone()
    };
    let mut group_path = vec![group.to_string()];
    group_path.extend(entry.path.iter().cloned());
    Exposed {
        name,
        ty: entry.input.ty,
        value: node
            .inputs
            .get(pin)
            .map(|value| value.convert(entry.input.ty))
            .unwrap_or(entry.input.default),
        range: entry.input.range,
        hint: entry.input.hint.clone(),
        group_path,
        target: PinRef::new(node.id, pin),
    }
}

/// The flat inputs each exposed parameter starts from: `(node, pin)` → name, the seed
/// [`group::flatten_traced`] follows into the groups.
pub fn bindings(exposed: &[Exposed]) -> Bindings {
    exposed
        .iter()
        .map(|entry| {
            (
                (entry.target.node, entry.target.pin.clone()),
                entry.name.clone(),
            )
        })
        .collect()
}

/// Why a parameter could not be set.
#[derive(Debug, thiserror::Error)]
pub enum ParameterError {
    #[error("no parameter named '{name}' ({})", list(.known))]
    Unknown { name: String, known: Vec<String> },
    #[error("parameter '{name}' takes a {ty}: {problem}")]
    BadValue {
        name: String,
        ty: ValueType,
        problem: String,
    },
    #[error("parameter '{name}' takes values from {min} to {max}; {value} is outside")]
    OutOfRange {
        name: String,
        min: f64,
        max: f64,
        value: f64,
    },
    #[error("no parameter preset named '{name}' ({})", list(.known))]
    UnknownPreset { name: String, known: Vec<String> },
}

/// `names` for a message: `known: a, b` or `the graph has none`.
fn list(names: &[String]) -> String {
    if names.is_empty() {
        "the graph has none".to_string()
    } else {
        format!("known: {}", super::names::elided(names.to_vec(), ", "))
    }
}

/// A parameter value as the CLI and parameter files give it: one number, a list of
/// two or three, or a word (an option of a choice, `on`/`off` for a toggle).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Given {
    Number(f64),
    List(Vec<f64>),
    Word(String),
}

impl Given {
    /// Reads `0.7`, `0.1,0.2,0.3`, `#ff8800` (a colour in sRGB hex, stored as its
    /// 0–1 components) or a word: anything else without a comma (`geodesic`, `3D`; a
    /// slider then refuses it as not a number).
    pub fn parse(text: &str) -> Result<Given, String> {
        let text = text.trim();
        let single = !text.contains(',') && !text.starts_with('#');
        if single && text.parse::<f64>().is_err() {
            return Ok(Given::Word(text.to_string()));
        }
        if let Some(hex) = text.strip_prefix('#') {
            if hex.len() != 6 || !hex.chars().all(|c| c.is_ascii_hexdigit()) {
                return Err(format!("'{text}' is not a colour like #ff8800"));
            }
            let channel =
                |k: usize| f64::from(u8::from_str_radix(&hex[k..k + 2], 16).unwrap_or(0)) / 255.0;
            return Ok(Given::List(vec![channel(0), channel(2), channel(4)]));
        }
        let numbers = text
            .split(',')
            .map(|part| {
                part.trim()
                    .parse::<f64>()
                    .map_err(|_| format!("'{}' is not a number", part.trim()))
            })
            .collect::<Result<Vec<f64>, String>>()?;
        Ok(match numbers.as_slice() {
            [x] => Given::Number(*x),
            _ => Given::List(numbers),
        })
    }

    /// The value as type `ty` offered as `hint`: a number fills every component; a
    /// list must have the type's width; a word names an option of a choice (its index)
    /// or a toggle's state (`on`, `off`, `true`, `false`, `yes`, `no`).
    pub fn to_value(&self, ty: ValueType, hint: &Hint) -> Result<Value, String> {
        let components: Vec<f64> = match self {
            Given::Word(word) => vec![word_value(word, hint)?; ty.width()],
            Given::Number(x) => vec![*x; ty.width()],
            Given::List(list) if list.len() == ty.width() => list.clone(),
            Given::List(list) => {
                return Err(format!(
                    "{} numbers given, a {ty} has {}",
                    list.len(),
                    ty.width()
                ));
            }
        };
        if let Some(bad) = components.iter().find(|x| !x.is_finite()) {
            return Err(format!("{bad} is not a finite number"));
        }
        let c = |k: usize| components[k];
        Ok(match ty {
            ValueType::Float => Value::Float(c(0)),
            ValueType::Vec2 => Value::Vec2(c(0), c(1)),
            ValueType::Vec3 => Value::Vec3(c(0), c(1), c(2)),
            ValueType::Color => Value::Color(c(0), c(1), c(2)),
        })
    }

    /// The value's components, for a value of the graph.
    pub fn of(value: &Value) -> Given {
        match value.ty().width() {
            1 => Given::Number(value.components()[0]),
            width => Given::List(value.components()[..width].to_vec()),
        }
    }
}

/// The number a word stands for under `hint`.
fn word_value(word: &str, hint: &Hint) -> Result<f64, String> {
    match hint {
        Hint::Choice(options) => options
            .iter()
            .position(|option| option == word)
            .map(|k| k as f64)
            .ok_or_else(|| {
                format!(
                    "'{word}' is not one of its options ({})",
                    options.join(", ")
                )
            }),
        Hint::Toggle => match word.to_ascii_lowercase().as_str() {
            "on" | "true" | "yes" => Ok(1.0),
            "off" | "false" | "no" => Ok(0.0),
            _ => Err(format!("'{word}' is not on or off")),
        },
        Hint::Slider | Hint::Colour => Err(format!("'{word}' is not a number")),
    }
}

impl Exposed {
    /// `given` as this parameter's value, checked against its type and range.
    pub fn value_of(&self, given: &Given) -> Result<Value, ParameterError> {
        let value =
            given
                .to_value(self.ty, &self.hint)
                .map_err(|problem| ParameterError::BadValue {
                    name: self.name.clone(),
                    ty: self.ty,
                    problem,
                })?;
        if let Some((min, max)) = self.range
            && let Some(outside) = value.components()[..self.ty.width()]
                .iter()
                .find(|x| !(min..=max).contains(*x))
        {
            return Err(ParameterError::OutOfRange {
                name: self.name.clone(),
                min,
                max,
                value: *outside,
            });
        }
        Ok(value)
    }
}

/// A graph's exposed parameters by name, to set several of them in that graph (its
/// values may change in between, not its nodes).
pub struct ByName {
    exposed: Vec<Exposed>,
    index: HashMap<String, usize>,
    /// The position in the graph of each node a parameter is an input of.
    nodes: HashMap<NodeId, usize>,
}

impl ByName {
    /// The parameters `graph` exposes.
    pub fn of(graph: &Graph) -> ByName {
        let exposed = exposed(graph);
        let mut index = HashMap::with_capacity(exposed.len());
        let mut nodes: HashMap<NodeId, usize> = HashMap::new();
        for (k, entry) in exposed.iter().enumerate() {
            index.entry(entry.name.clone()).or_insert(k);
            nodes.insert(entry.target.node, usize::MAX);
        }
        for (position, node) in graph.nodes.iter().enumerate() {
            if let Some(slot) = nodes.get_mut(&node.id) {
                *slot = (*slot).min(position);
            }
        }
        ByName {
            exposed,
            index,
            nodes,
        }
    }

    /// The node of `graph` that parameter `entry` is an input of.
    fn node<'g>(&self, graph: &'g mut Graph, entry: &Exposed) -> Option<&'g mut super::Node> {
        let position = *self.nodes.get(&entry.target.node)?;
        graph.nodes.get_mut(position)
    }

    /// The parameters, as [`exposed`] lists them.
    pub fn list(&self) -> &[Exposed] {
        &self.exposed
    }

    /// The parameters, as [`exposed`] lists them.
    pub fn into_list(self) -> Vec<Exposed> {
        self.exposed
    }

    /// The parameter called `name`.
    pub fn find(&self, name: &str) -> Result<&Exposed, ParameterError> {
        match self.index.get(name) {
            Some(&k) => Ok(&self.exposed[k]),
            None => Err(ParameterError::Unknown {
                name: name.to_string(),
                known: self
                    .exposed
                    .iter()
                    .map(|entry| entry.name.clone())
                    .collect(),
            }),
        }
    }

    /// Sets parameter `name` of `graph` (the graph these were read from) to `given`,
    /// checking its type and range.
    pub fn set(&self, graph: &mut Graph, name: &str, given: &Given) -> Result<(), ParameterError> {
        let entry = self.find(name)?;
        let value = entry.value_of(given)?;
        if let Some(node) = self.node(graph, entry) {
            node.inputs.insert(entry.target.pin.clone(), value);
        }
        Ok(())
    }
}

/// Sets exposed parameter `name` of `graph` to `given`, checking its type and range.
pub fn set(graph: &mut Graph, name: &str, given: &Given) -> Result<(), ParameterError> {
    ByName::of(graph).set(graph, name, given)
}

/// The names of the parameters `graph` exposes.
pub fn exposed_names(graph: &Graph) -> HashSet<String> {
    exposed(graph).into_iter().map(|entry| entry.name).collect()
}

/// After nodes left the graph: drops the parameters that exposed them, and forgets in
/// every parameter preset the values of parameters among `before` (the names exposed
/// before) that the graph no longer exposes, so that the presets still check.
pub fn forget_removed(graph: &mut Graph, before: &HashSet<String>) {
    let ids: HashSet<NodeId> = graph.nodes.iter().map(|node| node.id).collect();
    graph
        .parameters
        .retain(|parameter| ids.contains(&parameter.node));
    let after = exposed_names(graph);
    for values in graph.presets.values_mut() {
        values.retain(|name, _| !before.contains(name) || after.contains(name));
    }
}

/// Applies parameter preset `preset` of the graph: the group parameters it does not
/// list go back to their groups' defaults, so that a preset looks the same whatever was
/// set before (top-level parameters it does not list keep their values: the graph
/// holds no other default for them).
pub fn apply_preset(graph: &mut Graph, preset: &str) -> Result<(), ParameterError> {
    apply_preset_with(graph, &ByName::of(graph), preset)
}

/// [`apply_preset`] with the graph's parameters looked up already.
fn apply_preset_with(
    graph: &mut Graph,
    parameters: &ByName,
    preset: &str,
) -> Result<(), ParameterError> {
    let Some(values) = graph.presets.get(preset).cloned() else {
        return Err(ParameterError::UnknownPreset {
            name: preset.to_string(),
            known: graph.presets.keys().cloned().collect(),
        });
    };
    for entry in &parameters.exposed {
        if entry.group_path.is_empty() || values.contains_key(&entry.name) {
            continue;
        }
        if let Some(node) = parameters.node(graph, entry) {
            node.inputs.remove(&entry.target.pin);
        }
    }
    for (name, value) in &values {
        parameters.set(graph, name, &Given::of(value))?;
    }
    Ok(())
}

/// A parameter file: a map from parameter names to values, each name given once.
#[derive(Debug, Default, Deserialize)]
#[serde(transparent)]
pub struct ParameterFile(
    #[serde(deserialize_with = "super::keys::unique")] pub BTreeMap<String, Given>,
);

/// Parses `text` as RON, or as JSON when `json`; errors start with `line:column: `.
/// Parameter files (a map from parameter names to [`Given`] values:
/// `{"ring_frequency": 0.7, "tint": (1.0, 0.5, 0.2)}` in RON, `[1.0, 0.5, 0.2]` for the
/// tuple in JSON) and batch files are read this way.
pub fn parse_ron_or_json<T: serde::de::DeserializeOwned>(
    text: &str,
    json: bool,
) -> Result<T, String> {
    if json {
        serde_json::from_str(text)
            .map_err(|error| format!("{}:{}: {error}", error.line(), error.column()))
    } else {
        ron::from_str(text).map_err(|error| {
            format!(
                "{}:{}: {}",
                error.span.start.line, error.span.start.col, error.code
            )
        })
    }
}

/// The JSON description of `exposed` written beside exports: per parameter its name,
/// the member of the `VeneerParameters` uniform struct, type, default, range, UI hint,
/// group path, and the member's byte offset and size in the struct.
pub fn describe(exposed: &[Exposed], members: &[Member]) -> String {
    let entries: Vec<serde_json::Value> = exposed
        .iter()
        .zip(members)
        .map(|(entry, member)| {
            let components = entry.value.components()[..entry.ty.width()].to_vec();
            let mut object = serde_json::json!({
                "name": entry.name,
                "member": member.name,
                "type": entry.ty.to_string(),
                "default": if components.len() == 1 { serde_json::json!(components[0]) } else { serde_json::json!(components) },
                "hint": entry.hint.name(),
                "group_path": entry.group_path,
                "offset": member.offset,
                "size": member.size,
            });
            if let Some((min, max)) = entry.range {
                object["range"] = serde_json::json!([min, max]);
            }
            if let Hint::Choice(options) = &entry.hint {
                object["options"] = serde_json::json!(options);
            }
            object
        })
        .collect();
    let size = members
        .last()
        .map_or(0, |m| (m.offset + m.size).div_ceil(16) * 16);
    let description = serde_json::json!({
        "struct": "VeneerParameters",
        "binding": { "group": 1, "binding": 0 },
        "size": size,
        "parameters": entries,
    });
    let mut text = serde_json::to_string_pretty(&description).unwrap_or_default();
    text.push('\n');
    text
}

/// One member of the `VeneerParameters` uniform struct.
#[derive(Clone, Debug, PartialEq)]
pub struct Member {
    /// The WGSL identifier.
    pub name: String,
    pub ty: ValueType,
    /// Byte offset in the struct (WGSL uniform layout, the same as std140 for these
    /// types: f32 aligned to 4, vec2f to 8, vec3f to 16).
    pub offset: u32,
    /// Bytes the value takes (4, 8 or 12).
    pub size: u32,
}

/// The uniform struct's members for `exposed`, with WGSL identifiers made from the
/// parameter names by `identifier`, laid out in order.
pub fn members(
    exposed: &[Exposed],
    mut identifier: impl FnMut(&str, u32) -> String,
) -> Vec<Member> {
    let mut offset = 0u32;
    exposed
        .iter()
        .enumerate()
        .map(|(k, entry)| {
            let (align, size) = match entry.ty.width() {
                1 => (4, 4),
                2 => (8, 8),
                _ => (16, 12),
            };
            offset = offset.div_ceil(align) * align;
            let member = Member {
                name: identifier(&entry.name, k as u32),
                ty: entry.ty,
                offset,
                size,
            };
            offset += size;
            member
        })
        .collect()
}

/// Changes to a graph's exposed parameters asked for on a command line or in a batch
/// job: a parameter preset, then values by name, applied in that order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Overrides {
    pub preset: Option<String>,
    pub values: Vec<(String, Given)>,
}

impl Overrides {
    /// Whether nothing is changed.
    pub fn is_empty(&self) -> bool {
        self.preset.is_none() && self.values.is_empty()
    }

    /// Applies the preset, then each value.
    pub fn apply(&self, graph: &mut Graph) -> Result<(), ParameterError> {
        let parameters = ByName::of(graph);
        if let Some(preset) = &self.preset {
            apply_preset_with(graph, &parameters, preset)?;
        }
        for (name, given) in &self.values {
            parameters.set(graph, name, given)?;
        }
        Ok(())
    }
}
