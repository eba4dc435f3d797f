//! Parameters of the tensile analysis, validated on construction.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

/// Tuning of the per-fibre analysis. Every field is dimensionless.
///
/// Build with [`TensileParams::default`] and adjust, then call
/// [`TensileParams::validate`] (the analysis does it too).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TensileParams {
    /// Effective-knot threshold on friction stress / strength (MODELS.md §3,
    /// Table 5.1). Default 0.08 (8 %); range (0, 1).
    pub effective_threshold: f64,
    /// Friction window: the friction stress is the mean stress over
    /// 0 … `friction_window` · ε_f. Default 0.4; range (0, 1].
    pub friction_window: f64,
    /// "Near zero" after fracture: the final drop must fall below
    /// `break_level` · strength. Default 0.1; range (0, 0.5).
    pub break_level: f64,
    /// A record that ends before the stress is near zero still counts as
    /// fractured when its final drop is at least `truncated_drop` · the
    /// stress at break (the instrument stopped recording during the drop).
    /// Default 0.25; range (0, 1].
    pub truncated_drop: f64,
    /// Smallest stress drop counted, as a fraction of the strength. Default
    /// 0.02; range (0, 1).
    pub drop_min_fraction: f64,
    /// Smallest stress drop counted, in multiples of the noise standard
    /// deviation (estimated from first differences). The hysteresis of drop
    /// detection is the larger of the two. Default 5; range [0, 100].
    pub noise_factor: f64,
    /// Knot release is clear only if the final rise starts at a stress at
    /// most `release_max_fraction` · strength. Default 0.5; range (0, 1).
    pub release_max_fraction: f64,
    /// Without an unfastening drop, a release from the zero-stress floor is
    /// accepted only when that floor extends beyond `release_min_strain` ·
    /// ε_f (evidence of a loose knot region). Default 0.1; range (0, 1).
    pub release_min_strain: f64,
    /// Drops whose peak exceeds `unfastening_factor` × the plateau level
    /// (median stress before ε*), in the trailing run before ε*, count as
    /// the final unfastening; the others as plateau stick-slip. Default 1.5;
    /// range (1, 100].
    pub unfastening_factor: f64,
    /// Modulus window width as a fraction of the strain at maximum stress
    /// (windows with fewer than 5 samples are skipped). Default 0.01: it reproduces the T150 and
    /// Bluehill moduli within 5 % (docs/tensile.md); range (0, 1].
    pub modulus_window: f64,
    /// Stated stress window [σ_lo, σ_hi], MPa, for the modulus by
    /// regression (ISO 6892-1 Annex G, ASTM E111); when absent the modulus
    /// is the steepest slope (`modulus_window`). Default none; 0 ≤ σ_lo < σ_hi.
    pub modulus_stress_window_mpa: Option<[f64; 2]>,
    /// Strain offset of the offset yield (ISO 6892-1 R_p0.2, ASTM E8).
    /// Default 0.002; range (0, 0.1].
    pub yield_offset: f64,
}

impl Default for TensileParams {
    fn default() -> Self {
        TensileParams {
            effective_threshold: 0.08,
            friction_window: 0.4,
            break_level: 0.1,
            truncated_drop: 0.25,
            drop_min_fraction: 0.02,
            noise_factor: 5.0,
            release_max_fraction: 0.5,
            release_min_strain: 0.1,
            unfastening_factor: 1.5,
            modulus_window: 0.01,
            modulus_stress_window_mpa: None,
            yield_offset: 0.002,
        }
    }
}

impl TensileParams {
    /// Checks every field against its range.
    pub fn validate(&self) -> Result<()> {
        if let Some([lo, hi]) = self.modulus_stress_window_mpa {
            if !(lo.is_finite() && hi.is_finite() && lo >= 0.0 && hi > lo) {
                return Err(Error::Config(format!(
                    "tensile parameter modulus_stress_window_mpa = [{lo}, {hi}]: expected 0 ≤ low < high, in MPa"
                )));
            }
        }
        let checks: [(&str, f64, f64, f64, bool); 11] = [
            (
                "effective_threshold",
                self.effective_threshold,
                0.0,
                1.0,
                false,
            ),
            ("friction_window", self.friction_window, 0.0, 1.0, true),
            ("break_level", self.break_level, 0.0, 0.5, false),
            ("truncated_drop", self.truncated_drop, 0.0, 1.0, true),
            ("drop_min_fraction", self.drop_min_fraction, 0.0, 1.0, false),
            ("noise_factor", self.noise_factor, -1e-300, 100.0, true),
            (
                "release_max_fraction",
                self.release_max_fraction,
                0.0,
                1.0,
                false,
            ),
            (
                "release_min_strain",
                self.release_min_strain,
                0.0,
                1.0,
                false,
            ),
            (
                "unfastening_factor",
                self.unfastening_factor,
                1.0,
                100.0,
                true,
            ),
            ("modulus_window", self.modulus_window, 0.0, 1.0, true),
            ("yield_offset", self.yield_offset, 0.0, 0.1, true),
        ];
        for (name, v, lo, hi, hi_closed) in checks {
            let ok = v.is_finite() && v > lo && (v < hi || (hi_closed && v <= hi));
            if !ok {
                let close = if hi_closed { ']' } else { ')' };
                // noise_factor's lower bound is a tiny negative number so that 0 passes
                let open = if lo < 0.0 { '[' } else { '(' };
                return Err(Error::Config(format!(
                    "tensile parameter {name} = {v}: expected a value in {open}{}, {hi}{close}",
                    lo.max(0.0)
                )));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_ranges_are_enforced() {
        TensileParams::default().validate().unwrap();
        let bad = TensileParams {
            effective_threshold: 1.5,
            ..Default::default()
        };
        let msg = bad.validate().unwrap_err().to_string();
        assert!(msg.contains("effective_threshold = 1.5"), "{msg}");
        let nan = TensileParams {
            break_level: f64::NAN,
            ..Default::default()
        };
        assert!(nan.validate().is_err());
        let zero_noise = TensileParams {
            noise_factor: 0.0,
            ..Default::default()
        };
        zero_noise.validate().unwrap();
    }
}
