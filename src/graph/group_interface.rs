//! Renaming and removing a group's inputs and outputs. A group's pins are named in its
//! instances (their values, the wires into and out of them), in the groups that inherit
//! its inputs, in the graph's exposed parameters and in its parameter presets: every one
//! of those follows the change, at any depth of nesting.

use super::group::{self, BOUNDARY, GroupDef, Interface, Route};
use super::{Graph, Node, NodeId, PinRef, Wire};
use std::collections::BTreeMap;

/// Which side of a group's interface an edit concerns.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    Input,
    Output,
}

/// Renames input or output `old` of group `group` to `new`.
pub fn rename(
    graph: &mut Graph,
    group: &str,
    side: Side,
    old: &str,
    new: &str,
) -> Result<(), String> {
    check_name(new)?;
    let names = pin_names(graph, group, side, old)?;
    if old != new && names.iter().any(|name| name == new) {
        return Err(format!(
            "group '{group}' has an {} named '{new}' already",
            side.word()
        ));
    }
    edit(graph, group, side, old, Some(new));
    Ok(())
}

/// Removes input or output `name` of group `group`, and every wire to or from it; the
/// inner pins a removed input fed keep its default.
pub fn remove(graph: &mut Graph, group: &str, side: Side, name: &str) -> Result<(), String> {
    pin_names(graph, group, side, name)?;
    edit(graph, group, side, name, None);
    Ok(())
}

/// The names of the inputs or outputs of group `group`, which must include `name`.
fn pin_names(graph: &Graph, group: &str, side: Side, name: &str) -> Result<Vec<String>, String> {
    let definition = graph
        .groups
        .get(group)
        .ok_or(format!("no group named '{group}'"))?;
    let names: Vec<String> = match side {
        Side::Input => definition.inputs.iter().map(|i| i.name.clone()).collect(),
        Side::Output => definition.outputs.iter().map(|o| o.name.clone()).collect(),
    };
    if !names.iter().any(|known| known == name) {
        return Err(format!("group '{group}' has no {} '{name}'", side.word()));
    }
    Ok(names)
}

impl Side {
    /// The side's name in messages: `input` or `output`.
    pub fn word(self) -> &'static str {
        match self {
            Side::Input => "input",
            Side::Output => "output",
        }
    }
}

/// A pin name engines can use as a struct member: a letter or '_', then letters,
/// digits and '_'.
fn check_name(name: &str) -> Result<(), String> {
    let mut chars = name.chars();
    let first_ok = chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_');
    if first_ok && chars.all(|c| c.is_ascii_alphanumeric() || c == '_') {
        Ok(())
    } else {
        Err(format!(
            "'{name}' cannot name a pin: use letters, digits and '_', starting with a letter"
        ))
    }
}

/// Renames (`new` given) or removes pin `old` on `side` of group `group` and follows
/// the change everywhere the graph names the group's pins.
fn edit(graph: &mut Graph, group: &str, side: Side, old: &str, new: Option<&str>) {
    let before = group::interfaces(&graph.groups).unwrap_or_default();
    let exposed_before = super::parameters::exposed(graph);
    let definition = graph.groups.get_mut(group).expect("checked by the caller");
    match side {
        Side::Input => {
            if new.is_none() {
                keep_removed_value(definition, old);
            }
            rename_or_drop(
                &mut definition.inputs,
                |input| (input.name == old).then_some(&mut input.name),
                new,
            );
            rename_or_drop(
                &mut definition.wires,
                |wire| {
                    (wire.from.node == BOUNDARY && wire.from.pin == old)
                        .then_some(&mut wire.from.pin)
                },
                new,
            );
        }
        Side::Output => {
            rename_or_drop(
                &mut definition.outputs,
                |output| (output.name == old).then_some(&mut output.name),
                new,
            );
            rename_or_drop(
                &mut definition.wires,
                |wire| (wire.to.node == BOUNDARY && wire.to.pin == old).then_some(&mut wire.to.pin),
                new,
            );
        }
    }
    definition.linked = false;
    let after = group::interfaces(&graph.groups).unwrap_or_default();
    let renames = match side {
        Side::Input => input_renames(&before, &after, group, old, new),
        Side::Output => BTreeMap::from([(
            group.to_string(),
            BTreeMap::from([(old.to_string(), new.map(str::to_string))]),
        )]),
    };
    rename_in_instances(&mut graph.nodes, &mut graph.wires, &renames, side);
    for definition in graph.groups.values_mut() {
        rename_in_instances(&mut definition.nodes, &mut definition.wires, &renames, side);
    }
    if side == Side::Input {
        follow_parameters(graph, &renames, &exposed_before);
    }
    group::resolve(graph);
}

/// Gives the inner pins that input `name` of `definition` feeds the input's default,
/// so that removing the input leaves the group computing what it did by default.
fn keep_removed_value(definition: &mut GroupDef, name: &str) {
    let Some(default) = definition
        .inputs
        .iter()
        .find(|input| input.name == name)
        .map(|input| input.default)
    else {
        return;
    };
    let fed: Vec<PinRef> = definition
        .wires
        .iter()
        .filter(|wire| wire.from.node == BOUNDARY && wire.from.pin == name)
        .map(|wire| wire.to.clone())
        .collect();
    for target in fed {
        let Some(node) = definition
            .nodes
            .iter_mut()
            .find(|node| node.id == target.node)
        else {
            continue;
        };
        let signature = node.kind.signature();
        if let Some((_, pin)) = signature.input(&target.pin) {
            node.inputs
                .insert(target.pin.clone(), default.convert(pin.ty));
        }
    }
}

/// What happens to a pin name: renamed (`Some`) or gone (`None`).
type Change = Option<String>;

/// Follows `change` (none: the name stays) on `name`; `false` when the name is gone.
fn follow(name: &mut String, change: Option<Change>) -> bool {
    match change {
        Some(Some(new)) => {
            *name = new;
            true
        }
        Some(None) => false,
        None => true,
    }
}

/// Follows `changes` on the keys of `map`, dropping the entries of names that go.
fn follow_keys<V>(map: &mut BTreeMap<String, V>, changes: &BTreeMap<String, Change>) {
    // All taken out first, so that names trading places do not clobber each other.
    let moved: Vec<(Change, V)> = changes
        .iter()
        .filter_map(|(old, new)| Some((new.clone(), map.remove(old)?)))
        .collect();
    for (new, value) in moved {
        if let Some(new) = new {
            map.insert(new, value);
        }
    }
}

/// Renames to `new` (or, `new` absent, drops) the items whose name `name_of` picks.
fn rename_or_drop<T>(
    items: &mut Vec<T>,
    mut name_of: impl FnMut(&mut T) -> Option<&mut String>,
    new: Option<&str>,
) {
    items.retain_mut(|item| match name_of(item) {
        Some(name) => follow(name, Some(new.map(str::to_string))),
        None => true,
    });
}

/// For every group, its instances' input pins that change name (to `Some`) or go
/// (`None`) when input `old` of group `changed` is renamed to `new` or removed: the
/// group's own, and those inherited through groups that hold it.
fn input_renames(
    before: &BTreeMap<String, Interface>,
    after: &BTreeMap<String, Interface>,
    changed: &str,
    old: &str,
    new: Option<&str>,
) -> BTreeMap<String, BTreeMap<String, Change>> {
    let mut renames: BTreeMap<String, BTreeMap<String, Change>> = BTreeMap::new();
    renames.insert(
        changed.to_string(),
        BTreeMap::from([(old.to_string(), new.map(str::to_string))]),
    );
    // Inherited inputs follow the group they come from: repeat until nothing changes
    // (each pass reaches one level of nesting further out).
    loop {
        let mut grew = false;
        for (name, interface) in before {
            let Some(now) = after.get(name) else { continue };
            for entry in &interface.inputs {
                let Route::Inherited { node, pin } = &entry.route else {
                    continue;
                };
                let Some(inner) = entry.path.first() else {
                    continue;
                };
                let Some(change) = renames.get(inner).and_then(|map| map.get(pin)).cloned() else {
                    continue;
                };
                let followed = change.and_then(|inner_pin| {
                    now.inputs
                        .iter()
                        .find(|e| {
                            e.route
                                == Route::Inherited {
                                    node: *node,
                                    pin: inner_pin.clone(),
                                }
                        })
                        .map(|e| e.input.name.clone())
                });
                let map = renames.entry(name.clone()).or_default();
                if map.get(&entry.input.name) != Some(&followed) {
                    map.insert(entry.input.name.clone(), followed);
                    grew = true;
                }
            }
        }
        if !grew {
            return renames;
        }
    }
}

/// Applies `renames` to the instances among `nodes` (their values on `side` inputs)
/// and to the wires among `wires` that reach their pins.
fn rename_in_instances(
    nodes: &mut [Node],
    wires: &mut Vec<Wire>,
    renames: &BTreeMap<String, BTreeMap<String, Change>>,
    side: Side,
) {
    let mut changes: BTreeMap<NodeId, &BTreeMap<String, Change>> = BTreeMap::new();
    for node in nodes.iter_mut() {
        let Some(map) = group::group_name(node).and_then(|name| renames.get(name)) else {
            continue;
        };
        changes.insert(node.id, map);
        if side == Side::Input {
            follow_keys(&mut node.inputs, map);
        }
    }
    wires.retain_mut(|wire| {
        let end = match side {
            Side::Input => &mut wire.to,
            Side::Output => &mut wire.from,
        };
        let change = changes.get(&end.node).and_then(|map| map.get(&end.pin));
        follow(&mut end.pin, change.cloned())
    });
}

/// Follows the renames in the graph's exposed parameters (top-level pins of group
/// nodes) and in its parameter presets (by the names parameters had before).
fn follow_parameters(
    graph: &mut Graph,
    renames: &BTreeMap<String, BTreeMap<String, Change>>,
    exposed_before: &[super::parameters::Exposed],
) {
    let change_of = |graph: &Graph, node: NodeId, pin: &str| {
        let name = graph.node(node).and_then(group::group_name)?;
        renames.get(name)?.get(pin).cloned()
    };
    let mut parameters = std::mem::take(&mut graph.parameters);
    parameters.retain_mut(|parameter| {
        let change = change_of(graph, parameter.node, &parameter.pin);
        follow(&mut parameter.pin, change)
    });
    graph.parameters = parameters;
    let exposed_after = super::parameters::exposed(graph);
    let mut names: BTreeMap<String, Change> = BTreeMap::new();
    for entry in exposed_before {
        let target = &entry.target;
        let pin = match change_of(graph, target.node, &target.pin) {
            Some(change) => change,
            None => Some(target.pin.clone()),
        };
        let now = pin.and_then(|pin| {
            exposed_after
                .iter()
                .find(|e| e.target.node == target.node && e.target.pin == pin)
                .map(|e| e.name.clone())
        });
        if now.as_deref() != Some(entry.name.as_str()) {
            names.insert(entry.name.clone(), now);
        }
    }
    for values in graph.presets.values_mut() {
        follow_keys(values, &names);
    }
}
