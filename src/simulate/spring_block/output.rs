//! Output tables of a sweep: one row per run (`spring_block`), one per
//! pattern and pressure (`spring_block_summary`) and the decimated T(t)
//! curves (`spring_block_curves`). Schemas in `schemas/spring_block*.toml`.

use super::scene::ScenePlan;
use super::sweep::SweepRun;
use crate::error::Result;
use crate::table::{Table, TableBuilder};

/// References recorded in every table's provenance.
pub const REFERENCES: &[&str] = &[
    "MODELS.md §7 (2-D spring-block model)",
    "thesis §4.3 (Costagliola et al. 2018)",
];

/// Per-run table of one scene.
pub fn runs_table(plan: &ScenePlan, runs: &[SweepRun]) -> Result<Table> {
    let f = |g: &dyn Fn(&SweepRun) -> Option<f64>| runs.iter().map(g).collect::<Vec<_>>();
    let i = |g: &dyn Fn(&SweepRun) -> i64| runs.iter().map(|r| Some(g(r))).collect::<Vec<_>>();
    TableBuilder::new()
        .str("pattern", runs.iter().map(|_| Some(plan.name.as_str())))
        .f64("pressure_Pa", f(&|r| Some(r.pressure)))
        .i64("run", i(&|r| r.run as i64))
        .i64("seed", i(&|r| r.seed as i64))
        .f64("mu_static", f(&|r| r.report.mu_static))
        .f64("mu_dynamic", f(&|r| r.report.mu_dynamic))
        .str("status", runs.iter().map(|r| Some(r.report.status())))
        .str(
            "message",
            runs.iter().map(|r| {
                let m = r.report.message();
                (!m.is_empty()).then_some(m)
            }),
        )
        .f64("angle_deg", f(&|r| Some(r.angle.to_degrees())))
        .f64("static_force_N", f(&|r| r.report.static_force))
        .f64("dynamic_force_N", f(&|r| r.report.dynamic_force))
        .f64("normal_load_N", f(&|r| Some(r.report.normal_load)))
        .f64("peak_time_s", f(&|r| r.report.peak_time))
        .f64("end_time_s", f(&|r| Some(r.report.end_time)))
        .f64("contact_fraction", f(&|r| Some(r.report.contact_fraction)))
        .i64("steps", i(&|r| r.report.steps as i64))
        .i64("jumps", i(&|r| r.report.jumps as i64))
        .i64("block_steps", i(&|r| r.report.block_steps as i64))
        .build()
}

/// Mean and sample standard deviation (n − 1) of the values; sd is `None`
/// below two values.
pub fn mean_sd(v: &[f64]) -> (Option<f64>, Option<f64>) {
    if v.is_empty() {
        return (None, None);
    }
    let n = v.len() as f64;
    let m = v.iter().sum::<f64>() / n;
    let sd =
        (v.len() > 1).then(|| (v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0)).sqrt());
    (Some(m), sd)
}

/// One row of the summary.
#[derive(Debug, Clone)]
pub struct SummaryRow {
    /// Pattern label.
    pub pattern: String,
    /// p \[Pa\].
    pub pressure: f64,
    /// Runs with a static peak.
    pub n: usize,
    /// Runs without one (diverged or max time).
    pub n_failed: usize,
    /// Mean μ_s.
    pub mu_static_mean: Option<f64>,
    /// Sample sd of μ_s.
    pub mu_static_sd: Option<f64>,
    /// Mean μ_d.
    pub mu_dynamic_mean: Option<f64>,
    /// Sample sd of μ_d.
    pub mu_dynamic_sd: Option<f64>,
}

/// Summary rows per pressure (in the plan's order).
pub fn summarise(plan: &ScenePlan, runs: &[SweepRun]) -> Vec<SummaryRow> {
    (0..plan.pressures.len())
        .map(|k| {
            let these: Vec<&SweepRun> = runs.iter().filter(|r| r.pressure_index == k).collect();
            let s: Vec<f64> = these.iter().filter_map(|r| r.report.mu_static).collect();
            let d: Vec<f64> = these.iter().filter_map(|r| r.report.mu_dynamic).collect();
            let (ms, ss) = mean_sd(&s);
            let (md, sd) = mean_sd(&d);
            SummaryRow {
                pattern: plan.name.clone(),
                pressure: plan.pressures[k],
                n: s.len(),
                n_failed: these.len() - s.len(),
                mu_static_mean: ms,
                mu_static_sd: ss,
                mu_dynamic_mean: md,
                mu_dynamic_sd: sd,
            }
        })
        .collect()
}

/// The summary table.
pub fn summary_table(rows: &[SummaryRow]) -> Result<Table> {
    TableBuilder::new()
        .str("pattern", rows.iter().map(|r| Some(r.pattern.as_str())))
        .f64("pressure_Pa", rows.iter().map(|r| Some(r.pressure)))
        .i64("n", rows.iter().map(|r| Some(r.n as i64)))
        .f64("mu_static_mean", rows.iter().map(|r| r.mu_static_mean))
        .f64("mu_static_sd", rows.iter().map(|r| r.mu_static_sd))
        .f64("mu_dynamic_mean", rows.iter().map(|r| r.mu_dynamic_mean))
        .f64("mu_dynamic_sd", rows.iter().map(|r| r.mu_dynamic_sd))
        .i64("n_failed", rows.iter().map(|r| Some(r.n_failed as i64)))
        .build()
}

/// The decimated T(t) curves.
pub fn curves_table(plan: &ScenePlan, runs: &[SweepRun]) -> Result<Table> {
    let rows: Vec<(&SweepRun, f64, f64)> = runs
        .iter()
        .flat_map(|r| r.report.curve.iter().map(move |&(t, f)| (r, t, f)))
        .collect();
    TableBuilder::new()
        .str("pattern", rows.iter().map(|_| Some(plan.name.as_str())))
        .f64("pressure_Pa", rows.iter().map(|(r, _, _)| Some(r.pressure)))
        .i64("run", rows.iter().map(|(r, _, _)| Some(r.run as i64)))
        .f64("time_s", rows.iter().map(|(_, t, _)| Some(*t)))
        .f64("friction_N", rows.iter().map(|(_, _, f)| Some(*f)))
        .f64(
            "mu",
            rows.iter().map(|(r, _, f)| Some(f / r.report.normal_load)),
        )
        .build()
}

/// Tables of several scenes, stacked.
pub struct SweepTables {
    /// Per run.
    pub runs: Table,
    /// Per pattern and pressure.
    pub summary: Table,
    /// T(t) curves.
    pub curves: Table,
    /// The summary's rows, typed.
    pub summary_rows: Vec<SummaryRow>,
    /// The curves, typed: one per run, in the table's order.
    pub curve_runs: Vec<CurveRun>,
}

/// One run's decimated T(t) curve, as the curves table holds it.
#[derive(Debug, Clone)]
pub struct CurveRun {
    /// Pattern label.
    pub pattern: String,
    /// p \[Pa\].
    pub pressure: f64,
    /// The run's index at its pressure.
    pub run: usize,
    /// (t \[s\], T \[N\]) points.
    pub points: Vec<(f64, f64)>,
}

/// Builds and stacks the tables of several scenes.
pub fn sweep_tables(scenes: &[(&ScenePlan, &[SweepRun])]) -> Result<SweepTables> {
    let mut runs = Vec::new();
    let mut summary = Vec::new();
    let mut curves = Vec::new();
    let mut curve_runs = Vec::new();
    for (plan, r) in scenes {
        runs.push(runs_table(plan, r)?);
        summary.extend(summarise(plan, r));
        curves.push(curves_table(plan, r)?);
        curve_runs.extend(r.iter().map(|r| CurveRun {
            pattern: plan.name.clone(),
            pressure: r.pressure,
            run: r.run,
            points: r.report.curve.clone(),
        }));
    }
    Ok(SweepTables {
        runs: Table::concat(runs)?.expect("at least one scene"),
        summary: summary_table(&summary)?,
        curves: Table::concat(curves)?.expect("at least one scene"),
        summary_rows: summary,
        curve_runs,
    })
}
