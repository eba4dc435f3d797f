//! Sweeps, scene files and output tables of the spring-block simulator:
//! determinism across thread counts, validation of bad scenes, the shipped
//! pipeline scenes, and the written tables.
#![deny(clippy::float_cmp)]

use crate::common;
use std::path::Path;

use tribo::simulate::spring_block::{load_input, run_sweep, SceneSpec, SimulationInput, SweepRun};
use tribo::table::Table;

/// A small, fast scene (8 × 8, fast slider, short sliding window).
const SMALL: &str = r#"
name = "B"
seed = 7
repetitions = 2
pressures_Pa = [5e3, 20e3]
[lattice]
nx = 8
ny = 8
[pattern]
kind = "holes"
diameter_m = 5e-6
pitch_m = 15e-6
[slider]
speed_m_per_s = 0.02
[integrator]
dt_s = 2e-8
[run]
sliding_time_s = 2e-6
curve_interval_s = 1e-6
"#;

fn plan(text: &str) -> tribo::Result<tribo::simulate::spring_block::ScenePlan> {
    SceneSpec::from_toml(text, Path::new("scene.toml"))?.plan()
}

fn fingerprint(runs: &[SweepRun]) -> Vec<(u64, u64, u64, usize)> {
    runs.iter()
        .map(|r| {
            (
                r.seed,
                r.report.mu_static.unwrap_or(f64::NAN).to_bits(),
                r.report.mu_dynamic.unwrap_or(f64::NAN).to_bits(),
                r.report.curve.len(),
            )
        })
        .collect()
}

#[test]
fn same_seed_is_bit_identical_on_1_and_2_threads() {
    let p = plan(SMALL).unwrap();
    let run = |n: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .unwrap()
            .install(|| run_sweep(&p, &|| {}))
            .unwrap()
    };
    let (a, b) = (run(1), run(2));
    assert_eq!(fingerprint(&a), fingerprint(&b));
    for (x, y) in a.iter().zip(&b) {
        let bits = |c: &[(f64, f64)]| {
            c.iter()
                .map(|(t, f)| (t.to_bits(), f.to_bits()))
                .collect::<Vec<_>>()
        };
        assert_eq!(bits(&x.report.curve), bits(&y.report.curve));
    }
    // Every run found its peak; runs differ (fresh coefficients and angle).
    assert!(
        a.iter().all(|r| r.report.stop.status() == "ok"),
        "{:?}",
        a.iter()
            .map(|r| r.report.stop.message())
            .collect::<Vec<_>>()
    );
    assert_ne!(a[0].seed, a[1].seed);
    let mu: Vec<f64> = a.iter().map(|r| r.report.mu_static.unwrap()).collect();
    assert!((mu[0] - mu[1]).abs() > 0.0);
    // Macroscopic μ_s sits below the local mean 4.5 plus adhesion/p and
    // above the contact fraction times the weakest plausible local value.
    let adh = 23.8e3;
    for r in &a {
        let upper = 4.5 + 5.0 * 0.2 + adh / r.pressure;
        let m = r.report.mu_static.unwrap();
        assert!(m > 0.3 && m < upper, "{m} at {}", r.pressure);
    }
}

#[test]
fn bad_scenes_are_rejected_before_running() {
    let cases = [
        ("repetitions = 2", "repetitions = 0", "repetitions is 0"),
        (
            "pressures_Pa = [5e3, 20e3]",
            "pressures_Pa = [5e3, -1e3]",
            "pressure -1000 Pa",
        ),
        (
            "pitch_m = 15e-6",
            "pitch_m = 60e-6",
            "larger than the lattice",
        ),
        ("[lattice]", "[lattice]\ncolour = 1", "unknown field"),
        ("dt_s = 2e-8", "dt_s = 0.0", "dt [s] is 0"),
        (
            "speed_m_per_s = 0.02",
            "speed_m_per_s = 0.02\nangle_min_deg = 50",
            "angle range",
        ),
    ];
    for (from, to, expected) in cases {
        assert!(SMALL.contains(from), "{from}");
        let e = plan(&SMALL.replacen(from, to, 1)).unwrap_err().to_string();
        assert!(e.contains(expected), "{to}: {e}");
    }
}

#[test]
fn shipped_scenes_are_valid_and_match_table_4_1() {
    let dir = crate::common::root().join("pipelines");
    let (input, hashes) = load_input(&dir.join("spring_block_compare.toml")).unwrap();
    assert_eq!(hashes.len(), 7);
    let SimulationInput::Study(study) = input else {
        panic!("expected a study")
    };
    let names: Vec<&str> = study.scenes.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["flat", "A", "B", "C", "Sx", "Sy"]);
    for s in &study.scenes {
        assert_eq!(
            (s.params.nx, s.params.ny, s.repetitions, s.pressures.len()),
            (85, 85, 10, 8)
        );
    }
    // AF of Table 4.1 (0.95, 0.65, 0.56, 0.67), to the table's two digits.
    let af: Vec<f64> = study
        .links
        .iter()
        .map(|l| l.area_fraction.unwrap())
        .collect();
    for (got, want) in af.iter().zip([1.0, 0.95, 0.65, 0.56, 0.67, 0.67]) {
        assert!((got - want).abs() < 0.006, "{got} vs {want}");
    }
    let groups: Vec<&str> = study
        .links
        .iter()
        .map(|l| l.group.as_deref().unwrap())
        .collect();
    assert_eq!(groups, ["F", "A", "B", "C", "S (x)", "S (y)"]);
}

#[test]
fn study_writes_schema_checked_tables() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("b.toml"), SMALL).unwrap();
    std::fs::write(
        dir.path().join("study.toml"),
        "scenes = [\"b.toml\"]\n[[measured.fit]]\ngroup = \"B\"\nregime = \"static\"\nmu = 2.0\ntau0_Pa = 10e3\n",
    )
    .unwrap();
    let study = dir.path().join("study.toml");
    let (input, _) = load_input(&study).unwrap();
    let outcome = input.compute(&|| {}).unwrap();
    assert_eq!(outcome.runs, 4);
    assert_eq!(outcome.failures, 0, "{:?}", outcome.failure_messages);
    let out = dir.path().join("out");
    let settings = common::file_setting("scene", &study);
    let report =
        common::run_stage("spring-block", settings, &out, "simulate spring-block").unwrap();
    assert_eq!(report.rows_without_result(), 0);
    let (runs, meta) = Table::read_parquet(&out.join("spring_block.parquet")).unwrap();
    assert_eq!(runs.height(), 4);
    assert!(meta
        .iter()
        .any(|(k, v)| k == "tribo.command" && v.contains("spring-block")));
    let (summary, _) = Table::read_parquet(&out.join("spring_block_summary.parquet")).unwrap();
    assert_eq!(summary.height(), 2);
    // The summary mean is the mean of the per-run values.
    let mu = runs.f64("mu_static").unwrap();
    let mean = summary.f64("mu_static_mean").unwrap();
    let m0 = (mu[0].unwrap() + mu[1].unwrap()) / 2.0;
    assert!((mean[0].unwrap() - m0).abs() < 1e-12 * m0);
    let (cmp, _) = Table::read_parquet(&out.join("spring_block_compare.parquet")).unwrap();
    assert_eq!(cmp.height(), 4);
    // Static row at 5 kPa: measured 2.0 + 10e3/5e3 = 4.0 from the given fit.
    let meas = cmp.f64("mu_measured").unwrap();
    assert!((meas[0].unwrap() - 4.0).abs() < 1e-12);
    let ratio = cmp.f64("ratio_simulated_to_measured").unwrap();
    assert!((ratio[0].unwrap() - m0 / 4.0).abs() < 1e-12);
    let (curves, _) = Table::read_parquet(&out.join("spring_block_curves.parquet")).unwrap();
    assert!(curves.height() > 4);
}
