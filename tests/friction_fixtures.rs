//! The friction stage on the bundled fixtures, whose features are known by
//! construction (fixtures/generate.py), and the bundled CETR exports against
//! the instrument's own COF.

use crate::common;

use std::path::Path;

use tribo::table::Table;

use common::run_friction_fixtures as run_demo;

struct Rows {
    t: Table,
}

impl Rows {
    fn rows_of(&self, file: &str) -> Vec<usize> {
        let src = self.t.str("source").unwrap();
        (0..src.len())
            .filter(|&i| src[i].as_deref().unwrap().ends_with(file))
            .collect()
    }
    fn f(&self, col: &str, i: usize) -> f64 {
        self.t.f64(col).unwrap()[i].unwrap_or_else(|| panic!("{col} null at row {i}"))
    }
}

fn friction(out: &Path) -> Rows {
    Rows {
        t: Table::read_parquet(&out.join("friction.parquet"))
            .unwrap()
            .0,
    }
}

#[test]
fn fixtures_run_clean_and_write_every_table() {
    let dir = tempfile::tempdir().unwrap();
    let report = run_demo(dir.path());
    assert_eq!(report.failures.len(), 0, "{:?}", report.failures);
    assert_eq!(report.files, 6);
    for name in ["friction", "friction_steps", "stickslip", "errors"] {
        assert!(
            dir.path().join(format!("{name}.parquet")).is_file(),
            "{name}"
        );
    }
    // The traces: a dataset, one file per input, listed by its manifest.
    let traces = dir.path().join("traces");
    assert!(dir.path().join("traces.dataset.json").is_file());
    assert_eq!(crate::common::files_with_ext(&traces, "parquet").len(), 6);
}

/// Sled: detachment 1200 mN at 2 s, plateau 1000 mN, Fz 2000 mN, noise sd
/// 5 mN. μ_s within 0.01 (the raw maximum near the peak carries up to ~2σ
/// of noise: 10 mN / 2000 mN = 0.005); μ_d within 5e-4 (7000 samples: the
/// standard error is 5/√7000/2000 = 3e-5).
#[test]
fn sled_static_and_dynamic_match_construction() {
    let dir = tempfile::tempdir().unwrap();
    run_demo(dir.path());
    let r = friction(dir.path());
    let i = r.rows_of("sled_mN.csv");
    assert_eq!(i.len(), 1);
    let i = i[0];
    assert!((r.f("mu_static", i) - 0.6).abs() < 0.01);
    assert!((r.f("static_time_s", i) - 2.0).abs() < 0.01);
    assert!((r.f("mu_dynamic", i) - 0.5).abs() < 5e-4);
    let start = r.f("dynamic_window_start_s", i);
    assert!((2.15..2.5).contains(&start), "window starts at {start}");
    assert!((r.f("normal_force_N", i) - 2.0).abs() < 1e-3);
}

/// Reciprocating: 6 strokes of alternating sign; μ_s = 0.46 and μ_d = 0.40
/// plus a drift of at most 0.1 N / 10 N = 0.01; noise 0.02 N.
#[test]
fn reciprocating_strokes_are_segmented_with_their_coefficients() {
    let dir = tempfile::tempdir().unwrap();
    run_demo(dir.path());
    let r = friction(dir.path());
    let rows = r.rows_of("reciprocating_latin1.csv");
    assert_eq!(rows.len(), 6);
    for (k, &i) in rows.iter().enumerate() {
        let sign = r.f("direction_sign", i);
        assert!((sign - if k % 2 == 0 { 1.0 } else { -1.0 }).abs() < 1e-12);
        let drift = 0.01 * r.f("segment_start_s", i) / 12.0;
        assert!(
            (r.f("mu_static", i) - 0.46 - drift).abs() < 0.015,
            "stroke {k}"
        );
        assert!(
            (r.f("mu_dynamic", i) - 0.40 - drift).abs() < 0.012,
            "stroke {k}"
        );
    }
}

/// Stick-slip: teeth from 0.9 to 1.1 N every 0.5 s after 1.1 s; the
/// manifest's mass_g = 200 gives N = 1.96133 N.
#[test]
fn stick_slip_events_have_the_built_in_drop_and_period() {
    let dir = tempfile::tempdir().unwrap();
    run_demo(dir.path());
    let r = friction(dir.path());
    let i = r.rows_of("stickslip.tsv")[0];
    assert!((r.f("normal_force_N", i) - 0.2 * 9.80665).abs() < 1e-12);
    assert!((r.f("mu_static", i) - 1.5 / 1.96133).abs() < 0.01);
    let events = r.t.i64("stickslip_events").unwrap()[i].unwrap();
    assert!((7..=9).contains(&events), "{events}");
    let (ss, _) = Table::read_parquet(&dir.path().join("stickslip.parquet")).unwrap();
    let src = ss.str("source").unwrap();
    let drop = ss.f64("drop_N").unwrap();
    let period = ss.f64("period_s").unwrap();
    let (peak_t, peak_f) = (
        ss.f64("peak_time_s").unwrap(),
        ss.f64("peak_force_N").unwrap(),
    );
    let (rise, fall) = (
        ss.f64("rise_time_s").unwrap(),
        ss.f64("drop_time_s").unwrap(),
    );
    let mut n = 0;
    let mut drops = Vec::new();
    for k in (0..src.len()).filter(|&k| src[k].as_deref().unwrap().ends_with("stickslip.tsv")) {
        n += 1;
        assert!((drop[k].unwrap() - 0.2).abs() < 0.01, "drop {:?}", drop[k]);
        drops.push(drop[k].unwrap());
        if let Some(p) = period[k] {
            assert!((p - 0.5).abs() < 0.025, "period {p}");
        }
        // The saw-tooth's tops: the sample before each reset, at
        // 1.595 + 0.5 j s and 0.9 + 0.2 · 0.495/0.5 = 1.098 N; the slip lasts
        // one 5 ms sample, the stick the 0.495 s between. The ramp climbs
        // 2 mN a sample, as much as the noise's sd, so the lowest point
        // after a reset is up to a few samples on (0.005–0.020 s in this
        // file), and the generator's floating-point phase puts some resets
        // a sample late (4.1 s for 4.095 s): three samples of slack.
        let t = peak_t[k].unwrap();
        let j = ((t - 1.595) / 0.5).round();
        assert!((t - (1.595 + 0.5 * j)).abs() <= 0.0151, "peak at {t} s");
        assert!(
            (peak_f[k].unwrap() - 1.098).abs() < 0.008,
            "{:?}",
            peak_f[k]
        );
        let slip = fall[k].unwrap();
        assert!((0.0049..=0.0251).contains(&slip), "slip {slip} s");
        if let Some(stick) = rise[k] {
            assert!((stick - 0.495).abs() <= 0.0251, "stick {stick} s");
        }
    }
    assert_eq!(n as i64, events);
    // The friction row: the events' mean drop, and events per second from
    // the static peak to the trace's last sample (5.995 s).
    let mean = drops.iter().sum::<f64>() / drops.len() as f64;
    assert!((r.f("stickslip_mean_drop_N", i) - mean).abs() < 1e-12);
    let freq = events as f64 / (5.995 - r.f("static_time_s", i));
    assert!((r.f("stickslip_frequency_Hz", i) - freq).abs() < 1e-9 * freq);
    assert!((1.5..2.0).contains(&freq), "{freq} Hz");
}

/// Stepped pin-on-disc: 4 speeds, μ = 0.30, 0.25, 0.20, 0.15 with noise sd
/// 0.005 over 240 samples per steady part: within 4 standard errors.
#[test]
fn velocity_steps_recover_mu_of_v() {
    let dir = tempfile::tempdir().unwrap();
    run_demo(dir.path());
    let (t, _) = Table::read_parquet(&dir.path().join("friction_steps.parquet")).unwrap();
    let src = t.str("source").unwrap();
    let rows: Vec<usize> = (0..t.height())
        .filter(|&i| src[i].as_deref().unwrap().ends_with("stepped.tsv"))
        .collect();
    assert_eq!(rows.len(), 4);
    let v = t.f64("velocity_m_per_s").unwrap();
    let mu = t.f64("mu_mean").unwrap();
    for (k, &i) in rows.iter().enumerate() {
        let (ve, me) = ([0.025, 0.05, 0.1, 0.2][k], [0.30, 0.25, 0.20, 0.15][k]);
        assert!(
            (v[i].unwrap() - ve).abs() < 1e-6 * ve.max(1.0) + 1e-9,
            "{:?}",
            v[i]
        );
        assert!(
            (mu[i].unwrap() - me).abs() < 4.0 * 0.005 / 240f64.sqrt(),
            "{:?}",
            mu[i]
        );
    }
}

/// The bundled CETR exports: our μ_d against the mean of the instrument's
/// COF over the same window, computed here from the raw file independently
/// (COF = |Fx| / |Fz| per sample, so the ratio of means differs from the
/// mean of ratios by the covariance of Fz, below 1e-3 relative).
#[test]
fn cetr_mu_agrees_with_the_instruments_cof() {
    let dir = tempfile::tempdir().unwrap();
    run_demo(dir.path());
    let r = friction(dir.path());
    for file in ["HT-2n-6-4_2_001.csv", "HT-2n-6-4_2_050.csv"] {
        let raw =
            std::fs::read_to_string(common::root().join("fixtures/friction/cetr_umt").join(file))
                .unwrap();
        let rows = r.rows_of(file);
        assert_eq!(rows.len(), 2, "one stroke per Step section");
        let sections = r.t.str("section").unwrap();
        for &i in &rows {
            let section = sections[i].clone().unwrap();
            let (t0, t1) = (
                r.f("dynamic_window_start_s", i),
                r.f("dynamic_window_end_s", i),
            );
            let cof = mean_cof_in_window(&raw, &section, t0, t1);
            let ours = r.f("mu_dynamic", i);
            assert!(
                ((ours - cof) / cof).abs() < 1e-3,
                "{file} {section}: {ours} vs {cof}"
            );
            assert!((0.5..1.0).contains(&ours), "{ours}");
        }
    }
}

/// Mean of the COF column of a CETR file within a Step section and a time
/// window, by plain string splitting.
fn mean_cof_in_window(raw: &str, section: &str, t0: f64, t1: f64) -> f64 {
    let step = section.trim_start_matches("Step ");
    let mut in_step = false;
    let (mut sum, mut n) = (0.0, 0);
    for line in raw.lines() {
        let line = line.trim_end_matches('\r');
        if let Some(s) = line.strip_prefix("Step No. ") {
            in_step = s.trim() == step;
            continue;
        }
        let f: Vec<&str> = line.split(',').collect();
        if in_step && f.len() == 11 {
            if let (Ok(t), Ok(c)) = (f[8].parse::<f64>(), f[10].parse::<f64>()) {
                if t >= t0 - 1e-9 && t <= t1 + 1e-9 {
                    sum += c;
                    n += 1;
                }
            }
        }
    }
    assert!(n > 0);
    sum / n as f64
}

/// The same inputs give identical tables on 1 and 2 threads.
#[test]
fn output_does_not_depend_on_the_thread_count() {
    let tables = |threads: usize| {
        let dir = tempfile::tempdir().unwrap();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| run_demo(dir.path()));
        ["friction", "friction_steps", "stickslip"].map(|n| {
            format!(
                "{:?}",
                Table::read_parquet(&dir.path().join(format!("{n}.parquet")))
                    .unwrap()
                    .0
            )
        })
    };
    assert_eq!(tables(1), tables(2));
}

/// Provenance: every table carries the tool version, the count of its
/// inputs and one SHA-256 of their list (`sha256sum` lines sorted by
/// path); the list is `files.parquet` (each data file's SHA-256) and the
/// sample manifest. Each file's SHA-256 and the list's are checked
/// against coreutils' sha256sum when it is installed.
#[test]
fn tables_carry_input_hashes() {
    let dir = tempfile::tempdir().unwrap();
    run_demo(dir.path());
    let (_, kv) = Table::read_parquet(&dir.path().join("friction.parquet")).unwrap();
    let get = |k: &str| {
        kv.iter()
            .find(|(a, _)| a == k)
            .map(|(_, v)| v.clone())
            .unwrap()
    };
    assert_eq!(get("tribo.version"), env!("CARGO_PKG_VERSION"));
    assert_eq!(get("tribo.build"), tribo::BUILD);
    let hash = tribo::BUILD.strip_prefix(concat!(env!("CARGO_PKG_VERSION"), "+"));
    assert!(
        hash.is_some_and(|h| h.len() == 16 && h.bytes().all(|b| b.is_ascii_hexdigit())),
        "{}",
        tribo::BUILD
    );
    assert_eq!(get("tribo.table"), "friction");
    // The six traces and the sample manifest, which also shapes the rows.
    assert_eq!(get("tribo.inputs_count"), "7");
    assert_eq!(get("tribo.inputs_table"), "files");
    let params: serde_json::Value = serde_json::from_str(&get("tribo.parameters")).unwrap();
    assert_eq!(params["friction"]["median_window"], 3);
    let (files, _) = Table::read_parquet(&dir.path().join("files.parquet")).unwrap();
    let (sources, hashes) = (files.str("source").unwrap(), files.str("sha256").unwrap());
    assert_eq!(sources.len(), 6);
    let sha256sum = |args: &[&str], stdin: Option<&str>| -> Option<String> {
        use std::io::Write;
        let mut child = std::process::Command::new("sha256sum")
            .args(args)
            .stdin(std::process::Stdio::piped())
            .stdout(std::process::Stdio::piped())
            .spawn()
            .ok()?;
        let mut input = child.stdin.take()?;
        input.write_all(stdin.unwrap_or("").as_bytes()).ok()?;
        drop(input);
        let out = child.wait_with_output().ok()?;
        Some(String::from_utf8_lossy(&out.stdout).to_string())
    };
    let mut lines: Vec<(String, String)> = Vec::new();
    for (path, hash) in sources.iter().zip(&hashes) {
        let (path, hash) = (path.clone().unwrap(), hash.clone().unwrap());
        lines.push((path, hash));
    }
    let manifest = common::root().join("fixtures/friction/samples.csv");
    let manifest = manifest.display().to_string();
    let Some(printed) = sha256sum(&[&manifest], None) else {
        eprintln!("SKIP the checks against coreutils: sha256sum is not installed");
        return;
    };
    lines.push((manifest, printed.split_whitespace().next().unwrap().into()));
    lines.sort();
    let mut list = String::new();
    for (path, hash) in &lines {
        let printed = sha256sum(&[path], None).unwrap();
        assert_eq!(printed.split_whitespace().next().unwrap(), hash, "{path}");
        list.push_str(&format!("{hash}  {path}\n"));
    }
    let of_list = sha256sum(&[], Some(&list)).unwrap();
    assert_eq!(
        get("tribo.inputs_sha256"),
        of_list.split_whitespace().next().unwrap()
    );
}

/// traces.parquet joins to friction.parquet on (source, section, stroke):
/// the samples of each stroke with a force are that row's n_samples, and
/// their mean force has the row's direction sign.
#[test]
fn trace_samples_carry_the_stroke_of_their_friction_row() {
    let dir = tempfile::tempdir().unwrap();
    run_demo(dir.path());
    let r = friction(dir.path());
    let traces = crate::common::read_table(&dir.path().join("traces"));
    let (src, stroke) = (traces.str("source").unwrap(), traces.i64("stroke").unwrap());
    let force = traces.f64("friction_force_N").unwrap();
    let strokes = r.t.i64("stroke").unwrap();
    let rows = r.rows_of("reciprocating_latin1.csv");
    assert_eq!(rows.len(), 6);
    for &i in &rows {
        let k = strokes[i].unwrap();
        let mine: Vec<f64> = (0..src.len())
            .filter(|&j| {
                src[j]
                    .as_deref()
                    .unwrap()
                    .ends_with("reciprocating_latin1.csv")
            })
            .filter(|&j| stroke[j] == Some(k))
            .filter_map(|j| force[j])
            .collect();
        assert_eq!(mine.len() as f64, r.f("n_samples", i), "stroke {k}");
        let mean = mine.iter().sum::<f64>() / mine.len() as f64;
        assert_eq!(mean.signum(), r.f("direction_sign", i), "stroke {k}");
    }
    // Some samples lie between strokes (the reversals): null there.
    assert!(stroke.iter().any(Option::is_none));
}
