//! How a node is read from a graph file: as written, except that its `inputs` map may
//! not give the same pin twice (a map would keep one value silently, and `fmt` would
//! drop the other).

use super::{Node, NodeId, NodeKind, Value};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::collections::btree_map::Entry;

/// A node as the file gives it, before its inputs are checked for repeated pins.
#[derive(Deserialize)]
#[serde(rename = "Node")]
pub(super) struct NodeFile {
    id: NodeId,
    #[serde(default)]
    label: String,
    kind: NodeKind,
    #[serde(default)]
    inputs: Inputs,
    #[serde(default)]
    position: (f32, f32),
}

/// The inputs map, and the first pin it gives twice.
#[derive(Default)]
struct Inputs {
    values: BTreeMap<String, Value>,
    repeated: Option<String>,
}

impl<'de> Deserialize<'de> for Inputs {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Inputs, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = Inputs;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a map from input names to values")
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                mut map: A,
            ) -> Result<Inputs, A::Error> {
                let mut inputs = Inputs::default();
                while let Some((pin, value)) = map.next_entry::<String, Value>()? {
                    match inputs.values.entry(pin) {
                        Entry::Occupied(given) => {
                            inputs.repeated.get_or_insert_with(|| given.key().clone());
                        }
                        Entry::Vacant(new) => {
                            new.insert(value);
                        }
                    }
                }
                Ok(inputs)
            }
        }
        deserializer.deserialize_map(Visitor)
    }
}

impl TryFrom<NodeFile> for Node {
    type Error = String;

    fn try_from(file: NodeFile) -> Result<Node, String> {
        let node = Node {
            id: file.id,
            label: file.label,
            kind: file.kind,
            inputs: file.inputs.values,
            position: file.position,
            origin: None,
        };
        match file.inputs.repeated {
            Some(pin) => Err(format!("{node}: input '{pin}' is given twice")),
            None => Ok(node),
        }
    }
}
