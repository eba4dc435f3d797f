//! A value two states share: an input the run found unchanged keeps the
//! last run's entry, counted, not copied. At 20 000 inputs a copy of each
//! entry was 20 000 × six allocations of fresh memory a run pays to touch
//! (`docs/scheduling.md`), for values equal to the ones already held.

use std::fmt;
use std::ops::Deref;
use std::sync::Arc;

use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// A shared, immutable value; written and read as the value itself.
pub struct Shared<T>(Arc<T>);

impl<T> Shared<T> {
    /// Shares `value`.
    pub fn new(value: T) -> Self {
        Shared(Arc::new(value))
    }
}

impl<T: Clone> Shared<T> {
    /// The value, to change: copied only when another holder shares it.
    pub fn make_mut(&mut self) -> &mut T {
        Arc::make_mut(&mut self.0)
    }
}

impl<T> Clone for Shared<T> {
    fn clone(&self) -> Self {
        Shared(Arc::clone(&self.0))
    }
}

impl<T> Deref for Shared<T> {
    type Target = T;
    fn deref(&self) -> &T {
        &self.0
    }
}

impl<T> From<T> for Shared<T> {
    fn from(value: T) -> Self {
        Shared::new(value)
    }
}

/// Equal when they are one value (no comparison), or equal values.
impl<T: PartialEq> PartialEq for Shared<T> {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0) || *self.0 == *other.0
    }
}

impl<T: fmt::Debug> fmt::Debug for Shared<T> {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        self.0.fmt(f)
    }
}

impl<T: Serialize> Serialize for Shared<T> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.0.serialize(s)
    }
}

impl<'de, T: Deserialize<'de>> Deserialize<'de> for Shared<T> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        T::deserialize(d).map(Shared::new)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn it_is_written_as_its_value_and_shares_on_clone() {
        let cfg = bincode::config::standard();
        let v = Shared::new(vec![1u32, 2, 3]);
        let bytes = bincode::serde::encode_to_vec(&v, cfg).unwrap();
        assert_eq!(bytes, bincode::serde::encode_to_vec(&*v, cfg).unwrap());
        let back: Shared<Vec<u32>> = bincode::serde::decode_from_slice(&bytes, cfg).unwrap().0;
        assert_eq!(back, v);
        assert_eq!(serde_json::to_string(&v).unwrap(), "[1,2,3]");
        let mut copy = v.clone();
        assert!(Arc::ptr_eq(&copy.0, &v.0));
        copy.make_mut().push(4);
        assert_eq!((v.len(), copy.len()), (3, 4));
        assert_ne!(copy, v);
    }
}
