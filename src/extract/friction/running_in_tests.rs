//! Tests of [`super`]: generated running-in with a known onset.

use super::*;
use crate::signal::testing::gaussian_noise;

/// μ_k = μ∞ + A e^(−k/τ) + noise; the onset is the first cycle where
/// A e^(−k/τ) ≤ 2 % of μ∞.
pub(crate) fn decay(
    n: usize,
    plateau: f64,
    a: f64,
    tau: f64,
    sigma: f64,
    seed: u64,
) -> (Vec<f64>, usize) {
    let e = gaussian_noise(n, sigma, seed);
    let mu = (0..n)
        .map(|k| plateau + a * (-(k as f64) / tau).exp() + e[k])
        .collect();
    let onset = (tau * (a.abs() / (0.02 * plateau)).ln()).ceil() as usize;
    (mu, onset)
}

/// Known running-in, falling and rising, over time constants, noise
/// levels (per-cycle noise up to 3 % of μ∞, more than the 2 % band) and
/// 50 seeds each: the onset within max(2 cycles, 10 %), the steady μ
/// within 2 standard errors of the plateau in at least 92 % of all seeds
/// and 80 % of each case's (a 2-se interval holds 95 %), always within 4.
#[test]
fn a_known_running_in_is_found() {
    let cases = [
        (0.25, 20.0, 0.003, 400),
        (0.25, 30.0, 0.01, 600),
        (0.25, 60.0, 0.004, 1500),
        (0.25, 8.0, 0.002, 120),
        (-0.15, 25.0, 0.005, 500),
        (0.4, 3.0, 0.005, 60),
    ];
    let mut all = 0;
    for (a, tau, sigma, n) in cases {
        let mut within_2se = 0;
        for seed in 0..50u64 {
            let (mu, truth) = decay(n, 0.3, a, tau, sigma, 1000 * seed + n as u64);
            let s = steady_state(&mu, &SteadyParams::default());
            assert!(s.status.is_ok(), "τ {tau} seed {seed}: {}", s.status);
            assert_eq!(s.method, Some(Method::Exponential));
            let onset = s.onset.unwrap();
            let tol = (0.1 * truth as f64).max(2.0);
            assert!(
                (onset as f64 - truth as f64).abs() <= tol,
                "τ {tau} seed {seed}: onset {onset} vs {truth}"
            );
            let (m, se) = (s.mu.unwrap(), s.se.unwrap());
            assert!(
                (m - 0.3).abs() < 4.0 * se,
                "τ {tau} seed {seed}: {m} ± {se}"
            );
            within_2se += usize::from((m - 0.3).abs() < 2.0 * se);
        }
        assert!(within_2se >= 40, "τ {tau}: {within_2se}/50 within 2 se");
        all += within_2se;
    }
    assert!(
        all as f64 >= 0.92 * 50.0 * cases.len() as f64,
        "{all} within 2 se"
    );
}

/// A running-in that is no exponential (a straight fall over 80 cycles,
/// then a plateau) is judged by the band: the onset where the line enters
/// ±2 % of the plateau, cycle 78.
#[test]
fn a_linear_running_in_goes_to_the_band() {
    let e = gaussian_noise(500, 0.001, 4);
    let mu: Vec<f64> = (0..500)
        .map(|k| 0.3 + (0.2 * (1.0 - k as f64 / 80.0)).max(0.0) + e[k])
        .collect();
    let s = steady_state(&mu, &SteadyParams::default());
    assert_eq!(s.method, Some(Method::Band), "{s:?}");
    // 0.2 (1 − k/80) ≤ 0.006 from k = 77.6.
    let onset = s.onset.unwrap() as f64;
    assert!((onset - 78.0).abs() <= 7.8, "{onset}");
    assert!((s.mu.unwrap() - 0.3).abs() < 3.0 * s.se.unwrap(), "{s:?}");
}

/// No running-in: the onset is the first cycle; a constant (no noise at
/// all) is steady with sd 0.
#[test]
fn a_flat_series_is_steady_from_the_start() {
    let mu = gaussian_noise(200, 0.01, 9)
        .iter()
        .map(|e| 0.5 + e)
        .collect::<Vec<_>>();
    let s = steady_state(&mu, &SteadyParams::default());
    assert_eq!(s.onset, Some(0), "{s:?}");
    let flat = steady_state(&[0.25; 50], &SteadyParams::default());
    assert_eq!(
        (flat.onset, flat.mu, flat.sd),
        (Some(0), Some(0.25), Some(0.0)),
        "{flat:?}"
    );
}

/// A μ that keeps rising, or decays too slowly to settle within the test,
/// has no steady state; too few cycles are not judged.
#[test]
fn an_unsettled_series_says_so() {
    let e = gaussian_noise(600, 0.01, 3);
    let rising: Vec<f64> = (0..600).map(|k| 0.3 + 5e-4 * k as f64 + e[k]).collect();
    let slow: Vec<f64> = (0..600)
        .map(|k| 0.3 + 0.3 * (-(k as f64) / 400.0).exp() + e[k])
        .collect();
    let late: Vec<f64> = (0..600)
        .map(|k| 0.3 + 0.3 * (-(k as f64) / 130.0).exp() + e[k])
        .collect();
    for mu in [rising, slow, late] {
        let s = steady_state(&mu, &SteadyParams::default());
        assert!(s.status.has(Code::NoSteadyState), "{}", s.status);
        assert_eq!((s.mu, s.onset), (None, None));
    }
    let s = steady_state(&[0.3; 6], &SteadyParams::default());
    assert!(s.status.has(Code::NoSteadyState), "{}", s.status);
}
