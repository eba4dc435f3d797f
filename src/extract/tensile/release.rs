//! Knot release ε* and the stress drops of a knotted fibre (MODELS.md §3).
//!
//! Between the start of loading and the break point the stress of a knotted
//! fibre shows a friction plateau with stick-slip drops, a few pronounced
//! unfastening peaks (one per turn of the knot) and, once the knot is
//! released, a final monotone rise that follows the unknotted fibre up to
//! fracture. ε* is the start of that final rise:
//!
//! 1. Drops are found with hysteresis h = max(`noise_factor` · s_noise,
//!    `drop_min_fraction` · strength) ([`crate::signal::drops`]), so noise
//!    neither creates nor splits drops.
//! 2. The rise starts at the later of (a) the trough of the last drop and
//!    (b) the last sample whose stress is at most h (the zero-stress floor,
//!    for a knot that slides out without stick-slip).
//! 3. ε* is **clear** when the rise starts at a stress ≤
//!    `release_max_fraction` · strength and either a drop precedes it or the
//!    floor extends beyond `release_min_strain` · ε_f. Otherwise no ε* is
//!    given (status `unclear`) and the control fibre is used (Eq. 5.4).
//!
//! Drops before ε* are split into the **final unfastening** (the trailing
//! run of drops whose peak exceeds `unfastening_factor` × the plateau
//! level, the median stress before ε*) and the **plateau** (all others).

use crate::signal::drops::{detect_drops, Drop};
use crate::signal::stats::noise_sigma;

use super::params::TensileParams;

/// How ε* was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ReleaseStatus {
    /// The final rise starts at the trough of the last unfastening drop.
    AfterDrop,
    /// No unfastening drop: the final rise starts where the stress leaves
    /// the zero floor after a loose knot region.
    FromFloor,
    /// No clear release (Eq. 5.3 not applicable; Eq. 5.4 with the control).
    Unclear,
    /// Unknotted fibre.
    NotApplicable,
}

impl ReleaseStatus {
    /// Name used in tables.
    pub fn name(self) -> &'static str {
        match self {
            ReleaseStatus::AfterDrop => "after_drop",
            ReleaseStatus::FromFloor => "from_floor",
            ReleaseStatus::Unclear => "unclear",
            ReleaseStatus::NotApplicable => "not_applicable",
        }
    }
}

/// The result of the release analysis on `start..=b`.
#[derive(Debug, Clone, PartialEq)]
pub struct Release {
    /// How ε* was found.
    pub status: ReleaseStatus,
    /// Index of ε* in the whole curve, when clear.
    pub index: Option<usize>,
    /// Stress drops in the plateau.
    pub plateau_drops: usize,
    /// Stress drops in the final unfastening.
    pub unfastening_drops: usize,
    /// The hysteresis h used, Pa.
    pub hysteresis_pa: f64,
}

/// Finds ε* and counts drops on the loaded part `start..=b` of a knotted
/// fibre's curve. `strength` is the maximum stress, `strain_at_break` ε_f.
pub fn find_release(
    strain: &[f64],
    stress: &[f64],
    start: usize,
    b: usize,
    strength: f64,
    params: &TensileParams,
) -> Release {
    let seg = &stress[start..=b];
    let noise = noise_sigma(seg).unwrap_or(0.0);
    let h = (params.noise_factor * noise).max(params.drop_min_fraction * strength);
    let drops: Vec<Drop> = detect_drops(seg, h)
        .into_iter()
        .map(|d| Drop {
            peak: d.peak + start,
            trough: d.trough + start,
            ..d
        })
        .collect();
    let last_trough = drops.last().map(|d| d.trough);
    let floor = (start..=b).rev().find(|&i| stress[i] <= h);
    let rise = match (last_trough, floor) {
        (Some(t), Some(f)) => Some(t.max(f)),
        (t, f) => t.or(f),
    };
    let strain_at_break = strain[b];
    let status = match rise {
        Some(r) if stress[r] > params.release_max_fraction * strength => ReleaseStatus::Unclear,
        Some(r) if last_trough.is_some_and(|t| t == r) => ReleaseStatus::AfterDrop,
        Some(r) if strain[r] > params.release_min_strain * strain_at_break => {
            if last_trough.is_some() {
                // the floor after the last drop: still a release after a drop
                ReleaseStatus::AfterDrop
            } else {
                ReleaseStatus::FromFloor
            }
        }
        _ => ReleaseStatus::Unclear,
    };
    let index = match status {
        ReleaseStatus::AfterDrop | ReleaseStatus::FromFloor => rise,
        _ => None,
    };
    let knot_end = index.unwrap_or(b);
    let before: Vec<&Drop> = drops.iter().filter(|d| d.trough <= knot_end).collect();
    let plateau_level = crate::signal::stats::median(&stress[start..=knot_end]).unwrap_or(0.0);
    let unfastening = before
        .iter()
        .rev()
        .take_while(|d| stress[d.peak] > params.unfastening_factor * plateau_level)
        .count();
    Release {
        status,
        index,
        plateau_drops: before.len() - unfastening,
        unfastening_drops: unfastening,
        hysteresis_pa: h,
    }
}
