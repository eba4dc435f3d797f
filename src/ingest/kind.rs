//! What a file holds, as far as the pipeline's routing is concerned: a
//! friction trace, a tensile curve, a stylus profile or an areal map.
//!
//! A reader for one instrument declares its kind ([`super::Reader::kind`]).
//! For the generic reader the kind follows from the columns, by the same
//! names and units the stages use to find their channels:
//! - friction trace: a column that takes the friction-force or the
//!   instrument-coefficient role ([`super::roles`]);
//! - tensile curve: a stress column, a dimensionless column named
//!   `strain`, or a force column (`load`, `force`, `Kraft`) beside an
//!   extension (`extension`, `displacement`, `Weg`, an extensometer), as
//!   the tensile analysis finds them ([`super::roles::tensile_channel`]);
//! - areal map: three length columns (or columns named x, y, z), or a
//!   headerless table of more than three columns (a z matrix);
//! - profile: two columns that are lengths or are named as a profile's
//!   axes (`x`, `distance`, `lateral`; `z`, `height`, `profile`).
//!
//! - a binary file's decoded channel on a grid: a profile when it has one
//!   row, else an areal map.
//!
//! Anything else has no kind: the pipeline then lists the file as taken by
//! no stage rather than guessing.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::roles::{assign_roles, tensile_channel, Role, TensileRole};
use super::{Channel, Dataset, Section, READERS};
use crate::units::{parse_unit, Quantity};

/// The kinds of data tribo's per-file stages take.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DataKind {
    /// A friction force (or coefficient) against time.
    FrictionTrace,
    /// Force or stress against extension or strain.
    TensileCurve,
    /// Heights along a line.
    Profile,
    /// Heights on a grid.
    ArealMap,
}

impl DataKind {
    /// Stable text form (`friction_trace`, …).
    pub fn as_str(self) -> &'static str {
        match self {
            DataKind::FrictionTrace => "friction_trace",
            DataKind::TensileCurve => "tensile_curve",
            DataKind::Profile => "profile",
            DataKind::ArealMap => "areal_map",
        }
    }
}

impl std::fmt::Display for DataKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The kind of a read file: its reader's, else from its columns (with the
/// user's column overrides for the friction roles).
pub fn classify(ds: &Dataset, columns: &BTreeMap<Role, String>) -> Option<DataKind> {
    // A binary file's decoded grid channel: one row is a profile.
    if let Some(g) = ds.grids.iter().find(|g| g.data.is_some()) {
        return Some(match g.ny {
            1 => DataKind::Profile,
            _ => DataKind::ArealMap,
        });
    }
    if let Some(kind) = READERS
        .iter()
        .find(|r| r.name() == ds.format)
        .and_then(|r| r.kind())
    {
        return Some(kind);
    }
    let section = ds.sections.iter().max_by_key(|s| s.rows())?;
    let roles = assign_roles(section, columns);
    if roles.contains_key(&Role::FrictionForce) || roles.contains_key(&Role::InstrumentCof) {
        return Some(DataKind::FrictionTrace);
    }
    if is_tensile(&section.channels) {
        return Some(DataKind::TensileCurve);
    }
    surface_kind(section)
}

fn quantity(c: &Channel) -> Option<Quantity> {
    parse_unit(&c.raw_unit).map(|u| u.as_force().quantity)
}

fn named(c: &Channel, words: &[&str]) -> bool {
    let n = c.name.to_ascii_lowercase();
    words.iter().any(|w| n.contains(w))
}

fn is_tensile(ch: &[Channel]) -> bool {
    let has = |q: Quantity, words: &[&str]| {
        ch.iter()
            .any(|c| quantity(c) == Some(q) && (words.is_empty() || named(c, words)))
    };
    // A force and an extension as the tensile analysis finds them
    // (German `Kraft` and `Weg`, an extensometer); a friction trace was
    // recognised before by its friction force.
    let both = [TensileRole::Force, TensileRole::Extension];
    has(Quantity::Stress, &[])
        || has(Quantity::Dimensionless, &["strain"])
        || both.iter().all(|r| tensile_channel(ch, *r).is_some())
}

fn surface_kind(s: &Section) -> Option<DataKind> {
    let ch = &s.channels;
    let length = |c: &Channel| quantity(c) == Some(Quantity::Length);
    let exact = |c: &Channel, names: &[&str]| {
        let n = c.name.trim().to_ascii_lowercase();
        names
            .iter()
            .any(|w| n == *w || n.starts_with(&format!("{w} ")))
    };
    match ch.len() {
        3 if ch.iter().all(length)
            || (exact(&ch[0], &["x"]) && exact(&ch[1], &["y"]) && exact(&ch[2], &["z"])) =>
        {
            Some(DataKind::ArealMap)
        }
        n if n > 3 && s.header_line.is_none() => Some(DataKind::ArealMap),
        2 if ch.iter().all(length)
            || (exact(&ch[0], &["x", "distance", "lateral", "position"])
                && exact(&ch[1], &["z", "height", "profile", "raw"])) =>
        {
            Some(DataKind::Profile)
        }
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ingest::{read_bytes, IngestOptions};
    use std::path::Path;

    fn kind_of(text: &str) -> Option<DataKind> {
        let ds = read_bytes(
            Path::new("t.csv"),
            text.as_bytes(),
            &IngestOptions::default(),
        )
        .unwrap();
        classify(&ds, &BTreeMap::new())
    }

    #[test]
    fn kinds_from_columns() {
        let rows = "1,2\n2,3\n3,4\n4,5\n";
        assert_eq!(
            kind_of(&format!("t (s),Fx (N)\n{rows}")),
            Some(DataKind::FrictionTrace)
        );
        assert_eq!(
            kind_of(&format!("Strain (mm/mm),Stress (MPa)\n{rows}")),
            Some(DataKind::TensileCurve)
        );
        assert_eq!(
            kind_of(&format!("Extension (mm),Load (N)\n{rows}")),
            Some(DataKind::TensileCurve)
        );
        assert_eq!(
            kind_of(&format!("x (mm),z (um)\n{rows}")),
            Some(DataKind::Profile)
        );
        assert_eq!(
            kind_of("x,y,z\n1,2,3\n2,2,3\n3,2,3\n4,2,4\n"),
            Some(DataKind::ArealMap)
        );
        assert_eq!(kind_of(&format!("a,b\n{rows}")), None);
        // A force beside a time is not a tensile curve; without a friction
        // role it has no kind.
        assert_eq!(kind_of(&format!("time (s),force (N)\n{rows}")), None);
    }
}
