//! Scene files: every example in `fixtures/alsfm/` parses, validates, runs
//! and writes schema-checked tables; bad scenes are rejected before any
//! computation; the output does not depend on the thread count.
#![deny(clippy::float_cmp)]

#[allow(dead_code)] // `run` (ExitCode) is for the binary
#[path = "../src/cli/simulate_alsfm.rs"]
mod simulate_alsfm;

use std::path::{Path, PathBuf};

use tribo::models::alsfm::closed_form::{mu_across, WedgeCase};
use tribo::simulate::alsfm::plan::Plan;
use tribo::simulate::alsfm::{run, run_scene_file};
use tribo::table::Table;

fn fixtures() -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = glob::glob(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/fixtures/alsfm/*.toml"
    ))
    .unwrap()
    .map(|p| p.unwrap())
    .collect();
    v.sort();
    v
}

fn read(dir: &Path, name: &str) -> Table {
    Table::read_parquet(&dir.join(format!("{name}.parquet")))
        .unwrap()
        .0
}

/// Each example runs; `alsfm.parquet` has one row per (β, load) with a
/// known path, and the extra tables the scene asks for exist.
#[test]
fn every_example_scene_runs() {
    let files = fixtures();
    assert!(files.len() >= 6, "{files:?}");
    for f in files {
        let dir = tempfile::tempdir().unwrap();
        let text = std::fs::read_to_string(&f).unwrap();
        let plan = Plan::from_toml(&text).unwrap();
        let s = run_scene_file(&f, dir.path()).unwrap_or_else(|e| panic!("{}: {e}", f.display()));
        let t = read(dir.path(), "alsfm");
        assert_eq!(
            t.height(),
            plan.beta_deg.len() * plan.loads.len(),
            "{}",
            f.display()
        );
        for p in t.str("path").unwrap() {
            let p = p.unwrap();
            assert!(
                ["flat", "closed_form", "numeric_1d", "numeric_2d"].contains(&p.as_str()),
                "{p}"
            );
        }
        assert_eq!(
            s.failures,
            0,
            "{}: {:?}",
            f.display(),
            t.str("message").unwrap()
        );
        for (want, name) in [
            (plan.outputs.time_series, "alsfm_time_series"),
            (plan.outputs.adhesion, "alsfm_adhesion"),
            (plan.outputs.wear, "alsfm_wear"),
            (plan.outputs.hierarchy, "alsfm_hierarchy"),
            (!plan.outputs.contact_maps.is_empty(), "alsfm_contact_map"),
        ] {
            assert_eq!(
                dir.path().join(format!("{name}.parquet")).exists(),
                want,
                "{} {name}",
                f.display()
            );
        }
    }
}

/// The light-load example reproduces MODELS.md §5 in its table: exact
/// (closed-form path) at 0.2 and 0.05, numeric and 0.6 % / 7 % / 11 % high
/// below the boundary.
#[test]
fn light_load_example_table() {
    let dir = tempfile::tempdir().unwrap();
    let f = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/alsfm/case2_light_load.toml");
    run_scene_file(&f, dir.path()).unwrap();
    let t = read(dir.path(), "alsfm");
    // The scene gives φ to 6 decimals of a degree.
    let cf = mu_across(WedgeCase::BothRough, 0.3, 21.801409_f64.to_radians()).unwrap();
    let mu = t.f64("mu").unwrap();
    let path = t.str("path").unwrap();
    // Loads [0.2, 0.05, 0.04, 0.03, 0.01, 0.005]; expected excess, ±10 %.
    for (k, want) in [(0, 0.0), (1, 0.0), (3, 0.006), (4, 0.07), (5, 0.11)] {
        let e = mu[k].unwrap() / cf - 1.0;
        if want < 1e-3 {
            assert!(e.abs() < 1e-12, "row {k}: {e}");
            assert_eq!(path[k].as_deref(), Some("closed_form"));
        } else {
            assert!((e - want).abs() < 0.1 * want, "row {k}: {e} vs {want}");
            assert_eq!(path[k].as_deref(), Some("numeric_1d"));
        }
    }
}

/// Unknown fields, bad ranges and contradictory settings are rejected with
/// a message naming the field.
#[test]
fn bad_scenes_are_rejected() {
    let base = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/alsfm/wedges_beta_sweep.toml"),
    )
    .unwrap();
    let cases = [
        (
            base.replace("mu0 = 0.3", "mu0 = 0.3\nmu_zero = 1.0"),
            "mu_zero",
        ),
        (base.replace("mu0 = 0.3", "mu0 = -0.3"), "mu0"),
        (base.replace("load = 0.1", "load = -0.1"), "adhesion"),
        (
            base.replacen("phi_rise_deg = 21.801409", "phi_rise_deg = 95.0", 1),
            "phi_rise",
        ),
        (
            base.replace("springs = 200", "springs = 200\ntolerance = 1e-3"),
            "tolerance",
        ),
        (base.replace("springs = 200", "springs = 0"), "springs"),
        (base.replace("[outputs]", "[outputs]\nwear = true"), "wear"),
        (
            base.replace("kind = \"wedges\"", "kind = \"hexagons\""),
            "hexagons",
        ),
    ];
    for (text, word) in cases {
        let e = Plan::from_toml(&text).unwrap_err().to_string();
        assert!(e.contains(word), "expected '{word}' in: {e}");
    }
}

/// The same scene on 1 and 3 threads gives identical rows.
#[test]
fn output_does_not_depend_on_thread_count() {
    let f = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/alsfm/sinusoid_2d_adhesion.toml");
    let plan = Plan::from_toml(&std::fs::read_to_string(f).unwrap()).unwrap();
    let on = |n: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .unwrap()
            .install(|| run(&plan).unwrap())
    };
    assert!(on(1) == on(3));
}

/// The CLI entry point writes the tables and returns exit code 0; a scene
/// whose surfaces lock finishes with exit code 1 and a `locked` row.
#[test]
fn cli_runs_a_scene() {
    let dir = tempfile::tempdir().unwrap();
    let args = simulate_alsfm::SimulateAlsfmArgs {
        scene: Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/alsfm/wedges_beta_sweep.toml"),
        out: dir.path().join("out"),
    };
    assert_eq!(simulate_alsfm::exit_code(&args).unwrap(), 0);
    assert!(dir.path().join("out/alsfm.parquet").exists());
    let text = std::fs::read_to_string(&args.scene)
        .unwrap()
        .replace("mu0 = 0.3", "mu0 = 2.6");
    let scene = dir.path().join("locked.toml");
    std::fs::write(&scene, text).unwrap();
    let args = simulate_alsfm::SimulateAlsfmArgs {
        scene,
        out: dir.path().join("locked"),
    };
    assert_eq!(simulate_alsfm::exit_code(&args).unwrap(), 1);
    let t = read(&args.out, "alsfm");
    let status = t.str("status").unwrap();
    assert_eq!(status[0].as_deref(), Some("locked"));
    assert!(t.str("message").unwrap()[0]
        .as_deref()
        .unwrap()
        .contains("21.8014"));
}
