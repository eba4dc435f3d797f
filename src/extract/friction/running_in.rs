//! Running-in and steady state of μ through a test (MODELS.md §11), on the
//! per-cycle μ of its whole cycles, in order. The band is the running-in's
//! end: μ within `running_in_band` (2 %) of its plateau.
//!
//! 1. **Noise** σ_c of one cycle's μ: the MAD of the first differences
//!    (× 1.4826 / √2), blind to the slow running-in trend.
//! 2. **Tail**: the final `steady_tail_fraction` (¼) of the cycles, at
//!    least 5. A straight line through it that drifts by more than the band
//!    with |slope| > 3 standard errors means no steady state
//!    (`no_steady_state`).
//! 3. **Exponential running-in** (method `exponential`): μ_k = c + A·e^(−k/τ)
//!    fitted by least squares ([`super::decay`]). It is used when it
//!    describes the cycles (its residual sd at most 1.5 σ_c) and when its
//!    transient is significant (F test against a constant, F > 10; else
//!    there is no running-in, onset 0). The onset is the first cycle where
//!    |A|·e^(−k/τ) ≤ band × |c|; the steady μ is the mean of the cycles from
//!    where the fitted transient is below a quarter of that mean's standard
//!    error (so the running-in's tail does not bias it).
//! 4. **Band** (method `band`, when the curve is not an exponential): the
//!    plateau μ∞ is the tail's mean and the band h = 2 % × |μ∞|, widened to
//!    4 σ_c/√w where the noise needs it; a moving mean over w cycles (w odd,
//!    just large enough for 4 σ_c/√w to fit in the band, 5 to n/5) is
//!    fitted by the closest monotone sequence (isotonic regression) towards
//!    the plateau, and the onset is where that fit enters μ∞ ± h, after the
//!    last window beyond h + 3 σ_c/√w. The steady μ is the mean of the
//!    second half of the steady state.
//!
//! Either way an onset within the tail means the test has not settled
//! (`no_steady_state`); the steady μ carries its standard error sd/√n.

use super::decay::fit_decay;
use crate::signal::stats;
use crate::status::{Code, Status};

/// Parameters of running-in detection (in `[friction]`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteadyParams {
    /// Band half-width, a fraction of the plateau.
    pub band: f64,
    /// Final fraction of the cycles that is the tail.
    pub tail_fraction: f64,
    /// Fewest whole cycles to judge.
    pub min_cycles: usize,
}

impl Default for SteadyParams {
    fn default() -> Self {
        SteadyParams {
            band: 0.02,
            tail_fraction: 0.25,
            min_cycles: 10,
        }
    }
}

/// How the onset was found (the `running_in_method` column).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// The fitted exponential approach to the plateau.
    Exponential,
    /// The monotone fit of the moving mean entering the band.
    Band,
}

impl Method {
    /// The stable text form.
    pub fn as_str(self) -> &'static str {
        match self {
            Method::Exponential => "exponential",
            Method::Band => "band",
        }
    }
}

/// Noise factor of the moving mean that the band must hold.
const BAND_SE: f64 = 4.0;
/// |slope| / se of the tail's line beyond which its drift is real.
const TREND_T: f64 = 3.0;
/// F of the exponential transient against a constant, to be one.
const F_TRANSIENT: f64 = 10.0;
/// Residual sd over the cycle noise up to which the exponential describes
/// the running-in.
const FIT_RATIO: f64 = 1.5;

/// Running-in and steady state of a series of per-cycle μ.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SteadyState {
    /// Cycles judged.
    pub n: usize,
    /// How the onset was found.
    pub method: Option<Method>,
    /// Index (into the series) of the first cycle of the steady state: the
    /// running-in's length in cycles.
    pub onset: Option<usize>,
    /// Index of the first cycle averaged into the steady μ.
    pub mean_from: Option<usize>,
    /// Steady μ.
    pub mu: Option<f64>,
    /// Sample sd of the averaged cycles' μ.
    pub sd: Option<f64>,
    /// Standard error of the steady μ.
    pub se: Option<f64>,
    /// The plateau: the fit's c, or the tail's mean.
    pub plateau: Option<f64>,
    /// Band half-width.
    pub band: Option<f64>,
    /// The fitted time constant, cycles (method `exponential`).
    pub tau_cycles: Option<f64>,
    /// `ok`, or why there is no steady state.
    pub status: Status,
}

/// The running-in and steady state of `mu`, the μ of a test's whole cycles
/// in order (finite values).
pub fn steady_state(mu: &[f64], p: &SteadyParams) -> SteadyState {
    let n = mu.len();
    let mut out = SteadyState {
        n,
        ..Default::default()
    };
    let fewest = p.min_cycles.max(5);
    if n < fewest {
        let why = format!("{n} whole cycles, need at least {fewest} to judge a steady state");
        out.status = Status::of(Code::NoSteadyState, why);
        return out;
    }
    let noise = stats::noise_sigma(mu).unwrap_or(0.0);
    let tail_len = ((p.tail_fraction * n as f64).ceil() as usize).clamp(5, n);
    let tail_mean = stats::mean(&mu[n - tail_len..]).unwrap_or(f64::NAN);
    if let Some(why) = tail_drift(&mu[n - tail_len..], p.band * tail_mean.abs()) {
        out.status = Status::of(Code::NoSteadyState, why);
        return out;
    }
    let onset = match exponential(mu, noise, p) {
        Some((fit_onset, fit)) => {
            (out.method, out.plateau, out.tau_cycles) =
                (Some(Method::Exponential), Some(fit.plateau), Some(fit.tau));
            out.band = Some(p.band * fit.plateau.abs());
            if fit_onset <= n - tail_len {
                out.mean_from = Some(fit_mean_from(mu, &fit, fit_onset).min(n - tail_len));
            }
            fit_onset
        }
        None => {
            let (onset, h) = band_onset(mu, noise, tail_mean, p);
            (out.method, out.plateau, out.band) = (Some(Method::Band), Some(tail_mean), Some(h));
            out.mean_from = Some(onset + (n - onset.min(n)) / 2);
            onset
        }
    };
    if onset > n - tail_len {
        out.mean_from = None;
        out.status = Status::of(
            Code::NoSteadyState,
            format!(
                "the running-in reaches the band (±{:.4} around {:.4}) at cycle {} of {n}, within the final {tail_len}",
                out.band.unwrap_or(f64::NAN),
                out.plateau.unwrap_or(f64::NAN),
                onset + 1
            ),
        );
        return out;
    }
    out.onset = Some(onset);
    let from = out.mean_from.unwrap_or(onset);
    let (mean, sd) = stats::mean_sd(&mu[from..]).unwrap_or((f64::NAN, None));
    out.mu = Some(mean);
    out.sd = sd;
    out.se = sd.map(|s| s / ((n - from) as f64).sqrt());
    out
}

/// Why the tail is not steady: a line through it drifting by more than
/// `band` with |slope| > 3 standard errors.
fn tail_drift(tail: &[f64], band: f64) -> Option<String> {
    let m = tail.len();
    let k: Vec<f64> = (0..m).map(|i| i as f64).collect();
    let line = stats::line_fit(&k, tail)?;
    let resid = stats::sd_by(m, |i| tail[i] - (line.a + line.b * k[i])).unwrap_or(0.0);
    let sxx: f64 = k.iter().map(|v| (v - (m - 1) as f64 / 2.0).powi(2)).sum();
    let dof = ((m - 1) as f64 / (m as f64 - 2.0).max(1.0)).sqrt();
    let se_b = resid * dof / sxx.sqrt();
    let drift = line.b * (m - 1) as f64;
    (drift.abs() > band && line.b.abs() > TREND_T * se_b).then(|| {
        format!("μ drifts by {drift:+.4} over the final {m} cycles, beyond the band ±{band:.4}")
    })
}

/// The exponential running-in, when it describes the cycles: its onset
/// (0 without a significant transient) and the fit.
fn exponential(
    mu: &[f64],
    noise: f64,
    p: &SteadyParams,
) -> Option<(usize, super::decay::DecayFit)> {
    let n = mu.len();
    let fit = fit_decay(mu)?;
    let resid_sd = (fit.ssr / (n as f64 - 3.0)).sqrt();
    if resid_sd > FIT_RATIO * noise && resid_sd > 1e-12 * fit.plateau.abs() {
        return None;
    }
    let mean = stats::mean(mu)?;
    let ssr0: f64 = mu.iter().map(|v| (v - mean).powi(2)).sum();
    let f = ((ssr0 - fit.ssr) / 2.0) / (fit.ssr / (n as f64 - 3.0));
    let h = p.band * fit.plateau.abs();
    let significant = f > F_TRANSIENT || (fit.ssr == 0.0 && ssr0 > 0.0);
    let onset = match significant && fit.amplitude.abs() > h {
        true => (fit.tau * (fit.amplitude.abs() / h).ln()).ceil().max(0.0) as usize,
        false => 0,
    };
    Some((onset.min(n), fit))
}

/// The first cycle from which the fitted transient is below a quarter of
/// the standard error of the mean taken from there.
fn fit_mean_from(mu: &[f64], fit: &super::decay::DecayFit, onset: usize) -> usize {
    let n = mu.len();
    let sd = (fit.ssr / (n as f64 - 3.0)).sqrt();
    let a = fit.amplitude.abs();
    let mut k = onset;
    for _ in 0..4 {
        let se = sd / ((n - k.min(n - 1)) as f64).sqrt();
        if a == 0.0 || se == 0.0 {
            break;
        }
        let need = (fit.tau * (4.0 * a / se).ln()).ceil();
        k = k.max(need.max(0.0) as usize).min(n - 1);
    }
    k
}

/// The moving mean of `w` values around each index (the window shifted
/// inside the record near its ends), by prefix sums.
fn moving_mean(x: &[f64], w: usize) -> Vec<f64> {
    let n = x.len();
    let mut prefix = Vec::with_capacity(n + 1);
    prefix.push(0.0);
    for v in x {
        prefix.push(prefix[prefix.len() - 1] + v);
    }
    (0..n)
        .map(|j| {
            let a = j.saturating_sub(w / 2).min(n - w);
            (prefix[a + w] - prefix[a]) / w as f64
        })
        .collect()
}

/// Pool-adjacent-violators: the non-increasing sequence closest to `x` in
/// least squares.
fn isotonic_falling(x: &[f64]) -> Vec<f64> {
    let mut blocks: Vec<(f64, usize)> = Vec::with_capacity(x.len());
    for &v in x {
        let (mut sum, mut count) = (v, 1usize);
        while let Some(&(s, c)) = blocks.last() {
            if s / c as f64 >= sum / count as f64 {
                break;
            }
            (sum, count) = (sum + s, count + c);
            blocks.pop();
        }
        blocks.push((sum, count));
    }
    blocks
        .into_iter()
        .flat_map(|(s, c)| std::iter::repeat_n(s / c as f64, c))
        .collect()
}

/// The band method's onset and band half-width.
fn band_onset(mu: &[f64], noise: f64, plateau: f64, p: &SteadyParams) -> (usize, f64) {
    let n = mu.len();
    let level = p.band * plateau.abs();
    let cap = ((n / 5).max(5) | 1).min(n);
    let needed = match level > 0.0 {
        true => ((BAND_SE * noise / level).powi(2).ceil() as usize).max(5) | 1,
        false => cap,
    };
    let w = needed.min(cap);
    let h = level.max(BAND_SE * noise / (w as f64).sqrt());
    let m = moving_mean(mu, w);
    let far = h + 3.0 * noise / (w as f64).sqrt();
    let last_far = m
        .iter()
        .rposition(|v| (v - plateau).abs() > far)
        .map_or(0, |j| j + 1);
    let Some(start) = m.get(last_far) else {
        return (last_far, h);
    };
    // Falling from above, or rising from below (negated to fall).
    let sign = if *start >= plateau { 1.0 } else { -1.0 };
    let toward: Vec<f64> = m[last_far..].iter().map(|v| sign * (v - plateau)).collect();
    let fit = isotonic_falling(&toward);
    (
        last_far + fit.iter().position(|d| *d <= h).unwrap_or(fit.len()),
        h,
    )
}

#[cfg(test)]
#[path = "running_in_tests.rs"]
mod tests;
