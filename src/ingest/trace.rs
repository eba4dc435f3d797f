//! The canonical friction trace: the channels the friction stage needs, in
//! SI, taken from one section of a [`Dataset`].

use std::collections::BTreeMap;

use super::roles::{assign_roles, Role};
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
    pub friction_n: Vec<f64>,
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
    /// Column used for each role, for `inspect` and provenance.
    pub columns: BTreeMap<Role, String>,
    /// True when the file's normal force was negative for compression (as
    /// on the CETR UMT) and its sign was flipped.
    pub normal_flipped: bool,
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
}

/// The SI values of the channel that has `role`, or `None` when no channel
/// has it. A channel without a unit, or with one of the wrong quantity, is
/// an error naming the column.
fn channel_si(
    ds: &Dataset,
    section: &Section,
    roles: &BTreeMap<Role, usize>,
    role: Role,
    quantity: Quantity,
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
    Ok(Some(c.values.iter().map(|&v| unit.to_si(v)).collect()))
}

/// Builds the friction trace of section `index`. Needs a time and a
/// friction-force column.
pub fn friction_trace(
    ds: &Dataset,
    index: usize,
    overrides: &BTreeMap<Role, String>,
) -> Result<Trace> {
    let section = &ds.sections[index];
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
    let roles = assign_roles(section, overrides);
    let need = |role: Role| {
        roles.get(&role).copied().ok_or_else(|| {
            let names: Vec<&str> = section.channels.iter().map(|c| c.name.as_str()).collect();
            Error::input(
                Location { path: ds.source.clone(), line: section.header_line, column: None },
                format!(
                    "no {} column among {names:?}; name it in the pipeline's [ingest] columns ({} = \"...\")",
                    role.key(),
                    role.key()
                ),
            )
        })
    };
    need(Role::Time)?;
    need(Role::FrictionForce)?;
    let get = |role, q| channel_si(ds, section, &roles, role, q);
    let time_s = get(Role::Time, Quantity::Time)?.expect("checked");
    let friction_n = get(Role::FrictionForce, Quantity::Force)?.expect("checked");
    let mut normal_n = get(Role::NormalForce, Quantity::Force)?;
    let mut normal_flipped = false;
    if let Some(n) = &mut normal_n {
        let finite: Vec<f64> = n.iter().copied().filter(|v| v.is_finite()).collect();
        if crate::signal::stats::median(&finite).is_some_and(|m| m < 0.0) {
            n.iter_mut().for_each(|v| *v = -*v);
            normal_flipped = true;
        }
    }
    let columns = roles
        .iter()
        .map(|(r, &i)| (*r, section.channels[i].name.clone()))
        .collect();
    Ok(Trace {
        section: section.name.clone(),
        time_s,
        friction_n,
        normal_n,
        velocity_m_per_s: get(Role::Velocity, Quantity::Velocity)?,
        position_m: get(Role::Position, Quantity::Length)?,
        temperature_k: get(Role::Temperature, Quantity::Temperature)?,
        instrument_cof: get(Role::InstrumentCof, Quantity::Dimensionless)?,
        columns,
        normal_flipped,
    })
}
