//! How a node is read from a graph file: as written, except that its `inputs` map may
//! not give the same pin twice (a map would keep one value silently, and `fmt` would
//! drop the other).

use super::keys::KeyedOnce;
use super::{Node, NodeId, NodeKind, Value};
use serde::Deserialize;

/// A node as the file gives it, before its inputs are checked for repeated pins.
#[derive(Deserialize)]
#[serde(rename = "Node")]
pub(super) struct NodeFile {
    id: NodeId,
    #[serde(default)]
    label: String,
    kind: NodeKind,
    #[serde(default)]
    inputs: KeyedOnce<Value>,
    #[serde(default)]
    position: (f32, f32),
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
