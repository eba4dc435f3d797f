//! Which column is time, friction force, normal force, velocity, position,
//! temperature, or the instrument's own coefficient of friction.
//!
//! Names are matched case-insensitively, ignoring spaces, `_` and `-`,
//! against a preference-ordered list, and the column's unit must measure the
//! right quantity (so `T \[s\]` is time and `T [°C]` temperature). `Fx` and
//! `Fz` follow the common tribometer convention: tangential and normal. A
//! pipeline file can name the column for any role.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::{Channel, Section};
use crate::units::{parse_unit, Quantity, Unit};

/// What a column means to the friction stage.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Role {
    /// Time.
    Time,
    /// Tangential (friction) force T.
    FrictionForce,
    /// Normal force N.
    NormalForce,
    /// Sliding velocity.
    Velocity,
    /// Position or sliding distance.
    Position,
    /// Temperature.
    Temperature,
    /// The instrument's own coefficient of friction.
    InstrumentCof,
    /// The step or segment of the test's recipe that a sample belongs to,
    /// as the file numbers it: the steps are the file's, not re-detected.
    Step,
    /// A lap (revolution) counter of a rotary test, whole or fractional.
    Laps,
    /// The angle of a rotary drive (a unit of angle required).
    Angle,
    /// A linear-wear (depth) channel: the pin's or ball's descent.
    WearDepth,
}

impl Role {
    /// All roles, in display order.
    pub const ALL: [Role; 11] = [
        Role::Time,
        Role::FrictionForce,
        Role::NormalForce,
        Role::Velocity,
        Role::Position,
        Role::Temperature,
        Role::InstrumentCof,
        Role::Step,
        Role::Laps,
        Role::Angle,
        Role::WearDepth,
    ];

    /// Normalised names that mean this role, most preferred first.
    fn names(self) -> &'static [&'static str] {
        match self {
            Role::Time => &[
                "time",
                "t",
                "times",
                "elapsedtime",
                "testtime",
                "timesec",
                "timestamp",
                "zeit1standardmessrate",
                "time1defaultsamplerate",
                "zeit",
            ],
            Role::FrictionForce => &[
                "fx",
                "frictionforce",
                "friction",
                "tangentialforce",
                "ft",
                "ff",
                "tangential",
                "fr",
                "ffriction",
                "forcex",
                "daqfx",
                "reibkraft",
                "reibungskraft",
            ],
            Role::NormalForce => &[
                "fz",
                "normalforce",
                "normalload",
                "fn",
                "load",
                "normal",
                "forcez",
                "daqfz",
                "normalkraft",
            ],
            Role::Velocity => &[
                "velocity",
                "v",
                "speed",
                "slidingvelocity",
                "slidingspeed",
                "linearvelocity",
                "linearspeed",
                "v1",
                "vx",
                "velocityx",
                "xvelocity",
                "meanspeed",
                "rotationalspeed",
                "spindlespeed",
                "discspeed",
                "rpm",
                "geschwindigkeit",
                "drehzahl",
                "rotaryvelocity",
            ],
            Role::Position => &[
                "position",
                "distance",
                "slidingdistance",
                "displacement",
                "pos",
                "x",
                "posx",
                "xposition",
                "positionx",
                "stroke",
                "strokeposition",
                "travel",
                "weg",
                "gleitweg",
            ],
            Role::Temperature => &[
                "temperature",
                "temp",
                "t",
                "temp1",
                "lubetemp",
                "temperatur",
            ],
            Role::InstrumentCof => &[
                "cof",
                "mu",
                "µ",
                "μ",
                "coefficientoffriction",
                "frictioncoefficient",
                "coef",
                "daqcof",
                "tractioncoeff",
                "tractioncoefficient",
                "reibwert",
                "reibungskoeffizient",
                "reibungszahl",
            ],
            Role::Step => &[
                "step",
                "stepno",
                "stepnumber",
                "stepnr",
                "segment",
                "segmentno",
                "schritt",
            ],
            Role::Laps => &[
                "laps",
                "lap",
                "lapcount",
                "revolutions",
                "revs",
                "turns",
                "rotations",
                "cycles",
                "cyclecount",
                "umdrehungen",
                "runden",
                "zyklen",
            ],
            Role::Angle => &[
                "angle",
                "angularposition",
                "rotaryangle",
                "rotaryposition",
                "theta",
                "winkel",
                "position",
            ],
            Role::WearDepth => &[
                "wear",
                "weardepth",
                "linearwear",
                "wearloss",
                "depth",
                "lineardepth",
                "verschleiss",
                "verschleiß",
                "verschleisstiefe",
            ],
        }
    }

    /// The quantities a column for this role may carry (`None` = no unit).
    /// An unknown unit is accepted here so that the column keeps its role
    /// and the conversion reports the unit as unknown, naming the column.
    fn accepts(self, unit: &str) -> bool {
        if !unit.is_empty() && parse_unit(unit).is_none() {
            return true;
        }
        let q = parse_unit(unit).map(|u| u.quantity);
        match self {
            Role::Time => q == Some(Quantity::Time) || unit.is_empty(),
            Role::FrictionForce | Role::NormalForce => {
                matches!(q, Some(Quantity::Force | Quantity::Mass)) || unit.is_empty()
            }
            Role::Velocity => {
                matches!(q, Some(Quantity::Velocity | Quantity::AngularVelocity)) || unit.is_empty()
            }
            Role::Position => q == Some(Quantity::Length) || unit.is_empty(),
            Role::Temperature => q == Some(Quantity::Temperature),
            Role::InstrumentCof | Role::Step | Role::Laps => {
                q == Some(Quantity::Dimensionless) || unit.is_empty()
            }
            // Names shared with other roles ("position"): the unit decides.
            Role::Angle => q == Some(Quantity::Angle),
            Role::WearDepth => q == Some(Quantity::Length),
        }
    }

    /// Whether a column name is one of this role's names (case, spaces,
    /// `_`, `-` and `.` ignored).
    pub fn is_named(self, name: &str) -> bool {
        self.names().contains(&normalise(name).as_str())
    }

    /// Snake-case name, as in pipeline files.
    pub fn key(self) -> &'static str {
        match self {
            Role::Time => "time",
            Role::FrictionForce => "friction_force",
            Role::NormalForce => "normal_force",
            Role::Velocity => "velocity",
            Role::Position => "position",
            Role::Temperature => "temperature",
            Role::InstrumentCof => "instrument_cof",
            Role::Step => "step",
            Role::Laps => "laps",
            Role::Angle => "angle",
            Role::WearDepth => "wear_depth",
        }
    }
}

/// What a column means to the tensile analysis. Recognised by unit and
/// name (English and German): the first channel whose unit measures the
/// role's quantity and whose lower-cased name contains one of its words.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum TensileRole {
    /// Engineering strain (a dimensionless unit: mm/mm, %, 1).
    Strain,
    /// Engineering stress (any stress unit, any name).
    Stress,
    /// Force on the specimen (a force or gram-force unit).
    Force,
    /// Crosshead or gauge extension (a length unit).
    Extension,
    /// Test time (a time unit).
    Time,
}

impl TensileRole {
    /// All tensile roles, in display order.
    pub const ALL: [TensileRole; 5] = [
        TensileRole::Strain,
        TensileRole::Stress,
        TensileRole::Force,
        TensileRole::Extension,
        TensileRole::Time,
    ];

    fn quantity(self) -> Quantity {
        match self {
            TensileRole::Strain => Quantity::Dimensionless,
            TensileRole::Stress => Quantity::Stress,
            TensileRole::Force => Quantity::Force,
            TensileRole::Extension => Quantity::Length,
            TensileRole::Time => Quantity::Time,
        }
    }

    /// Words one of which the name must contain; empty: any name.
    fn words(self) -> &'static [&'static str] {
        match self {
            TensileRole::Strain => &["strain", "dehnung"],
            TensileRole::Stress => &[],
            TensileRole::Force => &["load", "force", "kraft"],
            TensileRole::Extension => &[
                "extension",
                "displacement",
                "elongation",
                "position",
                "weg",
                "verlängerung",
            ],
            TensileRole::Time => &["time", "zeit"],
        }
    }

    /// Snake-case name, as `inspect` shows it.
    pub fn key(self) -> &'static str {
        match self {
            TensileRole::Strain => "strain",
            TensileRole::Stress => "stress",
            TensileRole::Force => "force",
            TensileRole::Extension => "extension",
            TensileRole::Time => "time",
        }
    }
}

/// The channel that has a tensile role, with the unit it converts with
/// (a mass unit on a force channel is gram- or kilogram-force).
pub fn tensile_channel(channels: &[Channel], role: TensileRole) -> Option<(usize, Unit)> {
    channels.iter().enumerate().find_map(|(i, c)| {
        let u = parse_unit(&c.raw_unit)?;
        let u = if role == TensileRole::Force {
            u.as_force()
        } else {
            u
        };
        let n = c.name.to_lowercase();
        let words = role.words();
        (u.quantity == role.quantity() && (words.is_empty() || words.iter().any(|w| n.contains(w))))
            .then_some((i, u))
    })
}

/// Whether a column's name says it is a force (`Fx`, `Fz`, `Ff`, `Fn`,
/// `Ft`, or a name with force, load or their German words), so that a mass
/// unit on it (`g`, `kg`) is gram- or kilogram-force even when the column
/// has no role.
pub fn is_force_name(name: &str) -> bool {
    let n = normalise(name);
    let axis =
        n.len() == 2 && n.starts_with('f') && n[1..].chars().all(|c| c.is_ascii_alphabetic());
    axis || ["force", "load", "kraft"].iter().any(|w| n.contains(w))
        || n.starts_with("last")
        || n.ends_with("last")
        || Role::FrictionForce.is_named(name)
        || Role::NormalForce.is_named(name)
}

fn normalise(name: &str) -> String {
    name.chars()
        .filter(|c| !matches!(c, ' ' | '_' | '-' | '.'))
        .collect::<String>()
        .to_lowercase()
}

/// Assigns roles to the channels of a section: overrides first (by exact
/// column name), then the best-preferred name match whose unit fits. A
/// channel takes at most one role. Returns role → channel index.
pub fn assign_roles(
    section: &Section,
    overrides: &BTreeMap<Role, String>,
) -> BTreeMap<Role, usize> {
    let mut taken = vec![false; section.channels.len()];
    let mut roles = BTreeMap::new();
    for (role, name) in overrides {
        if let Some(i) = section.channels.iter().position(|c| &c.name == name) {
            roles.insert(*role, i);
            taken[i] = true;
        }
    }
    // Unit-discriminated roles first, so `T [s]` goes to time before the
    // temperature list sees it.
    for role in Role::ALL {
        if roles.contains_key(&role) {
            continue;
        }
        let best = section
            .channels
            .iter()
            .enumerate()
            .filter(|(i, c)| !taken[*i] && role.accepts(&c.raw_unit))
            .filter_map(|(i, c)| {
                let n = normalise(&c.name);
                role.names()
                    .iter()
                    .position(|m| *m == n)
                    .map(|rank| (rank, i))
            })
            .min();
        if let Some((_, i)) = best {
            roles.insert(role, i);
            taken[i] = true;
        }
    }
    roles
}

#[cfg(test)]
mod tests {
    use super::*;

    fn section(cols: &[(&str, &str)]) -> Section {
        Section {
            name: "1".into(),
            metadata: vec![],
            header_line: Some(1),
            first_data_line: 2,
            channels: cols
                .iter()
                .map(|(n, u)| Channel {
                    name: n.to_string(),
                    raw_unit: u.to_string(),
                    values: vec![],
                })
                .collect(),
        }
    }

    #[test]
    fn cetr_columns() {
        let s = section(&[
            ("Fx", "g"),
            ("Fz", "g"),
            ("Z", "mm"),
            ("Y", "mm"),
            ("X", "mm"),
            ("V1", "mm/sec"),
            ("T", "sec"),
            ("Ff", "g"),
            ("COF", ""),
        ]);
        let r = assign_roles(&s, &BTreeMap::new());
        assert_eq!(r[&Role::Time], 6);
        assert_eq!(r[&Role::FrictionForce], 0);
        assert_eq!(r[&Role::NormalForce], 1);
        assert_eq!(r[&Role::InstrumentCof], 8);
        assert_eq!(r[&Role::Position], 4, "X");
        assert_eq!(r[&Role::Velocity], 5, "V1");
        assert!(!r.contains_key(&Role::Temperature));
        assert!(is_force_name("Ff") && is_force_name("Normal load") && !is_force_name("Fz2x"));
        assert!(!is_force_name("X") && !is_force_name("COF"));
    }

    #[test]
    fn temperature_needs_a_temperature_unit_and_overrides_win() {
        let s = section(&[
            ("t", "s"),
            ("Friction force", "N"),
            ("T", "°C"),
            ("Load", "N"),
        ]);
        let r = assign_roles(&s, &BTreeMap::new());
        assert_eq!(
            (r[&Role::Time], r[&Role::Temperature], r[&Role::NormalForce]),
            (0, 2, 3)
        );
        let o = BTreeMap::from([(Role::NormalForce, "Friction force".to_string())]);
        let r = assign_roles(&s, &o);
        assert_eq!(r[&Role::NormalForce], 1);
        assert!(!r.contains_key(&Role::FrictionForce));
    }
}
