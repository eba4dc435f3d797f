//! Random surfaces against the parameters that generated them, over several
//! seeds (`signal::testing::random_surface`: Gaussian random fields with a
//! prescribed PSD, MODELS §10). The truth is the generator's: the Hurst
//! exponent and the PSD's power law of a self-affine surface, its expected
//! Sq² = Σ C(q) / (N ΔxΔy) and that sum's variance, and the expected ACF
//! R(t) = Σ C(q) cos(q·t) / (N ΔxΔy) of a surface with known correlation
//! lengths. Each realisation is periodic, analysed as such (no window, a
//! circular ACF), so the estimators see what the generator made.

use tribo::extract::roughness::*;
use tribo::signal::testing::{grid_wavevector, random_surface};

const N: usize = 256;
const D: f64 = 1e-7;
const SEEDS: std::ops::Range<u64> = 1..7;

fn periodic() -> RoughnessParams {
    RoughnessParams {
        detrend: Detrend::Mean,
        periodic: true,
        ..Default::default()
    }
}

/// Σ over the grid's wavevectors (q = 0 left out, as the generator does).
fn grid_sum(psd: &dyn Fn(f64, f64) -> f64, term: &dyn Fn(f64, f64, f64) -> f64) -> f64 {
    let mut s = 0.0;
    for r in 0..N {
        for c in 0..N {
            if r + c > 0 {
                let (qx, qy) = grid_wavevector(c, r, N, N, D, D);
                s += term(qx, qy, psd(qx, qy));
            }
        }
    }
    s
}

fn mean_sd(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let m = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0);
    (m, var.sqrt())
}

/// Least-squares slope of ln C against ln q over the bins in [lo, hi].
fn log_slope(s: &psd::Spectrum, lo: f64, hi: f64) -> f64 {
    let pts: Vec<(f64, f64)> =
        s.q.iter()
            .zip(&s.c)
            .filter(|(q, _)| **q >= lo && **q <= hi)
            .map(|(q, c)| (q.ln(), c.ln()))
            .collect();
    let n = pts.len() as f64;
    let (mx, my) = pts
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let sxy: f64 = pts.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = pts.iter().map(|(x, _)| (x - mx).powi(2)).sum();
    sxy / sxx
}

/// See the test below.
const H_TOL: f64 = 0.12;
const SLOPE_TOL: f64 = 0.2;

#[test]
fn self_affine_surfaces_give_their_hurst_exponent_sq_and_psd_slope() {
    // C(q) = C0 q^−2(1+H) at every wavevector of the grid (no roll-off).
    // - The PSD's log-log slope between 4 q_min and q_max / 2 (no window,
    //   a periodic surface): the seeds' mean within 3 standard errors (of
    //   their own scatter) of −2(1 + H); each seed within 0.2 (the lowest
    //   bins hold few modes: measured 0.15 at worst, H 0.3);
    // - H from the structure function (rows and columns, lags 1 sample to
    //   10 % of the side), D = 3 − H: each seed within 0.12. The line
    //   structure function of a map bends towards the grid's cut-off:
    //   measured +0.05 to +0.09 at H 0.3, a bias, not scatter;
    // - Sq²: the seeds' mean within 3 standard errors of E[Sq²], the
    //   standard error from the generator's own variance
    //   Var[Sq²] = 2 Σ m(q)² / N⁴ with m(q) = N C(q)/ΔxΔy (each mode's
    //   |W|² is exponential), not from the sample.
    for h in [0.3, 0.5, 0.8] {
        // C0 at the longest wavelength: Sq of about 1 µm.
        let q0 = 2.0 * std::f64::consts::PI / (N as f64 * D);
        let c0 = 6.5e-22;
        let psd =
            move |qx: f64, qy: f64| c0 * ((qx * qx + qy * qy).sqrt() / q0).powf(-2.0 * (1.0 + h));
        let nn = (N * N) as f64;
        let expected_sq2 = grid_sum(&psd, &|_, _, c| c) / (nn * D * D);
        let var_sq2 = grid_sum(&psd, &|_, _, c| 2.0 * (nn * c / (D * D)).powi(2)) / nn.powi(4);
        let (q_min, q_max) = (
            2.0 * std::f64::consts::PI / (N as f64 * D),
            std::f64::consts::PI / D,
        );
        let mut sq2 = Vec::new();
        let mut seen = Vec::new();
        for seed in SEEDS {
            let z = random_surface(N, N, (D, D), psd, seed);
            let m = AreaMap::new("self-affine", D, D, N, N, z).unwrap();
            let r = analyze_map(&m, &periodic()).unwrap();
            let fit = r.fractal.as_ref().expect("a fractal fit");
            let d = fit.dimension.expect("0 < H ≤ 1");
            assert!((d - (3.0 - fit.hurst)).abs() < 1e-12);
            let slope = log_slope(&r.psd, 4.0 * q_min, q_max / 2.0);
            seen.push((seed, fit.hurst, slope));
            sq2.push(r.rq * r.rq);
        }
        let truth = -2.0 * (1.0 + h);
        for &(seed, hurst, slope) in &seen {
            assert!(
                (hurst - h).abs() < H_TOL && (slope - truth).abs() < SLOPE_TOL,
                "H {h}, seed {seed}: fitted H {hurst}, PSD slope {slope} (expected {truth}); all: {seen:?}"
            );
        }
        let slopes: Vec<f64> = seen.iter().map(|s| s.2).collect();
        let (m, sd) = mean_sd(&slopes);
        assert!(
            (m - truth).abs() < 3.0 * sd / (slopes.len() as f64).sqrt(),
            "H {h}: mean PSD slope {m} (sd {sd}), expected {truth}; all: {seen:?}"
        );
        let (mean, _) = mean_sd(&sq2);
        let se = (var_sq2 / sq2.len() as f64).sqrt();
        assert!(
            (mean - expected_sq2).abs() < 3.0 * se,
            "H {h}: mean Sq² {mean:e}, expected {expected_sq2:e} ± {se:e}"
        );
    }
}

/// The expected normalised ACF along x (`along_x`) or y at lag t, from the
/// generator's PSD, and the lag where it falls to s (bisection).
fn expected_decay(psd: &dyn Fn(f64, f64) -> f64, along_x: bool, s: f64) -> f64 {
    let r0 = grid_sum(psd, &|_, _, c| c);
    let f = |t: f64| {
        grid_sum(psd, &|qx, qy, c| {
            let q = if along_x { qx } else { qy };
            c * (q * t).cos()
        }) / r0
    };
    let (mut lo, mut hi) = (0.0, N as f64 * D / 2.0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if f(mid) > s {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[test]
fn correlated_surfaces_give_their_sal_and_str() {
    // C(q) ∝ exp(−(qx²τx² + qy²τy²)/4): the ACF is exp(−x²/τx² − y²/τy²)
    // (sampled and periodic on the grid: the truth is the grid's sum), so
    // the fastest decay to s = 0.2 is along x (τx < τy), the slowest along
    // y, and Str = Sal / that. Over the seeds, the means of Sal and Str
    // within 3 standard errors (their own scatter) of the truth, plus an
    // allowance for the estimators' resolution: bilinear interpolation
    // between lags of a Gaussian sampled every τ/4, (Δ/τ)²/8 = 8e-3, and
    // for Str the longest decay taken as the largest of 720 noisy rays,
    // which biases it up (Str down) by about its own scatter: 0.03. Each
    // seed within 20 % (a realisation holds L/τy = 32 correlation lengths
    // along the slow direction; at τy = 16Δ one seed's Str was 19 % low).
    let (tx, ty) = (4.0 * D, 8.0 * D);
    let psd =
        move |qx: f64, qy: f64| 1e-24 * (-(qx * qx * tx * tx + qy * qy * ty * ty) / 4.0).exp();
    let sal = expected_decay(&psd, true, 0.2);
    let slow = expected_decay(&psd, false, 0.2);
    let str_ratio = sal / slow;
    // Near the continuous Gaussian's τ√ln 5: the grid's sum lacks the
    // q = 0 term (the mean), which lowers the ACF by a constant.
    assert!(
        (sal / (tx * 5f64.ln().sqrt()) - 1.0).abs() < 0.02,
        "Sal {sal:e}"
    );
    let (mut sals, mut strs) = (Vec::new(), Vec::new());
    for seed in SEEDS {
        let z = random_surface(N, N, (D, D), psd, 100 + seed);
        let m = AreaMap::new("correlated", D, D, N, N, z).unwrap();
        let r = analyze_map(&m, &periodic()).unwrap();
        let (a, b) = (r.spatial.sal.unwrap(), r.spatial.str_ratio.unwrap());
        assert!(
            (a / sal - 1.0).abs() < 0.15,
            "seed {seed}: Sal {a:e}, truth {sal:e}"
        );
        assert!(
            (b / str_ratio - 1.0).abs() < 0.15,
            "seed {seed}: Str {b}, truth {str_ratio}"
        );
        sals.push(a);
        strs.push(b);
    }
    for (name, v, truth, bias) in [("Sal", &sals, sal, 8e-3), ("Str", &strs, str_ratio, 0.03)] {
        let (mean, sd) = mean_sd(v);
        let allowed = 3.0 * sd / (v.len() as f64).sqrt() + bias * truth;
        assert!(
            (mean - truth).abs() < allowed,
            "{name}: mean {mean:e} (sd {sd:e}), truth {truth:e}; all {v:?}"
        );
    }
}
