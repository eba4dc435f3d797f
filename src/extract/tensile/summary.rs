//! Group summaries of per-fibre results (thesis Tables 5.1, 5.2; MODELS.md §3).
//!
//! Fibres are grouped by material × knot × effective-knot class. Within a
//! group the statistics use the fibres that have both a strength and a
//! toughness (as Table 5.1 does: a fibre without toughness does not count
//! in the strength mean either): n, mean and sample standard deviation
//! (n − 1) of strength and toughness; T_u' over the fibres that have it.
//!
//! Against the unknotted controls (knot `none`) of the same material:
//! toughness ratio = mean T_k / mean T_u, increase % = (ratio − 1) × 100,
//! strength change % = (mean strength / control mean strength − 1) × 100.
//! The per-fibre ratios (Eq. 5.3 or 5.4) are summarised too.

use std::collections::{BTreeMap, HashMap};

use crate::error::{Error, Result};
use crate::status::{InputRow, Status};
use crate::table::{ColumnType, Table, TableBuilder};

use super::curve::Knot;

/// The columns of one fibre that the summary uses (table units: MPa, J/g).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FibreRow {
    /// Sample identifier (to resolve control ids), if given.
    pub sample_id: Option<String>,
    /// Material.
    pub material: String,
    /// Knot name (canonical, see [`Knot::name`]).
    pub knot: String,
    /// Effective-knot class.
    pub knot_effective: Option<bool>,
    /// Strength, MPa.
    pub strength_mpa: Option<f64>,
    /// T_u or T_k, J/g.
    pub toughness: Option<f64>,
    /// T_u', J/g.
    pub toughness_after_release: Option<f64>,
    /// Friction stress / strength.
    pub friction_ratio: Option<f64>,
    /// Per-fibre T_k/T_u' or T_k/T_u.
    pub toughness_ratio: Option<f64>,
    /// Control fibre id.
    pub control_id: Option<String>,
    /// The row for people, with the warnings of its own status.
    pub input: InputRow,
}

fn need(t: &Table, name: &str) -> Result<()> {
    if t.column_names().iter().any(|c| c == name) {
        Ok(())
    } else {
        Err(Error::Config(format!(
            "per-fibre table has no column '{name}'; columns are {:?}",
            t.column_names()
        )))
    }
}

fn opt_f64(t: &Table, name: &str) -> Result<Vec<Option<f64>>> {
    match t.column_type(name) {
        None => Ok(vec![None; t.height()]),
        Some(ColumnType::F64) | Some(ColumnType::I64) => t.f64(name),
        Some(other) => Err(Error::Config(format!(
            "column '{name}' is {}, expected numbers",
            other.name()
        ))),
    }
}

fn opt_str(t: &Table, name: &str) -> Result<Vec<Option<String>>> {
    match t.column_type(name) {
        None => Ok(vec![None; t.height()]),
        Some(ColumnType::Str | ColumnType::Cat) => t.str(name),
        Some(ColumnType::F64) | Some(ColumnType::I64) => Ok(t
            .f64(name)?
            .into_iter()
            .map(|v| v.map(|v| v.to_string()))
            .collect()),
        Some(ColumnType::Bool) => Ok(t
            .bool(name)?
            .into_iter()
            .map(|v| v.map(|v| v.to_string()))
            .collect()),
        Some(ColumnType::StrList) => Err(Error::Config(format!(
            "column '{name}' holds lists; expected text"
        ))),
    }
}

/// Reads the rows the summary needs from a per-fibre table (our
/// `tensile.parquet` or a spreadsheet export with the same column names).
/// Required: `material`, `knot`, `strength_MPa`, `toughness_J_per_g`.
/// Optional: `knot_effective` (else computed from `friction_ratio` and
/// `threshold`), `toughness_after_release_J_per_g`, `toughness_ratio`,
/// `sample_id`, `control_id`.
pub fn rows_from_table(t: &Table, threshold: f64) -> Result<Vec<FibreRow>> {
    for c in ["material", "knot", "strength_MPa", "toughness_J_per_g"] {
        need(t, c)?;
    }
    let material = opt_str(t, "material")?;
    let knot = opt_str(t, "knot")?;
    let strength = opt_f64(t, "strength_MPa")?;
    let tough = opt_f64(t, "toughness_J_per_g")?;
    let after = opt_f64(t, "toughness_after_release_J_per_g")?;
    let friction = opt_f64(t, "friction_ratio")?;
    let ratio = opt_f64(t, "toughness_ratio")?;
    let sample = opt_str(t, "sample_id")?;
    let control = opt_str(t, "control_id")?;
    let effective: Vec<Option<bool>> = match t.column_type("knot_effective") {
        Some(ColumnType::Bool) => t.bool("knot_effective")?,
        Some(ColumnType::F64) | Some(ColumnType::I64) => t
            .f64("knot_effective")?
            .into_iter()
            .map(|v| v.map(|v| v > 0.5))
            .collect(),
        Some(ColumnType::Str | ColumnType::Cat | ColumnType::StrList) => {
            return Err(Error::Config(
                "column 'knot_effective' holds text; expected true/false".into(),
            ))
        }
        None => vec![None; t.height()],
    };
    let has_effective = t.column_type("knot_effective").is_some();
    let mut inputs = t.input_rows()?;
    Ok((0..t.height())
        .map(|i| {
            let k = Knot::parse(knot[i].as_deref().unwrap_or(""));
            let eff = if !k.is_knotted() {
                None
            } else if has_effective {
                effective[i]
            } else {
                friction[i].map(|r| r > threshold)
            };
            FibreRow {
                sample_id: sample[i].clone(),
                material: material[i].clone().unwrap_or_default(),
                knot: k.name().to_string(),
                knot_effective: eff,
                strength_mpa: strength[i],
                toughness: tough[i],
                toughness_after_release: after[i],
                friction_ratio: friction[i],
                toughness_ratio: ratio[i],
                control_id: control[i].clone(),
                input: std::mem::take(&mut inputs[i]),
            }
        })
        .collect())
}

/// Fills `toughness_ratio` where it is missing: T_k/T_u' (Eq. 5.3) when T_u'
/// is known, else T_k/T_u of the row named by `control_id` (Eq. 5.4).
pub fn fill_ratios(rows: &mut [FibreRow]) {
    let by_id: HashMap<String, Option<f64>> = rows
        .iter()
        .filter_map(|r| r.sample_id.clone().map(|id| (id, r.toughness)))
        .collect();
    for r in rows.iter_mut() {
        if r.toughness_ratio.is_some() || r.knot == "none" {
            continue;
        }
        let Some(tk) = r.toughness else { continue };
        let denom = r.toughness_after_release.or_else(|| {
            r.control_id
                .as_ref()
                .and_then(|c| by_id.get(c).copied().flatten())
        });
        r.toughness_ratio = denom.filter(|d| *d > 0.0).map(|d| tk / d);
    }
}

/// Mean and sample standard deviation (n − 1); sd is `None` for n < 2.
pub fn mean_sd(v: &[f64]) -> (Option<f64>, Option<f64>) {
    let n = v.len();
    if n == 0 {
        return (None, None);
    }
    let m = v.iter().sum::<f64>() / n as f64;
    if n < 2 {
        return (Some(m), None);
    }
    let ss: f64 = v.iter().map(|x| (x - m) * (x - m)).sum();
    (Some(m), Some((ss / (n as f64 - 1.0)).sqrt()))
}

/// One group of the summary.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct GroupSummary {
    /// Material.
    pub material: String,
    /// Knot name.
    pub knot: String,
    /// Effective-knot class.
    pub knot_effective: Option<bool>,
    /// Fibres with strength and toughness.
    pub n: usize,
    /// Strength mean and sd, MPa.
    pub strength: (Option<f64>, Option<f64>),
    /// Toughness mean and sd, J/g.
    pub toughness: (Option<f64>, Option<f64>),
    /// T_u' mean and sd, J/g.
    pub after_release: (Option<f64>, Option<f64>),
    /// Fibres with T_u'.
    pub after_release_n: usize,
    /// Fibres left out (strength or toughness missing).
    pub n_incomplete: usize,
    /// Controls of the same material used for the comparison.
    pub control_n: usize,
    /// Control means: strength (MPa), toughness (J/g).
    pub control_strength: Option<f64>,
    /// Control mean toughness T_u, J/g.
    pub control_toughness: Option<f64>,
    /// Per-fibre ratio mean and sd, and their count.
    pub fibre_ratio: (Option<f64>, Option<f64>),
    /// Number of per-fibre ratios.
    pub fibre_ratio_n: usize,
    /// `ok`, or `doubtful_points`: fibres used (the group's, and for a
    /// knotted group its controls) that carry warnings of their own.
    pub status: Status,
}

impl GroupSummary {
    /// Mean toughness / control mean toughness (knotted groups).
    pub fn toughness_ratio_vs_control(&self) -> Option<f64> {
        if self.knot == "none" {
            return None;
        }
        Some(self.toughness.0? / self.control_toughness.filter(|c| *c > 0.0)?)
    }
    /// (ratio − 1) × 100.
    pub fn toughness_increase_pct(&self) -> Option<f64> {
        self.toughness_ratio_vs_control().map(|r| (r - 1.0) * 100.0)
    }
    /// (mean strength / control mean strength − 1) × 100 (knotted groups).
    pub fn strength_change_pct(&self) -> Option<f64> {
        if self.knot == "none" {
            return None;
        }
        let c = self.control_strength.filter(|c| *c > 0.0)?;
        Some((self.strength.0? / c - 1.0) * 100.0)
    }
}

type Key = (String, String, Option<bool>);

/// Group summaries, ordered by material, knot, effective class.
pub fn summarize(rows: &[FibreRow]) -> Vec<GroupSummary> {
    let mut groups: BTreeMap<Key, Vec<&FibreRow>> = BTreeMap::new();
    for r in rows {
        groups
            .entry((r.material.clone(), r.knot.clone(), r.knot_effective))
            .or_default()
            .push(r);
    }
    fn complete(r: &&&FibreRow) -> bool {
        r.strength_mpa.is_some() && r.toughness.is_some()
    }
    // Each material's complete unknotted fibres: its controls.
    let controls: HashMap<String, Vec<&FibreRow>> = groups
        .iter()
        .filter(|((_, knot, _), _)| knot == "none")
        .map(|((mat, _, _), g)| (mat.clone(), g.iter().filter(complete).copied().collect()))
        .collect();
    groups
        .into_iter()
        .map(|((material, knot, eff), g)| {
            let c: Vec<&&FibreRow> = g.iter().filter(complete).collect();
            let col = |f: &dyn Fn(&FibreRow) -> Option<f64>| -> Vec<f64> {
                c.iter().filter_map(|r| f(r)).collect()
            };
            let after = col(&|r| r.toughness_after_release);
            let ratios = col(&|r| r.toughness_ratio);
            let control = controls.get(&material).map_or(&[][..], Vec::as_slice);
            let control_mean = |f: fn(&FibreRow) -> Option<f64>| {
                mean_sd(&control.iter().filter_map(|r| f(r)).collect::<Vec<_>>()).0
            };
            let mut used: Vec<&FibreRow> = c.iter().map(|r| **r).collect();
            if knot != "none" {
                used.extend(control);
            }
            let mut status = Status::ok();
            status.inherit(used.iter().map(|r| &r.input));
            GroupSummary {
                status,
                n: c.len(),
                strength: mean_sd(&col(&|r| r.strength_mpa)),
                toughness: mean_sd(&col(&|r| r.toughness)),
                after_release: mean_sd(&after),
                after_release_n: after.len(),
                n_incomplete: g.len() - c.len(),
                control_n: control.len(),
                control_strength: control_mean(|r| r.strength_mpa),
                control_toughness: control_mean(|r| r.toughness),
                fibre_ratio: mean_sd(&ratios),
                fibre_ratio_n: ratios.len(),
                material,
                knot,
                knot_effective: eff,
            }
        })
        .collect()
}

/// The `tensile_groups` table (`schemas/tensile_groups.toml`).
pub fn groups_table(groups: &[GroupSummary]) -> Result<Table> {
    let f = |g: &dyn Fn(&GroupSummary) -> Option<f64>| groups.iter().map(g).collect::<Vec<_>>();
    let i = |g: &dyn Fn(&GroupSummary) -> usize| {
        groups.iter().map(|x| Some(g(x) as i64)).collect::<Vec<_>>()
    };
    TableBuilder::new()
        .str("material", groups.iter().map(|g| Some(&g.material)))
        .str("knot", groups.iter().map(|g| Some(&g.knot)))
        .bool("knot_effective", groups.iter().map(|g| g.knot_effective))
        .i64("n", i(&|g| g.n))
        .f64("strength_mean_MPa", f(&|g| g.strength.0))
        .f64("strength_sd_MPa", f(&|g| g.strength.1))
        .f64("toughness_mean_J_per_g", f(&|g| g.toughness.0))
        .f64("toughness_sd_J_per_g", f(&|g| g.toughness.1))
        .f64(
            "toughness_after_release_mean_J_per_g",
            f(&|g| g.after_release.0),
        )
        .f64(
            "toughness_after_release_sd_J_per_g",
            f(&|g| g.after_release.1),
        )
        .i64("toughness_after_release_n", i(&|g| g.after_release_n))
        .i64("n_incomplete", i(&|g| g.n_incomplete))
        .i64("control_n", i(&|g| g.control_n))
        .f64("control_strength_mean_MPa", f(&|g| g.control_strength))
        .f64(
            "control_toughness_mean_J_per_g",
            f(&|g| g.control_toughness),
        )
        .f64(
            "toughness_ratio_vs_control",
            f(&|g| g.toughness_ratio_vs_control()),
        )
        .f64("toughness_increase_pct", f(&|g| g.toughness_increase_pct()))
        .f64("strength_change_pct", f(&|g| g.strength_change_pct()))
        .i64("fibre_ratio_n", i(&|g| g.fibre_ratio_n))
        .f64("fibre_ratio_mean", f(&|g| g.fibre_ratio.0))
        .f64("fibre_ratio_sd", f(&|g| g.fibre_ratio.1))
        .f64(
            "fibre_increase_mean_pct",
            f(&|g| g.fibre_ratio.0.map(|r| (r - 1.0) * 100.0)),
        )
        .status(groups.iter().map(|g| &g.status))
        .build()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A group's status names the fibres it used that carry warnings: its
    /// own, and for a knotted group its material's controls (their means
    /// make its ratios); an incomplete fibre (no toughness) is not used and
    /// not named, and a group of clean fibres of another material is `ok`.
    #[test]
    fn groups_inherit_the_warnings_of_the_fibres_they_use() {
        use crate::status::Code;
        let statuses = [
            Status::of(Code::DefaultedDensity, "1.3 g/cm³ assumed"),
            Status::ok(),
            Status::of(Code::FractureTruncated, "no fracture"),
            Status::ok(),
            Status::ok(),
        ];
        let t = TableBuilder::new()
            .str(
                "source",
                ["u1.txt", "k1.txt", "k2.txt", "v1.txt", "v2.txt"].map(Some),
            )
            .str(
                "material",
                ["silk", "silk", "silk", "nylon", "nylon"].map(Some),
            )
            .str(
                "knot",
                ["none", "noose", "noose", "none", "noose"].map(Some),
            )
            .f64("strength_MPa", [Some(500.0); 5])
            .f64(
                "toughness_J_per_g",
                [Some(50.0), Some(70.0), None, Some(40.0), Some(45.0)],
            )
            .status(statuses.iter())
            .build()
            .unwrap();
        let groups = summarize(&rows_from_table(&t, 0.5).unwrap());
        let status = |mat: &str, knot: &str| {
            let g = groups
                .iter()
                .find(|g| g.material == mat && g.knot == knot)
                .unwrap();
            g.status.to_string()
        };
        let control = "u1.txt (defaulted_density)";
        assert_eq!(
            status("silk", "none"),
            format!("doubtful_points: 1 of the 1 rows used carry warnings: {control}")
        );
        assert_eq!(
            status("silk", "noose"),
            format!("doubtful_points: 1 of the 2 rows used carry warnings: {control}")
        );
        assert_eq!(status("nylon", "noose"), "ok");
        let table = groups_table(&groups).unwrap();
        assert_eq!(
            table.str("status").unwrap()[0].as_deref(),
            Some("ok"),
            "nylon first"
        );
    }

    #[test]
    fn sample_sd_uses_n_minus_one() {
        // 2, 4, 4, 4, 5, 5, 7, 9: mean 5, Σ(x − m)² = 32, sd = √(32/7)
        let (m, s) = mean_sd(&[2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0]);
        assert!((m.unwrap() - 5.0).abs() < 1e-15);
        assert!((s.unwrap() - (32.0f64 / 7.0).sqrt()).abs() < 1e-15);
        assert_eq!(mean_sd(&[3.0]), (Some(3.0), None));
        assert_eq!(mean_sd(&[]), (None, None));
    }
}
