//! The canonical friction trace: the channels the friction stage needs, in
//! SI, taken from one section of a [`Dataset`].

use std::collections::BTreeMap;

use super::radius::TrackRadius;
use super::roles::{assign_roles, missing_column, Role};
use super::{Dataset, Section};
use crate::error::{Error, Location, Result};
use crate::units::{Quantity, Unit};

/// A friction trace in SI units. Optional channels are `None` when the file
/// has no such column.
#[derive(Debug, Clone, PartialEq)]
pub struct Trace {
    /// Section name within the file.
    pub section: String,
    /// Time, s.
    pub time_s: Vec<f64>,
    /// Tangential force T, N, with its sign (it flips with the stroke).
    /// When the file has no friction-force column but the instrument's
    /// coefficient, T = μ N (see `friction_from_cof`).
    pub friction_n: Vec<f64>,
    /// True when T was computed as μ N from the instrument's coefficient
    /// and the normal force (column or manifest), the file having no
    /// friction-force column.
    pub friction_from_cof: bool,
    /// Normal force N, N, as a compressive magnitude (see `normal_flipped`).
    pub normal_n: Option<Vec<f64>>,
    /// Sliding velocity, m/s.
    pub velocity_m_per_s: Option<Vec<f64>>,
    /// Position or sliding distance, m.
    pub position_m: Option<Vec<f64>>,
    /// Temperature, K.
    pub temperature_k: Option<Vec<f64>>,
    /// The instrument's own coefficient of friction.
    pub instrument_cof: Option<Vec<f64>>,
    /// The recipe step of each sample, as the file numbers it (a step or
    /// segment column): the velocity steps are then the file's.
    pub step: Option<Vec<f64>>,
    /// The file's lap counter (rotary tests), laps.
    pub laps: Option<Vec<f64>>,
    /// The rotary drive's angle, rad.
    pub angle_rad: Option<Vec<f64>>,
    /// A linear-wear (depth) channel, m, as the file signs it.
    pub wear_depth_m: Option<Vec<f64>>,
    /// Column used for each role, for `inspect` and provenance.
    pub columns: BTreeMap<Role, String>,
    /// True when the file's normal force was negative for compression (as
    /// on the CETR UMT) and its sign was flipped.
    pub normal_flipped: bool,
    /// The track radius that turned a rotational speed into the sliding
    /// velocity, with its source; `None` when the velocity is linear.
    pub track_radius: Option<TrackRadius>,
}

impl Trace {
    /// Number of samples.
    pub fn len(&self) -> usize {
        self.time_s.len()
    }
    /// Whether the trace has no samples.
    pub fn is_empty(&self) -> bool {
        self.time_s.is_empty()
    }
    /// A trace of section `1` with time, friction force and, when given,
    /// normal force, every other channel absent (a generated trace).
    pub fn of_forces(time_s: Vec<f64>, friction_n: Vec<f64>, normal_n: Option<Vec<f64>>) -> Trace {
        Trace {
            section: "1".into(),
            time_s,
            friction_n,
            friction_from_cof: false,
            normal_n,
            velocity_m_per_s: None,
            position_m: None,
            temperature_k: None,
            instrument_cof: None,
            step: None,
            laps: None,
            angle_rad: None,
            wear_depth_m: None,
            columns: Default::default(),
            normal_flipped: false,
            track_radius: None,
        }
    }
}

/// The numbers of a section's channels as a trace takes them: copied from
/// a dataset that others still read, or moved out of one the trace owns
/// (then converted to SI in place: no second copy of a long trace).
enum Values<'c> {
    Copy(&'c Section),
    /// The channels' values, and how many roles still read each.
    Move(Vec<Vec<f64>>, Vec<usize>),
}

impl Values<'_> {
    /// Channel `i`'s values, as written.
    fn take(&mut self, i: usize) -> Vec<f64> {
        match self {
            Values::Copy(section) => section.channels[i].values.clone(),
            // A column that two roles read is copied for all but the last.
            Values::Move(values, uses) => {
                uses[i] = uses[i].saturating_sub(1);
                match uses[i] {
                    0 => std::mem::take(&mut values[i]),
                    _ => values[i].clone(),
                }
            }
        }
    }
}

/// Values in `unit` converted to SI in place, each by [`Unit::to_si`].
fn to_si(mut v: Vec<f64>, unit: &Unit) -> Vec<f64> {
    // The same conversion per value, on all threads: the same bits.
    use rayon::prelude::*;
    v.par_iter_mut().for_each(|x| *x = unit.to_si(*x));
    v
}

/// The SI values of the channel that has `role`, or `None` when no channel
/// has it. A channel without a unit, or with one of the wrong quantity, is
/// an error naming the column.
fn channel_si(
    ds: &Dataset,
    section: &Section,
    roles: &BTreeMap<Role, usize>,
    (role, quantity): (Role, Quantity),
    values: &mut Values,
) -> Result<Option<Vec<f64>>> {
    let Some(&i) = roles.get(&role) else {
        return Ok(None);
    };
    let c = &section.channels[i];
    let location = || Location {
        path: ds.source.clone(),
        line: section.header_line,
        column: Some(c.name.clone()),
    };
    let unit: Unit = match c.unit(&ds.source)? {
        Some(u) if quantity == Quantity::Force => u.as_force(),
        Some(u) => u,
        None if quantity == Quantity::Dimensionless => crate::units::parse_unit("1").expect("known"),
        None => {
            return Err(Error::Unit {
                location: location(),
                unit: String::new(),
                expected: format!(
                    "a {quantity:?} unit for the {} column (the file gives none; set it in the pipeline's [ingest] units, for example {} = \"{}\")",
                    role.key(),
                    c.name,
                    quantity.si_symbol()
                ),
            })
        }
    };
    if unit.quantity != quantity {
        return Err(Error::Unit {
            location: location(),
            unit: c.raw_unit.clone(),
            expected: format!(
                "a {quantity:?} unit for the {} column: {}",
                role.key(),
                crate::units::accepted(quantity)
            ),
        });
    }
    Ok(Some(to_si(values.take(i), &unit)))
}

/// Builds the friction trace of section `index`. Needs a time and a
/// friction-force column, or a coefficient column and a normal-force
/// column (see [`friction_trace_with`]).
pub fn friction_trace(
    ds: &Dataset,
    index: usize,
    overrides: &BTreeMap<Role, String>,
) -> Result<Trace> {
    friction_trace_with(ds, index, overrides, &ManifestHints::default())
}

/// A column the pipeline maps to `friction_force` that is a coefficient of
/// friction (by its name, or by a dimensionless unit): refused, because
/// reading μ as newtons gives μ/N as the coefficient, silently wrong.
fn refuse_coefficient_as_force(
    ds: &Dataset,
    section: &Section,
    overrides: &BTreeMap<Role, String>,
) -> Result<()> {
    let Some(name) = overrides.get(&Role::FrictionForce) else {
        return Ok(());
    };
    let Some(c) = section.channel(name) else {
        return Ok(());
    };
    let dimensionless = crate::units::parse_unit(&c.raw_unit)
        .is_some_and(|u| u.quantity == Quantity::Dimensionless);
    if Role::InstrumentCof.is_named(name) || dimensionless {
        return Err(Error::input(
            Location { path: ds.source.clone(), line: section.header_line, column: Some(name.clone()) },
            format!(
                "the pipeline maps friction_force to '{name}', which is a coefficient of friction, not a force; \
                 remove that mapping: tribo reads '{name}' as the instrument's μ and computes T = μ·N \
                 from the normal force (a normal-force column, or normal_force_N or mass_g in the manifest)"
            ),
        ));
    }
    Ok(())
}

/// The friction force of a trace without a friction-force column: T = μ N
/// (MODELS.md §1, μ = T/N read backwards), from the coefficient column and
/// the normal force, pointwise from its column or the manifest's constant.
fn friction_from_coefficient(
    ds: &Dataset,
    section: &Section,
    cof: &[f64],
    normal_n: Option<&[f64]>,
    manifest_normal_n: Option<f64>,
    cof_name: &str,
) -> Result<Vec<f64>> {
    match (normal_n, manifest_normal_n) {
        (Some(n), _) => Ok(cof.iter().zip(n).map(|(m, n)| m * n).collect()),
        (None, Some(n)) => Ok(cof.iter().map(|m| m * n).collect()),
        (None, None) => Err(Error::input(
            Location { path: ds.source.clone(), line: section.header_line, column: Some(cof_name.to_string()) },
            format!(
                "no friction-force column, and the coefficient '{cof_name}' needs a normal force to give T = μ·N: \
                 add normal_force_N (or mass_g) to the manifest row of this file, or name the normal-force \
                 column in the pipeline's [ingest] columns (normal_force = \"...\")"
            ),
        )),
    }
}

/// What the sample manifest adds to a trace read from a file.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ManifestHints {
    /// Normal force, N, for traces without a normal-force column.
    pub normal_force_n: Option<f64>,
    /// Radius of the wear track, m (v = ω r), for every section that
    /// `radii` leaves without one.
    pub track_radius_m: Option<f64>,
    /// Each section's track radius and its source
    /// ([`super::radius::track_radii`]); empty: `track_radius_m` for all.
    pub radii: Vec<Option<TrackRadius>>,
}

impl ManifestHints {
    /// The track radius of section `index`.
    fn radius(&self, index: usize) -> Option<TrackRadius> {
        self.radii
            .get(index)
            .copied()
            .flatten()
            .or(self.track_radius_m.map(|radius_m| TrackRadius {
                radius_m,
                source: super::radius::RadiusSource::Manifest,
            }))
    }
}

/// A velocity column in rpm (or another angular unit) becomes the sliding
/// velocity v = ω r with the section's track radius (returned beside it);
/// without a radius it is an error that says how to give one.
fn sliding_velocity(
    ds: &Dataset,
    section: &Section,
    roles: &BTreeMap<Role, usize>,
    radius: Option<TrackRadius>,
    values: &mut Values,
) -> Result<(Option<Vec<f64>>, Option<TrackRadius>)> {
    let Some(&i) = roles.get(&Role::Velocity) else {
        return Ok((None, None));
    };
    let c = &section.channels[i];
    match crate::units::parse_unit(&c.raw_unit) {
        Some(u) if u.quantity == Quantity::AngularVelocity => match radius {
            Some(r) if r.radius_m > 0.0 && r.radius_m.is_finite() => {
                let mut v = values.take(i);
                v.iter_mut().for_each(|w| *w = u.to_si(*w) * r.radius_m);
                Ok((Some(v), Some(r)))
            }
            _ => Err(Error::input(
                Location { path: ds.source.clone(), line: section.header_line, column: Some(c.name.clone()) },
                format!(
                    "the velocity column '{}' of section '{}' is a rotational speed ({}); the sliding velocity \
                     v = ω·r needs the track radius: add track_radius_mm (> 0) to the manifest row of this file \
                     (the first step's when the stage moves between steps; or track_centre_mm, the disc centre \
                     in the stage's coordinate; or step_track_radius_mm, one radius per step: '4:6 7:9')",
                    c.name, section.name, c.raw_unit
                ),
            )),
        },
        _ => {
            let q = (Role::Velocity, Quantity::Velocity);
            Ok((channel_si(ds, section, roles, q, values)?, None))
        }
    }
}

/// As [`friction_trace`], with what the manifest says: the normal force for
/// traces that give only the coefficient of friction (such a trace is a
/// friction trace with T = μ N, `friction_from_cof`), and the track radius
/// for a rotational speed. Mapping a coefficient column to `friction_force`
/// is refused.
pub fn friction_trace_with(
    ds: &Dataset,
    index: usize,
    overrides: &BTreeMap<Role, String>,
    hints: &ManifestHints,
) -> Result<Trace> {
    let section = &ds.sections[index];
    build(ds, index, overrides, hints, Values::Copy(section))
}

/// The traces of every section, as [`friction_trace_with`]; from a dataset
/// given away, each trace takes its section's columns and converts them to
/// SI in place, so that a long file is never held both in its units and
/// in SI.
pub fn friction_traces(
    ds: std::borrow::Cow<'_, Dataset>,
    overrides: &BTreeMap<Role, String>,
    hints: &ManifestHints,
) -> Result<Vec<Trace>> {
    let mut ds = match ds {
        std::borrow::Cow::Borrowed(ds) => {
            return (0..ds.sections.len())
                .map(|i| friction_trace_with(ds, i, overrides, hints))
                .collect()
        }
        std::borrow::Cow::Owned(ds) => ds,
    };
    let mut traces = Vec::with_capacity(ds.sections.len());
    for i in 0..ds.sections.len() {
        let channels = &mut ds.sections[i].channels;
        let moved = channels.iter_mut().map(|c| std::mem::take(&mut c.values));
        let values = Values::Move(moved.collect(), vec![0; channels.len()]);
        traces.push(build(&ds, i, overrides, hints, values)?);
    }
    Ok(traces)
}

/// The track radius a file states in its preamble, in m
/// ([`super::radius::declared_in`]).
pub fn declared_track_radius_m(ds: &Dataset) -> Result<Option<f64>> {
    super::radius::declared_in(&ds.preamble, &ds.source)
}

/// Every column the pipeline maps a role to must exist.
fn check_overrides(
    ds: &Dataset,
    section: &Section,
    overrides: &BTreeMap<Role, String>,
) -> Result<()> {
    for (role, name) in overrides {
        if section.channel(name).is_none() {
            let names: Vec<&str> = section.channels.iter().map(|c| c.name.as_str()).collect();
            return Err(Error::input(
                Location::file(&ds.source).with_column(name),
                format!(
                    "the pipeline maps {} to '{name}', but the columns are {names:?}",
                    role.key()
                ),
            ));
        }
    }
    Ok(())
}

/// A normal force recorded as negative (median of its finite samples below
/// zero) is turned positive; whether it was. The sign of the median needs
/// only the count of negative samples, except when an even count has its
/// two middle values either side of zero: then the median itself is taken.
fn flip_if_negative(n: &mut [f64]) -> bool {
    let (finite, negative) = n
        .iter()
        .filter(|v| v.is_finite())
        .fold((0usize, 0usize), |(f, m), &v| {
            (f + 1, m + usize::from(v < 0.0))
        });
    let k = finite / 2;
    let flip = if finite == 0 {
        false
    } else if negative > k {
        true // the middle value (and the one below it) is negative
    } else if finite % 2 == 1 || negative < k {
        false // the middle value(s) ≥ −0
    } else {
        let values = crate::signal::select::Values {
            positions: n.len(),
            read: |r: std::ops::Range<usize>| n[r].iter().copied().filter(|v| v.is_finite()),
        };
        crate::signal::select::median(&values, finite).is_some_and(|m| m < 0.0)
    };
    if flip {
        n.iter_mut().for_each(|v| *v = -*v);
    }
    flip
}

/// The trace of section `index`, its numbers taken through `values`.
fn build(
    ds: &Dataset,
    index: usize,
    overrides: &BTreeMap<Role, String>,
    hints: &ManifestHints,
    mut values: Values,
) -> Result<Trace> {
    let manifest_normal_n = hints.normal_force_n;
    let section = &ds.sections[index];
    check_overrides(ds, section, overrides)?;
    refuse_coefficient_as_force(ds, section, overrides)?;
    let roles = assign_roles(section, overrides);
    let missing = |role: Role| missing_column(&ds.source, section, role);
    // Missing columns first, then units: a file without a friction column
    // hears about that before any unit problem.
    for role in [Role::Time, Role::FrictionForce] {
        let alt = role == Role::FrictionForce && roles.contains_key(&Role::InstrumentCof);
        if !roles.contains_key(&role) && !alt {
            return Err(missing(role));
        }
    }
    if let Values::Move(_, uses) = &mut values {
        roles.values().for_each(|&i| uses[i] += 1);
    }
    let mut get = |role, q| channel_si(ds, section, &roles, (role, q), &mut values);
    let time_s = get(Role::Time, Quantity::Time)?.ok_or_else(|| missing(Role::Time))?;
    let instrument_cof = get(Role::InstrumentCof, Quantity::Dimensionless)?;
    let mut normal_n = get(Role::NormalForce, Quantity::Force)?;
    let friction = get(Role::FrictionForce, Quantity::Force)?;
    // In the order of before, so that the first unit error is the same.
    let (velocity_m_per_s, track_radius) =
        sliding_velocity(ds, section, &roles, hints.radius(index), &mut values)?;
    let mut get = |role, q| channel_si(ds, section, &roles, (role, q), &mut values);
    let position_m = get(Role::Position, Quantity::Length)?;
    let temperature_k = get(Role::Temperature, Quantity::Temperature)?;
    let normal_flipped = normal_n.as_mut().is_some_and(|n| flip_if_negative(n));
    let friction_from_cof = !roles.contains_key(&Role::FrictionForce);
    let friction_n = match (friction, &instrument_cof) {
        (Some(t), _) => t,
        (None, Some(mu)) => friction_from_coefficient(
            ds,
            section,
            mu,
            normal_n.as_deref(),
            manifest_normal_n,
            &section.channels[roles[&Role::InstrumentCof]].name,
        )?,
        (None, None) => return Err(missing(Role::FrictionForce)),
    };
    let columns = roles
        .iter()
        .map(|(r, &i)| (*r, section.channels[i].name.clone()))
        .collect();
    Ok(Trace {
        section: section.name.clone(),
        time_s,
        friction_n,
        friction_from_cof,
        normal_n,
        velocity_m_per_s,
        position_m,
        temperature_k,
        instrument_cof,
        step: get(Role::Step, Quantity::Dimensionless)?,
        laps: get(Role::Laps, Quantity::Dimensionless)?,
        angle_rad: get(Role::Angle, Quantity::Angle)?,
        wear_depth_m: get(Role::WearDepth, Quantity::Length)?,
        columns,
        normal_flipped,
        track_radius,
    })
}

#[cfg(test)]
mod tests {
    use super::flip_if_negative;

    /// The count of negative samples decides as the median's sign does (the
    /// definition, from a sorted copy of the finite samples), including an
    /// even count whose middle values straddle zero either way, signed
    /// zeros, NaN and no finite sample at all.
    #[test]
    fn flip_follows_the_sign_of_the_median() {
        let cases: [&[f64]; 11] = [
            &[-1.0, -2.0, 3.0],
            &[-1.0, 2.0, 3.0],
            &[-3.0, 1.0],
            &[-1.0, 3.0],
            &[-1.0, 1.0],
            &[-0.0, -0.0, 1.0, -2.0],
            &[-0.0, 0.0],
            &[f64::NAN, -1.0, f64::NAN],
            &[f64::NAN],
            &[],
            &[-5.0, -4.0, 1.0, 2.0, f64::INFINITY, f64::NAN],
        ];
        for case in cases {
            let mut finite: Vec<f64> = case.iter().copied().filter(|v| v.is_finite()).collect();
            let want = crate::signal::stats::median_in_place(&mut finite).is_some_and(|m| m < 0.0);
            let mut n = case.to_vec();
            assert_eq!(flip_if_negative(&mut n), want, "{case:?}");
            let expect: Vec<f64> = case.iter().map(|v| if want { -v } else { *v }).collect();
            assert_eq!(format!("{n:?}"), format!("{expect:?}"));
        }
    }
}
