//! Traces that give the coefficient of friction and the normal load but no
//! friction force (many tribometers export only these): the friction force
//! is T = μ N, μ comes out as the instrument's, and mapping the coefficient
//! column to `friction_force` is refused.

use crate::common;

use std::path::Path;

use tribo::table::Table;

/// True coefficient of the synthetic plateau.
const MU: f64 = 0.15;
/// Normal load, N.
const LOAD: f64 = 5.0;

/// μ(t): a ramp to a break-away of 0.2 at 1 s, a drop to the plateau μ by
/// 1.2 s, then the plateau with a small oscillation (±0.002) that averages
/// out over the window.
fn mu_at(t: f64) -> f64 {
    if t < 1.0 {
        0.2 * t
    } else if t < 1.2 {
        0.2 - (0.2 - MU) * (t - 1.0) / 0.2
    } else {
        MU + 0.002 * (37.0 * t).sin()
    }
}

/// Writes a 20 s trace at 50 Hz: `Time (s)`, optionally `Fz (N)` (the load
/// with a ±1 % ripple uncorrelated with μ), and `COF`.
fn write_trace(path: &Path, with_load: bool) {
    let mut s = String::from(if with_load {
        "Time (s),Fz (N),COF\n"
    } else {
        "Time (s),COF\n"
    });
    for i in 0..1000 {
        let t = i as f64 * 0.02;
        let n = LOAD * (1.0 + 0.01 * (11.0 * t).sin());
        match with_load {
            true => s.push_str(&format!("{t:.2},{n:.5},{:.6}\n", mu_at(t))),
            false => s.push_str(&format!("{t:.2},{:.6}\n", mu_at(t))),
        }
    }
    std::fs::write(path, s).unwrap();
}

fn run(dir: &Path, extra: &str) -> std::process::Output {
    std::fs::write(
        dir.join("p.toml"),
        format!(
            "stages = [\"friction\"]\n[input]\nfiles = [\"*.csv\"]\nsamples = \"samples.txt\"\n[output]\ndir = \"out\"\n{extra}"
        ),
    )
    .unwrap();
    common::tribo(dir, &["run", "p.toml"])
}

/// The μ-only trace gives the true μ to 0.5 % whether the load comes from
/// a column or from the manifest; T = μ N is reported as such and the
/// instrument's μ is kept beside ours.
#[test]
fn mu_only_traces_give_the_true_mu() {
    let dir = tempfile::tempdir().unwrap();
    write_trace(&dir.path().join("with_load.csv"), true);
    write_trace(&dir.path().join("manifest_load.csv"), false);
    std::fs::write(
        dir.path().join("samples.txt"),
        format!("file,sample_id,normal_force_N\nmanifest_load.csv,M,{LOAD}\n"),
    )
    .unwrap();
    let o = run(dir.path(), "");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (t, _) = Table::read_parquet(&dir.path().join("out/friction.parquet")).unwrap();
    assert_eq!(t.height(), 2);
    let (src, status) = (t.str("source").unwrap(), t.str("status").unwrap());
    let (mu_d, mu_i) = (
        t.f64("mu_dynamic").unwrap(),
        t.f64("mu_instrument").unwrap(),
    );
    let (mu_s, origin) = (
        t.f64("mu_static").unwrap(),
        t.str("friction_force_source").unwrap(),
    );
    let normal_src = t.str("normal_force_source").unwrap();
    for i in 0..2 {
        let name = src[i].as_deref().unwrap();
        assert_eq!(status[i].as_deref(), Some("ok"), "{name}");
        assert_eq!(origin[i].as_deref(), Some("coefficient"), "{name}");
        let d = mu_d[i].unwrap();
        assert!((d - MU).abs() / MU < 0.005, "{name}: μ_d = {d}, true {MU}");
        // The instrument's μ over the same window, kept as it was.
        assert!((mu_i[i].unwrap() - MU).abs() / MU < 0.005, "{name}");
        // The break-away peak of 0.2 (the 3-sample median smooths a sharp
        // apex by at most one step of the ramp: 0.2 × 0.02 s = 0.004).
        assert!(
            (mu_s[i].unwrap() - 0.2).abs() < 0.005,
            "{name}: μ_s = {:?}",
            mu_s[i]
        );
        let expected = if name.ends_with("with_load.csv") {
            "trace"
        } else {
            "manifest"
        };
        assert_eq!(normal_src[i].as_deref(), Some(expected), "{name}");
    }
}

/// Without a normal force the coefficient cannot give T: a per-file error
/// that says what to add, exit code 1, never a number.
#[test]
fn a_mu_only_trace_without_a_load_is_a_file_error() {
    let dir = tempfile::tempdir().unwrap();
    write_trace(&dir.path().join("no_load.csv"), false);
    std::fs::write(
        dir.path().join("samples.txt"),
        "file,sample_id\nno_load.csv,X\n",
    )
    .unwrap();
    let o = run(dir.path(), "");
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("no_load.csv") && err.contains("normal_force_N"),
        "{err}"
    );
}

/// Following the old advice (map `friction_force` to the coefficient, give
/// it a force unit) gave μ_d = μ/N silently. It is refused, naming the
/// column and saying what tribo does instead.
#[test]
fn mapping_a_coefficient_to_friction_force_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    write_trace(&dir.path().join("with_load.csv"), true);
    std::fs::write(dir.path().join("samples.txt"), "file\n").unwrap();
    let o = run(
        dir.path(),
        "[[ingest.override]]\nfiles = \"*.csv\"\ncolumns = { friction_force = \"COF\" }\nunits = { COF = \"N\" }\n",
    );
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("'COF'") && err.contains("coefficient of friction, not a force"),
        "{err}"
    );
    let (t, _) = Table::read_parquet(&dir.path().join("out/friction.parquet")).unwrap();
    assert_eq!(t.height(), 0, "no row from a refused mapping");
}
