//! From an ingested file to a stress–strain curve and the instrument's own
//! results.
//!
//! Channels are recognised by unit and name: strain (a dimensionless unit
//! such as `mm/mm` or `%`, name containing "strain"), stress (a stress
//! unit), force (a force unit, name containing "load" or "force"), and
//! extension (a length unit, name containing "extension", "displacement",
//! "elongation" or "position").
//!
//! - **Stress**: the stress column when there is one, rescaled by
//!   (d_file / d)² when the manifest's diameter d differs from the file's;
//!   otherwise σ = F / (π d² / 4) from the force column and the diameter
//!   (manifest first, else file).
//! - **Strain**: the strain column when there is one; otherwise
//!   (x − x₀) / L from the extension, with x₀ its value at the start of
//!   the final loading ([`foot`]: the first sample, unless the load falls
//!   back to its first level before its maximum) and L the gauge length
//!   (l0 for a knotted fibre, else the manifest's `gauge_length_mm`, else
//!   l, else the file's).
//! - **Direction**: compression when the largest load is negative (or the
//!   manifest says so); stress and strain are then turned into magnitudes.
//! - **Strain reference length** (for the conversion to l0 of Eq. 5.2): the
//!   file's gauge length when stated (Bluehill `Length`), else the
//!   least-squares slope of extension against strain (T150).

use std::f64::consts::PI;
use std::path::Path;

use crate::error::{Error, Location, Result};
use crate::ingest::roles::{tensile_channel, TensileRole};
use crate::ingest::{Channel, Dataset};
use crate::status::{Code, Status};
use crate::units::Unit;

use super::class::Direction;
use super::curve::{FibreMeta, StressStrainCurve};
pub use super::facts::{file_facts, FileFacts};

/// The channel with a tensile role and its unit ([`tensile_channel`]).
/// Stress in Pa: the stress column (rescaled by (d_file / d)² when the
/// manifest's diameter differs from the file's), else force over the
/// section (circular, rectangular or the file's area).
fn stress_pa(
    source: &Path,
    stress_ch: Option<(&Channel, Unit)>,
    force_ch: Option<(&Channel, Unit)>,
    meta: &FibreMeta,
    facts: &FileFacts,
) -> Result<Vec<f64>> {
    let loc = || Location::file(source);
    let diameter = meta.diameter_m.or(facts.diameter_m);
    if let Some(d) = diameter {
        if !(d > 0.0 && d.is_finite()) {
            return Err(Error::input(
                loc(),
                format!("fibre diameter {} um: expected a value > 0", d * 1e6),
            ));
        }
    }
    Ok(match (stress_ch, force_ch, diameter) {
        (Some((c, u)), _, _) => {
            let s = si(c, &u);
            match (meta.diameter_m, facts.diameter_m) {
                (Some(d), Some(df)) => {
                    let k = (df / d).powi(2);
                    s.into_iter().map(|v| v * k).collect()
                }
                _ => s,
            }
        }
        (None, Some((c, u)), Some(d)) => {
            let area = PI * d * d / 4.0;
            si(c, &u).into_iter().map(|f| f / area).collect()
        }
        (None, Some((c, u)), None) => {
            let w = meta.width_m.or(facts.width_m);
            let t = meta.thickness_m.or(facts.thickness_m);
            let area = match (w, t) {
                (Some(w), Some(t)) => Some(w * t),
                _ => meta.area_m2.or(facts.area_m2),
            };
            match area {
                Some(a) if a > 0.0 && a.is_finite() => {
                    si(c, &u).into_iter().map(|f| f / a).collect()
                }
                _ => {
                    return Err(Error::input(
                        loc().with_column(&c.name),
                        "force column but no section: give diameter_um (circular) or \
                         width_mm and thickness_mm (rectangular, each > 0) in the manifest",
                    ))
                }
            }
        }
        (None, None, _) => {
            return Err(Error::input(
                loc(),
                "no stress column (unit Pa, kPa, MPa, GPa) and no force column \
                 (unit N, mN, ...; name containing 'load' or 'force')",
            ))
        }
    })
}

/// Strain, and the length it is relative to when known: the strain column
/// (reference from the file's gauge length or the extension), else the
/// extension over the gauge length from its value at the sample `foot`
/// (the start of the final loading, [`foot`]).
fn strain_and_reference(
    source: &Path,
    strain_ch: Option<(&Channel, Unit)>,
    ext: Option<Vec<f64>>,
    foot: usize,
    meta: &FibreMeta,
    facts: &FileFacts,
) -> Result<(Vec<f64>, Option<f64>)> {
    let loc = || Location::file(source);
    Ok(match (strain_ch, &ext) {
        (Some((c, u)), _) => {
            let e = si(c, &u);
            let r = facts
                .gauge_length_m
                .or_else(|| ext.as_ref().and_then(|x| reference_from_extension(&e, x)));
            (e, r)
        }
        (None, Some(x)) => {
            let gauge = if meta.knot.is_knotted() {
                meta.end_distance_m
            } else {
                meta.gauge_length_m
                    .or(meta.fibre_length_m)
                    .or(meta.end_distance_m)
            }
            .or(facts.gauge_length_m)
            .ok_or_else(|| {
                Error::input(
                    loc(),
                    "extension but no strain column and no gauge length: give \
                     gauge_length_mm (or a fibre's fibre_length_mm / end_distance_mm) \
                     in the manifest",
                )
            })?;
            let x0 = x[foot..]
                .iter()
                .chain(x)
                .copied()
                .find(|v| v.is_finite())
                .unwrap_or(0.0);
            (x.iter().map(|v| (v - x0) / gauge).collect(), Some(gauge))
        }
        (None, None) => {
            return Err(Error::input(
                loc(),
                "no strain column (unit mm/mm, %, 1; name containing 'strain') and no \
                 extension column (unit mm, um, ...)",
            ))
        }
    })
}

/// A displacement channel zeroed again before the maximum load (a tare at
/// the preload, as MTS procedures do): one step more than 50 times the
/// channel's median step and 20 times the steps around it, while the load
/// moves by less than 5 % of its largest magnitude (a fracture drops it). Each such step is taken
/// out: the samples before it are shifted so that the channel joins there,
/// moving at the tare's sample as its neighbours do. Returns the corrected channel
/// and, per step, its sample and size.
pub fn join_rezeroed(x: &[f64], load: &[f64], upto: usize) -> (Vec<f64>, Vec<(usize, f64)>) {
    let n = x.len().min(load.len()).min(upto + 1);
    let steps = |v: &[f64]| -> Vec<f64> {
        let mut d: Vec<f64> = (1..n)
            .map(|i| (v[i] - v[i - 1]).abs())
            .filter(|d| d.is_finite() && *d > 0.0)
            .collect();
        d.sort_by(f64::total_cmp);
        d
    };
    let median = |d: &[f64]| d.get(d.len() / 2).copied();
    let mut out = x.to_vec();
    let Some(dx) = median(&steps(x)) else {
        return (out, Vec::new());
    };
    let top = load[..n]
        .iter()
        .filter(|v| v.is_finite())
        .fold(0.0_f64, |a, v| a.max(v.abs()));
    let step = |i: usize| match i >= 1 && i < x.len() {
        true => (x[i] - x[i - 1]).abs(),
        false => 0.0,
    };
    let mut jumps = Vec::new();
    for i in 1..n {
        let (jx, jf) = (x[i] - x[i - 1], (load[i] - load[i - 1]).abs());
        // isolated: the steps around it are ordinary (a necking specimen
        // stretches fast at a flat load, step after step)
        let around = [i.saturating_sub(2), i - 1, i + 1, i + 2]
            .into_iter()
            .filter(|&k| k != i)
            .map(step)
            .fold(0.0, f64::max);
        if jx.abs() > 50.0 * dx && jx.abs() > 20.0 * around && jf < 0.05 * top {
            // the motion during the tare's step is that of its neighbours
            let signed = |k: usize| (k >= 1 && k < x.len()).then(|| x[k] - x[k - 1]);
            let near: Vec<f64> = [signed(i - 1), signed(i + 1)]
                .into_iter()
                .flatten()
                .collect();
            let moved = near.iter().sum::<f64>() / near.len().max(1) as f64;
            let shift = jx - moved;
            jumps.push((i, shift));
            out[..i].iter_mut().for_each(|v| *v += shift);
        }
    }
    (out, jumps)
}

/// The start of the final loading: the last sample before the largest
/// load magnitude at which the magnitude is at most its first value. A
/// record that rises from its first sample starts there; a hot tensile
/// test that holds its grips (and expands) before it is pulled starts at
/// the foot of the pull, so that heating is not counted as strain.
pub fn foot(load: &[f64]) -> usize {
    let mag = |i: usize| load[i].abs();
    let Some(m) = (0..load.len())
        .filter(|&i| load[i].is_finite())
        .max_by(|&i, &j| mag(i).total_cmp(&mag(j)).then(j.cmp(&i)))
    else {
        return 0;
    };
    let first = (0..=m).find(|&i| load[i].is_finite()).unwrap_or(0);
    (first..=m)
        .rev()
        .find(|&i| mag(i) <= mag(first))
        .unwrap_or(first)
}

/// The direction of a test from its load: compression when the largest
/// magnitude is negative.
fn direction_of(load: &[f64]) -> Direction {
    let (lo, hi) = load
        .iter()
        .filter(|v| v.is_finite())
        .fold((0.0_f64, 0.0_f64), |(lo, hi), &v| (lo.min(v), hi.max(v)));
    match -lo > hi {
        true => Direction::Compression,
        false => Direction::Tension,
    }
}

/// Turns a compression record into magnitudes: the load negated when its
/// extreme is negative, the strain when it falls from its start to the
/// load's extreme (a strain column signed with the load, a crosshead that
/// moves down).
fn as_magnitudes(strain: &mut [f64], stress: &mut [f64]) {
    let Some(m) = super::general::max_index(&stress.iter().map(|v| v.abs()).collect::<Vec<_>>())
    else {
        return;
    };
    if stress[m] < 0.0 {
        stress.iter_mut().for_each(|v| *v = -*v);
    }
    let first = strain
        .iter()
        .copied()
        .find(|v| v.is_finite())
        .unwrap_or(0.0);
    if strain[m] < first {
        strain.iter_mut().for_each(|v| *v = -*v);
    }
}

fn find(channels: &[Channel], role: TensileRole) -> Option<(&Channel, Unit)> {
    tensile_channel(channels, role).map(|(i, u)| (&channels[i], u))
}

fn si(c: &Channel, u: &Unit) -> Vec<f64> {
    c.values.iter().map(|&v| u.to_si(v)).collect()
}

/// Least-squares slope of extension (m) on strain over samples with ε ≥ 0.
fn reference_from_extension(strain: &[f64], ext: &[f64]) -> Option<f64> {
    let pts: Vec<(f64, f64)> = strain
        .iter()
        .zip(ext)
        .filter(|(e, x)| **e >= 0.0 && e.is_finite() && x.is_finite())
        .map(|(e, x)| (*e, *x))
        .collect();
    let n = pts.len() as f64;
    if pts.len() < 3 {
        return None;
    }
    let me = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let mx = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let see: f64 = pts.iter().map(|p| (p.0 - me) * (p.0 - me)).sum();
    let sex: f64 = pts.iter().map(|p| (p.0 - me) * (p.1 - mx)).sum();
    (see > 0.0).then(|| sex / see).filter(|l| *l > 0.0)
}

/// Builds the stress–strain curve of a specimen from its file (its
/// largest section): stress and strain as magnitudes, the direction, and
/// the largest force when the file has a force column; the notes say what
/// was corrected (a re-zeroed displacement, [`join_rezeroed`]).
pub fn curve_from_dataset(
    ds: &Dataset,
    meta: &FibreMeta,
    facts: &FileFacts,
) -> Result<(StressStrainCurve, Status)> {
    let loc = || Location::file(&ds.source);
    let section = ds
        .sections
        .iter()
        .max_by_key(|s| s.rows())
        .ok_or_else(|| Error::input(loc(), "no data section"))?;
    let ch = &section.channels;
    // English and German names (testXpert: Dehnung, Standardkraft,
    // Standardweg): ingest::roles::TensileRole.
    let strain_ch = find(ch, TensileRole::Strain);
    let stress_ch = find(ch, TensileRole::Stress);
    let force_ch = find(ch, TensileRole::Force);
    let ext_ch = find(ch, TensileRole::Extension);
    let force = force_ch.as_ref().map(|(c, u)| si(c, u));
    let mut stress = stress_pa(&ds.source, stress_ch, force_ch, meta, facts)?;
    let at = foot(&stress);
    let mut notes = Status::ok();
    let ext = ext_ch.map(|(c, u)| {
        let peak = super::general::max_index(&stress.iter().map(|v| v.abs()).collect::<Vec<_>>());
        let (x, jumps) = join_rezeroed(&si(c, &u), &stress, peak.unwrap_or(0));
        for (i, j) in jumps {
            notes.push(
                Code::Rezeroed,
                format!(
                    "'{}' was zeroed again at data row {} (a step of {} mm at a steady load): \
                     the samples before it are shifted to join",
                    c.name,
                    i + 1,
                    crate::crosscheck::sig(j * 1e3)
                ),
            );
        }
        x
    });
    let (mut strain, reference) =
        strain_and_reference(&ds.source, strain_ch, ext, at, meta, facts)?;
    let direction = meta.direction.unwrap_or_else(|| direction_of(&stress));
    if direction == Direction::Compression {
        as_magnitudes(&mut strain, &mut stress);
    }
    let mut curve = StressStrainCurve::new(strain, stress)?;
    curve.strain_reference_m = reference;
    curve.direction = direction;
    curve.max_force_n = force.and_then(|f| {
        let sign = match direction {
            Direction::Compression if direction_of(&f) == Direction::Compression => -1.0,
            _ => 1.0,
        };
        f.iter()
            .map(|v| sign * v)
            .filter(|v| v.is_finite())
            .reduce(f64::max)
    });
    Ok((curve, notes))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_foot_is_the_start_of_the_final_pull() {
        // a preload that rises at once
        assert_eq!(foot(&[1.0, 2.0, 3.0, 2.0]), 0);
        // a hold at 120 with a dip to -270, then the pull
        assert_eq!(
            foot(&[123.0, -274.0, 130.0, 110.0, 500.0, 7000.0, 300.0]),
            3
        );
        // compression: magnitudes
        assert_eq!(foot(&[-1.2, -1.1, -50.0, -470.0, 0.1]), 1);
        assert_eq!(foot(&[]), 0);
        assert_eq!(
            direction_of(&[0.1, -3.0, -470.0, 0.2]),
            Direction::Compression
        );
        let (mut e, mut s) = (vec![0.0, -0.001, -0.002], vec![0.0, -10e6, -20e6]);
        as_magnitudes(&mut e, &mut s);
        assert_eq!((e[2], s[2]), (0.002, 20e6));
    }

    /// MTS 793's tare at the preload: the displacement jumps by 1.7 mm at
    /// one step while the load goes on rising at its usual pace.
    #[test]
    fn a_rezeroed_displacement_is_joined() {
        let load: Vec<f64> = (0..40).map(|i| -(i as f64) * 2.0).collect();
        let mut x: Vec<f64> = (0..40).map(|i| -1.7 - 0.006 * i as f64).collect();
        for v in &mut x[20..] {
            *v += 1.7;
        }
        let (joined, jumps) = join_rezeroed(&x, &load, 39);
        assert_eq!(jumps.len(), 1);
        assert_eq!(jumps[0].0, 20);
        // continuous: every step is the steady −0.006 but the joined one (0)
        let steps: Vec<f64> = joined.windows(2).map(|w| w[1] - w[0]).collect();
        assert!(steps
            .iter()
            .enumerate()
            .all(|(i, d)| i == 19 || (d + 0.006).abs() < 1e-9));
        // a jump with the load (a fracture) is not a tare
        let mut f = load.clone();
        f[20] = 60.0;
        assert!(join_rezeroed(&x, &f, 39).1.is_empty());
        // nor a run of long steps at a flat load (necking)
        let flat = vec![100.0; 40];
        let neck: Vec<f64> = (0..40)
            .map(|i| {
                if i < 20 {
                    i as f64 * 1e-4
                } else {
                    0.002 + (i - 20) as f64 * 0.03
                }
            })
            .collect();
        assert!(join_rezeroed(&neck, &flat, 39).1.is_empty());
    }
}
