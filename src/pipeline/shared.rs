//! A value two states share: an input the run found unchanged keeps the
//! last run's entry, counted, not copied. At 20 000 inputs a copy of each
//! entry was 20 000 × six allocations of fresh memory a run pays to touch
//! (`docs/scheduling.md`), for values equal to the ones already held.

use std::fmt;
use std::ops::Deref;
use std::sync::Arc;

use serde::de::{self, Visitor};
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

/// Reads a shared string in one allocation. serde reads an `Arc<str>` as
/// a `String`, then copies it into the `Arc`: two allocations for each of
/// the three strings of every input the state holds.
pub(crate) fn shared_str<'de, D: Deserializer<'de>>(d: D) -> Result<Arc<str>, D::Error> {
    d.deserialize_str(StrVisitor(|s| Arc::from(s)))
}

/// [`shared_str`], for an optional one.
pub(crate) fn shared_str_opt<'de, D: Deserializer<'de>>(
    d: D,
) -> Result<Option<Arc<str>>, D::Error> {
    d.deserialize_option(OptionVisitor)
}

/// Reads a name many entries share (a reader's): every entry of a
/// state holds one, from a handful of names, read as one shared string
/// each ([`interned`]).
pub(crate) fn shared_name<'de, D: Deserializer<'de>>(d: D) -> Result<Arc<str>, D::Error> {
    d.deserialize_str(StrVisitor(interned))
}

/// `name` as a shared string: the one this thread made before for an
/// equal name, while it has made few.
pub(crate) fn interned(name: &str) -> Arc<str> {
    /// The names kept: more are made anew (a damaged state must not make
    /// the search long).
    const KEPT: usize = 64;
    thread_local! {
        static NAMES: std::cell::RefCell<Vec<Arc<str>>> = const { std::cell::RefCell::new(Vec::new()) };
    }
    NAMES.with_borrow_mut(|names| {
        if let Some(n) = names.iter().find(|n| ***n == *name) {
            return Arc::clone(n);
        }
        let n: Arc<str> = Arc::from(name);
        if names.len() < KEPT {
            names.push(Arc::clone(&n));
        }
        n
    })
}

/// Reads a string as a shared one, made by its function.
struct StrVisitor(fn(&str) -> Arc<str>);

impl Visitor<'_> for StrVisitor {
    type Value = Arc<str>;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a string")
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<Arc<str>, E> {
        Ok((self.0)(v))
    }
}

struct OptionVisitor;

impl<'de> Visitor<'de> for OptionVisitor {
    type Value = Option<Arc<str>>;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a string or none")
    }

    fn visit_none<E: de::Error>(self) -> Result<Self::Value, E> {
        Ok(None)
    }

    fn visit_unit<E: de::Error>(self) -> Result<Self::Value, E> {
        Ok(None)
    }

    fn visit_some<D: Deserializer<'de>>(self, d: D) -> Result<Self::Value, D::Error> {
        shared_str(d).map(Some)
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

    #[derive(Debug, PartialEq, Serialize, Deserialize)]
    struct Strings {
        #[serde(deserialize_with = "shared_str")]
        one: Arc<str>,
        #[serde(default, deserialize_with = "shared_str_opt")]
        maybe: Option<Arc<str>>,
    }

    #[test]
    fn shared_strings_read_as_serde_reads_them() {
        let cfg = bincode::config::standard();
        for maybe in [None, Some("b".into())] {
            let v = Strings {
                one: "a".into(),
                maybe,
            };
            let bytes = bincode::serde::encode_to_vec(&v, cfg).unwrap();
            let back: Strings = bincode::serde::decode_from_slice(&bytes, cfg).unwrap().0;
            assert_eq!(back, v);
            let plain: (Arc<str>, Option<Arc<str>>) =
                bincode::serde::decode_from_slice(&bytes, cfg).unwrap().0;
            assert_eq!((plain.0, plain.1), (v.one.clone(), v.maybe.clone()));
            let json = serde_json::to_string(&v).unwrap();
            assert_eq!(serde_json::from_str::<Strings>(&json).unwrap(), v);
        }
        let (a, b) = (interned("csv"), interned(&String::from("csv")));
        assert!(Arc::ptr_eq(&a, &b));
        assert!(!Arc::ptr_eq(&a, &interned("tsv")));
        let missing: Strings = serde_json::from_str(r#"{"one":"a"}"#).unwrap();
        assert_eq!(missing.maybe, None);
        assert!(serde_json::from_str::<Strings>(r#"{"one":1}"#).is_err());
    }
}
