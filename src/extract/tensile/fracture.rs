//! Start of loading and the fracture point (MODELS.md §3, "Fracture").
//!
//! - **Start of loading**: the first sample with strain ≥ 0. Samples before
//!   it (slack, negative strain) are not part of any integral; integrals
//!   start exactly at ε = 0 by interpolation.
//! - **Break point**: the last point before the final load drop to near
//!   zero. Let σ_max be the largest stress after the start and k the last
//!   sample with σ ≥ `break_level` · σ_max (everything after k is near
//!   zero). Walking back from k while the stress rises (in reverse), the
//!   walk stops at the local maximum that starts the final drop: that is
//!   the break point b, and ε_f = ε\[b\].
//! - A record that never falls near zero (k is the last sample) was cut
//!   during the drop or holds no fracture: it counts as fractured
//!   (`truncated`) only if the stress has fallen from σ\[b\] by at least
//!   `truncated_drop` · σ\[b\] at the last sample.

use super::params::TensileParams;
use crate::status::{Code, Status};

/// Where the break is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BreakPoint {
    /// Index of the first sample with strain ≥ 0.
    pub start: usize,
    /// Index of the break point b (the last point before the final drop).
    pub index: usize,
    /// Index k of the last sample with σ ≥ `break_level` · σ_max: the last
    /// recorded point before the stress falls near zero (ISO 527-1's and
    /// ISO 6892-1's point of fracture; k ≥ b).
    pub last_loaded: usize,
    /// Index of the maximum stress in `start..=index`.
    pub max_index: usize,
    /// The record ends during the final drop (no sample near zero after it).
    pub truncated: bool,
}

/// Why no break point was found.
#[derive(Debug, Clone, PartialEq)]
pub enum NoBreak {
    /// No sample has strain ≥ 0.
    NoLoading,
    /// The stress is never positive after the start of loading.
    NoLoad,
    /// The record holds no final drop: the stress at the end is still
    /// `end_fraction` of the stress at the last peak.
    NoFracture {
        /// σ(last sample) / σ(b).
        end_fraction: f64,
    },
}

impl NoBreak {
    /// Short status code for tables.
    pub fn status(&self) -> Status {
        match self {
            NoBreak::NoLoading => Status::of(Code::NoLoading, "no sample with strain >= 0"),
            NoBreak::NoLoad => Status::of(Code::NoLoad, "stress never positive"),
            NoBreak::NoFracture { end_fraction } => Status::of(
                Code::NoFracture,
                format!(
                    "record ends at {:.0} % of the last peak stress",
                    100.0 * end_fraction
                ),
            ),
        }
    }
}

/// Finds the start of loading and the break point. The slices must be
/// finite and of equal length.
pub fn find_break(
    strain: &[f64],
    stress: &[f64],
    params: &TensileParams,
) -> Result<BreakPoint, NoBreak> {
    let n = strain.len().min(stress.len());
    let start = (0..n)
        .find(|&i| strain[i] >= 0.0)
        .ok_or(NoBreak::NoLoading)?;
    let (max_index, smax) =
        (start..n)
            .map(|i| (i, stress[i]))
            .fold((start, f64::NEG_INFINITY), |acc, (i, s)| {
                if s > acc.1 {
                    (i, s)
                } else {
                    acc
                }
            });
    // NaN-safe: a NaN maximum is not positive either
    if smax.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return Err(NoBreak::NoLoad);
    }
    let near = params.break_level * smax;
    // the maximum itself satisfies the condition, so k exists
    let k = (start..n)
        .rev()
        .find(|&i| stress[i] >= near)
        .unwrap_or(max_index);
    let mut b = k;
    while b > start && stress[b - 1] > stress[b] {
        b -= 1;
    }
    let truncated = k + 1 == n;
    if truncated {
        let end_fraction = stress[n - 1] / stress[b];
        if 1.0 - end_fraction < params.truncated_drop {
            return Err(NoBreak::NoFracture { end_fraction });
        }
    }
    let max_index = (start..=b)
        .max_by(|&i, &j| stress[i].total_cmp(&stress[j]).then(j.cmp(&i)))
        .unwrap_or(b);
    Ok(BreakPoint {
        start,
        index: b,
        last_loaded: k,
        max_index,
        truncated,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn break_is_the_peak_before_the_final_drop() {
        let e = [-0.1, -0.05, 0.0, 0.1, 0.2, 0.3, 0.31, 0.32, 0.33];
        let s = [5.0, 3.0, 0.0, 10.0, 20.0, 30.0, 12.0, 1.0, 0.5];
        let b = find_break(&e, &s, &TensileParams::default()).unwrap();
        assert_eq!((b.start, b.index, b.max_index), (2, 5, 5));
        assert!(!b.truncated);
    }

    #[test]
    fn a_record_cut_during_the_drop_is_a_truncated_fracture() {
        let e = [0.0, 0.1, 0.2, 0.3, 0.31, 0.32];
        let s = [0.0, 10.0, 20.0, 30.0, 25.0, 15.0];
        let b = find_break(&e, &s, &TensileParams::default()).unwrap();
        assert_eq!(b.index, 3);
        assert!(b.truncated);
    }

    #[test]
    fn a_record_without_drop_has_no_fracture() {
        let e = [0.0, 0.1, 0.2, 0.3];
        let s = [0.0, 10.0, 20.0, 30.0];
        let err = find_break(&e, &s, &TensileParams::default()).unwrap_err();
        assert!(matches!(err, NoBreak::NoFracture { .. }), "{err:?}");
        assert!(err.status().has(Code::NoFracture));
        assert_eq!(
            find_break(&[-1.0, -0.5], &[1.0, 2.0], &TensileParams::default()),
            Err(NoBreak::NoLoading)
        );
        assert_eq!(
            find_break(&[0.0, 0.5], &[0.0, -2.0], &TensileParams::default()),
            Err(NoBreak::NoLoad)
        );
    }

    #[test]
    fn an_earlier_higher_peak_is_the_strength_not_the_break() {
        // a knot peak above the final fracture stress
        let e = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6];
        let s = [0.0, 40.0, 5.0, 20.0, 30.0, 0.5, 0.2];
        let b = find_break(&e, &s, &TensileParams::default()).unwrap();
        assert_eq!((b.index, b.max_index), (4, 1));
    }
}
