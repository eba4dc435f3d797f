//! The real friction-trace exports of `../shared/data/real2` (tests skip,
//! saying so, when it is absent), and the MIT one kept as a fixture: their
//! steps, channels, SI units and rows, every row's printed coefficient
//! against the file's own forces, and the steps' sliding speeds.

use std::path::{Path, PathBuf};

use crate::common;

use tribo::ingest::inspect::inspect;
use tribo::ingest::radius::declared_in;
use tribo::ingest::{read_path, Dataset, IngestOptions};
use tribo::table::Table;

/// Half a unit in the last place a number is printed with.
fn half_ulp(s: &str) -> f64 {
    let decimals = s.split_once('.').map_or(0, |(_, d)| d.len());
    0.5 * 10f64.powi(-(decimals as i32))
}

/// |c − F/N| within what the printing of c, F and N allows.
fn agrees(c: &str, f: &str, n: &str) -> bool {
    let (c_, f_, n_) = (
        c.parse::<f64>().unwrap(),
        f.parse::<f64>().unwrap(),
        n.parse::<f64>().unwrap(),
    );
    let bound = half_ulp(c) + half_ulp(f) / n_.abs() + f_.abs() * half_ulp(n) / (n_ * n_);
    (c_ - f_ / n_).abs() <= bound * (1.0 + 1e-9)
}

/// Every data row of a text as its fields, split here (any line ending).
fn rows(path: &Path, delimiter: char, width: usize) -> Vec<Vec<String>> {
    let bytes = std::fs::read(path).unwrap();
    let text: String = bytes.iter().map(|&b| b as char).collect();
    text.split(['\r', '\n'])
        .map(|l| {
            l.split(delimiter)
                .map(|f| f.trim().to_string())
                .collect::<Vec<_>>()
        })
        .filter(|f| f.len() >= width && f[0].parse::<u32>().is_ok())
        .collect()
}

/// Runs the friction stage on a copy of `file` with `manifest`, returning
/// `friction_steps`.
fn steps_table(file: &Path, manifest: &str) -> Table {
    let dir = tempfile::tempdir().unwrap();
    let name = file.file_name().unwrap().to_str().unwrap();
    std::fs::copy(file, dir.path().join(name)).unwrap();
    std::fs::write(dir.path().join("samples.csv"), manifest.replace("{}", name)).unwrap();
    let o = common::tribo(
        dir.path(),
        &["friction", name, "--out", "o", "--samples", "samples.csv"],
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("1 of 1 files processed, 0 failed"), "{err}");
    Table::read_parquet(&dir.path().join("o/friction_steps.parquet"))
        .unwrap()
        .0
}

/// The mean of a column over a section's rows whose time lies in [a, b].
fn window_mean(ds: &Dataset, section: &str, time: &str, column: &str, (a, b): (f64, f64)) -> f64 {
    let s = ds.sections.iter().find(|s| s.name == section).unwrap();
    let t = &s.channel(time).unwrap().values;
    let v = &s.channel(column).unwrap().values;
    let w: Vec<f64> = t
        .iter()
        .zip(v)
        .filter(|(t, _)| **t >= a - 1e-9 && **t <= b + 1e-9)
        .map(|x| *x.1)
        .collect();
    w.iter().sum::<f64>() / w.len() as f64
}

fn rtec_file() -> Option<PathBuf> {
    let dir = common::shared_real2("rtec_rotary_saintgobain")?;
    Some(common::files_with_ext(&dir, "csv").remove(0))
}

/// The real Rtec log (a bare CR ends its first line): four steps of 1799
/// rows, the timestamp restarting at each, every channel in its role with
/// its SI unit, the recipe's keys paired with their values, and on every
/// one of its 7196 rows `DAQ.COF ()` = Fx/Fz as printed.
#[test]
fn rtec_log_reads_as_its_four_steps() {
    let Some(f) = rtec_file() else { return };
    let ds = read_path(&f, &IngestOptions::default()).unwrap();
    assert_eq!(ds.format, "rtec");
    let names: Vec<&str> = ds.sections.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["Step 4", "Step 7", "Step 10", "Step 13"]);
    for s in &ds.sections {
        assert_eq!(s.rows(), 1799, "{}", s.name);
        let t = &s.channel("Timestamp").unwrap().values;
        assert!(
            t[0] < 0.2 && t.windows(2).all(|w| w[1] > w[0]),
            "{}",
            s.name
        );
    }
    let cols: Vec<(String, String, Option<&str>)> = inspect(&ds, &Default::default()).sections[0]
        .columns
        .iter()
        .map(|c| (c.name.clone(), c.si_unit.clone(), c.role))
        .collect();
    let want = [
        ("Step", "1", Some("step")),
        ("Timestamp", "s", Some("time")),
        ("RecipeStep", "1", None),
        ("DAQ.Fz", "N", Some("normal_force")),
        ("DAQ.Fx", "N", Some("friction_force")),
        ("DAQ.COF", "", Some("instrument_cof")),
        ("Rotary.Velocity", "rad/s", Some("velocity")),
        ("XYZ.X Position", "m", None),
        ("XYZ.Y Position", "m", None),
        ("XYZ.Z Position", "m", None),
    ];
    let want: Vec<(String, String, Option<&str>)> = want
        .iter()
        .map(|(n, u, r)| (n.to_string(), u.to_string(), *r))
        .collect();
    assert_eq!(cols, want);
    let get = |k: &str| {
        ds.preamble
            .iter()
            .find(|m| m.key == k)
            .map(|m| m.value.as_str())
    };
    assert_eq!(
        get("Recipe"),
        Some("Rotary_3N_4tests_75-300mm-s_6-15mm-radius_3min-each.Rx")
    );
    assert_eq!(
        (get("Averaging"), get("LogFrequency"), get("Type")),
        (Some("100"), Some("1000"), Some("Rotary"))
    );
    let raw = rows(&f, ',', 6);
    assert_eq!(raw.len(), 7196);
    let read: Vec<f64> = ds
        .sections
        .iter()
        .flat_map(|s| s.channel("DAQ.COF").unwrap().values.clone())
        .collect();
    for (k, r) in raw.iter().enumerate() {
        assert!(
            agrees(&r[5], &r[4], &r[3]),
            "row {k}: COF {} vs {}/{}",
            r[5],
            r[4],
            r[3]
        );
        assert_eq!(read[k], r[5].parse::<f64>().unwrap());
    }
}

/// The log's steps through the friction stage: each step's radius from the
/// stage's Y position (3 mm further out at each step) and what fixes it
/// once (the file name's 6–15 mm range, which the rows say is a guess; one
/// reference radius of 6 mm; the disc centre at Y = −3.33 mm; a per-step
/// table), giving the file name's 75, 150, 225, 300 mm/s; μ the mean of
/// the instrument's COF over the same window.
#[test]
fn rtec_steps_have_their_own_track_radius() {
    let Some(f) = rtec_file() else { return };
    let ds = read_path(&f, &IngestOptions::default()).unwrap();
    for (manifest, source) in [
        ("file,sample_id\n{},S\n", "file_name_and_stage"),
        ("file,track_radius_mm\n{},6\n", "manifest_and_stage"),
        ("file,track_centre_mm\n{},-3.33\n", "manifest_centre"),
        (
            "file,step_track_radius_mm\n{},4:6 7:9 10:12 13:15\n",
            "manifest_step",
        ),
    ] {
        let t = steps_table(&f, manifest);
        assert_eq!(t.height(), 4, "{source}");
        let (v, r) = (
            t.f64("velocity_m_per_s").unwrap(),
            t.f64("track_radius_m").unwrap(),
        );
        let (src, status) = (
            t.str("track_radius_source").unwrap(),
            t.str("status").unwrap(),
        );
        let (mu, a, b) = (
            t.f64("mu_mean").unwrap(),
            t.f64("start_s").unwrap(),
            t.f64("end_s").unwrap(),
        );
        for k in 0..4 {
            let want_r = (6.0 + 3.0 * k as f64) * 1e-3;
            assert!(
                (r[k].unwrap() - want_r).abs() < 1e-9,
                "{source} {k}: {:?}",
                r[k]
            );
            let want_v = 0.075 * (k + 1) as f64;
            assert!(
                (v[k].unwrap() / want_v - 1.0).abs() < 0.005,
                "{source} {k}: {:?}",
                v[k]
            );
            assert_eq!(src[k].as_deref(), Some(source));
            let named = status[k]
                .as_deref()
                .unwrap()
                .starts_with("radius_from_file_name");
            assert_eq!(
                named,
                source == "file_name_and_stage",
                "{source}: {:?}",
                status[k]
            );
            let section = format!("Step {}", 4 + 3 * k);
            let cof = window_mean(
                &ds,
                &section,
                "Timestamp",
                "DAQ.COF",
                (a[k].unwrap(), b[k].unwrap()),
            );
            assert!(
                (mu[k].unwrap() / cof - 1.0).abs() < 1e-4,
                "{section}: {:?} vs {cof}",
                mu[k]
            );
        }
    }
}

/// The MTM test data file: `(path, steps with a table)`; the fixture holds
/// its first four steps.
fn mtm_files() -> Vec<(PathBuf, usize)> {
    let mut v = vec![(
        common::root().join("fixtures/friction/pcs_mtm311/demo-mtm-output-steps-1-4.txt"),
        2,
    )];
    if let Some(dir) = common::shared_real2("pcs_mtm_ehd") {
        v.push((dir.join("demo-mtm-output.txt"), 24));
    }
    v
}

/// PCS MTM "MTM311 Test Data File": the BOD_TIMED steps (2, 4, …) as
/// sections of 300 rows and the MAPPER steps in the preamble; the
/// repeated summary columns dropped; each step's disc track radius (21.232
/// mm); time, ball load, rolling speed and traction force in their roles;
/// and on every row `Traction Coeff (-)` = `Traction Force (N)` / `Ball
/// Load (N)` as printed.
#[test]
fn mtm_test_data_file_reads_as_its_steps() {
    for (f, tables) in mtm_files() {
        let ds = read_path(&f, &IngestOptions::default()).unwrap();
        assert_eq!(ds.format, "pcs-mtm");
        let names: Vec<String> = ds.sections.iter().map(|s| s.name.clone()).collect();
        let want: Vec<String> = (1..=tables).map(|k| format!("Step {}", 2 * k)).collect();
        assert_eq!(names, want);
        let mappers = ds
            .preamble
            .iter()
            .filter(|m| m.key == "tribo.step_without_table")
            .count();
        assert_eq!(mappers, if tables == 24 { 25 } else { 2 });
        let dups = ds
            .preamble
            .iter()
            .filter(|m| m.key == "tribo.duplicate_column")
            .count();
        assert_eq!(
            dups,
            2 * tables,
            "Step Time and Traction Coeff in every table"
        );
        let info = inspect(&ds, &Default::default());
        for (s, i) in ds.sections.iter().zip(&info.sections) {
            assert_eq!(s.rows(), 300);
            assert_eq!(
                declared_in(&s.metadata, &ds.source).unwrap(),
                Some(21.232e-3)
            );
            let role = |r: &str| {
                i.columns
                    .iter()
                    .find(|c| c.role == Some(r))
                    .map(|c| (c.name.as_str(), c.si_unit.as_str()))
            };
            assert_eq!(role("time"), Some(("Step Time", "s")));
            assert_eq!(role("normal_force"), Some(("Ball Load", "N")));
            assert_eq!(role("friction_force"), Some(("Traction Force", "N")));
            assert_eq!(role("velocity"), Some(("Rolling Speed", "m/s")));
            assert_eq!(role("instrument_cof"), Some(("Traction Coeff", "1")));
        }
        let raw = rows(&f, '\t', 35);
        assert_eq!(raw.len(), 300 * tables);
        for (k, r) in raw.iter().enumerate() {
            assert!(
                agrees(&r[34], &r[33], &r[11]),
                "row {k}: {} vs {}/{}",
                r[34],
                r[33],
                r[11]
            );
        }
    }
}

/// The MTM steps through the friction stage: step 2 is the load ramp (the
/// ball load 4.9 → 50 N), reported from its start to its end load; every
/// other step at 50 N with μ the mean of the printed traction coefficient
/// over the same window, at the 200 mm/s rolling speed.
#[test]
fn mtm_steps_through_the_friction_stage() {
    for (f, tables) in mtm_files() {
        let ds = read_path(&f, &IngestOptions::default()).unwrap();
        let t = steps_table(&f, "file,sample_id\n{},M\n");
        assert_eq!(t.height(), tables);
        let status = t.str("status").unwrap();
        let (n0, n1) = (
            t.f64("normal_start_N").unwrap(),
            t.f64("normal_end_N").unwrap(),
        );
        let (mu, v, load) = (
            t.f64("mu_mean").unwrap(),
            t.f64("velocity_m_per_s").unwrap(),
            t.f64("normal_force_N").unwrap(),
        );
        let (a, b) = (t.f64("start_s").unwrap(), t.f64("end_s").unwrap());
        assert!(
            status[0].as_deref().unwrap().starts_with("load_ramp"),
            "{:?}",
            status[0]
        );
        assert!((n0[0].unwrap() - 4.9).abs() < 0.2 && (n1[0].unwrap() - 50.0).abs() < 0.5);
        for k in 1..tables {
            assert_eq!(status[k].as_deref(), Some("ok"), "step {}", 2 * k + 2);
            assert!((load[k].unwrap() - 50.0).abs() < 0.2);
            assert!((v[k].unwrap() - 0.2).abs() < 1e-3);
            let section = format!("Step {}", 2 * k + 2);
            let c = window_mean(
                &ds,
                &section,
                "Step Time",
                "Traction Coeff",
                (a[k].unwrap(), b[k].unwrap()),
            );
            assert!(
                (mu[k].unwrap() / c - 1.0).abs() < 1e-3,
                "{section}: {:?} vs {c}",
                mu[k]
            );
        }
    }
}
