//! Values by name, in name order, in one vector: what the state keeps per
//! input (by its path) and per input and stage (its parts' keys, its
//! failures). A `BTreeMap` allocates nodes of eleven slots: a map per
//! input with one or two stages was most of the state's memory, and the
//! inputs' map, filled in order, leaves its nodes about half full. Memory
//! is time: a fresh page can cost more to touch than the work done in it
//! (`docs/scheduling.md`).

use std::fmt;
use std::marker::PhantomData;

use serde::de::{MapAccess, Visitor};
use serde::ser::SerializeMap;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// Values by name, in name order (byte order of the names, as a
/// `BTreeMap<String, _>`); written as a map.
#[derive(Debug, Clone, PartialEq)]
pub struct ByName<V>(Vec<(String, V)>);

impl<V> Default for ByName<V> {
    fn default() -> Self {
        ByName(Vec::new())
    }
}

impl<V> ByName<V> {
    /// The value of `name`.
    pub fn get(&self, name: &str) -> Option<&V> {
        let i = self.find(name).ok()?;
        Some(&self.0[i].1)
    }

    /// The value of `name`, to change.
    pub fn get_mut(&mut self, name: &str) -> Option<&mut V> {
        let i = self.find(name).ok()?;
        Some(&mut self.0[i].1)
    }

    /// Whether `name` has a value.
    pub fn contains_key(&self, name: &str) -> bool {
        self.find(name).is_ok()
    }

    /// Sets the value of `name`. Names given in order are appended.
    pub fn insert(&mut self, name: String, value: V) {
        match self.find(&name) {
            Ok(i) => self.0[i].1 = value,
            Err(i) => self.0.insert(i, (name, value)),
        }
    }

    /// Removes `name`, with its value.
    pub fn remove(&mut self, name: &str) -> Option<V> {
        let i = self.find(name).ok()?;
        Some(self.0.remove(i).1)
    }

    /// Sets (`Some`) or removes (`None`) the value of each name of
    /// `changes` (of a name given twice, the last stands). A few are put
    /// in place; more in one pass over both, in name order, where an
    /// insert each would move the names after it every time.
    pub fn merge(&mut self, changes: Vec<(String, Option<V>)>) {
        if changes.len() <= 8 {
            for (name, value) in changes {
                match value {
                    Some(v) => self.insert(name, v),
                    None => drop(self.remove(&name)),
                }
            }
            return;
        }
        let changes = in_name_order(changes);
        let old = std::mem::take(&mut self.0);
        let mut out = Vec::with_capacity(old.len() + changes.len());
        let mut old = old.into_iter().peekable();
        for (name, value) in changes {
            while let Some(kept) = old.next_if(|(k, _)| *k < name) {
                out.push(kept);
            }
            old.next_if(|(k, _)| *k == name);
            if let Some(v) = value {
                out.push((name, v));
            }
        }
        out.extend(old);
        self.0 = out;
    }

    /// Whether there is none.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// How many there are.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// Each name with its value, in name order.
    pub fn iter(&self) -> impl Iterator<Item = (&String, &V)> + Clone {
        self.0.iter().map(|(k, v)| (k, v))
    }

    /// The names, in order.
    pub fn keys(&self) -> impl Iterator<Item = &String> + Clone {
        self.0.iter().map(|(k, _)| k)
    }

    /// The values, in their names' order.
    pub fn values(&self) -> impl Iterator<Item = &V> + Clone {
        self.0.iter().map(|(_, v)| v)
    }

    /// Where `name` is, or would go. A name after the last is found
    /// without a search: states are read and made in name order.
    fn find(&self, name: &str) -> Result<usize, usize> {
        match self.0.last() {
            Some((last, _)) if last.as_str() < name => Err(self.0.len()),
            _ => self.0.binary_search_by(|(k, _)| k.as_str().cmp(name)),
        }
    }
}

/// As a map collected from pairs: the last value of a name stands.
impl<V> FromIterator<(String, V)> for ByName<V> {
    fn from_iter<I: IntoIterator<Item = (String, V)>>(iter: I) -> Self {
        ByName(in_name_order(iter.into_iter().collect()))
    }
}

/// `pairs` in name order, each name once with the last value given for it
/// (as inserting them one by one into a map leaves them).
fn in_name_order<T>(mut pairs: Vec<(String, T)>) -> Vec<(String, T)> {
    if !pairs.windows(2).all(|w| w[0].0 < w[1].0) {
        // Stable, so of a name's pairs the last given comes last.
        pairs.sort_by(|a, b| a.0.cmp(&b.0));
        pairs.dedup_by(|later, kept| {
            let same = later.0 == kept.0;
            if same {
                std::mem::swap(later, kept);
            }
            same
        });
    }
    pairs
}

impl<V: Serialize> Serialize for ByName<V> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(self.0.len()))?;
        for (k, v) in &self.0 {
            map.serialize_entry(k, v)?;
        }
        map.end()
    }
}

impl<'de, V: Deserialize<'de>> Deserialize<'de> for ByName<V> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_map(ByNameVisitor(PhantomData))
    }
}

struct ByNameVisitor<V>(PhantomData<V>);

impl<'de, V: Deserialize<'de>> Visitor<'de> for ByNameVisitor<V> {
    type Value = ByName<V>;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a map of names")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
        // The length a damaged file claims is not taken on trust. A large
        // map gets room for a few more: the state's inputs, read with its
        // log's new inputs put in after, were copied whole into a list
        // twice their size by the first one (12 MB at 20 000 inputs).
        let room = map.size_hint().unwrap_or(0).min(1 << 20);
        let mut out = ByName(Vec::with_capacity(room + room / 64));
        while let Some((k, v)) = map.next_entry::<String, V>()? {
            out.insert(k, v);
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeMap;

    #[test]
    fn it_reads_and_writes_as_the_map_it_stands_for() {
        let mut b = ByName::default();
        for (k, v) in [
            ("tensile", 2),
            ("friction", 1),
            ("roughness", 3),
            ("friction", 4),
        ] {
            b.insert(k.to_string(), v);
        }
        let map: BTreeMap<String, i32> = [("friction", 4), ("roughness", 3), ("tensile", 2)]
            .map(|(k, v)| (k.into(), v))
            .into();
        assert_eq!(
            b.iter()
                .map(|(k, v)| (k.clone(), *v))
                .collect::<BTreeMap<_, _>>(),
            map
        );
        assert_eq!((b.get("friction"), b.get("wear")), (Some(&4), None));
        // The same bytes and JSON as the map: states written before read.
        let cfg = bincode::config::standard();
        let bytes = bincode::serde::encode_to_vec(&b, cfg).unwrap();
        assert_eq!(bytes, bincode::serde::encode_to_vec(&map, cfg).unwrap());
        let back: ByName<i32> = bincode::serde::decode_from_slice(&bytes, cfg).unwrap().0;
        assert_eq!(back, b);
        let json = serde_json::to_string(&b).unwrap();
        assert_eq!(json, serde_json::to_string(&map).unwrap());
        assert_eq!(serde_json::from_str::<ByName<i32>>(&json).unwrap(), b);
    }

    /// Inserts, removals, merges and collections in a pseudo-random order
    /// leave the same names and values as a `BTreeMap` given the same.
    #[test]
    fn it_keeps_what_a_btree_map_keeps() {
        let mut seed = 7u64;
        let mut next = |n: u64| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 33) % n
        };
        let (mut b, mut map) = (ByName::default(), BTreeMap::new());
        for round in 0..400 {
            let name = format!(
                "in/{:02}{}",
                next(40),
                ["", "/a", "-b", ".c"][next(4) as usize]
            );
            match next(4) {
                0 | 1 => {
                    b.insert(name.clone(), round);
                    map.insert(name.clone(), round);
                }
                2 => assert_eq!(b.remove(&name), map.remove(&name)),
                _ => {
                    // In any order, a name perhaps twice: the last stands.
                    let changes: Vec<(String, Option<u64>)> = (0..next(20))
                        .map(|_| {
                            (
                                format!("in/{:02}", next(40)),
                                (next(3) > 0).then_some(round),
                            )
                        })
                        .collect();
                    for (k, v) in &changes {
                        match v {
                            Some(v) => map.insert(k.clone(), *v),
                            None => map.remove(k),
                        };
                    }
                    b.merge(changes);
                }
            }
            let pairs: Vec<(String, u64)> = b.iter().map(|(k, v)| (k.clone(), *v)).collect();
            assert_eq!(
                pairs,
                map.clone().into_iter().collect::<Vec<_>>(),
                "round {round}"
            );
            assert_eq!(b.len(), map.len());
            assert_eq!(b.get(&name), map.get(&name));
        }
        // Collected out of order with a name twice: the last one stands.
        let c: ByName<i32> = [("b", 1), ("a", 2), ("b", 3)]
            .map(|(k, v)| (k.into(), v))
            .into_iter()
            .collect();
        assert_eq!(
            c.iter().map(|(k, v)| (k.as_str(), *v)).collect::<Vec<_>>(),
            [("a", 2), ("b", 3)]
        );
    }
}
