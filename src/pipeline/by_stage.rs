//! A few values by stage name: what the state keeps per input and stage
//! (its parts' keys, its failures). An input has one or two; a map per
//! input allocated a node of eleven slots each, most of the state's memory
//! over a large archive and much of the time it took to read.

use std::fmt;
use std::marker::PhantomData;

use serde::de::{MapAccess, Visitor};
use serde::ser::SerializeMap;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// Values by stage name, in name order; written as a map.
#[derive(Debug, Clone, PartialEq)]
pub struct ByStage<V>(Vec<(String, V)>);

impl<V> Default for ByStage<V> {
    fn default() -> Self {
        ByStage(Vec::new())
    }
}

impl<V> ByStage<V> {
    /// The value of `stage`.
    pub fn get(&self, stage: &str) -> Option<&V> {
        let i = self.find(stage).ok()?;
        Some(&self.0[i].1)
    }

    /// Whether `stage` has a value.
    pub fn contains_key(&self, stage: &str) -> bool {
        self.find(stage).is_ok()
    }

    /// Sets the value of `stage`.
    pub fn insert(&mut self, stage: String, value: V) {
        match self.find(&stage) {
            Ok(i) => self.0[i].1 = value,
            Err(i) => self.0.insert(i, (stage, value)),
        }
    }

    /// Whether there is none.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// Each stage with its value, in name order.
    pub fn iter(&self) -> impl Iterator<Item = (&String, &V)> {
        self.0.iter().map(|(k, v)| (k, v))
    }

    /// The values, in their stages' name order.
    pub fn values(&self) -> impl Iterator<Item = &V> {
        self.0.iter().map(|(_, v)| v)
    }

    fn find(&self, stage: &str) -> Result<usize, usize> {
        self.0.binary_search_by(|(k, _)| k.as_str().cmp(stage))
    }
}

impl<V: Serialize> Serialize for ByStage<V> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(self.0.len()))?;
        for (k, v) in &self.0 {
            map.serialize_entry(k, v)?;
        }
        map.end()
    }
}

impl<'de, V: Deserialize<'de>> Deserialize<'de> for ByStage<V> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_map(ByStageVisitor(PhantomData))
    }
}

struct ByStageVisitor<V>(PhantomData<V>);

impl<'de, V: Deserialize<'de>> Visitor<'de> for ByStageVisitor<V> {
    type Value = ByStage<V>;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a map of stage names")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
        let mut out = ByStage(Vec::with_capacity(map.size_hint().unwrap_or(0).min(16)));
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
        let mut b = ByStage::default();
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
        let back: ByStage<i32> = bincode::serde::decode_from_slice(&bytes, cfg).unwrap().0;
        assert_eq!(back, b);
        let json = serde_json::to_string(&b).unwrap();
        assert_eq!(json, serde_json::to_string(&map).unwrap());
        assert_eq!(serde_json::from_str::<ByStage<i32>>(&json).unwrap(), b);
    }
}
