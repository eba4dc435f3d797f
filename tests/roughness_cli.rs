//! `tribo roughness` and the pipeline's roughness stage, run as a user
//! would: the binary in a temporary folder, outputs read back from Parquet.
#![deny(clippy::float_cmp)]

use std::path::{Path, PathBuf};
use std::process::Command;

use tribo::status::Code;
use tribo::table::Table;

fn fixture(p: &str) -> String {
    crate::common::root()
        .join("fixtures/roughness")
        .join(p)
        .display()
        .to_string()
}

fn tribo(args: &[&str], dir: &Path) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_tribo"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("run tribo");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn read(dir: &Path, name: &str) -> Table {
    crate::common::table_in(dir, name)
}

#[test]
fn roughness_command_writes_tables_with_settings_and_bearing_curve() {
    let tmp = tempfile::tempdir().unwrap();
    let (code, err) = tribo(
        &[
            "roughness",
            &fixture("dektak/dektak-1.csv"),
            "--out",
            "out",
            "--window",
            "468um,733um",
            "--pressure",
            "0.085MPa",
            "--hardness",
            "25.35MPa",
        ],
        tmp.path(),
    );
    assert_eq!(code, 0, "{err}");
    let out = tmp.path().join("out");
    let t = read(&out, "roughness");
    assert_eq!(t.height(), 1);
    let ra = t.f64("Ra_m").unwrap()[0].unwrap();
    // Same value as the library test against the instrument (MODELS §4),
    // through the CLI: half a unit of the 4th digit.
    assert!((ra - 0.005250e-6).abs() <= 0.0000005e-6, "{ra}");
    assert_eq!(t.i64("n_points").unwrap()[0], Some(1697));
    instrument_results_match_ours(&t);
    assert_eq!(t.str("detrend").unwrap()[0].as_deref(), Some("line"));
    assert_eq!(
        t.str("derivative").unwrap()[0].as_deref(),
        Some("iso7_point")
    );
    let w0 = t.f64("window_start_m").unwrap()[0].unwrap();
    assert!((w0 - 468e-6).abs() < 1e-15);
    assert_eq!(t.f64("filter_cutoff_m").unwrap()[0], None);
    // Contact length: ΔA = 0.085/25.35 and a = 2d/tan(Rdq) from the row.
    let da = t.f64("area_ratio").unwrap()[0].unwrap();
    assert!((da - 0.085 / 25.35).abs() < 1e-12);
    let d = t.f64("contact_depth_m").unwrap()[0].unwrap();
    let a = t.f64("contact_length_m").unwrap()[0].unwrap();
    let tan = t.f64("Rdq_deg").unwrap()[0].unwrap().to_radians().tan();
    assert!(((a - 2.0 * d / tan) / a).abs() < 1e-12);
    let b = read(&out, "bearing_curve");
    assert_eq!(b.height(), 101);
    let h = b.f64("height_m").unwrap();
    // Heights fall from the highest peak to the deepest valley.
    assert!(h.windows(2).all(|w| w[1].unwrap() <= w[0].unwrap()));
    assert_eq!(read(&out, "errors").height(), 0);
}

/// Without a window the Dektak export is analysed over the cursors the file
/// states (468–733 µm): the instrument's printed Ra 0.00525 µm, not the
/// 81 nm of the whole tilted scan; a fractal fit with r² = 0.74 says
/// `poor_fit`; the PSD and ACF tables hold the profile's curves. Over the
/// whole scan the row says `window_differs`.
#[test]
fn dektak_defaults_to_the_instruments_window_and_writes_spectra() {
    let tmp = tempfile::tempdir().unwrap();
    let file = fixture("dektak/dektak-1.csv");
    let (code, err) = tribo(&["roughness", &file, "--out", "out"], tmp.path());
    assert_eq!(code, 0, "{err}");
    let out = tmp.path().join("out");
    let t = read(&out, "roughness");
    let ra = t.f64("Ra_m").unwrap()[0].unwrap();
    // The printed 0.00525 µm to half a unit of its last digit.
    assert!((ra - 0.00525e-6).abs() <= 0.000005e-6, "Ra {ra}");
    let rq = t.f64("Rq_m").unwrap()[0].unwrap();
    assert!((rq - 0.01143e-6).abs() <= 0.00001e-6, "Rq {rq}");
    let rsk = t.f64("Rsk").unwrap()[0].unwrap();
    assert!((rsk - 6.96).abs() <= 0.01, "Rsk {rsk}");
    let w0 = t.f64("window_start_m").unwrap()[0].unwrap();
    let w1 = t.f64("window_end_m").unwrap()[0].unwrap();
    assert!((w0 - 468e-6).abs() < 1e-15 && (w1 - 733e-6).abs() < 1e-15);
    let status = &t.status_codes().unwrap()[0];
    let r2 = t.f64("fractal_r_squared").unwrap()[0].unwrap();
    assert!(r2 < 0.9, "r² {r2}");
    assert!(status.contains(&Code::PoorFit), "{status:?}");
    assert!(!status.contains(&Code::WindowDiffers), "{status:?}");
    assert!(!status.contains(&Code::InstrumentMismatch), "{status:?}");
    // The file's stylus (2.5 µm) gives the reliability cut-off.
    let tip = t.f64("tip_radius_m").unwrap()[0].unwrap();
    assert!((tip - 2.5e-6).abs() < 1e-18);
    let psd = read(&out, "psd");
    assert!(psd.height() > 10);
    assert!(psd
        .f64("psd_m3")
        .unwrap()
        .iter()
        .all(|v| v.is_some_and(|c| c > 0.0)));
    assert!(psd.f64("psd_m4").unwrap().iter().all(|v| v.is_none()));
    // Wavevectors from 2π/L to π/Δx (Δx = 0.15625 µm, L = 265 µm).
    let q = psd.f64("q_rad_per_m").unwrap();
    let (q0, q1) = (q[0].unwrap(), q[q.len() - 1].unwrap());
    assert!(q0 >= 2.0 * std::f64::consts::PI / 265.2e-6 * 0.999, "{q0}");
    assert!(q1 <= std::f64::consts::PI / 0.15625e-6 * 1.001, "{q1}");
    let acf = read(&out, "acf");
    assert_eq!(acf.f64("acf").unwrap()[0], Some(1.0));
    assert_eq!(acf.f64("lag_m").unwrap()[0], Some(0.0));
    assert!(acf
        .str("direction")
        .unwrap()
        .iter()
        .all(|d| d.as_deref() == Some("x")));

    let (code, err) = tribo(
        &[
            "roughness",
            &file,
            "--out",
            "whole",
            "--window",
            "0um,1500um",
        ],
        tmp.path(),
    );
    assert_eq!(code, 0, "{err}");
    let t = read(&tmp.path().join("whole"), "roughness");
    let status = &t.status_codes().unwrap()[0];
    assert!(status.contains(&Code::WindowDiffers), "{status:?}");
    // The whole tilted scan: the 81 nm of issue #30, far from the printed Ra.
    let ra = t.f64("Ra_m").unwrap()[0].unwrap();
    assert!(ra > 50e-9, "Ra {ra}");
}

#[test]
fn matrix_file_with_a_window_along_y_through_the_command_line() {
    let tmp = tempfile::tempdir().unwrap();
    let (code, err) = tribo(
        &[
            "roughness",
            &fixture("matrix/gwyddion_sine.txt"),
            "--out",
            "out",
            "--detrend",
            "mean",
            "--window-y",
            "0um,4.75um",
        ],
        tmp.path(),
    );
    assert_eq!(code, 0, "{err}");
    let t = read(&tmp.path().join("out"), "roughness");
    assert_eq!(t.str("kind").unwrap()[0].as_deref(), Some("areal"));
    // Rows y = 0 .. 4.75 µm: two whole periods of cos(2πy / 2.5 µm).
    assert_eq!(t.i64("n_points").unwrap()[0], Some(48 * 20));
    let sq = t.f64("Sq_m").unwrap()[0].unwrap();
    assert!((sq - 0.1e-6).abs() < 1e-15, "Sq {sq}");
    let wy = t.f64("window_y_end_m").unwrap()[0].unwrap();
    assert!((wy - 4.75e-6).abs() < 1e-18, "{wy}");
    assert_eq!(t.f64("window_start_m").unwrap()[0], None);
}

#[test]
fn a_bad_file_is_listed_and_the_others_are_still_written() {
    let tmp = tempfile::tempdir().unwrap();
    // Heights with a gap in x (non-uniform) and a file without units.
    std::fs::write(
        tmp.path().join("gap.csv"),
        "x (um),z (um)\n0,1\n1,2\n2,1\n3,2\n4,1\n5,2\n6,1\n7,2\n20,1\n21,2\n22,1\n",
    )
    .unwrap();
    std::fs::write(tmp.path().join("nounits.csv"), no_units_profile("x;z", ';')).unwrap();
    let (code, err) = tribo(
        &[
            "roughness",
            "gap.csv",
            "nounits.csv",
            &fixture("nanovea/test1.txt"),
            "--out",
            "out",
        ],
        tmp.path(),
    );
    assert_eq!(code, 1, "{err}");
    let out = tmp.path().join("out");
    let t = read(&out, "roughness");
    assert_eq!(t.height(), 1);
    assert_eq!(t.str("kind").unwrap()[0].as_deref(), Some("areal"));
    let e = read(&out, "errors");
    let msgs: Vec<String> = e.str("message").unwrap().into_iter().flatten().collect();
    assert_eq!(msgs.len(), 2);
    assert!(
        msgs.iter().any(|m| m.contains("not equally spaced")),
        "{msgs:?}"
    );
    assert!(msgs.iter().any(|m| m.contains("--x-unit")), "{msgs:?}");
    // With the units given, the decimal-comma file reads.
    let (code, err) = tribo(
        &[
            "roughness",
            "nounits.csv",
            "--out",
            "out2",
            "--x-unit",
            "mm",
            "--z-unit",
            "um",
        ],
        tmp.path(),
    );
    assert_eq!(code, 0, "{err}");
    let t = read(&tmp.path().join("out2"), "roughness");
    let len = t.f64("length_m").unwrap()[0].unwrap();
    assert!((len - 8e-6).abs() < 1e-15, "{len}");
}

/// Nine decimal-comma heights at 0.001 to 0.009 under `header`, each
/// cell quoted when `sep` is a comma.
fn no_units_profile(header: &str, sep: char) -> String {
    let q = if sep == ',' { "\"" } else { "" };
    let rows = [1, 2, 1, 3, 1, 2, 1, 4, 1].iter().enumerate();
    let rows = rows.map(|(i, z)| format!("{q}0,00{}{q}{sep}{q}0,{z}{q}\n", i + 1));
    format!("{header}\n{}", rows.collect::<String>())
}

/// The `"Distance","Profile"` layout states no units: it is read in its
/// layout's (mm, µm), each row saying so (`assumed_unit`) unless the user
/// gave the unit, and gives the numbers the units given would.
#[test]
fn the_distance_profile_layout_reads_in_its_units_and_says_so() {
    let tmp = tempfile::tempdir().unwrap();
    let text = no_units_profile("\"Distance\",\"Profile\"", ',');
    std::fs::write(tmp.path().join("p.csv"), text).unwrap();
    let run = |out: &str, units: &[&str]| {
        let args = [&["roughness", "p.csv", "--out", out][..], units].concat();
        let (code, err) = tribo(&args, tmp.path());
        assert_eq!(code, 0, "{err}");
        read(&tmp.path().join(out), "roughness")
    };
    let assumed = run("a", &[]);
    let given = run("b", &["--x-unit", "mm", "--z-unit", "um"]);
    let x_only = run("c", &["--x-unit", "mm"]);
    for col in ["length_m", "Ra_m", "Rq_m", "Rp_m"] {
        assert_eq!(assumed.f64(col).unwrap(), given.f64(col).unwrap(), "{col}");
    }
    let len = assumed.f64("length_m").unwrap()[0].unwrap();
    assert!((len - 8e-6).abs() < 1e-15, "{len}");
    let codes = |t: &Table| t.status_codes().unwrap().remove(0);
    assert!(codes(&assumed).contains(&Code::AssumedUnit));
    assert!(!codes(&given).contains(&Code::AssumedUnit));
    let detail = |t: &Table| t.str("status_detail").unwrap()[0].clone().unwrap();
    let (a, c) = (detail(&assumed), detail(&x_only));
    assert!(a.contains("read Distance as mm, Profile as um"), "{a}");
    assert!(
        c.contains("read Profile as um") && !c.contains("Distance as"),
        "{c}"
    );
}

#[test]
fn bad_settings_are_usage_errors() {
    let tmp = tempfile::tempdir().unwrap();
    let f = fixture("dektak/dektak-1.csv");
    for args in [
        vec!["roughness", &f, "--out", "o", "--cutoff", "0.8"],
        vec!["roughness", &f, "--out", "o", "--cutoff", "0.8N"],
        vec!["roughness", &f, "--out", "o", "--window", "733um,468um"],
        vec!["roughness", &f, "--out", "o", "--pressure", "1MPa"],
    ] {
        let (code, err) = tribo(&args, tmp.path());
        assert_eq!(code, 2, "{args:?}: {err}");
    }
}

#[test]
fn pipeline_file_runs_the_roughness_stage() {
    let tmp = tempfile::tempdir().unwrap();
    let spec = format!(
        r#"
stages = ["roughness"]
[input]
files = ["{}"]
samples = "samples.csv"
[output]
dir = "out"
[roughness]
cutoff = "0.1 mm"
derivative = "central"
fractal_method = "power_spectrum"
"#,
        fixture("nanovea/test1.txt")
    );
    let path: PathBuf = tmp.path().join("p.toml");
    std::fs::write(&path, spec).unwrap();
    std::fs::write(
        tmp.path().join("samples.csv"),
        "file,sample_id,pin\ntest1.txt,S7,P2\n",
    )
    .unwrap();
    let (code, err) = tribo(&["run", "p.toml"], tmp.path());
    assert_eq!(code, 0, "{err}");
    let t = read(&tmp.path().join("out"), "roughness");
    // The manifest's sample and pin are carried, so the ice fit can join.
    assert_eq!(t.str("sample_id").unwrap()[0].as_deref(), Some("S7"));
    assert_eq!(t.str("pin").unwrap()[0].as_deref(), Some("P2"));
    let pins = tribo::fit::ice::table::PinRoughness::from_table(&t).unwrap();
    // A map: its Sdq stands for the pin's slope.
    assert_eq!(t.f64("Rdq_deg").unwrap()[0], None);
    let rdq = t.f64("Sdq_deg").unwrap()[0].unwrap();
    assert_eq!(pins.rdq_deg.get("P2").copied(), Some(rdq));
    assert_eq!(
        t.str("fractal_method").unwrap()[0].as_deref(),
        Some("power_spectrum")
    );
    let c = t.f64("filter_cutoff_m").unwrap()[0].unwrap();
    assert!((c - 1e-4).abs() < 1e-18);
    // 101 points minus round(λc/2Δx) = 10 at each edge, squared.
    assert_eq!(t.i64("n_points").unwrap()[0], Some(81 * 81));
}

/// The GPL-3 pin-on-disc track profiles live only in ../shared; skipped in
/// a fresh clone.
#[test]
fn pin_on_disc_track_profiles_from_shared_data() {
    let Some(dir) = crate::common::shared_real("profile_pin_on_disc_track") else {
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    let files: Vec<String> = ["C1.csv", "C2.csv"]
        .iter()
        .map(|f| dir.join(f).display().to_string())
        .collect();
    let (code, err) = tribo(
        &[
            "roughness",
            &files[0],
            &files[1],
            "--out",
            "out",
            "--x-unit",
            "mm",
            "--z-unit",
            "um",
        ],
        tmp.path(),
    );
    assert_eq!(code, 0, "{err}");
    let t = read(&tmp.path().join("out"), "roughness");
    assert_eq!(t.height(), 2);
    // 4800 rows at 0.5 µm from 0.0005 to 2.4 mm.
    for n in t.i64("n_points").unwrap() {
        assert_eq!(n, Some(4800));
    }
    for len in t.f64("length_m").unwrap() {
        assert!((len.unwrap() - 2.3995e-3).abs() < 1e-12);
    }
    // Without the units: the layout's (mm, µm), the same numbers, said.
    let (code, err) = tribo(
        &["roughness", &files[0], &files[1], "--out", "bare"],
        tmp.path(),
    );
    assert_eq!(code, 0, "{err}");
    let bare = read(&tmp.path().join("bare"), "roughness");
    for col in ["length_m", "Ra_m", "Rq_m", "Rsk", "Rp_m", "Rv_m"] {
        assert_eq!(bare.f64(col).unwrap(), t.f64(col).unwrap(), "{col}");
    }
    for codes in bare.status_codes().unwrap() {
        assert!(codes.contains(&Code::AssumedUnit), "{codes:?}");
    }
}

/// The Dektak prints its own Ra, Rq, Skew and RzDin for the cursor window
/// 468–733 µm: the row carries them beside ours (computed on the same
/// window), and ours agree to one unit of the printed last digit (the
/// instrument truncates some values and rounds others: Rq 0.011436 µm is
/// printed 0.01143, Rsk 6.955 is printed 6.96).
fn instrument_results_match_ours(t: &Table) {
    let v = |c: &str| t.f64(c).unwrap()[0].unwrap();
    let printed = [
        ("Ra_m", "instrument_Ra_m", 0.00525e-6, 0.00001e-6),
        ("Rq_m", "instrument_Rq_m", 0.01143e-6, 0.00001e-6),
        ("Rsk", "instrument_Rsk", 6.96, 0.01),
    ];
    for (ours, theirs, value, unit) in printed {
        // As printed, converted to SI (to round-off of the µm conversion).
        assert!((v(theirs) - value).abs() < 1e-9 * value, "{theirs}");
        assert!(
            (v(ours) - value).abs() <= unit,
            "{ours} {} vs {value}",
            v(ours)
        );
    }
    // RzDin is not reproduced to its digits: five equal parts of the
    // line-detrended window give 0.049551 µm, 0.77 % above the printed
    // 0.04917 µm, and no shift of the part boundaries or the window by up
    // to 8 points closes the gap (the instrument's own processing of RzDin
    // is not stated in the file). Guard the agreement at 1 %.
    let (ours, theirs) = (v("Rz_DIN_m"), v("instrument_Rz_DIN_m"));
    assert!((theirs - 0.04917e-6).abs() < 1e-9 * theirs, "{theirs}");
    assert!(
        (ours / theirs - 1.0).abs() < 0.01,
        "Rz DIN {ours} vs {theirs}"
    );
    assert!((ours - 0.049551e-6).abs() < 0.000001e-6, "Rz DIN {ours}");
    assert!((v("instrument_window_start_m") - 468e-6).abs() < 1e-15);
    assert!((v("instrument_window_end_m") - 733e-6).abs() < 1e-15);
    // Rt bounds every per-part peak-to-valley height; Rp + Rv is Rt.
    assert!(v("Rt_m") >= v("Rz_DIN_m"));
    assert!((v("Rp_m") + v("Rv_m") - v("Rt_m")).abs() < 1e-9 * v("Rt_m"));
    // No filter: ISO's sampling length is a fifth, so the two Rz agree.
    assert!((v("Rz_m") - v("Rz_DIN_m")).abs() < 1e-9 * v("Rt_m"));
    assert_eq!(t.f64("Sa_m").unwrap()[0], None);
}

/// Regression: a Nanovea map whose export was cut short in its last scan
/// line was read as a map one row shorter, status `ok`. It is now a failed
/// file whose error names the line.
#[test]
fn truncated_nanovea_map_is_an_error_naming_the_line() {
    let tmp = tempfile::tempdir().unwrap();
    let full = std::fs::read_to_string(fixture("nanovea/test1.txt")).unwrap();
    // 101 scan lines of 101 points, each followed by two blank lines:
    // keep 100 whole lines and 12 points of the last (lines 10301–10312).
    let cut: Vec<&str> = full.lines().take(100 * 103 + 12).collect();
    std::fs::write(tmp.path().join("cut.txt"), cut.join("\n") + "\n").unwrap();
    let (code, err) = tribo(&["roughness", "cut.txt", "--out", "out"], tmp.path());
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("truncated map") && err.contains("lines 10301–10312"),
        "{err}"
    );
    let e = read(&tmp.path().join("out"), "errors");
    assert_eq!(e.height(), 1);
}
