//! Simulated against measured friction (thesis Fig. 4.10 and 4.11).
//!
//! A measured Coulomb fit τ = τ0 + μ p (Eq. 4.1) gives the macroscopic
//! coefficient T/N = μ + τ0/p at pressure p. For each simulated pattern and
//! pressure the table holds the simulated mean, the measured value of the
//! pattern's own fit (its *group*) and their ratio, plus the area-fraction
//! prediction from the flat fit, AF (μ_F + τ0_F/p) (Eq. 4.2), and the ratio
//! to it.
//!
//! The fits come from `coulomb.parquet` of `tribo fit coulomb` (columns
//! `group, regime, n, mu, mu_se, tau0_Pa, tau0_se_Pa, r2, status_codes`;
//! rows with a code other than `se_undefined` or `doubtful_points` are
//! ignored; groups look like `pattern=B`) or, without lab data, from Table
//! 4.2 of the thesis ([`thesis_table_4_2`]). A row compared with a fit
//! over doubtful rows says `doubtful_points` in turn.

use crate::status::{Code, InputRow, Status};
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use super::output::SummaryRow;
use crate::error::{Error, Location, Result};
use crate::table::{Table, TableBuilder};

/// A Coulomb fit τ = τ0 + μ p.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoulombFit {
    /// μ \[1\].
    pub mu: f64,
    /// τ0 \[Pa\].
    pub tau0: f64,
}

impl CoulombFit {
    /// T/N = μ + τ0/p (Eq. 4.1 divided by p).
    pub fn mu_at(&self, pressure: f64) -> f64 {
        self.mu + self.tau0 / pressure
    }
}

/// Measured fits by (group, regime), and where they come from.
#[derive(Debug, Clone)]
pub struct MeasuredFits {
    /// Fits keyed by (group, regime), regime `static` or `dynamic`.
    pub fits: BTreeMap<(String, String), CoulombFit>,
    /// The keys of the fits that say `doubtful_points`.
    pub doubtful: BTreeSet<(String, String)>,
    /// A path or "thesis Table 4.2".
    pub source: String,
}

/// Table 4.2 of the thesis (means over samples): groups F, A, B, C,
/// "S (x)", "S (y)", regimes static and dynamic.
pub fn thesis_table_4_2() -> MeasuredFits {
    let rows: [(&str, f64, f64, f64, f64); 6] = [
        ("F", 4.76, 23.45e3, 2.88, 11.85e3),
        ("A", 5.71, 15.41e3, 3.75, 4.02e3),
        ("B", 2.05, 24.85e3, 2.62, 2.98e3),
        ("C", 2.18, 4.30e3, 1.88, 1.05e3),
        ("S (x)", 2.44, 9.17e3, 2.67, 4.52e3),
        ("S (y)", 2.25, 1.16e3, 2.14, 0.09e3),
    ];
    let mut fits = BTreeMap::new();
    for (g, ms, ts, md, td) in rows {
        fits.insert((g.into(), "static".into()), CoulombFit { mu: ms, tau0: ts });
        fits.insert(
            (g.into(), "dynamic".into()),
            CoulombFit { mu: md, tau0: td },
        );
    }
    MeasuredFits {
        fits,
        doubtful: BTreeSet::new(),
        source: "thesis Table 4.2".into(),
    }
}

/// Reads the fits of `tribo fit coulomb` from a Parquet file.
pub fn read_coulomb(path: &Path) -> Result<MeasuredFits> {
    let (t, _) = Table::read_parquet(path)?;
    fits_from_table(&t, &path.display().to_string()).map_err(|e| match e {
        Error::Config(m) => Error::input(Location::file(path), m),
        e => e,
    })
}

/// The fits of a `coulomb` table (as the coulomb stage writes it); rows
/// with a code other than `se_undefined` (two points: μ and τ0 stand) or
/// `doubtful_points` (kept with the fit, for the comparison to inherit)
/// are left out. `source` names the table in the comparison.
pub fn fits_from_table(t: &Table, source: &str) -> Result<MeasuredFits> {
    let col = |r: Result<Vec<Option<String>>>, name: &str| {
        r.map_err(|_| {
            Error::Config(format!(
                "column '{name}' missing or not text; expected the columns of coulomb.parquet \
                 (group, regime, mu, tau0_Pa, status)"
            ))
        })
    };
    let num = |r: Result<Vec<Option<f64>>>, name: &str| {
        r.map_err(|_| {
            Error::Config(format!(
                "column '{name}' missing or not numeric; expected the columns of coulomb.parquet"
            ))
        })
    };
    let group = col(t.str("group"), "group")?;
    let regime = col(t.str("regime"), "regime")?;
    let codes = t.status_codes().map_err(|_| {
        Error::Config(
            "column 'status_codes' missing or not a list of codes; expected the columns of \
             coulomb.parquet"
                .into(),
        )
    })?;
    let mu = num(t.f64("mu"), "mu")?;
    let tau0 = num(t.f64("tau0_Pa"), "tau0_Pa")?;
    let (mut fits, mut doubtful) = (BTreeMap::new(), BTreeSet::new());
    for i in 0..t.height() {
        if !codes[i]
            .iter()
            .all(|c| matches!(c, Code::SeUndefined | Code::DoubtfulPoints))
        {
            continue;
        }
        if let (Some(g), Some(r), Some(m), Some(t0)) = (&group[i], &regime[i], mu[i], tau0[i]) {
            let key = (g.clone(), r.clone());
            if codes[i].contains(&Code::DoubtfulPoints) {
                doubtful.insert(key.clone());
            }
            fits.insert(key, CoulombFit { mu: m, tau0: t0 });
        }
    }
    Ok(MeasuredFits {
        fits,
        doubtful,
        source: source.to_string(),
    })
}

impl MeasuredFits {
    /// The status of a comparison that uses the fits of `groups` (distinct
    /// or not) in `regime`: `doubtful_points` naming those that carry
    /// doubts.
    fn status_of(&self, groups: &[&str], regime: &str) -> Status {
        let mut names: Vec<&str> = groups.to_vec();
        names.dedup();
        let used: Vec<InputRow> = names
            .iter()
            .map(|g| InputRow {
                label: format!("{g} {regime} fit"),
                codes: match self.doubtful.contains(&(g.to_string(), regime.to_string())) {
                    true => vec![Code::DoubtfulPoints],
                    false => Vec::new(),
                },
            })
            .collect();
        let mut status = Status::ok();
        status.inherit(&used);
        status
    }
}

/// How a simulated pattern maps to the measurements.
#[derive(Debug, Clone)]
pub struct PatternLink {
    /// Simulated pattern label.
    pub pattern: String,
    /// Measured group of the same pattern, if any.
    pub group: Option<String>,
    /// AF of the real pattern (for Eq. 4.2).
    pub area_fraction: Option<f64>,
}

/// One row of the comparison: a simulated pattern at one pressure and
/// regime beside the measured fit.
#[derive(Debug, Clone)]
pub struct CompareRow {
    /// Simulated pattern label.
    pub pattern: String,
    /// The measured group it is compared with.
    pub group: Option<String>,
    /// `static` or `dynamic`.
    pub regime: &'static str,
    /// p \[Pa\].
    pub pressure: f64,
    /// Runs with a result.
    pub n: i64,
    /// Mean simulated μ.
    pub sim: Option<f64>,
    /// Its sample sd.
    pub sd: Option<f64>,
    /// Measured μ at p (the group's Coulomb fit).
    pub meas: Option<f64>,
    /// AF of the real pattern.
    pub af: Option<f64>,
    /// AF × the flat reference's μ at p (Eq. 4.2).
    pub pred: Option<f64>,
    /// `ok`, or `doubtful_points` when a fit it uses (the group's, the
    /// flat reference's) rests on doubtful rows.
    pub status: Status,
}

/// The comparison's rows from summary rows. `flat_group` names the flat
/// reference's group for Eq. 4.2.
pub fn compare_rows(
    summary: &[SummaryRow],
    links: &[PatternLink],
    measured: &MeasuredFits,
    flat_group: &str,
) -> Vec<CompareRow> {
    let mut rows = Vec::new();
    for s in summary {
        let link = links.iter().find(|l| l.pattern == s.pattern);
        let group = link.and_then(|l| l.group.clone());
        let af = link.and_then(|l| l.area_fraction);
        for (regime, sim, sd) in [
            ("static", s.mu_static_mean, s.mu_static_sd),
            ("dynamic", s.mu_dynamic_mean, s.mu_dynamic_sd),
        ] {
            let fit = |g: &str| measured.fits.get(&(g.to_string(), regime.to_string()));
            let meas = group.as_deref().and_then(fit).map(|f| f.mu_at(s.pressure));
            let pred = fit(flat_group)
                .zip(af)
                .map(|(f, af)| af * f.mu_at(s.pressure));
            let used: Vec<&str> = [
                group.as_deref().filter(|_| meas.is_some()),
                Some(flat_group).filter(|_| pred.is_some()),
            ]
            .into_iter()
            .flatten()
            .collect();
            let status = measured.status_of(&used, regime);
            rows.push(CompareRow {
                pattern: s.pattern.clone(),
                group: group.clone(),
                regime,
                pressure: s.pressure,
                n: s.n as i64,
                sim,
                sd,
                meas,
                af,
                pred,
                status,
            });
        }
    }
    rows
}

/// Builds the comparison table from summary rows. `flat_group` names the
/// flat reference's group for Eq. 4.2.
pub fn compare_table(
    summary: &[SummaryRow],
    links: &[PatternLink],
    measured: &MeasuredFits,
    flat_group: &str,
) -> Result<Table> {
    compare_rows_table(
        &compare_rows(summary, links, measured, flat_group),
        measured,
    )
}

/// The comparison table of `rows`.
pub fn compare_rows_table(rows: &[CompareRow], measured: &MeasuredFits) -> Result<Table> {
    let ratio = |a: Option<f64>, b: Option<f64>| a.zip(b).map(|(a, b)| a / b);
    TableBuilder::new()
        .str("pattern", rows.iter().map(|r| Some(r.pattern.as_str())))
        .str("group", rows.iter().map(|r| r.group.as_deref()))
        .str("regime", rows.iter().map(|r| Some(r.regime)))
        .f64("pressure_Pa", rows.iter().map(|r| Some(r.pressure)))
        .i64("n", rows.iter().map(|r| Some(r.n)))
        .f64("mu_simulated_mean", rows.iter().map(|r| r.sim))
        .f64("mu_simulated_sd", rows.iter().map(|r| r.sd))
        .f64("mu_measured", rows.iter().map(|r| r.meas))
        .f64(
            "ratio_simulated_to_measured",
            rows.iter().map(|r| ratio(r.sim, r.meas)),
        )
        .f64("area_fraction", rows.iter().map(|r| r.af))
        .f64("mu_af_prediction", rows.iter().map(|r| r.pred))
        .f64(
            "ratio_simulated_to_af_prediction",
            rows.iter().map(|r| ratio(r.sim, r.pred)),
        )
        .str(
            "measured_source",
            rows.iter().map(|_| Some(measured.source.as_str())),
        )
        .status(rows.iter().map(|r| &r.status))
        .build()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_4_2_values_and_eq_4_2() {
        let m = thesis_table_4_2();
        let f = m.fits[&("F".to_string(), "static".to_string())];
        // Flat static fit: μ 4.76, τ0 23.45 kPa → T/N at 10 kPa = 4.76 + 2.345.
        assert!((f.mu_at(10e3) - 7.105).abs() < 1e-12);
        let summary = [SummaryRow {
            pattern: "B".into(),
            pressure: 10e3,
            n: 3,
            n_failed: 0,
            mu_static_mean: Some(4.0),
            mu_static_sd: Some(0.1),
            mu_dynamic_mean: None,
            mu_dynamic_sd: None,
        }];
        let links = [PatternLink {
            pattern: "B".into(),
            group: Some("B".into()),
            area_fraction: Some(0.65),
        }];
        let t = compare_table(&summary, &links, &m, "F").unwrap();
        assert_eq!(t.height(), 2);
        // B static: 2.05 + 24.85e3/10e3 = 4.535; ratio 4/4.535.
        let meas = t.f64("mu_measured").unwrap();
        assert!((meas[0].unwrap() - 4.535).abs() < 1e-12);
        let r = t.f64("ratio_simulated_to_measured").unwrap();
        assert!((r[0].unwrap() - 4.0 / 4.535).abs() < 1e-12);
        // Eq. 4.2: 0.65 × 7.105.
        let pred = t.f64("mu_af_prediction").unwrap();
        assert!((pred[0].unwrap() - 0.65 * 7.105).abs() < 1e-12);
        // No simulated dynamic value: ratio null, not NaN.
        assert!(r[1].is_none());
    }

    /// A measured fit over doubtful rows is used, and the comparisons that
    /// use it (as the group's fit or as the flat reference) say so; a fit
    /// with any other code is left out.
    #[test]
    fn comparisons_inherit_the_doubts_of_the_fits_they_use() {
        let statuses = [
            Status::of(Code::DoubtfulPoints, "1 of the 6 rows used carry warnings"),
            Status::ok(),
            Status::ok(),
            Status::of(Code::FewPoints, "3 points for 2 parameters"),
        ];
        let t = TableBuilder::new()
            .str(
                "group",
                ["pattern=F", "pattern=F", "pattern=B", "pattern=B"].map(Some),
            )
            .str(
                "regime",
                ["static", "dynamic", "static", "dynamic"].map(Some),
            )
            .f64("mu", [Some(0.5); 4])
            .f64("tau0_Pa", [Some(1e3); 4])
            .status(statuses.iter())
            .build()
            .unwrap();
        let m = fits_from_table(&t, "coulomb.parquet").unwrap();
        assert_eq!(m.fits.len(), 3, "few_points is left out");
        let summary = [SummaryRow {
            pattern: "B".into(),
            pressure: 10e3,
            n: 3,
            n_failed: 0,
            mu_static_mean: Some(0.6),
            mu_static_sd: None,
            mu_dynamic_mean: Some(0.5),
            mu_dynamic_sd: None,
        }];
        let links = [PatternLink {
            pattern: "B".into(),
            group: Some("pattern=B".into()),
            area_fraction: Some(0.65),
        }];
        let rows = compare_rows(&summary, &links, &m, "pattern=F");
        assert_eq!(
            rows[0].status.to_string(),
            "doubtful_points: 1 of the 2 rows used carry warnings: \
             pattern=F static fit (doubtful_points)"
        );
        // Dynamic: B's fit is left out (few_points), F's is clean.
        assert_eq!((rows[1].meas, rows[1].status.is_ok()), (None, true));
        let table = compare_rows_table(&rows, &m).unwrap();
        assert_eq!(
            table.str("status").unwrap(),
            [Some("doubtful_points".to_string()), Some("ok".to_string())]
        );
    }
}
