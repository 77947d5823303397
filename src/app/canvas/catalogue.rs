//! Every item the add-node search offers: the registry's node kinds, category by
//! category, the node groups (under "Groups"), then a comment frame; the search ranks
//! them, and wires dropped on empty space only get the kinds they can attach to.

use crate::graph::{Category, NodeKind, ValueType};

/// What an entry adds.
#[derive(Clone, Debug, PartialEq)]
pub enum Item {
    /// A node of this kind.
    Node(NodeKind),
    /// An instance of the node group of this name (the graph's or the library's).
    Group(String),
    /// An empty comment frame at the mouse.
    Frame,
    /// A comment frame around the selected nodes (offered when some are selected).
    FrameSelection,
}

/// One entry of the add-node search.
#[derive(Clone, Debug)]
pub struct Entry {
    /// Menu text, e.g. "fBm (gradient)".
    pub name: String,
    pub item: Item,
}

/// The group a frame is listed in, after the node categories.
pub const LAYOUT: &str = "Layout";

/// Words the search finds a frame by (peers call it a comment, a group, a box).
const FRAME_WORDS: &[&str] = &["frame", "comment", "group", "box", "note", "backdrop"];

/// Words the search finds a node group by.
const GROUP_WORDS: &[&str] = &["group", "node group", "function", "subgraph", "library"];

impl Entry {
    /// The heading the entry is listed under.
    pub fn group(&self) -> &'static str {
        match &self.item {
            Item::Node(kind) => kind.category().name(),
            Item::Group(_) => Category::Group.name(),
            Item::Frame | Item::FrameSelection => LAYOUT,
        }
    }

    /// The text the search matches: name, title and search words, lower case.
    fn haystack(&self) -> String {
        match &self.item {
            Item::Node(kind) => {
                let definition = kind.definition();
                format!(
                    "{} {} {}",
                    self.name,
                    definition.title(),
                    definition.keywords().join(" ")
                )
            }
            Item::Group(_) => format!("{} {}", self.name, GROUP_WORDS.join(" ")),
            Item::Frame | Item::FrameSelection => {
                format!("{} {}", self.name, FRAME_WORDS.join(" "))
            }
        }
        .to_lowercase()
    }
}

/// All entries, in menu order: the registry's, category by category, the node groups
/// called `groups`, then the frames.
pub fn entries(groups: &[String]) -> Vec<Entry> {
    let mut entries: Vec<Entry> = NodeKind::menu()
        .into_iter()
        .map(|(name, kind)| Entry {
            name,
            item: Item::Node(kind),
        })
        .chain(groups.iter().map(|name| Entry {
            name: name.clone(),
            item: Item::Group(name.clone()),
        }))
        .collect();
    let rank = |entry: &Entry| {
        let category = match &entry.item {
            Item::Node(kind) => kind.category(),
            Item::Group(_) => Category::Group,
            Item::Frame | Item::FrameSelection => return None,
        };
        Category::ALL.iter().position(|c| *c == category)
    };
    entries.sort_by_key(|entry| rank(entry));
    entries.push(Entry {
        name: "Frame (comment)".into(),
        item: Item::Frame,
    });
    entries.push(Entry {
        name: "Frame around selected nodes (Ctrl+J)".into(),
        item: Item::FrameSelection,
    });
    entries
}

/// Entries (with the node groups called `groups`) matching every word of `query`
/// (case-insensitive) in their name, title or search words, best first: names equal to
/// the query, then names starting with it, then names containing every word, then the
/// rest; menu order within each.
pub fn search(query: &str, groups: &[String]) -> Vec<Entry> {
    let query = query.trim().to_lowercase();
    let words: Vec<&str> = query.split_whitespace().collect();
    let mut found: Vec<(u8, Entry)> = entries(groups)
        .into_iter()
        .filter(|entry| {
            let haystack = entry.haystack();
            words.iter().all(|word| haystack.contains(word))
        })
        .map(|entry| {
            let name = entry.name.to_lowercase();
            let rank = if name == query {
                0
            } else if name.starts_with(&query) {
                1
            } else if words.iter().all(|word| name.contains(word)) {
                2
            } else {
                3
            };
            (rank, entry)
        })
        .collect();
    found.sort_by_key(|(rank, _)| *rank);
    found.into_iter().map(|(_, entry)| entry).collect()
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
        let all = entries(&["ring_wood".to_string()]);
        for category in Category::ALL {
            assert!(
                all.iter().any(|e| e.group() == category.name()),
                "{} is empty",
                category.name()
            );
        }
        assert!(all.len() > 50);
    }

    #[test]
    fn search_matches_all_words() {
        let found = search("fbm grad", &[]);
        assert_eq!(found.len(), 1);
        assert_eq!(found[0].name, "fBm (gradient)");
        assert!(search("zebra", &[]).is_empty());
    }

    #[test]
    fn search_ranks_names_before_search_words_and_finds_frames() {
        let found = search("noise", &[]);
        assert!(found.len() > 3);
        assert!(
            found[0].name.to_lowercase().starts_with("noise"),
            "{:?}",
            found.iter().map(|e| &e.name).collect::<Vec<_>>()
        );
        for word in ["frame", "Comment", "group"] {
            assert_eq!(search(word, &[])[0].item, Item::Frame, "{word}");
        }
        assert_eq!(entries(&[]).last().map(Entry::group), Some(LAYOUT));
        assert_eq!(search("frame sel", &[])[0].item, Item::FrameSelection);
    }

    #[test]
    fn groups_are_listed_under_groups_and_found_by_name() {
        let groups = ["ring_wood".to_string(), "veined_marble".to_string()];
        let found = search("ring_wood", &groups);
        assert_eq!(found[0].item, Item::Group("ring_wood".into()));
        assert_eq!(found[0].group(), "Groups");
        assert!(
            search("marble", &groups)
                .iter()
                .any(|e| e.item == Item::Group("veined_marble".into()))
        );
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
                    basis: crate::graph::Basis::Simplex,
                    period: 0,
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
