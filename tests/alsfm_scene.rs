//! Scene files: every example in `fixtures/alsfm/` parses, validates, runs
//! and writes schema-checked tables; bad scenes are rejected before any
//! computation; the output does not depend on the thread count.
#![deny(clippy::float_cmp)]

use std::path::{Path, PathBuf};

use tribo::models::alsfm::closed_form::{mu_across, WedgeCase};
use tribo::simulate::alsfm::plan::Plan;
use tribo::simulate::alsfm::run;

use crate::common;

/// The `alsfm` stage on one scene file, writing into `out`.
fn run_scene_file(scene: &Path, out: &Path) -> tribo::Result<tribo::pipeline::RunReport> {
    common::run_stage(
        "alsfm",
        common::file_setting("scene", scene),
        out,
        "simulate alsfm",
    )
}
use tribo::table::Table;

fn fixtures() -> Vec<PathBuf> {
    let pattern = crate::common::root().join("fixtures/alsfm/*.toml");
    let mut v: Vec<PathBuf> = glob::glob(&pattern.to_string_lossy())
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
        let plan =
            Plan::from_spec_at(&toml::from_str(&text).unwrap(), f.parent().unwrap()).unwrap();
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
            s.rows_without_result(),
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
    let f = crate::common::root().join("fixtures/alsfm/case2_light_load.toml");
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
        crate::common::root().join("fixtures/alsfm/wedges_beta_sweep.toml"),
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
    let f = crate::common::root().join("fixtures/alsfm/sinusoid_2d_adhesion.toml");
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
    let scene = crate::common::root().join("fixtures/alsfm/wedges_beta_sweep.toml");
    let code = |scene: &Path, out: &str| {
        let args = ["simulate", "alsfm", scene.to_str().unwrap(), "--out", out];
        common::tribo(dir.path(), &args).status.code()
    };
    assert_eq!(code(&scene, "out"), Some(0));
    assert!(dir.path().join("out/alsfm.parquet").exists());
    let text = std::fs::read_to_string(&scene)
        .unwrap()
        .replace("mu0 = 0.3", "mu0 = 2.6");
    let scene = dir.path().join("locked.toml");
    std::fs::write(&scene, text).unwrap();
    assert_eq!(code(&scene, "locked"), Some(1));
    let t = read(&dir.path().join("locked"), "alsfm");
    let status = t.str("status").unwrap();
    assert_eq!(status[0].as_deref(), Some("locked"));
    assert!(t.str("status_detail").unwrap()[0]
        .as_deref()
        .unwrap()
        .contains("21.8014"));
}

/// The rows of a scene with its lower surface given inline and the same
/// scene with that surface read from `file_table` (written beside it).
fn inline_and_file_rows(inline: &str, file_table: &str, name: &str, data: &str) -> (Table, Table) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join(name), data).unwrap();
    let head = "mu0 = 0.25\nbeta_deg = [0.0, 30.0, 90.0]\nload = [0.05, 0.005]\n\
                [resolution]\nsprings = 64\nsprings_y = 16\n[upper]\nkind = \"flat\"\n";
    let mut out = Vec::new();
    for (k, lower) in [inline, file_table].into_iter().enumerate() {
        let scene = dir.path().join(format!("scene{k}.toml"));
        std::fs::write(&scene, format!("{head}[lower]\n{lower}")).unwrap();
        let o = dir.path().join(format!("out{k}"));
        run_scene_file(&scene, &o).unwrap_or_else(|e| panic!("{e}"));
        out.push(read(&o, "alsfm"));
    }
    let b = out.pop().unwrap();
    (out.pop().unwrap(), b)
}

fn assert_same_rows(a: &Table, b: &Table) {
    for col in ["mu", "mu_parallel", "mu_perp"] {
        let (x, y) = (a.f64(col).unwrap(), b.f64(col).unwrap());
        assert_eq!(x.len(), y.len());
        for (x, y) in x.iter().zip(&y) {
            let (x, y) = (x.unwrap(), y.unwrap());
            // The file prints heights with 12 significant digits.
            assert!(
                (x - y).abs() <= 1e-10 * x.abs().max(1.0),
                "{col}: {x} vs {y}"
            );
        }
    }
    assert_eq!(a.str("path").unwrap(), b.str("path").unwrap());
}

/// A surface read from a profile file (x in mm, z in µm, as an instrument
/// writes it) is the inline sampled profile in metres: same rows.
#[test]
fn surface_from_a_profile_file_equals_the_inline_profile() {
    let z: Vec<f64> = (0..32)
        .map(|i| 0.02 * (i as f64 * 0.7).sin() + 0.01 * (i as f64 * 1.9).cos())
        .collect();
    let dx = 0.125;
    let inline = format!(
        "kind = \"profile\"\ndx = {dx}\nz = [{}]\n",
        z.iter()
            .map(|v| format!("{v:.12e}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let mut data = String::from("x (mm),z (um)\n");
    for (i, v) in z.iter().enumerate() {
        data += &format!("{},{:.12e}\n", i as f64 * dx * 1e3, v * 1e6);
    }
    let file = "kind = \"file\"\npath = \"p.csv\"\ndetrend = \"none\"\n";
    let (a, b) = inline_and_file_rows(&inline, file, "p.csv", &data);
    assert_same_rows(&a, &b);
    assert!(a
        .str("path")
        .unwrap()
        .iter()
        .all(|p| p.as_deref() == Some("numeric_1d")));
}

/// A surface read from a z matrix file is the inline map: same rows.
#[test]
fn surface_from_a_matrix_file_equals_the_inline_map() {
    let (nx, ny) = (12, 10);
    let z: Vec<f64> = (0..nx * ny)
        .map(|k| {
            let (c, r) = ((k % nx) as f64, (k / nx) as f64);
            0.03 * (c * 0.9).sin() * (r * 0.6).cos() + 0.005 * (c + 2.0 * r).sin()
        })
        .collect();
    let inline = format!(
        "kind = \"map\"\ndx = 0.25\ndy = 0.5\nnx = {nx}\nz = [{}]\n",
        z.iter()
            .map(|v| format!("{v:.12e}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let mut data = format!(
        "# Width: {} m\n# Height: {} m\n# Value units: m\n",
        0.25 * nx as f64,
        0.5 * ny as f64
    );
    for row in z.chunks(nx) {
        data += &row
            .iter()
            .map(|v| format!("{v:.12e}"))
            .collect::<Vec<_>>()
            .join("\t");
        data.push('\n');
    }
    let file = "kind = \"file\"\npath = \"m.txt\"\ndetrend = \"none\"\n";
    let (a, b) = inline_and_file_rows(&inline, file, "m.txt", &data);
    assert_same_rows(&a, &b);
    assert!(a
        .str("path")
        .unwrap()
        .iter()
        .all(|p| p.as_deref() == Some("numeric_2d")));
}

/// The Dektak example: the file's window, detrended, is the surface; the
/// table's provenance lists the profile file with its hash; windowing and
/// detrending are those of `tribo roughness` (the same Rq).
#[test]
fn dektak_scene_uses_the_windowed_detrended_profile() {
    use tribo::extract::roughness::{analyze_profile, Profile, RoughnessParams};
    use tribo::models::alsfm::surface::Surface;
    let f = crate::common::root().join("fixtures/alsfm/dektak_on_flat.toml");
    let spec = toml::from_str(&std::fs::read_to_string(&f).unwrap()).unwrap();
    let plan = Plan::from_spec_at(&spec, f.parent().unwrap()).unwrap();
    let Surface::Profile { dx, z } = &plan.lower else {
        panic!("{:?}", plan.lower)
    };
    assert_eq!(z.len(), 1697, "the cursor window holds 1697 points");
    // Rq of the scene's heights is the roughness stage's Rq of the window
    // (MODELS §4: 0.0114359 µm).
    let rq = (z.iter().map(|v| v * v).sum::<f64>() / z.len() as f64).sqrt();
    let rep = analyze_profile(
        &Profile::new("scene", 0.0, *dx, z.clone()).unwrap(),
        &RoughnessParams::default(),
    )
    .unwrap();
    assert!((rq - 0.0114359e-6).abs() < 1e-13, "{rq}");
    assert!((rep.rq - rq).abs() < 1e-3 * rq, "{} vs {rq}", rep.rq);
    assert_eq!(plan.surface_files.len(), 1);
    assert_eq!(plan.surface_files[0].sha256.len(), 64);
}

/// Bad surface files are named: a missing file, a section out of range, a
/// window with too few points, a file with no unit for z.
#[test]
fn bad_surface_files_are_named() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("nounit.csv"),
        (0..20)
            .map(|i| format!("{i},{}\n", i % 3))
            .collect::<String>(),
    )
    .unwrap();
    let head = "mu0 = 0.25\nbeta_deg = 0.0\nload = 0.05\n[upper]\nkind = \"flat\"\n[lower]\nkind = \"file\"\n";
    let dektak = crate::common::root()
        .join("fixtures/roughness/dektak/dektak-1.csv")
        .display()
        .to_string();
    let cases = [
        ("path = \"missing.csv\"".to_string(), "missing.csv"),
        (format!("path = '{dektak}'\nsection = 2"), "section = 2"),
        (
            format!("path = '{dektak}'\nwindow = [\"468 um\", \"468.5 um\"]"),
            "evaluation window",
        ),
        (
            "path = \"nounit.csv\"".to_string(),
            "no unit for the x column",
        ),
        (
            format!("path = '{dektak}'\nwindow = [\"468 s\", \"733 um\"]"),
            "window start",
        ),
    ];
    for (k, (lower, word)) in cases.into_iter().enumerate() {
        let scene = dir.path().join(format!("s{k}.toml"));
        std::fs::write(&scene, format!("{head}{lower}\n")).unwrap();
        let e = run_scene_file(&scene, &dir.path().join("out"))
            .map(|_| ())
            .unwrap_err()
            .to_string();
        assert!(
            e.contains(word) && e.contains("[lower]"),
            "expected '{word}' in: {e}"
        );
    }
}

/// Oblique sliding (β = 30°) over square-periodic 2-D sinusoids has no
/// period: s cos 30° = a λ and s sin 30° = b λ would make tan 30° = b/a
/// rational. The point is averaged over 16 spans of the longer axis period,
/// s = 16 λ / sin 30° = 32 λ, and says so with status `averaged_window`: a
/// result (exit code 0), not a failure. β = 0 on the same surfaces is exact.
#[test]
fn oblique_sliding_states_its_averaging_window() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("oblique.toml");
    let surface = "kind = \"sinusoid\"\namplitude = 0.05\nlambda_x = 1.0\nlambda_y = 1.0\n";
    let text = format!(
        "mu0 = 0.3\nbeta_deg = [0.0, 30.0]\nload = 0.1\n[resolution]\nsprings = 16\n\
         springs_y = 16\n[lower]\n{surface}[upper]\n{surface}"
    );
    std::fs::write(&scene, text).unwrap();
    let args = ["simulate", "alsfm", scene.to_str().unwrap(), "--out", "out"];
    assert_eq!(common::tribo(dir.path(), &args).status.code(), Some(0));
    let t = read(&dir.path().join("out"), "alsfm");
    let status = t.str("status").unwrap();
    let message = t.str("status_detail").unwrap();
    assert_eq!(status[0].as_deref(), Some("ok"));
    assert_eq!(status[1].as_deref(), Some("averaged_window"));
    let m = message[1].as_deref().unwrap();
    assert!(m.contains("3.200000e1 m"), "{m}");
    let mu = t.f64("mu").unwrap();
    let mu30 = mu[1].unwrap();
    assert!(mu30.is_finite() && mu30 > 0.3, "{mu30}");
}
