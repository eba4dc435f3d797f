//! A list as the one before it with its middle replaced: how the state's
//! log records a list in input order ([`super::state_log`]).

use serde::{Deserialize, Serialize};

/// A list as the one before it with its middle replaced: what a run that
/// adds, changes or removes a few inputs does to a list in input order.
#[derive(Debug, PartialEq, Serialize, Deserialize)]
pub(super) struct Splice<T> {
    /// Items kept from the start.
    front: u64,
    /// Items kept from the end.
    back: u64,
    /// The items between.
    middle: Vec<T>,
}

impl<T: Clone + PartialEq> Splice<T> {
    pub(super) fn between(old: &[T], new: &[T]) -> Self {
        let front = old.iter().zip(new).take_while(|(a, b)| a == b).count();
        let (old_rest, new_rest) = (&old[front..], &new[front..]);
        let back = old_rest
            .iter()
            .rev()
            .zip(new_rest.iter().rev())
            .take_while(|(a, b)| a == b)
            .count();
        Splice {
            front: front as u64,
            back: back as u64,
            middle: new_rest[..new_rest.len() - back].to_vec(),
        }
    }

    /// Whether a list of `len` items holds what it keeps.
    pub(super) fn fits(&self, len: usize) -> bool {
        let kept = self.front.checked_add(self.back);
        kept.is_some_and(|k| k <= len as u64)
    }

    /// Replaces the middle of `v`, which it [`fits`](Self::fits).
    pub(super) fn apply_to(self, v: &mut Vec<T>) {
        let (front, back) = (self.front as usize, self.back as usize);
        let tail = v.len() - back;
        v.splice(front..tail, self.middle);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_splice_rebuilds_the_new_list_from_the_old() {
        let cases: [(&[u32], &[u32]); 7] = [
            (&[], &[]),
            (&[], &[1, 2]),
            (&[1, 2, 3], &[]),
            (&[1, 2, 3], &[1, 9, 3]),
            (&[1, 2, 3], &[1, 2, 3, 4]),
            (&[1, 1, 1], &[1, 1]),
            (&[1, 2, 1, 2], &[1, 2, 7, 1, 2]),
        ];
        for (old, new) in cases {
            let s = Splice::between(old, new);
            assert!(s.middle.len() <= new.len());
            assert!(s.fits(old.len()));
            let mut v = old.to_vec();
            s.apply_to(&mut v);
            assert_eq!(v, new, "{old:?} -> {new:?}");
        }
        let s = Splice::between(&[1, 2, 3], &[1, 9, 3]);
        assert_eq!((s.front, s.back, s.middle.as_slice()), (1, 1, &[9][..]));
        // A list shorter than what the splice keeps of it is refused.
        assert!(!s.fits(1));
    }
}
