//! Hierarchical ALSFM (thesis Sec. 2.3, 2.4, Eq. 2.10–2.19; MODELS.md §5
//! "Hierarchy").
//!
//! Level i uses the previous level's global coefficient as its local one:
//! μ_i = f(μ_{i−1}; z1, z2, β) (Eq. 2.11), level 1 being the innermost (the
//! smallest scale) with μ0. Self-similar levels (Eq. 2.10, scale factor
//! A = B = C) have the same slopes at every level, and with the load scaled
//! with the level's size the contact looks the same at every level, so f is
//! one function evaluated once per level; scales are never resolved on one
//! grid. At β = 90° for wedges this gives Eq. 2.17.
//!
//! Applicability can fail at an outer level (μ_{i−1} ≥ cot φ): the cascade
//! stops there and reports the level at which the surfaces lock.
//!
//! Hierarchical wear (Sec. 2.4, Eq. 2.19): the innermost level wears first,
//! in T_w,1 = V0 / (W v); then level 2 in T_w,2 = c V0 / (W v) (its heights,
//! and so its volume, are c times larger, c the scale factor), and so on. While
//! level j wears, levels below it are flat (μ_{j−1} = μ0 for j = 1, ... the
//! local coefficient), and the levels above follow through the cascade.

use crate::error::{ErrorKind, Result};
use crate::status::Status;

/// The outcome of a cascade.
#[derive(Debug, Clone, PartialEq)]
pub struct Cascade {
    /// μ_0 (local), μ_1, ... up to the last level evaluated.
    pub mu: Vec<f64>,
    /// The level at which the cascade stopped (the surfaces lock, or no
    /// coefficient), with the status it stopped with.
    pub locked: Option<(usize, Status)>,
}

/// Runs μ_i = f(i, μ_{i−1}) for i = 1..=levels. A not-applicable error
/// from f stops the cascade and is recorded, with its status, as the level
/// that locks; other errors are returned.
pub fn cascade(
    mu0: f64,
    levels: usize,
    mut f: impl FnMut(usize, f64) -> Result<f64>,
) -> Result<Cascade> {
    let mut mu = vec![mu0];
    for level in 1..=levels {
        let prev = mu[level - 1];
        match f(level, prev) {
            Ok(m) => mu.push(m),
            Err(e) if e.kind() == ErrorKind::NotApplicable => {
                return Ok(Cascade {
                    mu,
                    locked: Some((level, e.status())),
                })
            }
            Err(e) => return Err(e),
        }
    }
    Ok(Cascade { mu, locked: None })
}

/// Which level is wearing at time t and its reduction B, for hierarchical
/// wear: level j (1-based, innermost first) wears during
/// [Σ_{k<j} T_k, Σ_{k≤j} T_k) with T_k = T_w,1 c^{k−1}. Returns
/// (level, B); after the last level, (levels + 1, 0): everything is flat.
pub fn wearing_level(t: f64, t_w1: f64, scale: f64, levels: usize) -> (usize, f64) {
    let mut start = 0.0;
    for j in 1..=levels {
        let tj = t_w1 * scale.powi(j as i32 - 1);
        if t < start + tj {
            return (j, 1.0 - (t - start) / tj);
        }
        start += tj;
    }
    (levels + 1, 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Error;

    /// The cascade applies f repeatedly and stops at the locking level.
    #[test]
    fn cascade_stops_at_lock() {
        let c = cascade(0.3, 4, |_, m| {
            if m > 0.5 {
                Err(Error::NotApplicable("lock".into()))
            } else {
                Ok(2.0 * m)
            }
        })
        .unwrap();
        assert_eq!(c.mu.len(), 2); // μ0 = 0.3, μ1 = 0.6; level 2 locks
        assert!((c.mu[1] - 0.6).abs() < 1e-15);
        assert_eq!(c.locked.as_ref().map(|l| l.0), Some(2));
    }

    /// Wear schedule: T_1 = 1, T_2 = 10 (c = 10).
    #[test]
    fn wear_schedule() {
        assert_eq!(wearing_level(0.5, 1.0, 10.0, 2).0, 1);
        let (l, b) = wearing_level(6.0, 1.0, 10.0, 2);
        assert!(l == 2 && (b - 0.5).abs() < 1e-15);
        assert_eq!(wearing_level(11.0, 1.0, 10.0, 2), (3, 0.0));
    }
}
