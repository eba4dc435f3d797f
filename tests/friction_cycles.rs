//! `friction_cycles` and `friction_tests` on real exports, checked against
//! the instruments' own printed values: the pin-on-disc export's μ per row
//! (averaged over each lap of its lap counter) and the CETR header's date
//! and crank.

use crate::common;

use std::collections::BTreeMap;
use std::path::Path;

use tribo::table::Table;

fn run(dir: &Path, file: &Path, manifest: Option<&str>) -> (Table, Table) {
    let mut args = vec!["friction", file.to_str().unwrap(), "--out", "o"];
    if let Some(m) = manifest {
        std::fs::write(dir.join("samples.txt"), m).unwrap();
        args.extend(["--samples", "samples.txt"]);
    }
    let o = common::tribo(dir, &args);
    assert!(
        o.status.code().is_some_and(|c| c <= 1),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let read = |n: &str| Table::read_parquet(&dir.join("o").join(n)).unwrap().0;
    (
        read("friction_cycles.parquet"),
        read("friction_tests.parquet"),
    )
}

/// The export's rows: time, lap counter and the instrument's μ (tab
/// separated, decimal comma), read here independently of tribo's reader.
fn pin_on_disc_rows(path: &Path) -> Vec<(f64, f64, f64)> {
    let text = std::fs::read_to_string(path).unwrap();
    let num = |s: &str| s.trim().replace(',', ".").parse::<f64>().unwrap();
    text.lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let f: Vec<&str> = l.split('\t').collect();
            (num(f[0]), num(f[2]), num(f[3]))
        })
        .collect()
}

/// Each lap's μ from the instrument equals the mean of the export's μ over
/// the rows of that lap (its lap counter's whole part) to 1e-9, there are
/// as many laps as the counter has, and the test's row states its cycle
/// source.
#[test]
fn pin_on_disc_laps_average_the_instruments_mu() {
    let Some(dir) = common::shared_real("tribometer_pin_on_disc_tsv") else {
        return;
    };
    for file in common::files_with_ext(&dir, "csv") {
        let out = tempfile::tempdir().unwrap();
        let manifest = format!(
            "file,sample_id,normal_force_N\n{},P,3\n",
            file.file_name().unwrap().to_str().unwrap()
        );
        std::fs::copy(&file, out.path().join(file.file_name().unwrap())).unwrap();
        let local = out.path().join(file.file_name().unwrap());
        let (cycles, tests) = run(out.path(), &local, Some(&manifest));
        let mut laps: BTreeMap<i64, Vec<f64>> = BTreeMap::new();
        for (_, lap, mu) in pin_on_disc_rows(&file) {
            laps.entry(lap.floor() as i64).or_default().push(mu);
        }
        assert_eq!(cycles.height(), laps.len(), "{}", file.display());
        let (lap, mu_i) = (
            cycles.i64("lap").unwrap(),
            cycles.f64("mu_instrument").unwrap(),
        );
        let kind = cycles.str("kind").unwrap();
        for i in 0..cycles.height() {
            assert_eq!(kind[i].as_deref(), Some("lap"));
            let k = lap[i].unwrap();
            let v = &laps[&k];
            let expected = v.iter().sum::<f64>() / v.len() as f64;
            let got = mu_i[i].unwrap();
            assert!(
                (got - expected).abs() < 1e-9,
                "lap {k}: {got} vs {expected}"
            );
        }
        assert_eq!(tests.height(), 1);
        assert_eq!(
            tests.str("cycle_source").unwrap()[0].as_deref(),
            Some("lap_counter")
        );
        assert_eq!(tests.i64("n_cycles").unwrap()[0], Some(laps.len() as i64));
    }
}

/// The CETR export: each stroke's μ (from Fx and Fz) equals the
/// instrument's COF averaged over the stroke's window to the rounding of
/// its print (1e-3), the test's date is the header's `Run date` (no UTC
/// offset stated: local time).
#[test]
fn cetr_strokes_agree_with_the_instruments_cof() {
    let Some(dir) = common::shared_real("tribometer_cetr_umt") else {
        return;
    };
    let out = tempfile::tempdir().unwrap();
    let (cycles, tests) = run(out.path(), &dir.join("HT-2n-6-4_2_001.csv"), None);
    assert!(cycles.height() >= 2);
    let (mu, mu_i) = (
        cycles.f64("mu").unwrap(),
        cycles.f64("mu_instrument").unwrap(),
    );
    let complete = cycles.bool("complete").unwrap();
    let mut checked = 0;
    for i in 0..cycles.height() {
        if let (Some(a), Some(b), Some(true)) = (mu[i], mu_i[i], complete[i]) {
            assert!(((a - b) / b).abs() < 1e-3, "stroke row {i}: {a} vs {b}");
            checked += 1;
        }
    }
    assert!(checked >= 2, "{checked} strokes checked");
    let started = cycles.str("test_started_at").unwrap();
    assert!(started
        .iter()
        .all(|s| s.as_deref() == Some("2022-05-12T12:21:50")));
    assert_eq!(
        tests.str("test_started_at").unwrap()[0].as_deref(),
        Some("2022-05-12T12:21:50")
    );
}

/// The test row of a CETR export inherits its strokes' `speed_mismatch`
/// (the header's crank speed does not fit the record's strokes), naming
/// the cycles, but not their strokes' `static_below_dynamic`: a doubt of
/// the static peak says nothing of a cycle's sliding μ.
#[test]
fn a_test_row_inherits_its_cycles_doubts_of_their_mu() {
    let out = tempfile::tempdir().unwrap();
    let file = common::root().join("fixtures/lab/friction/HT-2n-6-4_2_001.csv");
    let (cycles, tests) = run(out.path(), &file, None);
    let codes = cycles.status_codes().unwrap();
    assert!(codes
        .iter()
        .all(|c| c.contains(&tribo::status::Code::SpeedMismatch)
            && c.contains(&tribo::status::Code::StaticBelowDynamic)));
    let scope = tests.str("scope").unwrap();
    let detail = tests.str("status_detail").unwrap();
    let test = (0..tests.height())
        .find(|&i| scope[i].as_deref() == Some("test"))
        .unwrap();
    let detail = detail[test].as_deref().unwrap();
    let want = "doubtful_points: 2 of the 2 rows used carry warnings: \
                cycle 1 (speed_mismatch), cycle 2 (speed_mismatch)";
    assert!(detail.ends_with(want), "{detail}");
}

/// Deterministic noise, uniform in ±√3·σ (sd σ), from a 64-bit LCG.
fn noise(n: usize, sigma: f64, seed: u64) -> Vec<f64> {
    let mut s = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (0..n)
        .map(|_| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let u = (s >> 11) as f64 / (1u64 << 53) as f64;
            (2.0 * u - 1.0) * 3f64.sqrt() * sigma
        })
        .collect()
}

/// μ of cycle k: a running-in A·e^(−k/τ) onto the plateau 0.3, or a drift.
fn mu_of(k: usize, drift: bool) -> f64 {
    match drift {
        false => 0.3 + 0.2 * (-(k as f64) / 25.0).exp(),
        true => 0.3 + 0.0008 * k as f64,
    }
}

/// A rotary test of 300 laps of 20 samples (a fractional lap counter as
/// the real export has), 0.1 m slid per lap, N = 10 N, per-sample noise
/// `sigma` in μ.
fn write_laps(path: &Path, mu_of: impl Fn(usize) -> f64, sigma: f64) {
    let per = 20;
    let e = noise(300 * per, sigma, 7);
    let mut s = String::from("Time [s],Laps,Distance [m],Ff [N],Fn [N]\n");
    for (i, e) in e.iter().enumerate() {
        let mu = mu_of(i / per) + e;
        let lap = i as f64 / per as f64;
        s.push_str(&format!(
            "{:.3},{lap:.5},{:.6},{:.6},10\n",
            i as f64 * 0.05,
            0.1 * lap,
            mu * 10.0
        ));
    }
    std::fs::write(path, s).unwrap();
}

/// The generated running-in over laps: the onset (first lap whose
/// transient is within 2 % of the plateau: 25·ln(0.2/0.006) → lap 88) is
/// found within max(2, 10 %) and the steady μ is the plateau within 2
/// standard errors; a drifting test says `no_steady_state`.
#[test]
fn a_generated_running_in_over_laps_is_found() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("laps.csv");
    write_laps(&path, |k| mu_of(k, false), 0.01);
    let (cycles, tests) = run(dir.path(), &path, None);
    assert_eq!(cycles.height(), 300);
    let truth = (25.0f64 * (0.2f64 / 0.006).ln()).ceil();
    let onset = tests.i64("running_in_cycles").unwrap()[0].unwrap() as f64;
    assert!(
        (onset - truth).abs() <= (0.1 * truth).max(2.0),
        "onset {onset} vs {truth}"
    );
    let (mu, se) = (
        tests.f64("mu_steady").unwrap()[0].unwrap(),
        tests.f64("mu_steady_se").unwrap()[0].unwrap(),
    );
    assert!((mu - 0.3).abs() < 2.0 * se, "{mu} ± {se}");
    assert_eq!(tests.str("status").unwrap()[0].as_deref(), Some("ok"));
    // The fitted transient: time constant 25 laps, plateau 0.3, and the
    // first lap's μ 0.3 + 0.2 = 0.5 (a lap's mean of 20 samples has an sd
    // of 0.0022: within 0.01)
    let cell = |c: &str| tests.f64(c).unwrap()[0].unwrap();
    assert!(
        (cell("tau_cycles") - 25.0).abs() < 2.5,
        "{}",
        cell("tau_cycles")
    );
    assert!(
        (cell("mu_plateau") - 0.3).abs() < 0.003,
        "{}",
        cell("mu_plateau")
    );
    assert!(
        (cell("mu_first") - 0.5).abs() < 0.01,
        "{}",
        cell("mu_first")
    );
    // The steady band of an exponential running-in is 2 % of its fitted
    // plateau; the running-in's distance is its whole laps of 0.1 m, from
    // the first lap's start (the counter starts at 0: every lap is whole).
    assert_eq!(
        tests.str("running_in_method").unwrap()[0].as_deref(),
        Some("exponential")
    );
    let band = cell("band_mu");
    assert!((band - 0.02 * cell("mu_plateau")).abs() <= 1e-15, "{band}");
    assert!((band - 0.006).abs() < 6e-5, "{band}");
    let distance = cell("running_in_distance_m");
    assert!(
        (distance - 0.1 * onset).abs() < 1e-9,
        "{distance} vs {onset} laps"
    );
    let drifting = dir.path().join("drift.csv");
    write_laps(&drifting, |k| mu_of(k, true), 0.01);
    let out = tempfile::tempdir().unwrap();
    let (_, tests) = run(out.path(), &drifting, None);
    let status = tests.str("status").unwrap()[0].clone().unwrap();
    assert!(status.contains("no_steady_state"), "{status}");
    assert_eq!(tests.f64("mu_steady").unwrap()[0], None);
}

/// A running-in that is not an exponential: μ falls linearly from 0.5 to
/// the plateau 0.3 over 60 laps, without noise. The band method takes the
/// plateau from the tail (0.3) and its band as 2 % of it, 0.006 (nothing to
/// widen for); the ramp is within it from lap 58.2 on (0.2 (60 − k)/60 ≤
/// 0.006), which a 5-lap moving mean reaches within 2 laps; the running-in's
/// distance is its whole laps of 0.1 m.
#[test]
fn a_linear_running_in_is_found_by_the_band() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("ramp.csv");
    write_laps(
        &path,
        |k| 0.3 + 0.2 * (60.0 - k as f64).max(0.0) / 60.0,
        0.0,
    );
    let (_, tests) = run(dir.path(), &path, None);
    let cell = |c: &str| tests.f64(c).unwrap()[0].unwrap();
    assert_eq!(tests.str("status").unwrap()[0].as_deref(), Some("ok"));
    assert_eq!(
        tests.str("running_in_method").unwrap()[0].as_deref(),
        Some("band")
    );
    assert!((cell("mu_plateau") - 0.3).abs() < 1e-12);
    assert!(
        (cell("band_mu") - 0.006).abs() < 1e-12,
        "{}",
        cell("band_mu")
    );
    let onset = tests.i64("running_in_cycles").unwrap()[0].unwrap();
    assert!((57..=61).contains(&onset), "onset {onset}");
    let distance = cell("running_in_distance_m");
    assert!(
        (distance - 0.1 * onset as f64).abs() < 1e-9,
        "{distance} vs {onset} laps"
    );
    assert!((cell("mu_steady") - 0.3).abs() < 1e-12);
}

/// A rotary test whose wear channel deepens linearly with the distance
/// slid, d(s) = 5 µm + 2 µm/m · s (0.1 m a lap, 40 laps of 20 samples,
/// 0.1 m/s): each lap's wear depth is its samples' mean, the depth at the
/// middle of its distance span, since equally spaced samples of a linear
/// channel average to its midpoint; the test's depth rate is the 2e-6 m/m
/// of the construction (a least-squares line through exact points) with a
/// standard error of rounding only, and its change is that rate times the
/// distance between the first and last lap judged.
#[test]
fn a_linear_wear_channel_gives_its_rate_and_per_lap_depths() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("wear.csv");
    let (per, laps, dt, v) = (20usize, 40usize, 0.05, 0.1);
    let depth = |s: f64| 5e-6 + 2e-6 * s;
    let mut text = String::from("Time [s],Laps,Distance [m],Ff [N],Fn [N],Wear depth [um]\n");
    // Half a lap more: the last whole lap is followed by a sample, as the
    // others are (a partial last lap is not judged).
    for i in 0..per * laps + per / 2 {
        let (t, lap) = (i as f64 * dt, i as f64 / per as f64);
        let s = v * t;
        text.push_str(&format!(
            "{t:.3},{lap:.5},{s:.6},3,10,{:.9}\n",
            depth(s) * 1e6
        ));
    }
    std::fs::write(&path, text).unwrap();
    let (cycles, tests) = run(dir.path(), &path, None);
    let col = |t: &Table, c: &str| t.f64(c).unwrap();
    let (from, to, worn) = (
        col(&cycles, "distance_start_m"),
        col(&cycles, "distance_end_m"),
        col(&cycles, "wear_depth_m"),
    );
    let complete = cycles.bool("complete").unwrap();
    let judged: Vec<usize> = (0..cycles.height())
        .filter(|&k| complete[k] == Some(true))
        .collect();
    assert!(judged.len() >= laps - 2, "{} laps judged", judged.len());
    // A lap's samples run from its first to its last; its distance span
    // ends at the next lap's first sample: its samples' midpoint is half a
    // sample (0.0025 m, 5 nm of depth) before the span's.
    let half_sample = 0.5 * v * dt;
    let mid = |k: usize| 0.5 * (from[k].unwrap() + to[k].unwrap()) - half_sample;
    for &k in &judged {
        let want = depth(mid(k));
        assert!(
            (worn[k].unwrap() - want).abs() < 1e-12,
            "lap {k}: {:?} vs {want}",
            worn[k]
        );
    }
    let rate = col(&tests, "wear_depth_rate_m_per_m")[0].unwrap();
    assert!((rate - 2e-6).abs() < 1e-12, "{rate}");
    let se = col(&tests, "wear_depth_rate_se_m_per_m")[0].unwrap();
    assert!(se < 1e-12, "{se}");
    let (a, b) = (judged[0], judged[judged.len() - 1]);
    let change = col(&tests, "wear_depth_change_m")[0].unwrap();
    assert!(
        (change - 2e-6 * (mid(b) - mid(a))).abs() < 1e-12,
        "{change}"
    );
    // A lap's steady part is the whole lap: its first to its last sample
    // (20 at 0.05 s), and a lap has no break-away.
    let lap = cycles.i64("lap").unwrap();
    let n_window = cycles.i64("n_window").unwrap();
    let peak = cycles.f64("mu_peak").unwrap();
    for &k in &judged {
        let first = lap[k].unwrap() as f64 * per as f64 * dt;
        let (a, b) = (
            col(&cycles, "window_start_s")[k].unwrap(),
            col(&cycles, "window_end_s")[k].unwrap(),
        );
        assert!((a - first).abs() < 1e-9, "lap {k}: starts {a}, not {first}");
        let last = first + (per - 1) as f64 * dt;
        assert!((b - last).abs() < 1e-9, "lap {k}: ends {b}, not {last}");
        assert_eq!(n_window[k], Some(per as i64));
        assert_eq!(peak[k], None);
    }
    // A constant 3 N at 10 N: the test slid the trace's 809 steps of
    // 5 mm, dissipating ∫|T||dx| = 3 N × 4.045 m, at μ = 0.3 throughout.
    let cell = |c: &str| col(&tests, c)[0].unwrap();
    assert!(
        (cell("distance_m") - 4.045).abs() < 1e-9,
        "{}",
        cell("distance_m")
    );
    assert!(
        (cell("energy_J") - 3.0 * 4.045).abs() < 1e-9,
        "{}",
        cell("energy_J")
    );
    assert!((cell("normal_force_N") - 10.0).abs() < 1e-12);
    for c in ["mu_first", "mu_max", "mu_steady"] {
        assert!((cell(c) - 0.3).abs() < 1e-12, "{c} {}", cell(c));
    }
}

/// The reciprocating fixture (6 strokes of 2 s at 100 Hz, a break-away to
/// 4.6 N at sample 10 of each, the 4 N plateau from sample 20, N ≈ 10 N),
/// read here from its own rows (Latin-1, `;`, decimal comma): each
/// stroke's window holds n_window of the file's samples, after the
/// break-away and inside the stroke; mu is mean |Ft| / mean Fn over them and
/// mu_sd the sample sd of |Ft|/Fn, to 1e-12; mu_peak is the friction row's
/// mu_static (the row of the same stroke), within the noise (0.02 N) and
/// drift of the 0.46 built in.
#[test]
fn strokes_average_the_files_samples_over_their_window() {
    let file = common::root().join("fixtures/friction/reciprocating_latin1.csv");
    let bytes = std::fs::read(&file).unwrap();
    let text: String = bytes.iter().map(|&b| b as char).collect();
    let num = |s: &str| s.trim().replace(',', ".").parse::<f64>().unwrap();
    let rows: Vec<(f64, f64, f64)> = text
        .lines()
        .skip(3)
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let f: Vec<&str> = l.split(';').collect();
            (num(f[0]), num(f[1]), num(f[2]))
        })
        .collect();
    let dir = tempfile::tempdir().unwrap();
    let (cycles, _) = run(dir.path(), &file, None);
    let friction = Table::read_parquet(&dir.path().join("o/friction.parquet"))
        .unwrap()
        .0;
    assert_eq!(cycles.height(), 6);
    let f = |t: &Table, c: &str, i: usize| t.f64(c).unwrap()[i].unwrap();
    let stroke_of_row = friction.i64("stroke").unwrap();
    let n_window = cycles.i64("n_window").unwrap();
    for (i, stroke) in cycles.i64("stroke").unwrap().iter().enumerate() {
        let k = stroke.unwrap();
        let j = stroke_of_row.iter().position(|s| *s == Some(k)).unwrap();
        let (a, b) = (
            f(&cycles, "window_start_s", i),
            f(&cycles, "window_end_s", i),
        );
        assert_eq!(a, f(&friction, "dynamic_window_start_s", j));
        assert_eq!(b, f(&friction, "dynamic_window_end_s", j));
        let stroke_start = 2.0 * (k - 1) as f64;
        assert!(
            a > stroke_start + 0.1 && b < stroke_start + 2.0,
            "stroke {k}: {a}..{b}"
        );
        let inside: Vec<&(f64, f64, f64)> = rows
            .iter()
            .filter(|r| r.0 >= a - 1e-9 && r.0 <= b + 1e-9)
            .collect();
        assert_eq!(n_window[i], Some(inside.len() as i64), "stroke {k}");
        let n = inside.len() as f64;
        let mean_t = inside.iter().map(|r| r.1.abs()).sum::<f64>() / n;
        let mean_n = inside.iter().map(|r| r.2).sum::<f64>() / n;
        let mu = f(&cycles, "mu", i);
        assert!((mu - mean_t / mean_n).abs() < 1e-12, "stroke {k}: {mu}");
        let point: Vec<f64> = inside.iter().map(|r| r.1.abs() / r.2).collect();
        let m = point.iter().sum::<f64>() / n;
        let sd = (point.iter().map(|p| (p - m).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
        assert!((f(&cycles, "mu_sd", i) - sd).abs() < 1e-12, "stroke {k}");
        let peak = f(&cycles, "mu_peak", i);
        assert_eq!(peak, f(&friction, "mu_static", j));
        let drift = 0.01 * stroke_start / 12.0;
        assert!((peak - 0.46 - drift).abs() < 0.015, "stroke {k}: {peak}");
    }
}
