//! Readers of friction exports that declare their steps (Rtec logs, PCS
//! Instruments MTM files) and of HBM catman ASCII: every channel lands in
//! its role with its unit, and the friction stage's steps are the file's,
//! checked against what the file itself prints (its recipe, its own μ).

use crate::common;

use std::path::{Path, PathBuf};

use tribo::ingest::inspect::inspect;
use tribo::ingest::{read_path, Dataset, IngestOptions};
use tribo::table::Table;

fn fixture(name: &str) -> PathBuf {
    common::root().join("fixtures/friction").join(name)
}

/// (column, SI unit, role) of every section.
fn columns(ds: &Dataset) -> Vec<Vec<(String, String, Option<&'static str>)>> {
    inspect(ds, &Default::default())
        .sections
        .iter()
        .map(|s| {
            s.columns
                .iter()
                .map(|c| (c.name.clone(), c.si_unit.clone(), c.role))
                .collect()
        })
        .collect()
}

fn owned(
    cols: &[(&str, &str, Option<&'static str>)],
) -> Vec<(String, String, Option<&'static str>)> {
    cols.iter()
        .map(|(n, u, r)| (n.to_string(), u.to_string(), *r))
        .collect()
}

/// Runs `tribo friction` on a copy of `file` with a manifest, returning
/// the `friction_steps` table.
fn friction_steps(file: &Path, manifest: &str) -> Table {
    let dir = tempfile::tempdir().unwrap();
    let name = file.file_name().unwrap().to_str().unwrap();
    std::fs::copy(file, dir.path().join(name)).unwrap();
    std::fs::write(dir.path().join("samples.csv"), manifest).unwrap();
    let o = common::tribo(
        dir.path(),
        &["friction", name, "--out", "o", "--samples", "samples.csv"],
    );
    // Exit 1 only for friction rows without a result (a load-ramp step has
    // no plateau); the file itself must be read.
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.code().is_some_and(|c| c <= 1), "{err}");
    assert!(err.contains("1 of 1 files processed, 0 failed"), "{err}");
    Table::read_parquet(&dir.path().join("o/friction_steps.parquet"))
        .unwrap()
        .0
}

/// The mean of a section's `column` over the rows whose `time` lies in
/// [start, end]: the file's own value over a step's steady part.
fn window_mean(ds: &Dataset, section: &str, time: &str, column: &str, start: f64, end: f64) -> f64 {
    let s = ds.sections.iter().find(|s| s.name == section).unwrap();
    let t = &s.channel(time).unwrap().values;
    let v = &s.channel(column).unwrap().values;
    let picked: Vec<f64> = t
        .iter()
        .zip(v)
        .filter(|(t, _)| **t >= start - 1e-9 && **t <= end + 1e-9)
        .map(|(_, v)| *v)
        .collect();
    picked.iter().sum::<f64>() / picked.len() as f64
}

/// A number after `word` in a recipe line: `Rotary Speed 105 mm/s` → 105.
fn number_after(text: &str, word: &str) -> f64 {
    let rest = &text[text.find(word).unwrap() + word.len()..];
    rest.split_whitespace().next().unwrap().parse().unwrap()
}

/// Rtec: one section per recipe step, every channel in its role with its
/// unit (the timestamp in seconds, the velocity in rpm, Z without a
/// friction role, the rotary angle as the angle that counts laps).
#[test]
fn rtec_channels_land_in_their_roles() {
    let ds = read_path(&fixture("rtec_stepped.csv"), &IngestOptions::default()).unwrap();
    assert_eq!(ds.format, "rtec");
    let names: Vec<&str> = ds.sections.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["Step 1", "Step 2", "Step 3"]);
    assert!(ds.sections.iter().all(|s| s.rows() == 200));
    let expected = owned(&[
        ("Step", "1", Some("step")),
        ("Timestamp", "s", Some("time")),
        ("RecipeStep", "1", None),
        ("DAQ.Fz", "N", Some("normal_force")),
        ("DAQ.Fx", "N", Some("friction_force")),
        ("DAQ.COF", "", Some("instrument_cof")),
        ("Rotary.Velocity", "rad/s", Some("velocity")),
        ("XYZ.Z Depth", "m", None),
        ("XYZ.Z Position", "m", None),
        ("Rotary.Angle", "rad", Some("angle")),
    ]);
    for cols in columns(&ds) {
        assert_eq!(cols, expected);
    }
    // The preamble keeps the recipe, without the trailing commas.
    let radius = ds
        .preamble
        .iter()
        .find(|m| m.key == "Track Radius (mm)")
        .unwrap();
    assert_eq!(radius.value, "10");
}

/// Rtec steps: three rows, the file's; steps 1 and 2 (100 and 105 mm/s,
/// which a speed-based detector merges at its 10 % tolerance) stay two.
/// Speeds are the recipe's printed ones (rpm × the 10 mm radius), μ is the
/// mean of the instrument's own `DAQ.COF` over the same window, and the
/// ramp step reports the recipe's 5 → 15 N as a load ramp.
/// Without a manifest radius the file's own `Track Radius (mm) = 10` turns
/// rpm into the same sliding speeds; the manifest's radius wins when given,
/// and a radius the file states without a length unit is an error naming
/// its line.
#[test]
fn rtec_track_radius_comes_from_the_file_when_the_manifest_has_none() {
    let f = fixture("rtec_stepped.csv");
    let from_file = friction_steps(&f, "file,sample_id\nrtec_stepped.csv,R1\n");
    let from_manifest = friction_steps(&f, "file,track_radius_mm\nrtec_stepped.csv,10\n");
    let doubled = friction_steps(&f, "file,track_radius_mm\nrtec_stepped.csv,20\n");
    let v = |t: &Table| t.f64("velocity_m_per_s").unwrap();
    assert_eq!(v(&from_file), v(&from_manifest));
    for (a, b) in v(&doubled).iter().zip(v(&from_manifest)) {
        assert!((a.unwrap() / b.unwrap() - 2.0).abs() < 1e-12);
    }
    let tmp = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(&f).unwrap();
    let bad = tmp.path().join("rtec_bad_radius.csv");
    std::fs::write(
        &bad,
        text.replacen("Track Radius (mm)", "Track Radius (rpm)", 1),
    )
    .unwrap();
    let ds = read_path(&bad, &IngestOptions::default()).unwrap();
    let err = tribo::ingest::trace::declared_track_radius_m(&ds)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("rtec_bad_radius.csv") && err.contains("line 5"),
        "{err}"
    );
}

#[test]
fn rtec_steps_are_the_files_and_the_ramp_is_a_ramp() {
    let f = fixture("rtec_stepped.csv");
    let ds = read_path(&f, &IngestOptions::default()).unwrap();
    let t = friction_steps(&f, "file,track_radius_mm\nrtec_stepped.csv,10\n");
    assert_eq!(t.height(), 3);
    let step = t.i64("step").unwrap();
    let source = t.str("step_source").unwrap();
    let v = t.f64("velocity_m_per_s").unwrap();
    let mu = t.f64("mu_mean").unwrap();
    let (start, end) = (t.f64("start_s").unwrap(), t.f64("end_s").unwrap());
    let status = t.str("status").unwrap();
    let (n0, n1) = (
        t.f64("normal_start_N").unwrap(),
        t.f64("normal_end_N").unwrap(),
    );
    let recipe = |k: usize| {
        ds.preamble
            .iter()
            .find(|m| m.key == format!("Recipe Step {k}"))
            .unwrap()
            .value
            .clone()
    };
    for i in 0..3 {
        assert_eq!(step[i], Some(i as i64 + 1));
        assert_eq!(source[i].as_deref(), Some("file"));
        let printed = number_after(&recipe(i + 1), "Rotary Speed") * 1e-3;
        assert!(
            (v[i].unwrap() / printed - 1.0).abs() < 1e-6,
            "{:?} vs {printed}",
            v[i]
        );
    }
    for i in 0..2 {
        let section = format!("Step {}", i + 1);
        let cof = window_mean(
            &ds,
            &section,
            "Timestamp",
            "DAQ.COF",
            start[i].unwrap(),
            end[i].unwrap(),
        );
        assert!(
            (mu[i].unwrap() / cof - 1.0).abs() < 1e-4,
            "{:?} vs {cof}",
            mu[i]
        );
        assert_eq!(status[i].as_deref(), Some("ok"));
        assert!(n0[i].is_none() && n1[i].is_none());
    }
    assert!(
        status[2].as_deref().unwrap().starts_with("load_ramp"),
        "{:?}",
        status[2]
    );
    assert!(mu[2].is_none());
    let r = recipe(3);
    let (a, b) = (number_after(&r, "Load Ramp"), number_after(&r, " to"));
    assert!((n0[2].unwrap() - a).abs() < 1e-3 && (n1[2].unwrap() - b).abs() < 1e-3);
}

/// A metadata value of a section: `Load (N)` → `30`.
fn section_value(ds: &Dataset, section: &str, key: &str) -> String {
    let s = ds.sections.iter().find(|s| s.name == section).unwrap();
    s.metadata
        .iter()
        .find(|m| m.key == key)
        .unwrap()
        .value
        .clone()
}

/// PCS MTM: one section per step that has a table, named and numbered as
/// the file numbers it; the mapper step without a table is kept in the
/// preamble. Every channel in its role with its unit: the traction
/// coefficient is the instrument's μ, the mean speed the step's speed.
#[test]
fn pcs_mtm_channels_land_in_their_roles() {
    let ds = read_path(&fixture("pcs_mtm_steps.txt"), &IngestOptions::default()).unwrap();
    assert_eq!(ds.format, "pcs-mtm");
    let names: Vec<&str> = ds.sections.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["Step 1", "Step 3", "Step 4"]);
    assert!(ds.sections.iter().all(|s| s.rows() == 31));
    let skipped: Vec<(&str, &str)> = ds
        .preamble
        .iter()
        .map(|m| (m.key.as_str(), m.value.as_str()))
        .filter(|(k, _)| *k == "tribo.step_without_table" || *k == "Window load (N)")
        .collect();
    assert_eq!(
        skipped,
        [
            ("tribo.step_without_table", "Step 2 (Mapper)"),
            ("Window load (N)", "20")
        ]
    );
    let expected = owned(&[
        ("Step", "1", Some("step")),
        ("Time", "s", Some("time")),
        ("Mean Speed", "m/s", Some("velocity")),
        ("SRR", "1", None),
        ("Load", "N", Some("normal_force")),
        ("Traction Coeff", "", Some("instrument_cof")),
        ("Lube Temp", "K", Some("temperature")),
        ("Ball Speed", "m/s", None),
        ("Disc Speed", "m/s", None),
    ]);
    for cols in columns(&ds) {
        assert_eq!(cols, expected);
    }
}

/// PCS MTM steps: the file's numbers (1, 3, 4), speeds and loads as each
/// step's parameters print them, μ the mean of the instrument's traction
/// coefficient over the same window (T = μ·N from the Load column), and
/// the load-ramp step (`Load (N) 10 to 30`) reported as a ramp.
#[test]
fn pcs_mtm_steps_are_the_files_and_the_ramp_is_a_ramp() {
    let f = fixture("pcs_mtm_steps.txt");
    let ds = read_path(&f, &IngestOptions::default()).unwrap();
    let t = friction_steps(&f, "file,sample_id\npcs_mtm_steps.txt,M1\n");
    assert_eq!(t.height(), 3);
    let step = t.i64("step").unwrap();
    let v = t.f64("velocity_m_per_s").unwrap();
    let mu = t.f64("mu_mean").unwrap();
    let load = t.f64("normal_force_N").unwrap();
    let (start, end) = (t.f64("start_s").unwrap(), t.f64("end_s").unwrap());
    let status = t.str("status").unwrap();
    let (n0, n1) = (
        t.f64("normal_start_N").unwrap(),
        t.f64("normal_end_N").unwrap(),
    );
    for (i, number) in [1, 3, 4].into_iter().enumerate() {
        let section = format!("Step {number}");
        assert_eq!(step[i], Some(number));
        let printed: f64 = section_value(&ds, &section, "Mean speed (mm/s)")
            .parse()
            .unwrap();
        assert!((v[i].unwrap() - printed * 1e-3).abs() < 1e-12, "{:?}", v[i]);
        if number == 4 {
            continue;
        }
        let printed: f64 = section_value(&ds, &section, "Load (N)").parse().unwrap();
        assert!((load[i].unwrap() - printed).abs() < 1e-9, "{:?}", load[i]);
        let cof = window_mean(
            &ds,
            &section,
            "Time",
            "Traction Coeff",
            start[i].unwrap(),
            end[i].unwrap(),
        );
        assert!(
            (mu[i].unwrap() / cof - 1.0).abs() < 1e-9,
            "{:?} vs {cof}",
            mu[i]
        );
        assert_eq!(status[i].as_deref(), Some("ok"));
    }
    let ramp = section_value(&ds, "Step 4", "Load (N)");
    let (a, b) = ramp.split_once(" to ").unwrap();
    assert!(
        status[2].as_deref().unwrap().starts_with("load_ramp"),
        "{:?}",
        status[2]
    );
    assert!((n0[2].unwrap() - a.parse::<f64>().unwrap()).abs() < 1e-2);
    assert!((n1[2].unwrap() - b.parse::<f64>().unwrap()).abs() < 1e-2);
    assert!(mu[2].is_none() && load[2].is_none());
}

/// The catman no-value marker cells of each column, counted from the raw
/// text (split on tabs), independently of the reader.
fn marker_counts(path: &Path, header_line: usize, width: usize) -> Vec<usize> {
    let bytes = std::fs::read(path).unwrap();
    let text: String = bytes.iter().map(|&b| b as char).collect(); // Latin-1
    let mut counts = vec![0; width];
    for line in text.lines().skip(header_line) {
        for (k, cell) in line.split('\t').take(width).enumerate() {
            counts[k] += usize::from(cell.trim() == "1,00000E+308");
        }
    }
    counts
}

/// catman: German channel names in their roles; the no-value markers are
/// missing values, never numbers, and DMS_6 (all markers, not connected)
/// is dropped with a note.
#[test]
fn catman_channels_land_in_their_roles_and_markers_are_missing() {
    let f = fixture("hbm_catman_reibung.txt");
    let ds = read_path(&f, &IngestOptions::default()).unwrap();
    assert_eq!(ds.format, "hbm-catman");
    let expected = owned(&[
        ("Zeit  1 - Standardmessrate", "s", Some("time")),
        ("Reibkraft", "N", Some("friction_force")),
        ("Normalkraft", "N", Some("normal_force")),
        ("Weg", "m", Some("position")),
        ("Reibwert", "", Some("instrument_cof")),
        ("Temperatur", "K", Some("temperature")),
    ]);
    assert_eq!(columns(&ds), vec![expected]);
    let dropped: Vec<&str> = ds
        .preamble
        .iter()
        .filter(|m| m.key == "tribo.dropped_channel")
        .map(|m| m.value.as_str())
        .collect();
    assert_eq!(dropped.len(), 1);
    assert!(dropped[0].starts_with("'DMS_6'"), "{dropped:?}");
    let s = &ds.sections[0];
    let counts = marker_counts(&f, s.header_line.unwrap(), 7);
    assert_eq!(counts[6], s.rows(), "DMS_6 is all markers");
    for (k, c) in s.channels.iter().enumerate() {
        let nan = c.values.iter().filter(|v| v.is_nan()).count();
        assert_eq!(nan, counts[k], "{}", c.name);
        assert!(
            c.values.iter().all(|v| v.is_nan() || v.abs() < 1e300),
            "{}",
            c.name
        );
    }
    assert!(
        counts[5] > 0 && counts[1] > 0,
        "the fixture has markers to test"
    );
}

/// catman through the friction stage: the rows whose friction force is a
/// marker are dropped and counted, μ_d agrees with catman's own Reibwert
/// channel over the same window, and μ_s is the 6.6 N break-away at 20 N.
#[test]
fn catman_friction_drops_the_marked_rows_and_agrees_with_reibwert() {
    let f = fixture("hbm_catman_reibung.txt");
    let ds = read_path(&f, &IngestOptions::default()).unwrap();
    let counts = marker_counts(&f, ds.sections[0].header_line.unwrap(), 7);
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(&f, dir.path().join("c.txt")).unwrap();
    let o = common::tribo(dir.path(), &["friction", "c.txt", "--out", "o"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (t, _) = Table::read_parquet(&dir.path().join("o/friction.parquet")).unwrap();
    assert_eq!(t.height(), 1);
    assert_eq!(t.i64("n_nan_dropped").unwrap()[0], Some(counts[1] as i64));
    let mu_d = t.f64("mu_dynamic").unwrap()[0].unwrap();
    let mu_i = t.f64("mu_instrument").unwrap()[0].unwrap();
    assert!((mu_d / mu_i - 1.0).abs() < 1e-3, "{mu_d} vs {mu_i}");
    // μ_d's sd is the sample sd of the pointwise |T|/N over the window:
    // that of catman's own Reibwert over the same rows
    let sec = &ds.sections[0];
    let (time, cof) = (
        sec.channel("Zeit  1 - Standardmessrate").unwrap(),
        sec.channel("Reibwert").unwrap(),
    );
    let (from, to) = (
        t.f64("dynamic_window_start_s").unwrap()[0].unwrap(),
        t.f64("dynamic_window_end_s").unwrap()[0].unwrap(),
    );
    let within: Vec<f64> = (0..sec.rows())
        .filter(|&k| (from..=to).contains(&time.values[k]) && cof.values[k].is_finite())
        .map(|k| cof.values[k])
        .collect();
    let n = within.len() as f64;
    let mean = within.iter().sum::<f64>() / n;
    let sd = (within.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
    let ours = t.f64("mu_dynamic_sd").unwrap()[0].unwrap();
    assert!(
        (ours / sd - 1.0).abs() < 0.02,
        "{ours} vs Reibwert's {sd} over {n} rows"
    );
    let mu_s = t.f64("mu_static").unwrap()[0].unwrap();
    assert!((mu_s - 6.6 / 20.0).abs() < 0.01, "{mu_s}");
    assert_eq!(t.str("status").unwrap()[0].as_deref(), Some("ok"));
}

/// `tribo inspect` names the reader and shows every channel with its unit
/// and role, as the library's inspection does.
#[test]
fn inspect_shows_each_readers_channels_and_roles() {
    let dir = tempfile::tempdir().unwrap();
    for (file, format, lines) in [
        (
            "rtec_stepped.csv",
            "rtec",
            [
                "Step                     [1] -> 1  <- step",
                "Rotary.Velocity          [rpm] -> rad/s  <- velocity",
            ],
        ),
        (
            "pcs_mtm_steps.txt",
            "pcs-mtm",
            [
                "Traction Coeff           (no unit)  <- instrument_cof",
                "Mean Speed               [mm/s] -> m/s  <- velocity",
            ],
        ),
        (
            "hbm_catman_reibung.txt",
            "hbm-catman",
            [
                "Reibkraft                [N] -> N  <- friction_force",
                "Normalkraft              [N] -> N  <- normal_force",
            ],
        ),
    ] {
        let f = fixture(file);
        let o = common::tribo(dir.path(), &["inspect", f.to_str().unwrap()]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let out = String::from_utf8_lossy(&o.stdout);
        assert!(out.contains(&format!("format      {format}")), "{out}");
        for l in lines {
            assert!(out.contains(l), "{file}: no '{l}' in\n{out}");
        }
    }
}

/// An Rtec step number that is not a whole number is an error naming its
/// line and column, not a step 1.5.
#[test]
fn rtec_fractional_step_is_an_error_naming_the_line() {
    let dir = tempfile::tempdir().unwrap();
    let mut s = String::from(
        "Recipe,demo,\r\nStep, Timestamp, RecipeStep, DAQ.Fz (N),DAQ.Fx (N),DAQ.COF (),\r\n",
    );
    for (i, step) in ["1", "1", "1", "1.5", "2"].iter().enumerate() {
        s.push_str(&format!("{step}, {i}.0, 1, 5.0,1.0,0.2,\n"));
    }
    let f = dir.path().join("r.csv");
    std::fs::write(&f, s).unwrap();
    let e = read_path(&f, &IngestOptions::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("r.csv, line 6, column 'Step'"), "{e}");
    assert!(e.contains("whole step number"), "{e}");
}
