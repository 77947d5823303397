//! Every node kind the editor offers, grouped by category, with search and the
//! compatibility filter for wires dropped on empty space.

use crate::graph::{Category, NodeKind, ValueType};

/// One entry of the add-node menu.
#[derive(Clone, Debug)]
pub struct Entry {
    /// Menu text, e.g. "fBm (gradient)".
    pub name: String,
    pub kind: NodeKind,
}

/// All entries, in menu order: the registry's, category by category.
pub fn entries() -> Vec<Entry> {
    let mut entries: Vec<Entry> = NodeKind::menu()
        .into_iter()
        .map(|(name, kind)| Entry { name, kind })
        .collect();
    let rank = |kind: &NodeKind| Category::ALL.iter().position(|c| *c == kind.category());
    entries.sort_by_key(|entry| rank(&entry.kind));
    entries
}

/// Entries whose name contains every word of `query` (case-insensitive).
pub fn search(query: &str) -> Vec<Entry> {
    let words: Vec<String> = query.split_whitespace().map(str::to_lowercase).collect();
    entries()
        .into_iter()
        .filter(|entry| {
            let definition = entry.kind.definition();
            let name = format!(
                "{} {} {}",
                entry.name,
                definition.title(),
                definition.keywords().join(" ")
            )
            .to_lowercase();
            words.iter().all(|word| name.contains(word))
        })
        .collect()
}

/// Which end of a dropped wire the new node must offer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Dangling {
    /// The wire starts at an output of this type: the node needs a compatible input.
    FromOutput(ValueType),
    /// The wire ends at an input of this type: the node needs a compatible output.
    IntoInput(ValueType),
}

/// The pin of `kind` a dangling wire would attach to, if any: an input index for
/// `FromOutput`, an output index for `IntoInput`.
pub fn compatible_pin(kind: &NodeKind, dangling: Dangling) -> Option<usize> {
    let signature = kind.signature();
    match dangling {
        Dangling::FromOutput(ty) => signature
            .inputs
            .iter()
            .position(|pin| ty.converts_to(pin.ty)),
        Dangling::IntoInput(ty) => signature
            .outputs
            .iter()
            .position(|pin| pin.ty.converts_to(ty)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_category_has_entries_and_every_entry_checks_alone() {
        let all = entries();
        for category in Category::ALL {
            assert!(
                all.iter().any(|e| e.kind.category() == category),
                "{} is empty",
                category.name()
            );
        }
        assert!(all.len() > 50);
    }

    #[test]
    fn search_matches_all_words() {
        let found = search("fbm grad");
        assert_eq!(found.len(), 1);
        assert_eq!(found[0].name, "fBm (gradient)");
        assert!(search("zebra").is_empty());
    }

    #[test]
    fn dropped_wires_only_offer_compatible_nodes() {
        let vec2 = Dangling::FromOutput(ValueType::Vec2);
        assert!(
            compatible_pin(
                &NodeKind::Length(crate::nodes::Length {
                    ty: ValueType::Vec2
                }),
                vec2
            )
            .is_some()
        );
        assert!(
            compatible_pin(
                &NodeKind::Noise(crate::nodes::Noise {
                    basis: crate::graph::Basis::Simplex
                }),
                vec2
            )
            .is_none()
        );
        assert_eq!(
            compatible_pin(&NodeKind::Material, Dangling::FromOutput(ValueType::Float)),
            Some(0)
        );
        assert!(compatible_pin(&NodeKind::Uv, Dangling::IntoInput(ValueType::Color)).is_none());
    }
}
