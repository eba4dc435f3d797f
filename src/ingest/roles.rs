//! Which column is time, friction force, normal force, velocity, position,
//! temperature, or the instrument's own coefficient of friction.
//!
//! Names (English, German, Spanish, Portuguese) are matched
//! case-insensitively, ignoring spaces, `_` and `-`,
//! against a preference-ordered list, and the column's unit must measure the
//! right quantity (so `T \[s\]` is time and `T [°C]` temperature). `Fx` and
//! `Fz` follow the common tribometer convention: tangential and normal. A
//! pipeline file can name the column for any role.

use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};

use super::role_names;
use super::{Channel, Section};
use crate::error::{Error, Location};
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

    /// Normalised names that mean this role, most preferred first
    /// ([`super::role_names`]).
    fn names(self) -> &'static [&'static str] {
        match self {
            Role::Time => role_names::TIME,
            Role::FrictionForce => role_names::FRICTION_FORCE,
            Role::NormalForce => role_names::NORMAL_FORCE,
            Role::Velocity => role_names::VELOCITY,
            Role::Position => role_names::POSITION,
            Role::Temperature => role_names::TEMPERATURE,
            Role::InstrumentCof => role_names::INSTRUMENT_COF,
            Role::Step => role_names::STEP,
            Role::Laps => role_names::LAPS,
            Role::Angle => role_names::ANGLE,
            Role::WearDepth => role_names::WEAR_DEPTH,
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

    /// What the role's column measures.
    fn quantity(self) -> Quantity {
        match self {
            Role::Time => Quantity::Time,
            Role::FrictionForce | Role::NormalForce => Quantity::Force,
            Role::Velocity => Quantity::Velocity,
            Role::Position => Quantity::Length,
            Role::Temperature => Quantity::Temperature,
            Role::InstrumentCof | Role::Step | Role::Laps => Quantity::Dimensionless,
            Role::Angle => Quantity::Angle,
            Role::WearDepth => Quantity::Length,
        }
    }

    /// The section metadata key by which a reader names the column that
    /// has this role in its format (`tribo.role.velocity` = `Rolling
    /// Speed`: a traction machine's speed is its mean speed, though the
    /// file also has a sliding speed). The user's overrides still win.
    pub fn hint_key(self) -> String {
        format!("tribo.role.{}", self.key())
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
                "extensometer",
                "extenso",
                "maytec",
                "clip",
                "feindehnung",
                "ansetz",
                "xtens",
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
/// (a mass unit on a force channel is gram- or kilogram-force). Among
/// several candidates the best-ranked wins ([`tensile_rank`]), the first in
/// the file among equals; a setpoint is never a measurement.
pub fn tensile_channel(channels: &[Channel], role: TensileRole) -> Option<(usize, Unit)> {
    let mut best: Option<(u8, usize, Unit)> = None;
    for (i, c) in channels.iter().enumerate() {
        let Some(u) = parse_unit(&c.raw_unit) else {
            continue;
        };
        let u = if role == TensileRole::Force {
            u.as_force()
        } else {
            u
        };
        let n = c.name.to_lowercase();
        let words = role.words();
        if u.quantity != role.quantity()
            || !(words.is_empty() || words.iter().any(|w| n.contains(w)))
        {
            continue;
        }
        let Some(rank) = tensile_rank(role, &n) else {
            continue;
        };
        if best.as_ref().is_none_or(|b| rank < b.0) {
            best = Some((rank, i, u));
        }
    }
    best.map(|(_, i, u)| (i, u))
}

/// How well a (lower-cased) name fits a tensile role, 0 best; `None` for a
/// setpoint (`Ch 1 Kraft Sollwert`, `Load setpoint`, `command`). True
/// (Cauchy) stress and logarithmic strain rank below the engineering
/// values the analysis is defined on; an extensometer (`Maytec`, `clip
/// gauge`, `Feindehnung`) ranks above the crosshead (`Traverse`,
/// `Standardweg`, `Maschine`), whose travel includes the machine's
/// compliance.
pub fn tensile_rank(role: TensileRole, name: &str) -> Option<u8> {
    let has = |ws: &[&str]| ws.iter().any(|w| name.contains(w));
    if has(&["sollwert", "setpoint", "set point", "command", "demand"]) {
        return None;
    }
    Some(match role {
        TensileRole::Strain | TensileRole::Stress if has(&["true", "wahre", "logarithm"]) => 2,
        TensileRole::Strain | TensileRole::Stress
            if has(&["engineering", "nominal", "technisch"]) =>
        {
            0
        }
        TensileRole::Extension if has(EXTENSOMETER) => 0,
        TensileRole::Extension
            if has(&[
                "traverse",
                "crosshead",
                "standardweg",
                "wegaufnehmer",
                "maschine",
                "machine",
                "actuator",
            ]) =>
        {
            2
        }
        _ => 1,
    })
}

/// Words of extensometer channels (and brands of hot extensometers).
const EXTENSOMETER: &[&str] = &[
    "extensometer",
    "extenso",
    "maytec",
    "clip",
    "feindehnung",
    "ansetz",
    "xtens",
];

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

/// The error for a section with no column for `role`. A column named for
/// the role whose unit measures something else is named as such ("'mm' is
/// a length unit; the friction_force column needs a force unit"), not
/// reported as missing.
pub fn missing_column(path: &Path, section: &Section, role: Role) -> Error {
    let location = |column: Option<String>| Location {
        path: path.to_path_buf(),
        line: section.header_line,
        column,
    };
    let misunit = section.channels.iter().find_map(|c| {
        let q = parse_unit(&c.raw_unit)?.quantity;
        (role.is_named(&c.name) && !role.accepts(&c.raw_unit)).then_some((c, q))
    });
    if let Some((c, q)) = misunit {
        let need = role.quantity();
        return Error::input(
            location(Some(c.name.clone())),
            format!(
                "'{}' is a {} unit; the {} column needs a {} unit: {}",
                c.raw_unit,
                q.name(),
                role.key(),
                need.name(),
                crate::units::accepted(need)
            ),
        );
    }
    let names: Vec<&str> = section.channels.iter().map(|c| c.name.as_str()).collect();
    let also = match role {
        Role::FrictionForce => {
            " (or a coefficient-of-friction column with a normal force: T = μ·N)"
        }
        _ => "",
    };
    Error::input(
        location(None),
        format!(
            "no {} column among {names:?}{also}; name it in the pipeline's [ingest] columns ({} = \"...\")",
            role.key(),
            role.key()
        ),
    )
}

/// Assigns roles to the channels of a section: overrides first (by exact
/// column name), then the reader's hints ([`Role::hint_key`]), then the
/// best-preferred name match whose unit fits. A channel takes at most one
/// role. Returns role → channel index.
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
    for role in Role::ALL {
        let key = role.hint_key();
        let hinted = section.metadata.iter().find(|m| m.key == key);
        let column = hinted.and_then(|m| section.channels.iter().position(|c| c.name == m.value));
        if let Some(i) = column.filter(|&i| !taken[i] && !roles.contains_key(&role)) {
            roles.insert(role, i);
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
