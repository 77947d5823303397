//! Node ids to positions: a table indexed by id when the ids are dense (as the editor
//! and saved graphs number them), a hash map otherwise. On a million nodes the table is
//! several times faster, its lookups following the file instead of jumping through memory.

use super::NodeId;
use std::collections::HashMap;

/// A map from node ids to positions (indices into some list of nodes).
#[derive(Clone, Debug)]
pub enum IdIndex {
    /// `table[id]` is the position, or `u32::MAX` for none.
    Table(Vec<u32>),
    Map(HashMap<NodeId, usize>),
}

impl IdIndex {
    /// An empty index for positions below `len` and ids up to `max_id`.
    pub fn new(len: usize, max_id: Option<NodeId>) -> IdIndex {
        let size = max_id.map_or(0, |id| id.0 as usize + 1);
        if size <= 2 * len + 1024 && len < u32::MAX as usize {
            IdIndex::Table(vec![u32::MAX; size])
        } else {
            IdIndex::Map(HashMap::with_capacity(len))
        }
    }

    /// The position of `id`, if it has one.
    pub fn get(&self, id: NodeId) -> Option<usize> {
        match self {
            IdIndex::Table(table) => table
                .get(id.0 as usize)
                .filter(|&&position| position != u32::MAX)
                .map(|&position| position as usize),
            IdIndex::Map(map) => map.get(&id).copied(),
        }
    }

    /// Records `position` for `id` unless it has one already; returns whether it was new.
    pub fn insert_first(&mut self, id: NodeId, position: usize) -> bool {
        match self {
            IdIndex::Table(table) => match table.get_mut(id.0 as usize) {
                Some(slot) if *slot == u32::MAX => {
                    *slot = position as u32;
                    true
                }
                _ => false,
            },
            IdIndex::Map(map) => match map.entry(id) {
                std::collections::hash_map::Entry::Vacant(slot) => {
                    slot.insert(position);
                    true
                }
                std::collections::hash_map::Entry::Occupied(_) => false,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dense_and_sparse_ids_map_alike() {
        for (ids, dense) in [(vec![3, 1, 2, 1], true), (vec![7, 4_000_000_000, 7], false)] {
            let max = ids.iter().copied().max().map(NodeId);
            let mut index = IdIndex::new(ids.len(), max);
            assert_eq!(matches!(index, IdIndex::Table(_)), dense);
            let fresh: Vec<bool> = (0..ids.len())
                .map(|k| index.insert_first(NodeId(ids[k]), k))
                .collect();
            assert_eq!(fresh.last(), Some(&false));
            assert!(fresh[..fresh.len() - 1].iter().all(|&f| f));
            assert_eq!(index.get(NodeId(ids[0])), Some(0));
            assert_eq!(index.get(NodeId(5)), None);
        }
    }
}
