//! Coulomb fits over a friction table: grouping, the flat-reference
//! prediction (Eq. 4.2) and the across-sample summary (Table 4.2), as the
//! tables `coulomb` and `coulomb_summary`.
//!
//! Input columns (friction table written by `tribo friction`):
//! `sample_id`, `normal_force_N`, `static_force_N`, `dynamic_force_N`, and
//! `apparent_area_m2`, optionally `pattern`, `area_fraction`. The last three
//! may come instead from a samples manifest keyed by `sample_id`
//! ([`SampleInfo`]); the friction table wins where both have a value.

use crate::status::{Code, InputRow, Status};
use std::collections::BTreeMap;

use super::{
    fit_coulomb, mean_sd, predict_area_fraction, CoulombFit, CoulombParams, FrictionPoint,
};
use crate::error::{Error, Result};
use crate::table::{Table, TableBuilder};

pub use super::samples::{read_samples_csv, samples_of, SampleInfo};

/// Settings of [`coulomb_tables`].
#[derive(Debug, Clone, serde::Serialize)]
pub struct CoulombTableParams {
    /// Groupings: each is a list of columns; one fit per distinct value
    /// combination. Default `[["sample_id"], ["pattern"]]`.
    pub groupings: Vec<Vec<String>>,
    /// Pattern names of the flat reference for Eq. 4.2, matched without
    /// regard to case. Default `F` (thesis) and `flat`.
    pub reference_patterns: Vec<String>,
    /// Fit settings.
    pub fit: CoulombParams,
}

impl Default for CoulombTableParams {
    fn default() -> Self {
        CoulombTableParams {
            groupings: vec![vec!["sample_id".into()], vec!["pattern".into()]],
            reference_patterns: vec!["F".into(), "flat".into()],
            fit: CoulombParams::default(),
        }
    }
}

struct Row {
    /// The row for people, with the warnings of its own status.
    input: InputRow,
    keys: BTreeMap<String, Option<String>>,
    n: f64,
    t_static: f64,
    t_dynamic: f64,
    area: f64,
    pattern: Option<String>,
    af: Option<f64>,
}

fn opt_str(t: &Table, name: &str) -> Result<Option<Vec<Option<String>>>> {
    if !t.column_names().iter().any(|c| c == name) {
        return Ok(None);
    }
    Ok(Some(match t.column_type(name) {
        Some(crate::table::ColumnType::Str | crate::table::ColumnType::Cat) => t.str(name)?,
        _ => t
            .f64(name)?
            .into_iter()
            .map(|v| v.map(|v| v.to_string()))
            .collect(),
    }))
}

fn opt_f64(t: &Table, name: &str) -> Result<Option<Vec<Option<f64>>>> {
    if t.column_names().iter().any(|c| c == name) {
        Ok(Some(t.f64(name)?))
    } else {
        Ok(None)
    }
}

fn rows_of(t: &Table, samples: &BTreeMap<String, SampleInfo>, keys: &[String]) -> Result<Vec<Row>> {
    let need = |name: &str| -> Result<Vec<Option<f64>>> {
        opt_f64(t, name)?.ok_or_else(|| {
            Error::Config(format!(
                "friction table has no column '{name}'; columns are {:?}",
                t.column_names()
            ))
        })
    };
    let (nf, ts, td) = (
        need("normal_force_N")?,
        need("static_force_N")?,
        need("dynamic_force_N")?,
    );
    let sid = opt_str(t, "sample_id")?;
    let area = opt_f64(t, "apparent_area_m2")?;
    let pattern = opt_str(t, "pattern")?;
    let af = opt_f64(t, "area_fraction")?;
    let mut inputs = t.input_rows()?;
    let mut key_cols = BTreeMap::new();
    for k in keys {
        if let Some(c) = opt_str(t, k)? {
            key_cols.insert(k.clone(), c);
        }
    }
    let mut out = vec![];
    for i in 0..t.height() {
        let id = sid.as_ref().and_then(|c| c[i].clone());
        let info = id
            .as_ref()
            .and_then(|s| samples.get(s))
            .cloned()
            .unwrap_or_default();
        let pattern_i = pattern
            .as_ref()
            .and_then(|c| c[i].clone())
            .or(info.pattern.clone());
        let mut kv = BTreeMap::new();
        for k in keys {
            let v = match (key_cols.get(k), k.as_str()) {
                (Some(c), _) => c[i].clone(),
                (None, "pattern") => pattern_i.clone(),
                _ => None,
            };
            kv.insert(k.clone(), v);
        }
        out.push(Row {
            input: std::mem::take(&mut inputs[i]),
            keys: kv,
            n: nf[i].unwrap_or(f64::NAN),
            t_static: ts[i].unwrap_or(f64::NAN),
            t_dynamic: td[i].unwrap_or(f64::NAN),
            area: area
                .as_ref()
                .and_then(|c| c[i])
                .or(info.apparent_area_m2)
                .unwrap_or(f64::NAN),
            pattern: pattern_i,
            af: af.as_ref().and_then(|c| c[i]).or(info.area_fraction),
        });
    }
    Ok(out)
}

/// The members whose point enters the fit (in the regime `dynamic` or
/// not), each with those of its own warnings that concern that regime's
/// force.
fn used_rows(members: &[&Row], points: &[FrictionPoint], dynamic: bool) -> Vec<InputRow> {
    let concerns = |c: &Code| !dynamic || !c.doubts_static_peak_only();
    members
        .iter()
        .zip(points)
        .filter(|(_, p)| p.usable())
        .map(|(r, _)| InputRow {
            label: r.input.label.clone(),
            codes: r.input.codes.iter().copied().filter(concerns).collect(),
        })
        .collect()
}

fn points(rows: &[&Row], dynamic: bool) -> Vec<FrictionPoint> {
    rows.iter()
        .map(|r| FrictionPoint {
            normal_force_n: r.n,
            tangential_force_n: if dynamic { r.t_dynamic } else { r.t_static },
            area_m2: r.area,
        })
        .collect()
}

fn unique<T: PartialEq + Clone>(v: impl Iterator<Item = Option<T>>) -> Option<T> {
    let mut it = v;
    let first = it.next()??;
    it.all(|x| x.as_ref() == Some(&first)).then_some(first)
}

/// Rows of the friction table that no fit used: without an apparent area
/// (A_th, from the table or the samples manifest), or without a value in
/// one of a grouping's columns (left out of that grouping only).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct LeftOut {
    /// Rows without an apparent area.
    pub no_area: usize,
    /// Per grouping (`pattern`, `sample_id,direction`), rows without a value
    /// in one of its columns.
    pub no_key: BTreeMap<String, usize>,
}

/// One fit of one group in one regime: a row of the `coulomb` table.
#[derive(Debug, Clone)]
pub struct GroupFit {
    /// The grouping's columns, joined by commas.
    pub grouping: String,
    /// The group, `k=v,k=v`.
    pub group: String,
    /// `static` or `dynamic`.
    pub regime: &'static str,
    /// The group's points, as given to the fit.
    pub points: Vec<FrictionPoint>,
    /// The fit, or why there is none.
    pub fit: std::result::Result<CoulombFit, Status>,
    /// The group's area fraction, when all its rows agree on one.
    pub area_fraction: Option<f64>,
    /// μ, τ0 predicted from the flat reference (Eq. 4.2), and the measured
    /// μ over the predicted one.
    pub predicted: Option<(f64, f64, f64)>,
}

impl GroupFit {
    /// `ok`, a doubt of the fit, or why there is no fit.
    pub fn status(&self) -> &Status {
        match &self.fit {
            Ok(f) => &f.status,
            Err(s) => s,
        }
    }
}

/// The tables of [`coulomb_tables`] and the rows they leave out.
#[derive(Debug, Clone)]
pub struct CoulombTables {
    /// One row per group and regime.
    pub coulomb: Table,
    /// The same rows, typed.
    pub fits: Vec<GroupFit>,
    /// Mean ± sd of the per-sample fits by pattern and regime (Table 4.2).
    pub summary: Table,
    /// Rows no fit used.
    pub left_out: LeftOut,
}

/// Fits every group of every grouping for both regimes. Returns the
/// `coulomb` table and the `coulomb_summary` table (mean ± sd of the
/// per-sample μ and τ0 by pattern and regime, Table 4.2). Rows without an
/// apparent area or a grouping value are left out and counted.
pub fn coulomb_tables(
    friction: &Table,
    samples: &BTreeMap<String, SampleInfo>,
    params: &CoulombTableParams,
) -> Result<CoulombTables> {
    let mut fits = Vec::new();
    // (pattern, regime) -> per-sample (mu, tau0)
    let mut per_sample: BTreeMap<(String, &'static str), Vec<SampleFit>> = BTreeMap::new();
    // reference fits per regime
    let all_keys: Vec<String> = params.groupings.iter().flatten().cloned().collect();
    let mut rows = rows_of(friction, samples, &all_keys)?;
    let mut left_out = LeftOut::default();
    rows.retain(|r| {
        let keep = r.area.is_finite() && r.area > 0.0;
        left_out.no_area += usize::from(!keep);
        keep
    });
    let reference = reference_fits(&rows, params);
    for grouping in &params.groupings {
        let groups = group_rows(&rows, grouping, &mut left_out);
        for (key, members) in &groups {
            let pattern = unique(members.iter().map(|r| r.pattern.clone()));
            let af = unique(members.iter().map(|r| r.af.map(f64::to_bits))).map(f64::from_bits);
            for (regime, dynamic) in [("static", false), ("dynamic", true)] {
                let pts = points(members, dynamic);
                let fit = fit_coulomb(&pts, &params.fit).map(|mut f| {
                    f.status.inherit(&used_rows(members, &pts, dynamic));
                    f
                });
                let pred = match (&fit, reference.get(regime), af) {
                    (Ok(_), Some(rf), Some(af)) => predict_area_fraction(rf, af, &pts).ok(),
                    _ => None,
                };
                if let (Ok(f), true) = (&fit, grouping.len() == 1 && grouping[0] == "sample_id") {
                    per_sample
                        .entry((pattern.clone().unwrap_or_else(|| "all".into()), regime))
                        .or_default()
                        .push(SampleFit {
                            mu: f.mu,
                            tau0_pa: f.tau0_pa,
                            input: InputRow {
                                label: key.clone(),
                                codes: f.status.warnings(),
                            },
                        });
                }
                fits.push(GroupFit {
                    grouping: grouping.join(","),
                    group: key.clone(),
                    regime,
                    points: pts,
                    fit: fit.map_err(|e| e.status()),
                    area_fraction: af,
                    predicted: pred,
                });
            }
        }
    }
    let coulomb = coulomb_table(&fits, params)?;
    let summary = summary_table(&per_sample)?;
    Ok(CoulombTables {
        coulomb,
        fits,
        summary,
        left_out,
    })
}

/// The fits of the reference patterns' rows, per regime, against which
/// other groups' area fractions are predicted.
fn reference_fits(rows: &[Row], params: &CoulombTableParams) -> BTreeMap<&'static str, CoulombFit> {
    let is_ref = |p: &Option<String>| {
        p.as_ref().is_some_and(|p| {
            params
                .reference_patterns
                .iter()
                .any(|r| r.eq_ignore_ascii_case(p))
        })
    };
    let refs: Vec<&Row> = rows.iter().filter(|r| is_ref(&r.pattern)).collect();
    let mut reference = BTreeMap::new();
    for (regime, dynamic) in [("static", false), ("dynamic", true)] {
        if let Ok(f) = fit_coulomb(&points(&refs, dynamic), &params.fit) {
            reference.insert(regime, f);
        }
    }
    reference
}

/// The rows of each group of one grouping, keyed `k=v,k=v`; rows missing a
/// key are counted as left out.
fn group_rows<'r>(
    rows: &'r [Row],
    grouping: &[String],
    left_out: &mut LeftOut,
) -> BTreeMap<String, Vec<&'r Row>> {
    let mut groups: BTreeMap<String, Vec<&Row>> = BTreeMap::new();
    for r in rows {
        if grouping.iter().any(|k| r.keys[k].is_none()) {
            *left_out.no_key.entry(grouping.join(",")).or_default() += 1;
            continue;
        }
        let key = grouping
            .iter()
            .map(|k| format!("{k}={}", r.keys[k].as_deref().unwrap_or_default()))
            .collect::<Vec<_>>()
            .join(",");
        groups.entry(key).or_default().push(r);
    }
    groups
}

/// Mean and sd of the per-sample μ and τ0 per (pattern, regime).
/// One per-sample fit as the summary uses it.
struct SampleFit {
    mu: f64,
    tau0_pa: f64,
    /// The fit (`sample_id=…`) with the warnings of its status.
    input: InputRow,
}

fn summary_table(per_sample: &BTreeMap<(String, &'static str), Vec<SampleFit>>) -> Result<Table> {
    let mut s = SummaryOut::default();
    for ((pattern, regime), v) in per_sample {
        let mu: Vec<f64> = v.iter().map(|x| x.mu).collect();
        let tau: Vec<f64> = v.iter().map(|x| x.tau0_pa).collect();
        let mut status = Status::ok();
        status.inherit(v.iter().map(|x| &x.input));
        s.status.push(status);
        let (mm, ms) = mean_sd(&mu).unwrap_or((f64::NAN, None));
        let (tm, ts) = mean_sd(&tau).unwrap_or((f64::NAN, None));
        s.pattern.push(pattern.clone());
        s.regime.push(regime.to_string());
        s.n.push(v.len() as i64);
        s.mu_mean.push(mm);
        s.mu_sd.push(ms);
        s.tau_mean.push(tm);
        s.tau_sd.push(ts);
    }
    TableBuilder::new()
        .str("pattern", s.pattern.iter().map(Some))
        .str("regime", s.regime.iter().map(Some))
        .i64("n_samples", s.n.iter().map(|v| Some(*v)))
        .f64_values("mu_mean", s.mu_mean)
        .f64("mu_sd", s.mu_sd)
        .f64_values("tau0_mean_Pa", s.tau_mean)
        .f64("tau0_sd_Pa", s.tau_sd)
        .status(&s.status)
        .build()
}

#[derive(Default)]
struct SummaryOut {
    pattern: Vec<String>,
    regime: Vec<String>,
    n: Vec<i64>,
    mu_mean: Vec<f64>,
    mu_sd: Vec<Option<f64>>,
    tau_mean: Vec<f64>,
    tau_sd: Vec<Option<f64>>,
    status: Vec<Status>,
}

/// The `coulomb` table: one row per group and regime.
fn coulomb_table(fits: &[GroupFit], params: &CoulombTableParams) -> Result<Table> {
    let ok = |g: fn(&CoulombFit) -> Option<f64>| {
        fits.iter()
            .map(move |f| f.fit.as_ref().ok().and_then(g))
            .collect::<Vec<_>>()
    };
    let pred =
        |k: fn(&(f64, f64, f64)) -> f64| fits.iter().map(move |f| f.predicted.as_ref().map(k));
    let loss = params.fit.loss.name();
    TableBuilder::new()
        .str("group", fits.iter().map(|f| Some(&f.group)))
        .str("regime", fits.iter().map(|f| Some(f.regime)))
        .i64(
            "n",
            fits.iter()
                .map(|f| Some(f.fit.as_ref().map_or(0, |f| f.n as i64))),
        )
        .f64("mu", ok(|f| Some(f.mu)))
        .f64("mu_se", ok(|f| f.mu_se))
        .f64("tau0_Pa", ok(|f| Some(f.tau0_pa)))
        .f64("tau0_se_Pa", ok(|f| f.tau0_se_pa))
        .f64("r2", ok(|f| Some(f.r2)))
        .status(fits.iter().map(GroupFit::status))
        .str("grouping", fits.iter().map(|f| Some(&f.grouping)))
        .i64(
            "n_excluded",
            fits.iter().map(|f| {
                Some(match &f.fit {
                    Ok(fit) => fit.n_excluded as i64,
                    Err(_) => f.points.len() as i64,
                })
            }),
        )
        .i64(
            "n_outliers",
            fits.iter()
                .map(|f| f.fit.as_ref().ok().map(|f| f.outliers.len() as i64)),
        )
        .bool(
            "weighted",
            fits.iter().map(|_| Some(loss != "least_squares")),
        )
        .str("loss", fits.iter().map(|_| Some(loss)))
        .f64("area_fraction", fits.iter().map(|f| f.area_fraction))
        .f64("mu_predicted", pred(|p| p.0))
        .f64("tau0_predicted_Pa", pred(|p| p.1))
        .f64("ratio_measured_to_predicted", pred(|p| p.2))
        .build()
}
