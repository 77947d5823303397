//! Maps read from files (RON or JSON) whose keys must be given once: a map type would
//! keep one of two values silently, and writing the file back would drop the other.

use serde::Deserialize;
use std::collections::BTreeMap;
use std::collections::btree_map::Entry;

/// A map as a file gives it, and the first key the file gives twice.
pub struct KeyedOnce<V> {
    pub values: BTreeMap<String, V>,
    pub repeated: Option<String>,
}

impl<V> Default for KeyedOnce<V> {
    fn default() -> KeyedOnce<V> {
        KeyedOnce {
            values: BTreeMap::new(),
            repeated: None,
        }
    }
}

impl<'de, V: Deserialize<'de>> Deserialize<'de> for KeyedOnce<V> {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Visitor<V>(std::marker::PhantomData<V>);
        impl<'de, V: Deserialize<'de>> serde::de::Visitor<'de> for Visitor<V> {
            type Value = KeyedOnce<V>;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a map from names to values")
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                mut map: A,
            ) -> Result<KeyedOnce<V>, A::Error> {
                let mut keyed = KeyedOnce::default();
                while let Some((key, value)) = map.next_entry::<String, V>()? {
                    match keyed.values.entry(key) {
                        Entry::Occupied(given) => {
                            keyed.repeated.get_or_insert_with(|| given.key().clone());
                        }
                        Entry::Vacant(new) => {
                            new.insert(value);
                        }
                    }
                }
                Ok(keyed)
            }
        }
        deserializer.deserialize_map(Visitor(std::marker::PhantomData))
    }
}

/// Reads a map whose keys are each given once (for `#[serde(deserialize_with)]`): a
/// key given twice is an error naming it.
pub fn unique<'de, D, V>(deserializer: D) -> Result<BTreeMap<String, V>, D::Error>
where
    D: serde::Deserializer<'de>,
    V: Deserialize<'de>,
{
    let keyed = KeyedOnce::<V>::deserialize(deserializer)?;
    match keyed.repeated {
        Some(key) => Err(serde::de::Error::custom(format!(
            "'{}' is given twice",
            super::names::shown(&key)
        ))),
        None => Ok(keyed.values),
    }
}
