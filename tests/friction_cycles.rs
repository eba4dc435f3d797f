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
/// the real export has), N = 10 N, per-sample noise 0.01 in μ.
fn write_laps(path: &Path, drift: bool) {
    let per = 20;
    let e = noise(300 * per, 0.01, 7);
    let mut s = String::from("Time [s],Laps,Ff [N],Fn [N]\n");
    for (i, e) in e.iter().enumerate() {
        let mu = mu_of(i / per, drift) + e;
        let lap = i as f64 / per as f64;
        s.push_str(&format!(
            "{:.3},{lap:.5},{:.6},10\n",
            i as f64 * 0.05,
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
    write_laps(&path, false);
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
    let drifting = dir.path().join("drift.csv");
    write_laps(&drifting, true);
    let out = tempfile::tempdir().unwrap();
    let (_, tests) = run(out.path(), &drifting, None);
    let status = tests.str("status").unwrap()[0].clone().unwrap();
    assert!(status.contains("no_steady_state"), "{status}");
    assert_eq!(tests.f64("mu_steady").unwrap()[0], None);
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
