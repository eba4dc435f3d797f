//! One pipeline over a mixed lab folder: every file goes to the stage that
//! reads its kind, the fits and the simulation run in the same pipeline, and
//! their numbers are those the fixtures were built with
//! (`fixtures/lab/generate.py`).

use std::collections::BTreeSet;
use std::path::Path;

use tribo::table::Table;

use crate::common;

fn read(dir: &Path, name: &str) -> Table {
    Table::read_parquet(&dir.join(format!("{name}.parquet")))
        .unwrap_or_else(|e| panic!("{name}: {e}"))
        .0
}

fn names(list: &[&str]) -> BTreeSet<String> {
    list.iter().map(|s| s.to_string()).collect()
}

/// The row of a coulomb table for a group and regime: (μ, τ0).
fn fit(c: &Table, group: &str, regime: &str) -> (f64, f64) {
    let (g, r) = (c.str("group").unwrap(), c.str("regime").unwrap());
    let i = (0..c.height())
        .find(|&i| g[i].as_deref() == Some(group) && r[i].as_deref() == Some(regime))
        .unwrap_or_else(|| panic!("no fit for {group} {regime}"));
    (
        c.f64("mu").unwrap()[i].unwrap(),
        c.f64("tau0_Pa").unwrap()[i].unwrap(),
    )
}

/// The demo: 22 files of a week's lab folder, one glob, seven stages. The
/// notes file is listed as taken by no stage; nothing fails; each file is
/// in the table of its kind; the fits recover what the files were built
/// with.
#[test]
fn demo_lab_folder_runs_every_stage() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path();
    let report = common::run_demo(out);
    assert!(report.failures.is_empty(), "{:?}", report.failures);
    assert_eq!(report.exit_code(), 0, "{report:?}");
    let unrouted: Vec<&str> = report.unrouted.iter().map(|(f, _)| f.as_str()).collect();
    assert!(
        unrouted.len() == 1 && unrouted[0].ends_with("notes.txt"),
        "{unrouted:?}"
    );
    assert_eq!(read(out, "errors").height(), 0);
    let friction = common::sources(out, "friction");
    assert_eq!(friction.len(), 15, "{friction:?}");
    assert!(friction
        .iter()
        .all(|f| f.starts_with("sled_") || f.starts_with("HT-") || f.starts_with("pod_")));
    assert_eq!(
        common::sources(out, "roughness"),
        names(&["dektak-1.csv", "pin1_profile.csv", "test1.txt"])
    );
    assert_eq!(
        common::sources(out, "tensile"),
        names(&[
            "generic_force_extension.csv",
            "t150_knotted.txt",
            "t150_unknotted.txt"
        ])
    );
    // Per-sample fits of sample 1 recover thesis Table 4.2 (the traces'
    // construction): noise is 0.3 % of T_d per sample and the static peak is
    // a raw maximum, so μ within 1 % and τ0 (extrapolated to p = 0 from
    // 5-20 kPa) within 2 %.
    let c = read(out, "coulomb");
    for (group, want) in [
        ("sample_id=F-1", [4.76, 23.45e3, 2.88, 11.85e3]),
        ("sample_id=A-1", [5.71, 15.41e3, 3.75, 4.02e3]),
    ] {
        for (k, regime) in ["static", "dynamic"].iter().enumerate() {
            let (mu, tau0) = fit(&c, group, regime);
            let (mu_w, tau_w) = (want[2 * k], want[2 * k + 1]);
            assert!((mu / mu_w - 1.0).abs() < 0.01, "{group} {regime} mu {mu}");
            assert!(
                (tau0 / tau_w - 1.0).abs() < 0.02,
                "{group} {regime} tau0 {tau0}"
            );
        }
    }
    // The summary per pattern: the mean and sample sd (n − 1) of its
    // samples' fits, by hand from the coulomb rows.
    let sm = read(out, "coulomb_summary");
    let (pat, reg) = (sm.str("pattern").unwrap(), sm.str("regime").unwrap());
    for (pattern, regime) in [
        ("F", "static"),
        ("F", "dynamic"),
        ("A", "static"),
        ("A", "dynamic"),
    ] {
        let i = (0..sm.height())
            .find(|&i| pat[i].as_deref() == Some(pattern) && reg[i].as_deref() == Some(regime))
            .unwrap();
        let fits: Vec<(f64, f64)> = ["1", "2"]
            .iter()
            .map(|k| fit(&c, &format!("sample_id={pattern}-{k}"), regime))
            .collect();
        let mean_sd = |v: [f64; 2]| ((v[0] + v[1]) / 2.0, (v[0] - v[1]).abs() / 2f64.sqrt());
        let (mu, tau) = (
            mean_sd([fits[0].0, fits[1].0]),
            mean_sd([fits[0].1, fits[1].1]),
        );
        let cell = |c: &str| sm.f64(c).unwrap()[i].unwrap();
        assert_eq!(sm.i64("n_samples").unwrap()[i], Some(2));
        for (got, want) in [
            (cell("mu_mean"), mu.0),
            (cell("mu_sd"), mu.1),
            (cell("tau0_mean_Pa"), tau.0),
            (cell("tau0_sd_Pa"), tau.1),
        ] {
            assert!(
                (got - want).abs() <= 1e-12 * want.abs(),
                "{pattern} {regime}: {got} vs {want}"
            );
        }
    }
    // The pin-on-disc μ(v) was built with a = 5 mm and the upper bound at
    // Rdq 7.3°; the roughness stage measures the pin's Rdq from its profile
    // (7.32°, noise included): a within 2 % (2 % noise on 1600 samples).
    let ice = read(out, "ice_fit");
    let bound = ice.str("bound").unwrap();
    let up = bound
        .iter()
        .position(|b| b.as_deref() == Some("upper"))
        .unwrap();
    let a = ice.f64("a_m").unwrap()[up].unwrap();
    assert!((a / 5e-3 - 1.0).abs() < 0.02, "a = {a}");
    assert!(read(out, "tensile_groups").height() >= 2);
    // The simulated comparison uses the pipeline's own Coulomb fits.
    let cmp = read(out, "spring_block_compare");
    let src = cmp.str("measured_source").unwrap();
    assert!(src.iter().all(|s| s.as_deref() == Some("coulomb stage")));
    let measured = cmp.f64("mu_measured").unwrap();
    assert!(measured.iter().all(|m| m.is_some_and(|m| m > 0.0)));
}

/// The real exports of other labs and the bundled lab folder, mixed in one
/// folder and read with one glob: every file is in the table of its kind,
/// the licence files are taken by no stage, nothing fails, and the Coulomb
/// and ice fits and the tensile group summary are written beside the
/// per-file tables.
#[test]
fn real_exports_and_fixtures_in_one_folder() {
    let Some(real) = common::shared_real("") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let lab = dir.path().join("lab");
    common::copy_tree(&real, &lab.join("real"));
    for sub in ["friction", "profiles", "fibres"] {
        common::copy_tree(
            &common::root().join("fixtures/lab").join(sub),
            &lab.join(sub),
        );
    }
    // The pin-on-disc exports carry no normal force: 3 N (FrictionForce / mu).
    let mut manifest =
        std::fs::read_to_string(common::root().join("fixtures/lab/samples.csv")).unwrap();
    manifest.push_str("c1.csv,POD-c1,,3\nc2.csv,POD-c2,,3\n");
    std::fs::write(dir.path().join("samples.csv"), &manifest).unwrap();
    std::fs::write(
        dir.path().join("p.toml"),
        r#"
stages = ["friction", "roughness", "tensile", "tensile-summary", "coulomb", "ice"]
[input]
files = ["lab/**/*"]
samples = "samples.csv"
[output]
dir = "out"
# The wear-track profiles state no units: mm along the track, um heights.
[[ingest.override]]
files = "C[12].csv"
units = { Distance = "mm", Profile = "um" }
"#,
    )
    .unwrap();
    // Two CETR files are in both folders: a bare name in the manifest
    // would describe either, so the run refuses it, naming the row.
    let o = common::tribo(dir.path(), &["run", "p.toml"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("matches 2 input files") && err.contains("line "),
        "{err}"
    );
    let manifest = manifest.replace("\nHT-2n", "\nfriction/HT-2n");
    std::fs::write(dir.path().join("samples.csv"), manifest).unwrap();
    let o = common::tribo(dir.path(), &["run", "p.toml"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
    let out = dir.path().join("out");
    assert_eq!(read(&out, "errors").height(), 0);
    let friction = common::sources(&out, "friction");
    // The lab's 15 traces (two CETR files in both), the other three real
    // CETR files and the two pin-on-disc exports.
    assert_eq!(friction.len(), 15 + 3 + 2, "{friction:?}");
    assert!(friction.contains("c1.csv") && friction.contains("HT-2n-6-4_2_010.csv"));
    assert_eq!(
        common::sources(&out, "roughness"),
        names(&[
            "C1.csv",
            "C2.csv",
            "dektak-1.csv",
            "pin1_profile.csv",
            "test1.txt",
            "test2.txt"
        ])
    );
    let tensile = common::sources(&out, "tensile");
    for f in ["B_4_IS_1.txt", "Specimen_RawData_1.csv", "t150_knotted.txt"] {
        assert!(tensile.contains(f), "{tensile:?}");
    }
    assert!(!tensile
        .iter()
        .any(|f| f.starts_with("HT-") || f.ends_with(".md")));
    for t in ["coulomb", "ice_fit", "tensile_groups"] {
        assert!(read(&out, t).height() > 0, "{t}");
    }
    // Licence files are listed, not failed.
    assert!(err.contains("LICENSE"), "{err}");
}

/// A glob over the whole folder also matches the manifest and, on a rerun,
/// the previous outputs: neither is taken as an input.
#[test]
fn the_manifest_and_earlier_outputs_are_not_inputs() {
    let dir = tempfile::tempdir().unwrap();
    common::copy_tree(&common::root().join("fixtures/lab"), dir.path());
    std::fs::write(
        dir.path().join("p.toml"),
        "stages = [\"roughness\"]\n[input]\nfiles = [\"**/*\"]\nsamples = \"samples.csv\"\n[output]\ndir = \"out\"\n",
    )
    .unwrap();
    for _ in 0..2 {
        let o = common::tribo(dir.path(), &["run", "p.toml"]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(0), "{err}");
        let unrouted: Vec<&str> = err
            .lines()
            .filter(|l| l.starts_with("not taken by any stage"))
            .collect();
        assert!(unrouted.iter().any(|l| l.contains("generate.py")), "{err}");
        assert!(
            !unrouted
                .iter()
                .any(|l| l.contains("samples.csv") || l.contains(".parquet")),
            "{err}"
        );
    }
    assert_eq!(
        common::sources(&dir.path().join("out"), "roughness").len(),
        3
    );
}
