//! Doubts a friction row can carry: each checks one thing and pushes a
//! status note (or nulls a value that is not a measurement).

use super::rows::FrictionRow;
use crate::status::{Code, Status};

/// A static peak this early in a segment is likely the segment's edge (a
/// stroke reversal, the start of the record), not a break-away.
const EARLY_PEAK_SAMPLES: usize = 3;

/// A static peak at the edge of its segment.
pub(super) fn doubt_early_peak(index: usize, notes: &mut Status) {
    if index < EARLY_PEAK_SAMPLES {
        notes.push(
            Code::PeakAtStart,
            format!("static peak at sample {} of the segment", index + 1),
        );
    }
}

/// μ_s below μ_d: the "static peak" was taken before the force reached its
/// plateau (on a rising edge), or there is no break-away peak at all.
pub(super) fn doubt_static_below_dynamic(row: &FrictionRow, notes: &mut Status) {
    if let (Some(s), Some(d)) = (row.mu_static, row.mu_dynamic) {
        if s < d {
            notes.push(
                Code::StaticBelowDynamic,
                format!("μ_s = {s:.4} < μ_d = {d:.4}: the peak may be on a rising edge"),
            );
        }
    }
}

/// A normal force that ramps across the segment (a load-ramp step): its
/// "plateau" is a stretch of a ramp, not a steady state; the step rows say
/// the same.
/// `ramp` is [`super::steps::load_ramp`]'s finding over the stroke.
pub(super) fn doubt_load_ramp(ramp: Option<(f64, f64)>, notes: &mut Status) {
    if let Some((a, b)) = ramp {
        notes.push(
            Code::LoadRamp,
            format!("the normal force ramps from {a:.4} N to {b:.4} N across the segment: the dynamic window is part of a ramp"),
        );
    }
}

/// The largest coefficient of friction taken as a measurement. Clean metals
/// in vacuum and adhesive elastomers reach μ of a few to some tens; a μ
/// beyond this bound comes from a normal force in the wrong unit or a
/// near-zero load (Fz = 1e-300 N gives μ = 1e300), not from a contact.
pub const MU_PLAUSIBLE_MAX: f64 = 100.0;

/// μ values beyond [`MU_PLAUSIBLE_MAX`] are not reported as numbers: they
/// become null with an `absurd_magnitude` status naming them.
pub(super) fn refuse_absurd_mu(row: &mut FrictionRow, notes: &mut Status) {
    for (name, mu) in [("μ_s", &mut row.mu_static), ("μ_d", &mut row.mu_dynamic)] {
        if let Some(m) = mu.filter(|m| !m.is_finite() || m.abs() > MU_PLAUSIBLE_MAX) {
            notes.push(
                Code::AbsurdMagnitude,
                format!(
                    "{name} = {m:.4e} with N = {:.4e} N: beyond {MU_PLAUSIBLE_MAX}, not a coefficient of friction (check the normal force's unit and values)",
                    row.normal_force_n.unwrap_or(f64::NAN)
                ),
            );
            *mu = None;
        }
    }
    if row.mu_dynamic.is_none() {
        row.mu_dynamic_sd = None;
    }
}

/// No normal force at all, or a non-positive one: μ is undefined.
pub(super) fn doubt_normal_force(row: &FrictionRow, notes: &mut Status) {
    match row.normal_force_n {
        None if row.normal_force_source.is_none() => notes.push(
            Code::NoNormalForce,
            "neither a normal-force column nor normal_force_N/mass_g in the manifest",
        ),
        Some(n) if n <= 0.0 => notes.push(
            Code::NonpositiveNormalForce,
            format!("N = {n} N, μ undefined"),
        ),
        _ => {}
    }
}
