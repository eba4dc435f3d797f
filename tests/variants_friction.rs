//! Generated variants of each friction-trace family (Rtec logs, PCS MTM
//! test data files, CETR UMT exports, CSM pin-on-disc TSV): the same
//! content with another line ending, encoding, column order, locale or
//! software version's banner reads as the same sections, channels, SI
//! units, roles and values.

use crate::common;
use crate::common::variants::{
    assert_same, read_written, render, reorder, signature, Enc, Ending, ENDINGS,
};

use tribo::ingest::radius::{declared_in, track_radii, RadiusHints};

/// An Rtec rotary log of four steps (4, 7, 10, 13) on tracks of 6, 9, 12
/// and 15 mm at 75, 150, 225 and 300 mm/s, the stage's Y 3 mm further out
/// at each step, timestamps restarting per step. `keys_row`: the recipe as
/// a line of keys and a line of values (the real log) or as `key,value,`
/// lines; `swap`: Fx before Fz, Y before X.
fn rtec(keys_row: bool, swap: bool) -> String {
    let mut lines: Vec<String> = match keys_row {
        true => vec![
            "Recipe, UpperSample, LowerSample, OtherInfo, Averaging, LogFrequency, Type, Radius"
                .into(),
            "Rotary_3N_4tests.Rx,,,,100,1000,Rotary,1,".into(),
        ],
        false => vec![
            "Rtec Instruments Tribometer Data Log,".into(),
            "Software,MFT-5000 data export,".into(),
            "Recipe,Rotary_3N_4tests.Rx,".into(),
        ],
    };
    let mut table = vec!["Step, Timestamp, RecipeStep, DAQ.Fz (N),DAQ.Fx (N),DAQ.COF (),Rotary.Velocity (rpm),XYZ.X Position (mm),XYZ.Y Position (mm),XYZ.Z Position (mm),".to_string()];
    for k in 0..4 {
        let (step, r, v) = (4 + 3 * k, 6.0 + 3.0 * k as f64, 75.0 * (k + 1) as f64);
        let rpm = v / (2.0 * std::f64::consts::PI * r) * 60.0;
        for i in 0..30 {
            let fz = 3.0 + 0.01 * (i as f64).sin();
            let fx = (0.15 + 0.02 * k as f64) * fz;
            table.push(format!(
                "{step},{:.3},{step},{fz:.6},{fx:.7},{:.7},{rpm:.4},0,{:.2},-114.6078,",
                0.044 + 0.1 * i as f64,
                fx / fz,
                -9.33 - 3.0 * k as f64
            ));
        }
    }
    if swap {
        table = reorder(&table, ',', &[0, 1, 2, 4, 3, 5, 6, 8, 7, 9]);
    }
    lines.extend(table);
    lines.join("\n")
}

const RTEC_NAME: &str = "rtec_4tests_75-300mm-s_6-15mm-radius.csv";

/// Every line ending (a bare CR after the first line, as the real log),
/// UTF-8 with and without BOM and UTF-16, both recipe forms and both
/// column orders: the same steps, channels and values; each step's stage
/// position, and the 6–15 mm radii the file name's range gives with it.
#[test]
fn rtec_variants_read_alike() {
    let dir = tempfile::tempdir().unwrap();
    let base = read_written(
        dir.path(),
        RTEC_NAME,
        &render(&rtec(true, false), Ending::Crlf, Enc::Utf8),
    );
    assert_eq!(base.format, "rtec");
    let names: Vec<&str> = base.sections.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["Step 4", "Step 7", "Step 10", "Step 13"]);
    let want = signature(&base);
    for ending in ENDINGS {
        for enc in [Enc::Utf8, Enc::Utf8Bom, Enc::Utf16Le] {
            for (keys_row, swap) in [(true, false), (true, true), (false, false), (false, true)] {
                let what = format!("{ending:?} {enc:?} keys_row={keys_row} swap={swap}");
                let bytes = render(&rtec(keys_row, swap), ending, enc);
                let ds = read_written(dir.path(), RTEC_NAME, &bytes);
                assert_eq!(ds.format, "rtec", "{what}");
                assert_same(&want, &signature(&ds), &what);
                let recipe = ds.preamble.iter().find(|m| m.key == "Recipe").unwrap();
                assert_eq!(recipe.value, "Rotary_3N_4tests.Rx", "{what}");
                let radii = track_radii(&ds, &RadiusHints::default()).unwrap();
                for (k, r) in radii.iter().enumerate() {
                    let r = r.unwrap_or_else(|| panic!("{what}: no radius"));
                    assert!(
                        (r.radius_m - (6.0 + 3.0 * k as f64) * 1e-3).abs() < 1e-12,
                        "{what}"
                    );
                    assert_eq!(r.source.as_str(), "file_name_and_stage");
                }
            }
        }
    }
}

/// A PCS MTM test data file of three steps (a mapper step without a
/// table, a load ramp, a constant load); `banner` the model's, `swap` the
/// ball load and traction force columns exchanged.
fn mtm(banner: &str, swap: bool) -> String {
    let mut l: Vec<String> = vec![
        banner.into(),
        "Output file name:\tdemo.txt".into(),
        "Profile description:\tNew 3/4\" ball on disc profile".into(),
        "Lubricant name:\t".into(),
        String::new(),
        "Number of steps in profile:\t3".into(),
        "Test started at 23/03/2018 10:02:57".into(),
        String::new(),
        "Step 1 started at 23/03/2018 10:11:45".into(),
        "Step type\tMAPPER\tStep description\tNew mapper step".into(),
        "Zero traction force (N)\t-0.5786\t(measured at the start of this step)".into(),
        "Camera window load = 49.747 N".into(),
        String::new(),
    ];
    for (step, ramp) in [(2, true), (3, false)] {
        l.push(format!("Step {step} started at 23/03/2018 10:1{step}:01"));
        l.push("Step type\tBOD_TIMED\tStep description\tNew ball on disc timed step\tStep duration\t00:00:30".into());
        l.push("Zero traction force (N)\t-0.5444\t(measured at the start of this step)".into());
        l.push("Disc track radius used for this step (mm)\t21.232".into());
        let mut table = vec!["Step Time (s)\tTraction Coeff (-)\t\t\tStep Time (s)\tLube RTD Temp (°C)\tBall Load (N)\tPin Load (N)\tRolling Speed (mm/s)\tSliding Speed (mm/s)\tSRR (%)\t\tTraction Force (N)\tTraction Coeff (-)\t\t".to_string()];
        for i in 1..=30 {
            let load = if ramp { 4.9 + 1.5 * i as f64 } else { 50.0 };
            let mu = 0.02 + 0.001 * i as f64;
            let force = mu * load;
            table.push(format!(
                "{i}\t{:.4}\t\t\t{i}\t{:.1}\t{load:.3}\t\t{:.2}\t{:.2}\t100.000\t\t{force:.4}\t{:.4}\t\t",
                force / load,
                40.0 + 0.1 * i as f64,
                200.0,
                200.0,
                force / load
            ));
        }
        if swap {
            table = reorder(
                &table,
                '\t',
                &[0, 1, 2, 3, 4, 5, 12, 7, 8, 9, 10, 11, 6, 13, 14, 15],
            );
        }
        l.extend(table);
        l.push(String::new());
    }
    l.push("All steps completed, test completed normally at 23/03/2018 12:24:47".into());
    l.join("\n")
}

/// The model's banner (MTM311, MTM2, EHD2, ETM), CRLF, LF or CR, UTF-8,
/// ISO-8859-1 (the `°C`) or UTF-16, and either column order: the same two
/// table steps with the same roles, the repeated summary columns dropped,
/// the mapper step in the preamble and each step's track radius.
#[test]
fn pcs_mtm_variants_read_alike() {
    let dir = tempfile::tempdir().unwrap();
    let base_text = mtm("MTM311 Test Data File", false);
    let base = read_written(
        dir.path(),
        "m.txt",
        &render(&base_text, Ending::Crlf, Enc::Latin1),
    );
    assert_eq!(base.format, "pcs-mtm");
    let want = signature(&base);
    let roles: Vec<(String, Option<&str>)> = want[0]
        .1
        .iter()
        .filter(|c| c.2.is_some())
        .map(|c| (c.0.clone(), c.2))
        .collect();
    assert_eq!(
        roles,
        [
            ("Ball Load".to_string(), Some("normal_force")),
            ("Rolling Speed".to_string(), Some("velocity")),
            ("Step".to_string(), Some("step")),
            ("Step Time".to_string(), Some("time")),
            ("Traction Coeff".to_string(), Some("instrument_cof")),
            ("Traction Force".to_string(), Some("friction_force")),
        ]
    );
    for banner in [
        "MTM311 Test Data File",
        "MTM2 Test Data File",
        "EHD2 Test Data File",
        "ETM Test Data File",
    ] {
        for ending in [Ending::Crlf, Ending::Lf, Ending::Cr] {
            for enc in [Enc::Utf8, Enc::Latin1, Enc::Utf16Le] {
                for swap in [false, true] {
                    let what = format!("{banner} {ending:?} {enc:?} swap={swap}");
                    let ds = read_written(
                        dir.path(),
                        "m.txt",
                        &render(&mtm(banner, swap), ending, enc),
                    );
                    assert_eq!(ds.format, "pcs-mtm", "{what}");
                    assert_same(&want, &signature(&ds), &what);
                    let skipped = ds
                        .preamble
                        .iter()
                        .find(|m| m.key == "tribo.step_without_table");
                    assert_eq!(skipped.unwrap().value, "Step 1 (MAPPER)", "{what}");
                    for s in &ds.sections {
                        let r = declared_in(&s.metadata, &ds.source).unwrap();
                        assert_eq!(r, Some(21.232e-3), "{what} {}", s.name);
                    }
                }
            }
        }
    }
}

/// The CETR UMT fixture with LF endings, another viewer version, another
/// banner (`Created by UMT`, `Created by Bruker`), no banner at all, in
/// UTF-16, and with Fx and Fz exchanged in the header, the unit row and
/// the data: the same two steps, channels, units and values.
#[test]
fn cetr_variants_read_alike() {
    let dir = tempfile::tempdir().unwrap();
    let f = common::root().join("fixtures/friction/cetr_umt/HT-2n-6-4_2_001.csv");
    let text = std::fs::read_to_string(&f).unwrap().replace("\r\n", "\n");
    let base = read_written(dir.path(), "c.csv", text.as_bytes());
    assert_eq!(base.format, "cetr-umt");
    let want = signature(&base);
    let lines: Vec<String> = text.lines().map(str::to_string).collect();
    let swapped: Vec<String> = lines
        .iter()
        .map(|l| match l.split(',').count() == 11 {
            true => reorder(
                std::slice::from_ref(l),
                ',',
                &[1, 0, 2, 3, 4, 5, 6, 7, 8, 9, 10],
            )[0]
            .clone(),
            false => l.clone(),
        })
        .collect();
    let variants: Vec<(&str, String)> = vec![
        (
            "version",
            text.replace("ver.2.19.106", "ver.3.1.0")
                .replace("ver.1.136.257", "ver.2.0.4"),
        ),
        (
            "UMT banner",
            text.replace("Created by CETR Data Viewer", "Created by UMT Data Viewer"),
        ),
        (
            "Bruker banner",
            text.replace("Created by CETR", "Created by Bruker"),
        ),
        ("no banner", lines[2..].join("\n")),
        ("column order", swapped.join("\n")),
    ];
    for (what, v) in &variants {
        for ending in [Ending::Lf, Ending::Crlf, Ending::Cr] {
            for enc in [Enc::Utf8, Enc::Utf16Le] {
                let what = format!("{what} {ending:?} {enc:?}");
                let ds = read_written(dir.path(), "c.csv", &render(v, ending, enc));
                assert_eq!(ds.format, "cetr-umt", "{what}");
                assert_same(&want, &signature(&ds), &what);
            }
        }
    }
}

/// A pin-on-disc export of the CSM/Anton Paar family: `order` of the five
/// columns, `comma` for decimal commas and tabs (else points and
/// semicolons), `units` in the header, `mu` the coefficient's heading.
fn pod(order: &[usize], comma: bool, units: bool, mu: &str) -> String {
    let head = match units {
        true => ["Time [s]", "Distance [m]", "Laps", mu, "Friction force [N]"],
        false => ["Time ", "Distance", " Laps", mu, "FrictionForce"],
    };
    let (d, mark) = if comma { ('\t', ",") } else { (';', ".") };
    let mut lines = vec![order
        .iter()
        .map(|&k| head[k])
        .collect::<Vec<_>>()
        .join(&d.to_string())];
    for i in 1..=40 {
        let t = i as f64 * 0.1;
        let row = [
            format!("{t:.3}"),
            format!("{:.6}", 0.0188 * t),
            format!("{:.5}", t / 10.0),
            format!("{:.5}", 0.12 + 0.001 * i as f64),
            format!("{:.5}", 3.0 * (0.12 + 0.001 * i as f64)),
        ];
        let cells: Vec<String> = order.iter().map(|&k| row[k].replace('.', mark)).collect();
        lines.push(cells.join(&d.to_string()));
    }
    lines.join("\n")
}

/// Any column order, decimal comma or point, units in the header or not,
/// the µ sign in UTF-8 or ISO-8859-1 or as `mu`, any line ending: the same
/// channels (the family's names), SI units, roles and values.
#[test]
fn pin_on_disc_variants_read_alike() {
    let dir = tempfile::tempdir().unwrap();
    let base = read_written(
        dir.path(),
        "p.csv",
        pod(&[0, 1, 2, 3, 4], true, false, "mu").as_bytes(),
    );
    assert_eq!(base.format, "csm-pin-on-disc");
    let want = signature(&base);
    let names: Vec<&str> = want[0].1.iter().map(|c| c.0.as_str()).collect();
    assert_eq!(names, ["Distance", "FrictionForce", "Laps", "Time", "mu"]);
    for order in [[0, 1, 2, 3, 4], [0, 3, 4, 1, 2], [4, 3, 2, 1, 0]] {
        for (comma, units) in [(true, false), (false, false), (true, true), (false, true)] {
            for (mu, enc) in [
                ("mu", Enc::Utf8),
                ("µ", Enc::Utf8),
                ("µ", Enc::Latin1),
                ("µ", Enc::Utf16Le),
            ] {
                for ending in [Ending::Lf, Ending::Crlf] {
                    let what =
                        format!("{order:?} comma={comma} units={units} {mu} {enc:?} {ending:?}");
                    let ds = read_written(
                        dir.path(),
                        "p.csv",
                        &render(&pod(&order, comma, units, mu), ending, enc),
                    );
                    assert_eq!(ds.format, "csm-pin-on-disc", "{what}");
                    assert_same(&want, &signature(&ds), &what);
                }
            }
        }
    }
}
