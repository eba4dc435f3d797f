//! What `tribo inspect` reports: how a file was understood.

use std::collections::BTreeMap;

use serde::Serialize;

use super::roles::{assign_roles, tensile_channel, Role, TensileRole};
use super::{Dataset, Dialect, MetaEntry};
use crate::signal::stats::median;
use crate::units::parse_unit;

/// A column as understood.
#[derive(Debug, Clone, Serialize)]
pub struct ColumnInfo {
    /// Name.
    pub name: String,
    /// Unit as written.
    pub unit: String,
    /// SI unit it converts to; `unknown` or empty when there is none.
    pub si_unit: String,
    /// Role, if one was assigned.
    pub role: Option<&'static str>,
}

/// A section as understood.
#[derive(Debug, Clone, Serialize)]
pub struct SectionInfo {
    /// Name.
    pub name: String,
    /// Its metadata.
    pub metadata: Vec<MetaEntry>,
    /// 1-based line of the first header row.
    pub header_line: Option<usize>,
    /// 1-based line of the first data row.
    pub first_data_line: usize,
    /// Data rows.
    pub rows: usize,
    /// 1 / median time step, Hz, when there is a time column with a unit.
    pub sample_rate_hz: Option<f64>,
    /// Columns.
    pub columns: Vec<ColumnInfo>,
}

/// A file as understood.
#[derive(Debug, Clone, Serialize)]
pub struct Inspection {
    /// Path.
    pub source: String,
    /// SHA-256.
    pub sha256: String,
    /// Reader.
    pub format: &'static str,
    /// Dialect of a text export; null for a binary file.
    pub dialect: Option<Dialect>,
    /// Preamble.
    pub preamble: Vec<MetaEntry>,
    /// Sections.
    pub sections: Vec<SectionInfo>,
    /// Channels on a grid (binary and structured formats): name, unit,
    /// size, spacing, origin and, for the decoded one, the points not
    /// measured (`n_invalid`).
    pub grids: Vec<GridInfo>,
}

/// A channel on a grid as understood.
#[derive(Debug, Clone, Serialize)]
pub struct GridInfo {
    /// Name in the file.
    pub name: String,
    /// Unit of the values (`m` for heights).
    pub unit: String,
    /// Whether it holds heights (what the roughness stage takes by default).
    pub height: bool,
    /// Points per row.
    pub nx: usize,
    /// Rows (1 for a profile).
    pub ny: usize,
    /// Spacing along x (m).
    pub dx_m: f64,
    /// Spacing along y (m).
    pub dy_m: f64,
    /// Origin (m).
    pub x0_m: f64,
    /// Origin (m).
    pub y0_m: f64,
    /// Whether its values were decoded (the selected channel).
    pub decoded: bool,
    /// Points not measured, for the decoded channel.
    pub n_invalid: Option<usize>,
}

impl From<&super::grid::Grid> for GridInfo {
    fn from(g: &super::grid::Grid) -> Self {
        GridInfo {
            name: g.name.clone(),
            unit: g.unit.clone(),
            height: g.height,
            nx: g.nx,
            ny: g.ny,
            dx_m: g.dx,
            dy_m: g.dy,
            x0_m: g.x0,
            y0_m: g.y0,
            decoded: g.data.is_some(),
            n_invalid: g.data.as_ref().map(|d| d.n_invalid),
        }
    }
}

/// The role of column `i` of a profile or map, as the roughness stage
/// takes it ([`crate::extract::roughness::input`]): x, z of a profile; x,
/// y, z of points; every column of a z matrix a column of heights.
fn surface_role(s: &super::Section, i: usize) -> Option<&'static str> {
    match (s.channels.len(), i) {
        (2 | 3, 0) => Some("x"),
        (2, 1) => Some("height"),
        (3, 1) => Some("y"),
        (3, 2) => Some("height"),
        (n, _) if n > 3 && s.header_line.is_none() => Some("height"),
        _ => None,
    }
}

/// Describes a dataset with the roles the stage that takes it would use
/// (friction, tensile, or roughness for profiles and maps).
pub fn inspect(ds: &Dataset, overrides: &BTreeMap<Role, String>) -> Inspection {
    use super::kind::DataKind;
    let kind = super::kind::classify(ds, overrides);
    let tensile_file = kind == Some(DataKind::TensileCurve);
    let surface_file = matches!(kind, Some(DataKind::Profile | DataKind::ArealMap));
    let sections = ds
        .sections
        .iter()
        .map(|s| {
            let roles = assign_roles(s, overrides);
            // A tensile curve's channels have tensile roles (strain, stress,
            // force, extension, time); every other file's, friction roles.
            let tensile: Vec<(usize, &'static str)> = match tensile_file {
                true => TensileRole::ALL
                    .iter()
                    .filter_map(|r| tensile_channel(&s.channels, *r).map(|(i, _)| (i, r.key())))
                    .collect(),
                false => Vec::new(),
            };
            let role_of = |i: usize| match (tensile_file, surface_file) {
                (true, _) => tensile.iter().find(|(j, _)| *j == i).map(|(_, k)| *k),
                (_, true) => surface_role(s, i),
                _ => roles.iter().find(|(_, &j)| j == i).map(|(r, _)| r.key()),
            };
            let sample_rate_hz = roles.get(&Role::Time).and_then(|&i| {
                let c = &s.channels[i];
                let unit = parse_unit(&c.raw_unit)?;
                let dt: Vec<f64> = c
                    .values
                    .windows(2)
                    .map(|w| unit.to_si(w[1]) - unit.to_si(w[0]))
                    .filter(|d| d.is_finite())
                    .collect();
                median(&dt).filter(|d| *d > 0.0).map(|d| 1.0 / d)
            });
            SectionInfo {
                name: s.name.clone(),
                metadata: s.metadata.clone(),
                header_line: s.header_line,
                first_data_line: s.first_data_line,
                rows: s.rows(),
                sample_rate_hz,
                columns: s
                    .channels
                    .iter()
                    .enumerate()
                    .map(|(i, c)| ColumnInfo {
                        name: c.name.clone(),
                        unit: c.raw_unit.clone(),
                        si_unit: match (c.raw_unit.is_empty(), parse_unit(&c.raw_unit)) {
                            (true, _) => String::new(),
                            (false, Some(u))
                                if role_of(i).is_some_and(|r| r.ends_with("force"))
                                    || super::roles::is_force_name(&c.name) =>
                            {
                                u.as_force().quantity.si_symbol().into()
                            }
                            (false, Some(u)) => u.quantity.si_symbol().into(),
                            (false, None) => "unknown".into(),
                        },
                        role: role_of(i),
                    })
                    .collect(),
            }
        })
        .collect();
    Inspection {
        source: ds.source.display().to_string(),
        sha256: ds.sha256.clone(),
        format: ds.format,
        dialect: ds.dialect.clone(),
        preamble: ds.preamble.clone(),
        sections,
        grids: ds.grids.iter().map(GridInfo::from).collect(),
    }
}
