//! The friction stage's tables of a test through its cycles:
//! `friction_cycles` (one row per stroke or lap) and `friction_tests` (one
//! row per test, and per velocity step of a stepped test), declared here
//! with the code that turns the typed rows into their columns.

use super::analysis::FrictionFile;
use crate::error::Result;
use crate::extract::friction::assess::TestRow;
use crate::extract::friction::cycles::CycleRow;
use crate::schema::{Show, TableDef};
use crate::table::{Table, TableBuilder};

/// One row per cycle (stroke or lap) of every test.
pub static FRICTION_CYCLES: TableDef = TableDef::new(
    "friction_cycles",
    include_str!("../../../schemas/friction_cycles.toml"),
    Show::Hidden,
);

/// One row per test, and per velocity step of a stepped test.
pub static FRICTION_TESTS: TableDef = TableDef::new(
    "friction_tests",
    include_str!("../../../schemas/friction_tests.toml"),
    Show::PerFile(&[
        ("scope", "scope"),
        ("step", "step"),
        ("n_cycles", "cycles"),
        ("running_in_cycles", "running-in cycles"),
        ("running_in_distance_m", "running-in [m]"),
        ("mu_steady", "μ steady"),
        ("mu_steady_se", "se"),
        ("status", "status"),
    ]),
);

fn count(n: usize) -> Option<i64> {
    Some(n as i64)
}

/// `friction_cycles.parquet`.
pub fn cycles_table(files: &[FrictionFile]) -> Result<Table> {
    let rows: Vec<(&FrictionFile, &CycleRow)> = files
        .iter()
        .flat_map(|f| {
            f.features
                .iter()
                .flat_map(move |t| t.cycles.rows.iter().map(move |r| (f, r)))
        })
        .collect();
    let r =
        |g: fn(&CycleRow) -> Option<f64>| rows.iter().map(move |(_, c)| g(c)).collect::<Vec<_>>();
    TableBuilder::new()
        .str("source", rows.iter().map(|(f, _)| Some(&f.source)))
        .str("section", rows.iter().map(|(_, c)| Some(&c.section)))
        .str(
            "sample_id",
            rows.iter().map(|(f, _)| f.sample.sample_id.as_ref()),
        )
        .str(
            "test_started_at",
            rows.iter().map(|(f, _)| f.started_at.as_ref()),
        )
        .str(
            "test_id",
            rows.iter().map(|(f, _)| f.sample.test_id.as_ref()),
        )
        .i64("cycle", rows.iter().map(|(_, c)| count(c.cycle)))
        .i64("test_cycle", rows.iter().map(|(_, c)| count(c.cycle)))
        .str("kind", rows.iter().map(|(_, c)| Some(c.kind.as_str())))
        .i64(
            "stroke",
            rows.iter().map(|(_, c)| c.stroke.map(|s| s as i64)),
        )
        .i64("lap", rows.iter().map(|(_, c)| c.lap))
        .f64("direction_sign", r(|c| Some(c.direction_sign)))
        .f64("start_s", r(|c| Some(c.start_s)))
        .f64("end_s", r(|c| Some(c.end_s)))
        .f64("distance_start_m", r(|c| c.distance_m.map(|d| d.0)))
        .f64("distance_end_m", r(|c| c.distance_m.map(|d| d.1)))
        .f64("test_distance_start_m", r(|c| c.distance_m.map(|d| d.0)))
        .f64("test_distance_end_m", r(|c| c.distance_m.map(|d| d.1)))
        .f64("window_start_s", r(|c| c.window_s.map(|w| w.0)))
        .f64("window_end_s", r(|c| c.window_s.map(|w| w.1)))
        .i64("n_window", rows.iter().map(|(_, c)| count(c.n_window)))
        .f64("mu", r(|c| c.mu))
        .f64("mu_sd", r(|c| c.mu_sd))
        .f64("mu_peak", r(|c| c.mu_peak))
        .f64("normal_force_N", r(|c| c.normal_force_n))
        .f64("mu_instrument", r(|c| c.mu_instrument))
        .f64("energy_J", r(|c| c.energy_j))
        .f64("loop_area_J", r(|c| c.loop_area_j))
        .f64("wear_depth_m", r(|c| c.wear_depth_m))
        .bool("complete", rows.iter().map(|(_, c)| Some(c.complete)))
        .status(rows.iter().map(|(_, c)| &c.status))
        .build()
}

/// A `friction_tests` row with what it belongs to: a file's own rows, or
/// the row of a series of files ([`super::series`]).
pub struct TestLine<'a> {
    /// The file (a series: its first member).
    pub source: &'a str,
    /// The manifest's `sample_id`.
    pub sample_id: Option<&'a str>,
    /// When the test started.
    pub started_at: Option<&'a str>,
    /// The manifest's `test_id`.
    pub test_id: Option<&'a str>,
    /// Files the row covers.
    pub n_files: usize,
    /// How a series' files were ordered.
    pub order: Option<&'static str>,
    /// The row.
    pub row: &'a TestRow,
}

/// `friction_tests.parquet`.
pub fn tests_table(files: &[FrictionFile]) -> Result<Table> {
    let lines: Vec<TestLine> = files
        .iter()
        .flat_map(|f| {
            f.tests.iter().map(move |t| TestLine {
                source: &f.source,
                sample_id: f.sample.sample_id.as_deref(),
                started_at: f.started_at.as_deref(),
                test_id: f.sample.test_id.as_deref(),
                n_files: 1,
                order: None,
                row: t,
            })
        })
        .collect();
    test_lines_table(&lines)
}

/// The `friction_tests` table of these rows.
pub fn test_lines_table(lines: &[TestLine]) -> Result<Table> {
    let r =
        |g: fn(&TestRow) -> Option<f64>| lines.iter().map(move |l| g(l.row)).collect::<Vec<_>>();
    let cycle_of = |g: fn(&TestRow) -> Option<usize>| {
        lines
            .iter()
            .map(move |l| g(l.row).map(|c| c as i64))
            .collect::<Vec<_>>()
    };
    TableBuilder::new()
        .str("source", lines.iter().map(|l| Some(l.source)))
        .str("sample_id", lines.iter().map(|l| l.sample_id))
        .str("test_id", lines.iter().map(|l| l.test_id))
        .str("test_started_at", lines.iter().map(|l| l.started_at))
        .str("scope", lines.iter().map(|l| Some(l.row.scope.as_str())))
        .i64("n_files", lines.iter().map(|l| count(l.n_files)))
        .str("series_order", lines.iter().map(|l| l.order))
        .str(
            "section",
            lines.iter().map(|l| l.row.step.as_ref().map(|s| &s.0)),
        )
        .i64(
            "step",
            lines
                .iter()
                .map(|l| l.row.step.as_ref().map(|s| s.1 as i64)),
        )
        .f64("velocity_m_per_s", r(|t| t.velocity_m_per_s))
        .str("cycle_source", lines.iter().map(|l| l.row.cycle_source))
        .str(
            "distance_source",
            lines.iter().map(|l| l.row.distance_source),
        )
        .i64("n_cycles", lines.iter().map(|l| count(l.row.n_cycles)))
        .i64("n_judged", lines.iter().map(|l| count(l.row.n_judged)))
        .i64("first_cycle", cycle_of(|t| t.cycles.map(|c| c.0)))
        .i64("last_cycle", cycle_of(|t| t.cycles.map(|c| c.1)))
        .str(
            "running_in_method",
            lines
                .iter()
                .map(|l| l.row.steady.method.map(|m| m.as_str())),
        )
        .i64("running_in_cycles", cycle_of(|t| t.steady.onset))
        .f64("running_in_distance_m", r(|t| t.running_in_distance_m))
        .i64("steady_from_cycle", cycle_of(|t| t.steady_from_cycle))
        .f64("tau_cycles", r(|t| t.steady.tau_cycles))
        .f64("mu_plateau", r(|t| t.steady.plateau))
        .f64("band_mu", r(|t| t.steady.band))
        .f64("mu_steady", r(|t| t.steady.mu))
        .f64("mu_steady_sd", r(|t| t.steady.sd))
        .f64("mu_steady_se", r(|t| t.steady.se))
        .i64(
            "n_steady",
            cycle_of(|t| {
                t.steady
                    .mean_from
                    .filter(|_| t.steady.mu.is_some())
                    .map(|k| t.n_judged - k)
            }),
        )
        .f64("mu_first", r(|t| t.mu_first))
        .f64("mu_max", r(|t| t.mu_max))
        .f64("distance_m", r(|t| t.distance_m))
        .f64("energy_J", r(|t| t.energy_j))
        .f64("normal_force_N", r(|t| t.normal_force_n))
        .f64(
            "wear_depth_rate_m_per_m",
            r(|t| t.wear_depth_rate.map(|w| w.slope)),
        )
        .f64(
            "wear_depth_rate_se_m_per_m",
            r(|t| t.wear_depth_rate.and_then(|w| w.se)),
        )
        .f64("wear_depth_change_m", r(|t| t.wear_depth_change_m))
        .status(lines.iter().map(|l| &l.row.status))
        .build()
}
